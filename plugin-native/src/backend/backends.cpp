#include "backend/backends.h"

#include <string>

#include "backend/cpu/cpu_cloth.h"
#ifdef DRAPE_WITH_GLES
#include "backend/gles/gles_cloth.h"
#endif

namespace drape {

Result backend_available(drape_backend backend) {
    if (backend == DRAPE_BACKEND_CPU || backend == DRAPE_BACKEND_CPU_THREADED) return {};
#ifdef DRAPE_WITH_GLES
    if (backend == DRAPE_BACKEND_GLES) {
        std::string why;
        if (gles::context_current(&why) || gles::render_thread_device_ready()) return {};
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "backend GLES needs an OpenGL ES 3 context current on the calling "
                                                 "thread (or a Unity OpenGLES3 device): " + why};
    }
#endif
    return {DRAPE_ERROR_BACKEND_UNAVAILABLE,
            "backend " + std::to_string(backend) + " is not available in this build or on this thread"};
}

Result create_cloth(World& world, drape_backend backend, std::shared_ptr<const Description> description,
                    std::unique_ptr<Cloth>* out) {
#ifdef DRAPE_WITH_GLES
    if (backend == DRAPE_BACKEND_GLES) {
        // A context current here: GL work happens in the caller's calls. None (Unity main thread
        // with an OpenGLES3 device): calls record, the render event does the GL work.
        const bool here = gles::context_current();
        const auto mode = here ? gles::GlesCloth::Mode::Immediate : gles::GlesCloth::Mode::RenderThread;
        auto g = std::make_unique<gles::GlesCloth>(world, std::move(description), mode);
        if (here)
            if (Result r = g->init_gl(); !r.ok()) return r;
        *out = std::move(g);
        return {};
    }
#endif
    *out = std::make_unique<cpu::CpuCloth>(world, backend, std::move(description));
    return {};
}

void gl_context_lost() {
#ifdef DRAPE_WITH_GLES
    gles::context_lost();
#endif
}

}  // namespace drape
