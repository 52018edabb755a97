// Drives the Unity native plug-in interface the way Unity does, on headless EGL: a fake
// IUnityInterfaces/IUnityGraphics, a "render thread" that owns the GL context and fires the
// device events and the render event, and a "main thread" (the test thread, no context) that only
// makes Drape calls: load -> device init -> per-frame steps + render events -> destroy ->
// device shutdown -> unload.
#include "drape_test_util.h"
#include "gles_test_util.h"

extern "C" {
// Our exported entry points (declared by the library in src/unity/unity_interface.h).
void UnityPluginLoad(void* interfaces);
void UnityPluginUnload();
}

using namespace drape_test;

namespace {

// ---- Fake Unity (layouts as in shared docs/unity-notes.md section 2) -----------------------
using DeviceEventCallback = void (*)(int);
struct FakeGraphics {
    int (*GetRenderer)();
    void (*RegisterDeviceEventCallback)(DeviceEventCallback);
    void (*UnregisterDeviceEventCallback)(DeviceEventCallback);
    int (*ReserveEventIDRange)(int);
};
struct FakeInterfaces {
    void* (*GetInterface)(unsigned long long[2]);
    void (*RegisterInterface)(unsigned long long[2], void*);
    void* (*GetInterfaceSplit)(unsigned long long, unsigned long long);
    void (*RegisterInterfaceSplit)(unsigned long long, unsigned long long, void*);
};
DeviceEventCallback g_device_callback = nullptr;
FakeGraphics g_graphics{
    [] { return 11; },  // kUnityGfxRendererOpenGLES30
    [](DeviceEventCallback cb) { g_device_callback = cb; },
    [](DeviceEventCallback cb) {
        if (g_device_callback == cb) g_device_callback = nullptr;
    },
    [](int) { return 1000; }};
FakeInterfaces g_interfaces{nullptr, nullptr,
                            [](unsigned long long high, unsigned long long low) -> void* {
                                if (high == 0x7CBA0A9CA4DDB544ULL && low == 0x8C5AD4926EB17B11ULL) return &g_graphics;
                                return nullptr;
                            },
                            nullptr};

}  // namespace

TEST(Unity, PluginLifecycleOnARenderThread) {
    GlesRenderThread render;
    if (const std::string why = render.start(); !why.empty()) DRAPE_GLES_UNAVAILABLE(why);

    const GlNameCounts before = render.run([] { return GlNameCounts::take(); });
    // Unity loads the plug-in on the main thread, then the device fires Initialize on the render thread.
    UnityPluginLoad(&g_interfaces);
    ASSERT_NE(g_device_callback, nullptr);
    render.run([] { g_device_callback(0); });
    void* callback = nullptr;
    int32_t event_id = 0;
    ASSERT_DRAPE_OK(drape_unity_render_event(&callback, &event_id));
    ASSERT_NE(callback, nullptr);
    EXPECT_EQ(event_id, 1000);

    // Main thread: no context here, yet GLES is available (recorded for the render thread).
    uint32_t available = 0;
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 1u);
    WorldPtr w = make_world(1);
    const uint32_t cols = 12, rows = 10, n = cols * rows;
    drape_grid_desc g = grid_desc(cols, rows, 1.0f, 1.0f);
    g.origin[1] = 1.0f;
    drape_cloth* cpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_CPU);
    drape_cloth* gpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_GLES);
    ASSERT_NE(gpu, nullptr);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 1, 0}}, {sizeof(drape_pin), cols - 1, {1, 1, 0}}};
    for (drape_cloth* c : {cpu, gpu}) ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    // Unity's mesh buffer (made by Unity on the render thread; C# hands us its name).
    const GLuint vbo = render.run([&] {
        GLuint b = 0;
        glGenBuffers(1, &b);
        glBindBuffer(GL_ARRAY_BUFFER, b);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * 24), nullptr, GL_DYNAMIC_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        return b;
    });
    const drape_vertex_layout layout{sizeof(drape_vertex_layout), 24, 0, 12};
    ASSERT_DRAPE_OK(drape_cloth_set_output_buffer(gpu, vbo, &layout));

    for (int frame = 0; frame < 20; ++frame) {
        ASSERT_DRAPE_OK(drape_cloth_step(cpu, 1.0f / 60));
        ASSERT_DRAPE_OK(drape_cloth_step(gpu, 1.0f / 60));  // recorded only
        render.fire();  // GL work happens here
    }
    ASSERT_DRAPE_OK(drape_cloth_readback(gpu));
    render.fire();
    const std::vector<float> expect = positions(cpu);
    const std::vector<float> got = positions(gpu);  // the read-back copy, no GL on this thread
    float err = 0;
    for (size_t k = 0; k < expect.size(); ++k) err = std::max(err, std::fabs(expect[k] - got[k]));
    EXPECT_LE(err, 1e-5f * 20 * std::sqrt(2.0f));
    // The buffer Unity draws holds the positions.
    const float buffer_err = render.run([&] {
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        const auto* f = static_cast<const float*>(glMapBufferRange(GL_ARRAY_BUFFER, 0, GLsizeiptr(n * 24), GL_MAP_READ_BIT));
        float e = f ? 0.0f : 1e9f;
        for (uint32_t v = 0; f && v < n; ++v)
            for (int k = 0; k < 3; ++k) e = std::max(e, std::fabs(f[v * 6 + k] - expect[v * 3 + k]));
        glUnmapBuffer(GL_ARRAY_BUFFER);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        return e;
    });
    EXPECT_LE(buffer_err, 1e-5f * 20 * std::sqrt(2.0f));
    ASSERT_DRAPE_OK(drape_cloth_step(gpu, 1.0f / 60));  // left pending on purpose

    // Destroy on the main thread: GL objects go at the next render event.
    ASSERT_DRAPE_OK(drape_cloth_destroy(gpu));
    render.fire();
    render.run([&] { glDeleteBuffers(1, &vbo); });
    EXPECT_EQ(render.run([] { return GlNameCounts::take(); }), before);

    // A cloth alive at device shutdown keeps its state on the CPU.
    drape_cloth* late = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_GLES);
    ASSERT_DRAPE_OK(drape_cloth_step(late, 1.0f / 60));
    render.fire();
    render.run([] { g_device_callback(1); });  // Shutdown
    EXPECT_EQ(render.run([] { return GlNameCounts::take(); }), before);
    const std::vector<float> kept = positions(late);
    EXPECT_LT(kept[3 * (n - 1) + 1], 1.0f);  // it fell before the device went away
    UnityPluginUnload();
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 0u);
    w.reset();
    render.stop();
}

