#version 300 es
// Self-collision on GLES, second half: one transform-feedback pass over the particles, the CPU's
// kernels::self_collide_gather + self_collide_apply (backend/cpu/self_collide.h). Particle i reads
// the buckets of the 27 cells around its own (each bucket once) in the hash that self_hash.vert.glsl
// built this substep, DRAPE_SELF_LAYERS particles per bucket, and corrects itself by the mean of its
// pair corrections (self_contact.h) with the particles it may collide with: not itself, not
// closer than u_exclude_rest2 in the rest mesh, not sharing a spring. Writes x + corr and d + corr
// (two outputs, separate buffers: v_x, v_d), so the velocity includes the push.
//
// Reach: pairs closer than one cell (>= thickness) at the end of the substep, all of which lie in the
// 27 cells; a pair that passed through each other is caught while its end distance stays within it.
//
// Bucket capacity: a bucket with more than DRAPE_SELF_LAYERS particles keeps the largest indices
// (the others are not found by particles near them; they still find those kept, and push
// themselves, so a pair is lost only when both are dropped).
#ifndef DRAPE_SLOTS
#define DRAPE_SLOTS 12
#endif
#ifndef DRAPE_SELF_LAYERS
#define DRAPE_SELF_LAYERS 8
#endif
#if DRAPE_SELF_LAYERS < 1 || DRAPE_SELF_LAYERS > 8
#error "DRAPE_SELF_LAYERS: 1 to 8"
#endif
precision highp float;
precision highp int;

#include "layout.h"  // DRAPE_TEX_WIDTH: the particle textures and the hash table
#include "self_contact.h"

uniform highp sampler2D u_x;     // positions at the end of the substep (state records)
uniform highp sampler2D u_aux;   // displacements over the substep (state records)
uniform highp usampler2D u_nbr;  // neighbour table: texel i*DRAPE_SLOTS+s = (index, rest bits, group, 0)
uniform highp usampler2D u_info; // per particle (neighbour count, ...)
uniform highp usampler2D u_rest; // rest positions (float bits), texel i
uniform highp usampler2D u_layer0;  // hash layers: particle + 1, 0 = empty
#if DRAPE_SELF_LAYERS > 1
uniform highp usampler2D u_layer1;
#endif
#if DRAPE_SELF_LAYERS > 2
uniform highp usampler2D u_layer2;
#endif
#if DRAPE_SELF_LAYERS > 3
uniform highp usampler2D u_layer3;
#endif
#if DRAPE_SELF_LAYERS > 4
uniform highp usampler2D u_layer4;
#endif
#if DRAPE_SELF_LAYERS > 5
uniform highp usampler2D u_layer5;
#endif
#if DRAPE_SELF_LAYERS > 6
uniform highp usampler2D u_layer6;
#endif
#if DRAPE_SELF_LAYERS > 7
uniform highp usampler2D u_layer7;
#endif
uniform float u_inv_cell;        // 1 / cell size (1/m)
uniform int u_mask;              // buckets - 1
uniform vec4 u_contact;          // thickness (m), exclude_rest2 (m^2), friction, reach^2 (m^2: a cell)

in vec4 a_x;                     // own position record
in vec4 a_aux;                   // own displacement record
out vec4 v_x;
out vec4 v_d;

ivec2 texel(int t) { return ivec2(t % DRAPE_TEX_WIDTH, t / DRAPE_TEX_WIDTH); }

vec3 rest(int j) { return uintBitsToFloat(texelFetch(u_rest, texel(j), 0).xyz); }

// Pairs that never collide (kernels::self_candidates): neighbours at rest, or sharing a spring.
bool close_at_rest(int j, vec3 rest_i) {
    vec3 rij = rest_i - rest(j);
    return dot(rij, rij) < u_contact.y;
}
bool share_a_spring(int i, int j) {
    int count = int(texelFetch(u_info, texel(i), 0).x);
    for (int s = 0; s < count; ++s)
        if (int(texelFetch(u_nbr, texel(i * DRAPE_SLOTS + s), 0).x) == j) return true;
    return false;
}

// Particle i's contact with the particle a hash layer holds (stored = index + 1) if it lies in `cell`,
// within reach and may collide with i (cheapest tests first).
void visit(uint stored, ivec3 cell, int i, vec3 xi, vec3 di, float wi, vec3 rest_i, inout vec3 sum, inout int contacts) {
    int j = int(stored) - 1;
    vec4 xj = texelFetch(u_x, texel(j), 0);
    vec3 xij = xi - xj.xyz;
    // Self; or farther than reach (one cell: every pair closer is found, whatever the hash); or a
    // particle of another cell in this bucket (each is met once, in its own cell: the same bits and
    // function as the hash pass put it there with).
    if (j == i || !(dot(xij, xij) < u_contact.w) || self_cell(xj.xyz, u_inv_cell) != cell) return;
    if (close_at_rest(j, rest_i)) return;
    vec3 dxi;
    if (!self_contact(xij, di - texelFetch(u_aux, texel(j), 0).xyz, u_contact.x, wi / (wi + xj.w), u_contact.z,
                      i < j ? 1.0 : -1.0, dxi))
        return;
    if (share_a_spring(i, j)) return;
    sum += dxi;
    ++contacts;
}

void main() {
    int i = gl_VertexID;
    vec3 xi = a_x.xyz, di = a_aux.xyz;
    float wi = a_x.w;
    vec3 sum = vec3(0.0);
    int contacts = 0;
    if (wi != 0.0) {
        vec3 rest_i = rest(i);
        uint mask = uint(u_mask);
        ivec3 ci = self_cell(xi, u_inv_cell);
        for (int c = 0; c < 27; ++c) {
            ivec3 cell = ci + ivec3(c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1);
            uint b = self_bucket(cell, mask);
            ivec2 t = ivec2(int(b % uint(DRAPE_TEX_WIDTH)), int(b / uint(DRAPE_TEX_WIDTH)));
            // Layers fill in order: the first empty one ends the bucket (samplers are indexed by
            // constants only in GLSL ES 3.00, hence one line per layer).
            uint stored = texelFetch(u_layer0, t, 0).r;
            if (stored == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#if DRAPE_SELF_LAYERS > 1
            if ((stored = texelFetch(u_layer1, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 2
            if ((stored = texelFetch(u_layer2, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 3
            if ((stored = texelFetch(u_layer3, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 4
            if ((stored = texelFetch(u_layer4, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 5
            if ((stored = texelFetch(u_layer5, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 6
            if ((stored = texelFetch(u_layer6, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
#if DRAPE_SELF_LAYERS > 7
            if ((stored = texelFetch(u_layer7, t, 0).r) == 0u) continue;
            visit(stored, cell, i, xi, di, wi, rest_i, sum, contacts);
#endif
        }
    }
    vec3 corr = contacts > 0 ? sum * (1.0 / float(contacts)) : vec3(0.0);
    v_x = a_x + vec4(corr, 0.0);
    v_d = a_aux + vec4(corr, 0.0);
}
