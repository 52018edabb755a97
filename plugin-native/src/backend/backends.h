// The one place that knows every backend: which are available, and creating a cloth of one. The
// C ABI goes through it and otherwise calls only the Cloth interface (core/cloth.h).
#pragma once

#include <memory>

#include "core/cloth.h"

namespace drape {

/// OK, or why `backend` cannot create cloths in this build, on this thread.
Result backend_available(drape_backend backend);

/// A new cloth of an available backend in `world` (not yet added to it).
Result create_cloth(World& world, drape_backend backend, std::shared_ptr<const Description> description,
                    std::unique_ptr<Cloth>* out);

/// Every GL context the GLES backend used is gone (drape_gles_context_lost); nothing without GLES.
void gl_context_lost();

}  // namespace drape
