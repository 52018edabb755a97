#version 300 es
// Self-collision on GLES, first half: the spatial hash (Teschner et al. 2003) of the particles at the
// end of the substep, built by drawing every particle as one point onto the texel of its cell's
// bucket (self_contact.h self_bucket) in a table of DRAPE_TEX_WIDTH x rows texels. The table keeps
// up to DRAPE_SELF_LAYERS particles per bucket, one R32UI texture per layer (particle + 1; 0 =
// empty), by depth peeling without a depth buffer: fragments of one draw land in primitive order,
// so the last, the largest particle index, stays (self_hash.frag.glsl). Layer 0 keeps the largest
// index of each bucket; layer k the largest below layer k-1's. gles_self_collide.cpp runs it.
precision highp float;
precision highp int;

#include "layout.h"  // DRAPE_TEX_WIDTH
#include "self_contact.h"

uniform float u_inv_cell;  // 1 / cell size (1/m)
uniform int u_mask;        // buckets - 1 (buckets: a power of two)
uniform vec2 u_texel_ndc;  // 2 / (table width, rows): one texel in normalised device coordinates

in vec4 a_x;               // own position at the end of the substep (state record)
flat out highp uint v_particle;

void main() {
    uint b = self_bucket(self_cell(a_x.xyz, u_inv_cell), uint(u_mask));
    vec2 t = vec2(float(b % uint(DRAPE_TEX_WIDTH)), float(b / uint(DRAPE_TEX_WIDTH)));
    gl_Position = vec4((t + 0.5) * u_texel_ndc - 1.0, 0.0, 1.0);  // the texel's centre
    gl_PointSize = 1.0;
    v_particle = uint(gl_VertexID);
}
