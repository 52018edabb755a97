// Headless OpenGL ES for tests: Mesa's surfaceless EGL platform, an ES 3.0 context (strict with
// MESA_GLES_VERSION_OVERRIDE=3.0, set here before EGL starts and by ctest), a 1x1 FBO bound;
// on the driver GALLIUM_DRIVER names when it is set (the softpipe test preset); llvmpipe without
// rasterizer threads (LP_NUM_THREADS=0, set here; see create()).
// Under CI=true a missing context is a failure; locally the GLES tests skip.
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <string>
#include <thread>

#include "drape/drape.h"

/// GL ES calls libdrape made to entry point `name` (NULL: all) since it loaded them; exported by
/// the library's GL loader for tests and the bench, not part of drape.h.
extern "C" uint64_t drape_gl_call_count(const char* name);
/// Replaces the driver function behind libdrape's entry point `name`; returns the one replaced
/// (NULL for names it does not use). From the same loader, for tests that fake a device.
extern "C" void* drape_gl_replace(const char* name, void* fn);

namespace drape_test {

class HeadlessGles {
public:
    /// Creates the display + context (not current). Empty string on success.
    std::string create() {
        setenv("MESA_GLES_VERSION_OVERRIDE", "3.0", 0);
        // Mesa 22.3's llvmpipe (and lavapipe under zink) frees a scene's fence once its count reads
        // complete, unlocked, while the rasterizer thread that completed it may still be in
        // lp_fence_signal: its cnd_broadcast and mutex unlock then write into the freed block (a zero
        // at byte 8). That heap corruption crashed SelfCollisionGles.FoldingCloth... in malloc under
        // load. Without rasterizer threads the fence is signalled on the caller: no race, the same
        // images. A run that sets LP_NUM_THREADS keeps its value.
        setenv("LP_NUM_THREADS", "0", 0);
        auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!get_display) return "eglGetPlatformDisplayEXT missing";
        display_ = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY) return "no surfaceless EGL display";
        if (!eglInitialize(display_, nullptr, nullptr)) return "eglInitialize failed";
        eglBindAPI(EGL_OPENGL_ES_API);
        const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE};
        EGLConfig config;
        EGLint count = 0;
        if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) return "no ES3 EGL config";
        const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
        if (context_ == EGL_NO_CONTEXT) return "eglCreateContext failed";
        // A run asked for a driver (GALLIUM_DRIVER=softpipe) must get it, not Mesa's fallback.
        const char* driver = std::getenv("GALLIUM_DRIVER");
        if (driver && *driver) {
            if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return "eglMakeCurrent failed";
            const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
            const std::string got = renderer ? renderer : "none";
            release_current();
            if (got.find(driver) == std::string::npos)
                return std::string("GALLIUM_DRIVER=") + driver + " asked for, GL_RENDERER is " + got;
        }
        return {};
    }
    /// Makes the context current on this thread with a 1x1 FBO bound (the default framebuffer
    /// of a surfaceless context is incomplete).
    bool make_current() {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return false;
        if (!fbo_) {
            glGenRenderbuffers(1, &rbo_);
            glBindRenderbuffer(GL_RENDERBUFFER, rbo_);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
            glGenFramebuffers(1, &fbo_);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rbo_);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        return true;
    }
    void release_current() { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }
    void destroy() {
        if (context_ != EGL_NO_CONTEXT) {
            make_current();
            glDeleteFramebuffers(1, &fbo_);
            glDeleteRenderbuffers(1, &rbo_);
            fbo_ = rbo_ = 0;
            release_current();
            eglDestroyContext(display_, context_);
        }
        context_ = EGL_NO_CONTEXT;
        if (display_ != EGL_NO_DISPLAY) eglTerminate(display_);
        display_ = EGL_NO_DISPLAY;
    }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    GLuint fbo_ = 0, rbo_ = 0;
};

