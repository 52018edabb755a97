#version 300 es
// Self-collision hash, one layer (see self_hash.vert.glsl). DRAPE_PEEL: a layer after the first
// keeps only particles below the previous layer's particle in this bucket (u_prev).
precision highp float;
precision highp int;
#ifdef DRAPE_PEEL
uniform highp usampler2D u_prev;
#endif
flat in highp uint v_particle;
layout(location = 0) out highp uint o_particle;
void main() {
#ifdef DRAPE_PEEL
    if (v_particle + 1u >= texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0).r) discard;  // empty (0) keeps all out
#endif
    o_particle = v_particle + 1u;
}
