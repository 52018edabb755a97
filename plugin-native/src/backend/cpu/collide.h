// Per-particle collision kernel of one substep: particles against analytic colliders (sphere,
// capsule, oriented box, plane), with Coulomb friction and a swept test against tunnelling.
//
// Like kernels.h this is a gather: particle i reads its own substep-start record `start[i]` and
// its committed record `x[i]` and writes only x[i], so any split over threads gives the same bits
// and the GLES interaction pass does the same per vertex (colliders as a uniform array of
// CollideShape). The maths per particle and collider is shaders/collide_shape.h, shared with it.
// Each collider is given at the start and at the end of the substep (the host's previous -> new
// transform interpolated across the step's substeps, ColliderState::at_substep).
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "backend/cpu/glsl.h"  // glsl::shape_distance, collide_local (shaders/collide_shape.h)
#include "core/interaction.h"  // CollideShape

namespace drape::kernels {

/// Moves particles [begin, end) of x out of every collider (surface + margin) and applies
/// friction to their tangential motion relative to the collider over the substep.
/// Friction (position-based Coulomb, Macklin et al. 2014 "Unified particle physics", eq. 24):
/// with the contact push depth d and relative tangential displacement t over the substep, static
/// friction (|t| <= mu d) removes t, kinetic friction shortens it by mu d.
/// The substep start is x - d (d: displacement over the substep, kernels.h); a push moves x and
/// d together, so the velocity after the substep includes it.
/// normal (optional): the outward surface normal of the last frictionless collider that moved
/// particle i, 0 if none did (for the IMPLICIT solve of the next substep, implicit_solve.h).
inline void collide(const CollideShape* shapes, uint32_t shape_count, glm::vec4* x, glm::vec4* d,
                    glm::vec3* normal, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const float w = x[i].w;
        if (normal) normal[i] = glm::vec3(0.0f);
        if (w == 0.0f) continue;  // kinematic: goes where its pin says
        const glm::vec3 x_in(x[i]);
        glm::vec3 xi = x_in;
        const glm::vec3 si = x_in - glm::vec3(d[i]);
        for (uint32_t k = 0; k < shape_count; ++k) {
            const CollideShape& c = shapes[k];
            const glm::vec4 rot0(c.rot0.x, c.rot0.y, c.rot0.z, c.rot0.w), rot1(c.rot1.x, c.rot1.y, c.rot1.z, c.rot1.w);
            glm::vec3 q;
            if (!glsl::collide_moving(int(c.shape), c.size, c.margin, c.friction, c.pos0, rot0, c.pos1, rot1, si, xi, q))
                continue;
            xi = glsl::quat_rotate(rot1, q) + c.pos1;
            if (normal && c.friction == 0.0f) {
                glm::vec3 n;
                glsl::shape_distance(int(c.shape), c.size, q, n);
                normal[i] = glsl::quat_rotate(rot1, n);
            }
        }
        if (xi == x_in) continue;
        x[i] = glm::vec4(xi, w);
        d[i] += glm::vec4(xi - x_in, 0.0f);
    }
}

}  // namespace drape::kernels
