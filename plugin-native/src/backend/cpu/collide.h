// Per-particle collision kernel of one substep: particles against analytic colliders (sphere,
// capsule, oriented box, plane), with Coulomb friction and a swept test against tunnelling.
//
// Like kernels.h this is a gather: particle i reads its own substep-start record `start[i]` and
// its committed record `x[i]` and writes only x[i], so any split over threads gives the same bits
// and a GLES vertex shader can mirror it (colliders as a uniform array of CollideShape).
//
// Collider motion: each collider is given at the start and at the end of the substep (the host's
// previous -> new transform interpolated across the step's substeps, core/colliders.cpp). The test
// runs in the collider's local frame: p0 = particle at the substep start relative to the collider
// at the substep start, p1 = committed particle relative to the collider at the substep end. The
// segment p0 -> p1 is the relative motion; if it enters the (margin-inflated) shape, the entry
// point's normal decides which side the particle goes back to, so a collider that moves more than
// its own size in a substep still pushes the cloth instead of jumping through it.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "drape/drape.h"
#include "shaders/layout.h"

namespace drape::kernels {

/// One collider during one substep: the collider record of shaders/layout.h (DRAPE_COLLIDER_VEC4
/// vec4s; the GLES backend uploads shape as a float).
struct CollideShape {
    glm::vec3 pos0; float margin;     ///< centre at the substep start (m); margin (m, >= 0)
    glm::vec3 pos1; float friction;   ///< centre at the substep end (m); Coulomb coefficient (>= 0)
    glm::quat rot0;                   ///< orientation at the substep start (unit)
    glm::quat rot1;                   ///< orientation at the substep end (unit)
    glm::vec3 size; uint32_t shape;   ///< drape_collider_shape and its sizes (see drape_collider)
};
static_assert(sizeof(CollideShape) == DRAPE_COLLIDER_VEC4 * sizeof(glm::vec4), "collider record of shaders/layout.h");

/// Signed distance (m) of local point p from the shape's surface (negative inside) and the
/// outward unit normal at the closest surface point. Exact distance for all four shapes, so it
/// can be sphere-traced.
inline float shape_distance(uint32_t shape, const glm::vec3& size, const glm::vec3& p, glm::vec3* n) {
    switch (shape) {
    case DRAPE_COLLIDER_SPHERE: {
        const float len = glm::length(p);
        *n = len > 0 ? p / len : glm::vec3(0, 1, 0);
        return len - size.x;
    }
    case DRAPE_COLLIDER_CAPSULE: {  // segment along local y from -size.y to +size.y, radius size.x
        const glm::vec3 q(p.x, p.y - std::fmax(-size.y, std::fmin(size.y, p.y)), p.z);
        const float len = glm::length(q);
        *n = len > 0 ? q / len : glm::vec3(1, 0, 0);
        return len - size.x;
    }
    case DRAPE_COLLIDER_BOX: {  // half extents size
        const glm::vec3 q = glm::abs(p) - size;
        const glm::vec3 s(p.x < 0 ? -1.0f : 1.0f, p.y < 0 ? -1.0f : 1.0f, p.z < 0 ? -1.0f : 1.0f);
        if (q.x > 0 || q.y > 0 || q.z > 0) {
            const glm::vec3 o = glm::max(q, glm::vec3(0.0f));
            const float len = glm::length(o);
            *n = s * o / len;
            return len;
        }
        // Inside: the nearest face.
        if (q.x >= q.y && q.x >= q.z) {
            *n = glm::vec3(s.x, 0, 0);
            return q.x;
        }
        if (q.y >= q.z) {
            *n = glm::vec3(0, s.y, 0);
            return q.y;
        }
        *n = glm::vec3(0, 0, s.z);
        return q.z;
    }
    default: {  // DRAPE_COLLIDER_PLANE: local +y is the free side
        *n = glm::vec3(0, 1, 0);
        return p.y;
    }
    }
}

/// Moves particles [begin, end) of x out of every collider (surface + margin) and applies
/// friction to their tangential motion relative to the collider over the substep.
/// Friction (position-based Coulomb, Macklin et al. 2014 "Unified particle physics", eq. 24):
/// with the contact push depth d and relative tangential displacement t over the substep, static
/// friction (|t| <= mu d) removes t, kinetic friction shortens it by mu d.
/// The substep start is x - d (d: displacement over the substep, kernels.h); a push moves x and
/// d together, so the velocity after the substep includes it.
inline void collide(const CollideShape* shapes, uint32_t shape_count, glm::vec4* x, glm::vec4* d,
                    uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const float w = x[i].w;
        if (w == 0.0f) continue;  // kinematic: goes where its pin says
        const glm::vec3 x_in(x[i]);
        glm::vec3 xi = x_in;
        const glm::vec3 si = x_in - glm::vec3(d[i]);
        for (uint32_t k = 0; k < shape_count; ++k) {
            const CollideShape& c = shapes[k];
            const glm::vec3 p1 = glm::conjugate(c.rot1) * (xi - c.pos1);
            glm::vec3 n1;
            const float d1 = shape_distance(c.shape, c.size, p1, &n1) - c.margin;
            const glm::vec3 p0 = glm::conjugate(c.rot0) * (si - c.pos0);
            const glm::vec3 seg = p1 - p0;
            const float len = glm::length(seg);
            if (d1 >= 0 && len <= d1) continue;  // cannot have touched the shape this substep
            glm::vec3 n0;
            const float d0 = shape_distance(c.shape, c.size, p0, &n0) - c.margin;
            glm::vec3 q = p1;    // resolved local position
            glm::vec3 n = n1;    // contact normal
            bool contact = false;
            bool entered = false;  // the motion entered the shape at h with normal n
            glm::vec3 h;
            if (d0 > 0) {
                if (len > d0) {
                    // Started outside and could have reached the surface: sphere-trace p0 -> p1.
                    float t = 0.0f, d = d0;
                    const glm::vec3 dir = seg / len;
                    glm::vec3 nh = n0;
                    for (int it = 0; it < DRAPE_SWEEP_ITERATIONS && d > 1e-6f && t < len; ++it) {
                        t += d;
                        if (t >= len) break;
                        d = shape_distance(c.shape, c.size, p0 + dir * t, &nh) - c.margin;
                    }
                    if (t < len) {
                        entered = true;
                        h = p0 + dir * t;
                        n = nh;
                    }
                }
            } else {
                // Started in contact (or inside): its side is the one of the nearest surface point;
                // a motion that crosses that tangent plane inwards is a contact even if it ends
                // outside on the far side (it went through).
                h = p0 - d0 * n0;
                entered = glm::dot(p1 - h, n0) < 0;
                if (entered) n = n0;
            }
            if (entered) {  // back onto the tangent plane at the entry point
                q = p1 + std::fmax(0.0f, -glm::dot(p1 - h, n)) * n;
                glm::vec3 nq;
                const float dq = shape_distance(c.shape, c.size, q, &nq) - c.margin;
                if (dq < 0) q = glm::dot(nq, n) > 0 ? q - dq * nq : h;  // curved surface: onto it
                contact = true;
            } else if (d1 < 0) {  // inside, no crossing found: out along the nearest normal
                q = p1 - d1 * n1;
                contact = true;
            }
            if (!contact) continue;
            if (c.friction > 0) {
                const float depth = glm::length(q - p1);
                const glm::vec3 rel = q - p0;
                const glm::vec3 tangential = rel - glm::dot(rel, n) * n;
                const float tl = glm::length(tangential);
                const float limit = c.friction * depth;
                if (tl <= limit) q -= tangential;
                else q -= tangential * (limit / tl);
            }
            xi = c.rot1 * q + c.pos1;
        }
        if (xi == x_in) continue;
        x[i] = glm::vec4(xi, w);
        d[i] += glm::vec4(xi - x_in, 0.0f);
    }
}

}  // namespace drape::kernels