// Statically linked plug-in (Unity source plug-in, IL2CPP players): UnityPluginLoad is never
// called, so no device events arrive. The first render event on a thread with a GL ES 3 context
// makes GLES available, and GLES cloths then step on that thread's events.
TEST(Unity, RenderEventWithoutPluginLoadEnablesGles) {
    GlesRenderThread render;
    if (const std::string why = render.start(); !why.empty()) DRAPE_GLES_UNAVAILABLE(why);

    const int32_t event_id = GlesRenderThread::event_id();
    uint32_t available = 1;
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 0u);  // main thread: no context, no device yet
    render.fire(event_id + 7);  // another plug-in's event: ignored
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 0u);
    render.fire(event_id);
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 1u);

    WorldPtr w = make_world(1);
    drape_grid_desc g = grid_desc(8, 6, 1.0f, 1.0f);
    g.origin[1] = 1.0f;
    drape_cloth* cpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_CPU);
    drape_cloth* gpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_GLES);
    ASSERT_NE(gpu, nullptr);
    for (int frame = 0; frame < 5; ++frame) {
        ASSERT_DRAPE_OK(drape_cloth_step(cpu, 1.0f / 60));
        ASSERT_DRAPE_OK(drape_cloth_step(gpu, 1.0f / 60));
        render.fire(event_id);
    }
    ASSERT_DRAPE_OK(drape_cloth_readback(gpu));
    render.fire(event_id);
    const std::vector<float> expect = positions(cpu);
    const std::vector<float> got = positions(gpu);
    float err = 0;
    for (size_t k = 0; k < expect.size(); ++k) err = std::max(err, std::fabs(expect[k] - got[k]));
    EXPECT_LT(expect[1], 1.0f);  // it fell
    EXPECT_LE(err, 1e-5f * 5 * std::sqrt(2.0f));
    ASSERT_DRAPE_OK(drape_cloth_destroy(gpu));
    render.fire(event_id);  // GL objects go on the render thread
    w.reset();
    UnityPluginUnload();  // what remains of the device state (no Unity interfaces here)
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_GLES, &available));
    EXPECT_EQ(available, 0u);
    render.stop();
}

// The render thread's context is lost (Android): the main thread says so, the render thread makes
// a new one, and the cloth resumes from its last readback at the next render event, like a CPU
// cloth that was never interrupted.
TEST(Unity, RenderThreadClothResumesAfterContextLoss) {
    GlesRenderThread render;
    if (const std::string why = render.start(); !why.empty()) DRAPE_GLES_UNAVAILABLE(why);
    render.fire();  // makes GLES available (no plug-in load here)

    WorldPtr w = make_world(1);
    drape_grid_desc g = grid_desc(8, 6, 1.0f, 1.0f);
    g.origin[1] = 1.0f;
    drape_cloth* cpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_CPU);
    drape_cloth* gpu = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_GLES);
    ASSERT_NE(gpu, nullptr);
    auto frame = [&] {
        ASSERT_DRAPE_OK(drape_cloth_step(cpu, 1.0f / 60));
        ASSERT_DRAPE_OK(drape_cloth_step(gpu, 1.0f / 60));
        render.fire();
    };
    for (int f = 0; f < 4; ++f) frame();
    ASSERT_DRAPE_OK(drape_cloth_readback(gpu));
    render.fire();
    render.stop();
    ASSERT_DRAPE_OK(drape_gles_context_lost());
    const std::string again = render.start();
    ASSERT_TRUE(again.empty()) << again;
    for (int f = 0; f < 4; ++f) frame();
    ASSERT_DRAPE_OK(drape_cloth_readback(gpu));
    render.fire();
    ASSERT_DRAPE_OK(drape_cloth_step(gpu, 1.0f / 60));  // no error met on the render thread
    const std::vector<float> expect = positions(cpu);
    const std::vector<float> got = positions(gpu);
    float err = 0;
    for (size_t k = 0; k < expect.size(); ++k) err = std::max(err, std::fabs(expect[k] - got[k]));
    EXPECT_LT(expect[1], 0.99f);  // it fell
    EXPECT_LE(err, 1e-5f * 8 * std::sqrt(2.0f));
    ASSERT_DRAPE_OK(drape_cloth_destroy(gpu));
    render.fire();
    w.reset();
    UnityPluginUnload();
    render.stop();
}
