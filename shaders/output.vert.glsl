#version 300 es
// Drape GLES output pass: one vertex per caller vertex, captured by transform feedback straight
// into the caller's vertex buffer (Unity: Mesh.GetNativeVertexBufferPtr) in the caller's layout.
// Mirrors Cloth::read: positions of the simulated particle in the caller's space (the state is
// relative to the cloth's origin, u_origin), area-weighted vertex normals
// (sum of unnormalised face normals cross(p1 - p0, p2 - p0) in triangle order, normalised;
// (0,1,0) where the sum is zero).
//
// Variants by #define:
//   DRAPE_WRITE_POSITION   capture v_position
//   DRAPE_WRITE_NORMAL     capture v_normal (no normal code otherwise)
//   DRAPE_KEEP_DECLS       generated `in uvecN a_keepK; flat out uvecN v_keepK;` for the bytes of
//   DRAPE_KEEP_COPY        the record this pass does not own (copied bit for bit from a scratch copy)
//   DRAPE_TRI_SLOTS        incident-triangle table row length
#ifndef DRAPE_TRI_SLOTS
#define DRAPE_TRI_SLOTS 6
#endif
#if !defined(DRAPE_WRITE_POSITION) && !defined(DRAPE_WRITE_NORMAL)
#define DRAPE_WRITE_POSITION 1
#define DRAPE_WRITE_NORMAL 1
#endif
#include "layout.h"  // DRAPE_TEX_WIDTH

precision highp float;
precision highp int;

uniform highp sampler2D u_x;      // position records (one vec4 each) after the last substep
uniform highp usampler2D u_tris;  // texel i*DRAPE_TRI_SLOTS+t = incident triangle (p0, p1, p2, 0)
uniform highp usampler2D u_info;  // per particle (neighbours, active springs, triangles, 0)
// GENERATED BEGIN DrapeSim (tools/abi/generate.py from tools/abi/abi.py: do not edit)
// C++ twin: drape::gles::SimUniforms (sim_uniforms.h); std140, binding point 0.
layout(std140) uniform DrapeSim {
    float u_damping;            // N*s/m, drape_params.damping (eq. 2; PBD: dashpot)
    float u_air_drag;           // 1/s, drape_params.air_drag
    float u_h;                  // s, substep length
    float u_jacobi_coupling;    // kJacobiCoupling (core/params.h)
    vec3 u_stiffness;           // drape_params.stiffness per drape_group (0: group off)
    vec3 u_compliance;          // XPBD: 1 / (k h^2) per group, 0 where off
    vec3 u_damping_ratio;       // XPBD: damping / (k h) per group, 0 where off
    vec3 u_gravity;             // m/s^2, drape_params.gravity
    vec3 u_wind;                // m/s, drape_params.wind
    vec3 u_origin;              // m, Cloth::origin (whole metres: exact in float); the output pass adds it
};
// GENERATED END DrapeSim

in uint a_particle;               // caller vertex -> simulated particle (welding)
#ifdef DRAPE_WRITE_POSITION
out vec3 v_position;
#endif
#ifdef DRAPE_WRITE_NORMAL
out vec3 v_normal;
#endif
#ifdef DRAPE_KEEP_DECLS
DRAPE_KEEP_DECLS
#endif

ivec2 texel(int t) { return ivec2(t % DRAPE_TEX_WIDTH, t / DRAPE_TEX_WIDTH); }
vec3 position(int p) { return texelFetch(u_x, texel(p), 0).xyz; }

void main() {
    int i = int(a_particle);
#ifdef DRAPE_WRITE_POSITION
    v_position = position(i) + u_origin;  // one rounding, as Cloth::read_cpu_copy's double sum
#endif
#ifdef DRAPE_WRITE_NORMAL
    int tris = int(texelFetch(u_info, texel(i), 0).z);
    vec3 sum = vec3(0.0);
    for (int t = 0; t < tris; ++t) {
        uvec4 tri = texelFetch(u_tris, texel(i * DRAPE_TRI_SLOTS + t), 0);
        vec3 p0 = position(int(tri.x));
        vec3 p1 = position(int(tri.y));
        vec3 p2 = position(int(tri.z));
        sum += cross(p1 - p0, p2 - p0);
    }
    float len = length(sum);
    v_normal = len > 0.0 ? sum / len : vec3(0.0, 1.0, 0.0);
#endif
#ifdef DRAPE_KEEP_COPY
    DRAPE_KEEP_COPY
#endif
    gl_Position = vec4(0.0);
}
