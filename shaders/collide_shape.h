// One particle against one collider, in the collider's local frame: the collision maths of the CPU
// backend (backend/cpu/collide.h) and of the GLES interaction pass (sim.vert.glsl), written once in
// the common subset of glm and GLSL. C++ includes it with glm's types and functions under GLSL's names
// and DRAPE_OUT(T) = T& (backend/cpu/glsl.h); embed_shaders.cmake splices it into the shader, where DRAPE_OUT(T) = out T.
//
// Collider motion: each collider is given at the start and at the end of the substep. The test runs
// in its local frame: p0 = particle at the substep start relative to the collider at the substep
// start, p1 = committed particle relative to the collider at the substep end. The segment p0 -> p1
// is the relative motion; if it enters the (margin-inflated) shape, the entry point's normal decides
// which side the particle goes back to, so a collider that moves more than its own size in a substep
// still pushes the cloth instead of jumping through it.
#ifndef DRAPE_SHADERS_COLLIDE_SHAPE_H
#define DRAPE_SHADERS_COLLIDE_SHAPE_H

#include "layout.h"
#include "substep.h"  // quat_rotate, quat_conjugate

#ifdef GL_ES
#define DRAPE_OUT(T) out T
#define DRAPE_INLINE
#endif

// Signed distance (m) of local point p from the shape's surface (negative inside) and the outward
// unit normal n at the closest surface point. Exact distance for all four shapes (drape_collider_shape,
// sizes as in drape_collider), so it can be sphere-traced.
DRAPE_INLINE float shape_distance(int shape, vec3 size, vec3 p, DRAPE_OUT(vec3) n) {
    if (shape == DRAPE_COLLIDER_SPHERE) {
        float len = sqrt(dot(p, p));
        n = len > 0.0f ? p / len : vec3(0.0f, 1.0f, 0.0f);
        return len - size.x;
    }
    if (shape == DRAPE_COLLIDER_CAPSULE) {  // segment along local y from -size.y to +size.y, radius size.x
        vec3 q = vec3(p.x, p.y - max(-size.y, min(size.y, p.y)), p.z);
        float len = sqrt(dot(q, q));
        n = len > 0.0f ? q / len : vec3(1.0f, 0.0f, 0.0f);
        return len - size.x;
    }
    if (shape == DRAPE_COLLIDER_BOX) {  // half extents size
        vec3 q = abs(p) - size;
        vec3 s = vec3(p.x < 0.0f ? -1.0f : 1.0f, p.y < 0.0f ? -1.0f : 1.0f, p.z < 0.0f ? -1.0f : 1.0f);
        if (q.x > 0.0f || q.y > 0.0f || q.z > 0.0f) {
            vec3 o = max(q, vec3(0.0f));
            float len = sqrt(dot(o, o));
            n = s * o / len;
            return len;
        }
        // Inside: the nearest face.
        if (q.x >= q.y && q.x >= q.z) {
            n = vec3(s.x, 0.0f, 0.0f);
            return q.x;
        }
        if (q.y >= q.z) {
            n = vec3(0.0f, s.y, 0.0f);
            return q.y;
        }
        n = vec3(0.0f, 0.0f, s.z);
        return q.z;
    }
    n = vec3(0.0f, 1.0f, 0.0f);  // DRAPE_COLLIDER_PLANE: local +y is the free side
    return p.y;
}

// Moves local point p1 out of the shape (surface + margin) and applies friction to its tangential
// motion p0 -> p1. Returns false, leaving q = p1, when the motion does not touch the shape; else true
// with q the resolved local position.
// Friction (position-based Coulomb, Macklin et al. 2014 "Unified particle physics", eq. 24): with the
// contact push depth d and the relative tangential displacement t over the substep, static friction
// (|t| <= mu d) removes t, kinetic friction shortens it by mu d.
DRAPE_INLINE bool collide_local(int shape, vec3 size, float margin, float friction, vec3 p0, vec3 p1,
                                DRAPE_OUT(vec3) q) {
    q = p1;
    vec3 n1;
    float d1 = shape_distance(shape, size, p1, n1) - margin;
    vec3 seg = p1 - p0;
    float len = sqrt(dot(seg, seg));
    if (d1 >= 0.0f && len <= d1) return false;  // cannot have touched the shape this substep
    vec3 n0;
    float d0 = shape_distance(shape, size, p0, n0) - margin;
    vec3 n = n1;  // contact normal
    bool entered = false;  // the motion entered the shape at h with normal n
    vec3 h = vec3(0.0f);
    if (d0 > 0.0f) {
        if (len > d0) {
            // Started outside and could have reached the surface: sphere-trace p0 -> p1.
            float t = 0.0f;
            float d = d0;
            vec3 dir = seg / len;
            vec3 nh = n0;
            for (int it = 0; it < DRAPE_SWEEP_ITERATIONS && d > 1e-6f && t < len; ++it) {
                t += d;
                if (t >= len) break;
                d = shape_distance(shape, size, p0 + dir * t, nh) - margin;
            }
            if (t < len) {
                entered = true;
                h = p0 + dir * t;
                n = nh;
            }
        }
    } else {
        // Started in contact (or inside): its side is the one of the nearest surface point; a motion
        // that crosses that tangent plane inwards is a contact even if it ends outside on the far
        // side (it went through).
        h = p0 - d0 * n0;
        entered = dot(p1 - h, n0) < 0.0f;
        if (entered) n = n0;
    }
    if (entered) {  // back onto the tangent plane at the entry point
        q = p1 + max(0.0f, -dot(p1 - h, n)) * n;
        vec3 nq;
        float dq = shape_distance(shape, size, q, nq) - margin;
        if (dq < 0.0f) q = dot(nq, n) > 0.0f ? q - dq * nq : h;  // curved surface: onto it
    } else if (d1 < 0.0f) {  // inside, no crossing found: out along the nearest normal
        q = p1 - d1 * n1;
    } else {
        return false;
    }
    if (friction > 0.0f) {
        vec3 pen = q - p1;
        float depth = sqrt(dot(pen, pen));
        vec3 rel = q - p0;
        vec3 tangential = rel - dot(rel, n) * n;
        float tl = sqrt(dot(tangential, tangential));
        float limit = friction * depth;
        if (tl <= limit) q -= tangential;
        else q -= tangential * (limit / tl);
    }
    return true;
}

// One particle against one moving collider, which goes from (pos0, rot0) at the substep start to
// (pos1, rot1) at its end (rotations as quaternions (x, y, z, w)): s is the particle at the substep
// start, x where the solve put it. collide_local in the collider's frame (s in the start frame, x in the
// end frame); false when the motion does not touch the shape, else true with the resolved point q in the
// end frame (quat_rotate(rot1, q) + pos1 in the world).
DRAPE_INLINE bool collide_moving(int shape, vec3 size, float margin, float friction, vec3 pos0, vec4 rot0, vec3 pos1,
                                 vec4 rot1, vec3 s, vec3 x, DRAPE_OUT(vec3) q) {
    vec3 p0 = quat_rotate(quat_conjugate(rot0), s - pos0);
    vec3 p1 = quat_rotate(quat_conjugate(rot1), x - pos1);
    return collide_local(shape, size, margin, friction, p0, p1, q);
}

#endif
