#include "backend/gles/gl_loader.h"

#include <dlfcn.h>

#include <cstring>
#include <mutex>
#include <string>

namespace drape::gles {

#define DRAPE_GL_DEFINE(type, name) GlEntry<type> name;
DRAPE_GL_FUNCTIONS(DRAPE_GL_DEFINE)
#undef DRAPE_GL_DEFINE

namespace {

// Library names: Android has libGLESv3.so (API 18+) and libEGL.so; desktop Linux (Mesa,
// libglvnd) has the versioned names. The first that loads is used; it is never unloaded.
#if defined(__ANDROID__)
const char* const kGlesLibraries[] = {"libGLESv3.so", "libGLESv2.so"};
const char* const kEglLibraries[] = {"libEGL.so"};
#else
const char* const kGlesLibraries[] = {"libGLESv2.so.2", "libGLESv2.so"};
const char* const kEglLibraries[] = {"libEGL.so.1", "libEGL.so"};
#endif

std::once_flag g_once;
std::string g_error;
PFNEGLGETCURRENTCONTEXTPROC g_get_current_context = nullptr;

template <size_t N>
void* open_first(const char* const (&names)[N]) {
    for (const char* n : names)
        if (void* h = dlopen(n, RTLD_NOW | RTLD_LOCAL)) return h;
    return nullptr;
}

void load() {
    void* egl = open_first(kEglLibraries);
    void* gles = open_first(kGlesLibraries);
    if (!egl || !gles) {
        g_error = std::string("cannot load ") + (egl ? kGlesLibraries[0] : kEglLibraries[0]);
        return;
    }
    auto get_proc = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(egl, "eglGetProcAddress"));
    auto current = reinterpret_cast<PFNEGLGETCURRENTCONTEXTPROC>(dlsym(egl, "eglGetCurrentContext"));
    if (!get_proc || !current) {
        g_error = "the EGL library lacks eglGetProcAddress or eglGetCurrentContext";
        return;
    }
    // Core GL ES functions: exported by the GLES library; eglGetProcAddress as a fallback (it
    // returns core functions only with EGL 1.5 or EGL_KHR_get_all_proc_addresses).
    std::string missing;
    auto resolve = [&](const char* name) -> void* {
        void* p = dlsym(gles, name);
        if (!p) p = reinterpret_cast<void*>(get_proc(name));
        if (!p) missing += std::string(missing.empty() ? "" : ", ") + name;
        return p;
    };
#define DRAPE_GL_RESOLVE(type, name) name.fn = reinterpret_cast<type>(resolve(#name));
    DRAPE_GL_FUNCTIONS(DRAPE_GL_RESOLVE)
#undef DRAPE_GL_RESOLVE
    if (!missing.empty()) {
        g_error = "OpenGL ES functions not found: " + missing;
        return;
    }
    g_get_current_context = current;  // only when everything resolved: the backend's gate
}

}  // namespace

EGLContext eglGetCurrentContext() {
    std::call_once(g_once, load);
    return g_get_current_context ? g_get_current_context() : EGL_NO_CONTEXT;
}

const char* load_error() {
    std::call_once(g_once, load);
    return g_error.c_str();
}

}  // namespace drape::gles

uint64_t drape_gl_call_count(const char* name) {
    using namespace drape::gles;
    uint64_t total = 0;
#define DRAPE_GL_COUNT(type, fn_name)                                      \
    if (!name || std::strcmp(name, #fn_name) == 0) total += fn_name.calls.load(std::memory_order_relaxed);
    DRAPE_GL_FUNCTIONS(DRAPE_GL_COUNT)
#undef DRAPE_GL_COUNT
    return total;
}

void* drape_gl_replace(const char* name, void* fn) {
    using namespace drape::gles;
    if (!name) return nullptr;
    load_error();  // loads: what is replaced now stays replaced
#define DRAPE_GL_REPLACE(type, fn_name)                         \
    if (std::strcmp(name, #fn_name) == 0) {                       \
        void* replaced = reinterpret_cast<void*>(fn_name.fn);    \
        fn_name.fn = reinterpret_cast<type>(fn);                 \
        return replaced;                                         \
    }
    DRAPE_GL_FUNCTIONS(DRAPE_GL_REPLACE)
#undef DRAPE_GL_REPLACE
    return nullptr;
}
