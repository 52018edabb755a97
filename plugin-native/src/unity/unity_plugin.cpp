// Unity native plug-in entry points. They only register callbacks and record state; all GL work
// runs in the render-event callback and the device events, which Unity calls on its render thread
// with its GL context current.
#include "unity/unity_interface.h"

#include <atomic>

#include "api/last_error.h"
#include "drape/drape.h"
#ifdef DRAPE_WITH_GLES
#include "backend/gles/gles_cloth.h"
#endif

namespace {

using namespace drape::unity;

Graphics* g_graphics = nullptr;
std::atomic<int> g_event_id{0};  // Drape's event id (reserved from Unity, 0 before load)

void DRAPE_UNITY_API on_device_event(int type) {
    if (!g_graphics) return;
#ifdef DRAPE_WITH_GLES
    switch (type) {
        case kEventInitialize:
        case kEventAfterReset:
            // Only OpenGL ES 3 runs the GLES backend; other renderers keep using CPU cloths.
            // (Possibly on the main thread: the context is checked on the render thread, per event.)
            drape::gles::set_render_thread_device(g_graphics->GetRenderer() == kRendererOpenGLES30);
            break;
        case kEventShutdown:
        case kEventBeforeReset:
            if (drape::gles::render_thread_device_ready()) drape::gles::render_thread_shutdown();
            drape::gles::set_render_thread_device(false);
            break;
    }
#else
    (void)type;
#endif
}

void DRAPE_UNITY_API on_render_event(int event_id) {
#ifdef DRAPE_WITH_GLES
    // Guard against events from other plug-ins and against a missing or lost device.
    if (event_id != g_event_id.load()) return;
    // Statically linked (the Unity source plug-in in IL2CPP players): Unity calls no
    // UnityPluginLoad there, so no device events come; the render event itself runs on the render
    // thread, where a current GL ES 3 context makes the device usable.
    if (!g_graphics && !drape::gles::render_thread_device_ready() && drape::gles::context_current())
        drape::gles::set_render_thread_device(true);
    if (!drape::gles::render_thread_device_ready()) return;
    drape::gles::render_thread_tick();
#else
    (void)event_id;
#endif
}

}  // namespace

extern "C" {

DRAPE_UNITY_EXPORT void DRAPE_UNITY_API UnityPluginLoad(Interfaces* interfaces) {
    if (!interfaces || !interfaces->GetInterfaceSplit) return;
    g_graphics = static_cast<Graphics*>(interfaces->GetInterfaceSplit(kGraphicsGUID.high, kGraphicsGUID.low));
    if (!g_graphics) return;
    g_event_id = g_graphics->ReserveEventIDRange ? g_graphics->ReserveEventIDRange(1) : 1;
    g_graphics->RegisterDeviceEventCallback(on_device_event);
    // A plug-in loaded after the device was created misses Initialize: run it now (as Unity's
    // sample does). Unity calls UnityPluginLoad where the device's context is usable.
    on_device_event(kEventInitialize);
}

DRAPE_UNITY_EXPORT void DRAPE_UNITY_API UnityPluginUnload() {
    if (g_graphics) g_graphics->UnregisterDeviceEventCallback(on_device_event);
    g_graphics = nullptr;
#ifdef DRAPE_WITH_GLES
    drape::gles::set_render_thread_device(false);
#endif
}

drape_status drape_unity_render_event(void** out_callback, int32_t* out_event_id) {
    if (!out_callback) return drape::set_last_error(DRAPE_ERROR_NULL_POINTER, "out_callback is NULL");
    if (!out_event_id) return drape::set_last_error(DRAPE_ERROR_NULL_POINTER, "out_event_id is NULL");
    *out_callback = reinterpret_cast<void*>(&on_render_event);
    *out_event_id = g_event_id.load();
    return drape::set_last_error(DRAPE_OK, nullptr);
}

}  // extern "C"
