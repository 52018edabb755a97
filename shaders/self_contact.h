// One self-collision contact between particles i and j, and the spatial hash's bucket of a cell:
// the maths of the CPU self-collide stage (backend/cpu/self_collide.h) and of the GLES self-collide
// pass (self_collide.vert.glsl, self_hash.vert.glsl), written once in the common subset of glm and
// GLSL (as collide_shape.h: C++ includes it through backend/cpu/glsl.h).
//
// Particles have radius thickness/2 (Mueller et al., "Position based dynamics", 2007, sec. 4.4):
//   C(x_i, x_j) = n . (x_i - x_j) - thickness >= 0,   dx_i = +w_i/(w_i+w_j) * max(0, -C) * n,
// with n the unit direction from j to i at the end of the substep or, when the pair passed through
// each other during the substep (n0 . (x_i - x_j) < 0 for n0 the direction at the substep start,
// and the relative path came closer than thickness), n0: the pair goes back to the side it
// started on instead of completing the pass-through.
#ifndef DRAPE_SHADERS_SELF_CONTACT_H
#define DRAPE_SHADERS_SELF_CONTACT_H

#ifdef GL_ES
#define DRAPE_OUT(T) out T
#define DRAPE_INLINE
#endif

// Bucket of integer cell c in a table of mask+1 (a power of two) buckets (Teschner et al.,
// "Optimized spatial hashing for collision detection of deformable objects", VMV 2003, primes).
DRAPE_INLINE uint self_bucket(ivec3 c, uint mask) {
    return ((uint(c.x) * 92837111u) ^ (uint(c.y) * 689287499u) ^ (uint(c.z) * 283923481u)) & mask;
}

#ifdef GL_ES
// Integer cell of a point for cells of size 1/inv_cell, clamped so that a cell and its neighbours fit
// an int (the CPU's kernels::self_cell also sends NaN to one cell).
ivec3 self_cell(vec3 p, float inv_cell) { return ivec3(clamp(floor(p * inv_cell), vec3(-1e9), vec3(1e9))); }
#endif

// Particle i's correction dxi from its contact with j, or false when they are not in contact.
// xij = x_i - x_j and dij = d_i - d_j at the end of the substep (d: displacement over the substep,
// so the substep start is x - d); share = w_i / (w_i + w_j); coincident: +1 when i < j, else -1
// (coincident particles without any direction separate along +-y, opposite for the two ends).
// Friction: position-based Coulomb on the pair's relative tangential motion over the substep
// (as collide_shape.h; Macklin et al. 2014 eq. 24).
DRAPE_INLINE bool self_contact(vec3 xij, vec3 dij, float thickness, float share, float friction, float coincident,
                               DRAPE_OUT(vec3) dxi) {
    float t = thickness;
    float dist2 = dot(xij, xij);
    // Relative motion over the substep: s_ij -> x_ij.
    vec3 sij = xij - dij;
    float slen = sqrt(dot(sij, sij));
    vec3 n = vec3(0.0f);
    bool contact = false;
    if (slen > 0.0f) {
        vec3 n0 = sij * (1.0f / slen);
        if (dot(xij, n0) < 0.0f) {
            // Crossed the start plane: a pass-through if the relative path came closer than thickness.
            float dd = dot(dij, dij);
            float u = dd > 0.0f ? min(1.0f, max(0.0f, -dot(sij, dij) / dd)) : 0.0f;
            vec3 closest = sij + u * dij;
            if (dot(closest, closest) < t * t) {
                n = n0;
                contact = true;
            }
        }
    }
    if (!contact && dist2 < t * t) {
        float len = sqrt(dist2);
        n = len > 0.0f ? xij * (1.0f / len) : slen > 0.0f ? sij * (1.0f / slen) : vec3(0.0f, coincident, 0.0f);
        contact = true;
    }
    if (!contact) return false;
    float depth = t - dot(xij, n);  // > 0
    dxi = (share * depth) * n;
    if (friction > 0.0f) {
        vec3 rel = dij + depth * n;
        vec3 tng = rel - dot(rel, n) * n;
        float tl = sqrt(dot(tng, tng));
        float limit = friction * depth;
        if (tl > 0.0f) dxi -= share * (tl <= limit ? tng : tng * (limit / tl));
    }
    return true;
}

#endif