/// A thread owning the GL context (Unity's render thread); run() executes a job there and waits for it.
class RenderThread {
public:
    RenderThread() : thread_([this] { loop(); }) {}
    ~RenderThread() {
        {
            std::lock_guard<std::mutex> lock(m_);
            quit_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    template <class Fn>
    auto run(Fn fn) -> decltype(fn()) {
        std::packaged_task<decltype(fn())()> task(std::move(fn));
        auto result = task.get_future();
        {
            std::lock_guard<std::mutex> lock(m_);
            jobs_.emplace_back([&task] { task(); });
        }
        cv_.notify_all();
        return result.get();
    }

private:
    void loop() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(m_);
                cv_.wait(lock, [this] { return quit_ || !jobs_.empty(); });
                if (jobs_.empty()) return;
                job = std::move(jobs_.front());
                jobs_.pop_front();
            }
            job();
        }
    }
    std::mutex m_;
    std::condition_variable cv_;
    std::deque<std::function<void()>> jobs_;
    bool quit_ = false;
    std::thread thread_;
};

/// Unity's render thread in a test: a RenderThread with its own headless GLES context.
class GlesRenderThread : public RenderThread {
public:
    /// Creates the context and makes it current on the render thread: empty on success, else why not.
    std::string start() {
        const std::string why = run([this] { return gl.create(); });
        if (!why.empty()) return why;
        return run([this] { return gl.make_current(); }) ? std::string() : "eglMakeCurrent failed";
    }
    /// Destroys the context on the render thread.
    void stop() {
        run([this] { gl.destroy(); });
    }
    /// This plug-in's render event id (drape_unity_render_event).
    static int32_t event_id() {
        void* callback = nullptr;
        int32_t id = -1;
        drape_unity_render_event(&callback, &id);
        return id;
    }
    /// Issues render event `id` through the plug-in's callback on the render thread, as Unity's
    /// GL.IssuePluginEvent does each frame.
    void fire(int32_t id = event_id()) {
        void* callback = nullptr;
        int32_t own = -1;
        drape_unity_render_event(&callback, &own);
        run([&] { reinterpret_cast<void (*)(int)>(callback)(id); });
    }
    HeadlessGles gl;
};

inline bool running_in_ci() {
    const char* ci = std::getenv("CI");
    return ci && std::strcmp(ci, "true") == 0;
}

/// Fails under CI=true, skips otherwise.
#define DRAPE_GLES_UNAVAILABLE(why)                                                          \
    do {                                                                                     \
        if (drape_test::running_in_ci()) FAIL() << "no headless GLES context (CI=true): " << (why); \
        GTEST_SKIP() << "no headless GLES context: " << (why);                               \
    } while (0)

/// Test fixture with a headless GLES context current during each test (skipped without one,
/// failed under CI=true). Base: ::testing::Test or a TestWithParam.
template <class Base = ::testing::Test>
class WithHeadlessGles : public Base {
protected:
    void SetUp() override {
        const std::string why = gl_.create();
        if (!why.empty() || !gl_.make_current()) {
            gl_.destroy();
            DRAPE_GLES_UNAVAILABLE(why.empty() ? "eglMakeCurrent failed" : why);
        }
        ready_ = true;
    }
    void TearDown() override {
        if (ready_) gl_.destroy();
    }
    HeadlessGles gl_;
    bool ready_ = false;
};

/// Counts live GL object names 1..limit of each kind (glIs*): a leak check.
struct GlNameCounts {
    int buffers = 0, textures = 0, programs = 0, vertex_arrays = 0, framebuffers = 0, renderbuffers = 0;
    static GlNameCounts take(GLuint limit = 4096) {
        GlNameCounts c;
        for (GLuint n = 1; n <= limit; ++n) {
            c.buffers += glIsBuffer(n);
            c.textures += glIsTexture(n);
            c.programs += glIsProgram(n);
            c.vertex_arrays += glIsVertexArray(n);
            c.framebuffers += glIsFramebuffer(n);
            c.renderbuffers += glIsRenderbuffer(n);
        }
        return c;
    }
    bool operator==(const GlNameCounts& o) const {
        return buffers == o.buffers && textures == o.textures && programs == o.programs &&
               vertex_arrays == o.vertex_arrays && framebuffers == o.framebuffers && renderbuffers == o.renderbuffers;
    }
};
inline std::ostream& operator<<(std::ostream& os, const GlNameCounts& c) {
    return os << "{buffers " << c.buffers << ", textures " << c.textures << ", programs " << c.programs << ", vaos "
              << c.vertex_arrays << ", fbos " << c.framebuffers << ", rbos " << c.renderbuffers << "}";
}

}  // namespace drape_test
