// The maths the CPU kernels share with the GLES passes, written once in the common subset of glm and
// GLSL under shaders/ (substep.h: prediction, spring forces, constraint updates, tethers;
// collide_shape.h: particle against collider; self_contact.h: particle pairs), seen from C++: in
// namespace drape::kernels::glsl, with glm's types and functions under GLSL's names, DRAPE_OUT(T) = T&
// for GLSL's out parameters and DRAPE_INLINE = inline. The embed step splices the same files into the
// shaders (embed_shaders.cmake).
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "drape/drape.h"  // the shape and group ids that shaders/layout.h defines for GLSL

namespace drape::kernels::glsl {
using glm::abs;
using glm::cross;
using glm::dot;
using glm::ivec3;
using glm::mat3;
using glm::max;
using glm::min;
using glm::outerProduct;
using glm::vec3;
using glm::vec4;
using std::exp;
using std::sqrt;
using uint = uint32_t;
#define DRAPE_OUT(T) T&
#define DRAPE_INLINE inline
#include "shaders/substep.h"
#include "shaders/collide_shape.h"
#include "shaders/self_contact.h"
#undef DRAPE_OUT
#undef DRAPE_INLINE
}  // namespace drape::kernels::glsl
