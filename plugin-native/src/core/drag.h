// Touch drag (paper section IV, eq. 9): the projection / unprojection between simulation space and
// screen pixels (the screen-space falloff, touch_weight, is in shaders/substep.h, shared with GLES).
// Stateless; mirrored by the C# Core touch-drag math and usable by tests as the reference.
#pragma once

#include <cmath>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "drape/drape.h"

namespace drape {

/// Paper defaults (section IV: "A and sigma ... are respectively 200 and 300").
constexpr float kTouchAmplitude = 200.0f;
constexpr float kTouchSigma = 300.0f;  ///< px^2 (the paper's sigma divides r^2 directly)
constexpr uint32_t kMaxTouches = 16;
constexpr uint32_t kMaxGrabs = 16;

/// Simulation space <-> screen pixels for one drape_view, in double precision (the inverse of a
/// perspective projection loses digits in float).
struct ScreenMapping {
    glm::dmat4 mvp;      ///< projection * view * world
    glm::dmat4 inv_mvp;
    glm::dvec2 viewport; ///< px
};

/// origin: where a cloth's local coordinates start in simulation space (Cloth::origin); the
/// mapping then takes local coordinates.
ScreenMapping make_screen_mapping(const drape_view& v, const glm::dvec3& origin = glm::dvec3(0.0));

/// Pixel position (origin bottom-left) and NDC depth of x; false if x is at or behind the eye.
bool to_screen(const ScreenMapping& m, const glm::vec3& x, glm::dvec2* px, double* ndc_z);

/// The simulation-space point at pixel px and NDC depth ndc_z.
glm::dvec3 from_screen(const ScreenMapping& m, const glm::dvec2& px, double ndc_z);

}  // namespace drape
