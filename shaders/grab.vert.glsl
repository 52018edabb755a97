#version 300 es
// Drape GLES pick-and-hold grabs (GlesCloth's grab passes, gles_grab.cpp), without readback: the
// vertex a finger picks is found on the GPU, kept there, and held as a moving pin by the state's
// inverse mass (w = 0: every simulation pass then treats it as kinematic) and its pin target.
//
// Variants by #define:
//   DRAPE_PASS_PICK   Cloth::grab's search, drawn as points (rasterizer on) into the grab slot's
//                     texel of the pick target (kMaxGrabs x 1, RGBA32UI colour + float depth):
//                     every free particle (w != 0) in front of the eye and within the pick radius
//                     on screen lands on the texel at depth r^2 / radius^2; the depth test (LEQUAL,
//                     particles in index order) keeps the nearest, the last of equals, as the CPU's
//                     search does. Colour (pick.frag.glsl): (particle, NDC depth bits, pick serial, 0)
//   DRAPE_PASS_GRAB   transform feedback over the particles: v_x = a_x with w = 0 for a particle
//                     a slot holds, w restored (u_info.w) for one a slot releases; v_target = its
//                     pin target (the slot's finger unprojected at the pick's NDC depth, or where
//                     it is while not moved), a_ktarget for every other particle. The simulation
//                     passes read v_target as their kinematic targets while a grab is held
//   DRAPE_GRABS       slots (kMaxGrabs): texels of the pick target, records of u_grab
#if !defined(DRAPE_PASS_PICK) && !defined(DRAPE_PASS_GRAB)
#define DRAPE_PASS_GRAB 1
#endif
#ifndef DRAPE_GRABS
#define DRAPE_GRABS 16
#endif

precision highp float;
precision highp int;

in vec4 a_x;                        // own position record (xyz + inverse mass), local coordinates

#ifdef DRAPE_PASS_PICK
// This slot's pick, in the cloth's local frame: projection * view * world (with the cloth's
// origin) in columns 0-3; (finger px, radius^2 px^2, the slot's texel centre in NDC x);
// (viewport px, pick serial, 0).
uniform vec4 u_pick[6];
flat out highp uvec4 v_pick;

void main() {
    gl_PointSize = 1.0;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // clipped: not a candidate
    v_pick = uvec4(0u);
    mat4 mvp = mat4(u_pick[0], u_pick[1], u_pick[2], u_pick[3]);
    vec4 finger = u_pick[4], screen = u_pick[5];
    vec4 clip = mvp * vec4(a_x.xyz, 1.0);
    if (a_x.w == 0.0 || !(clip.w > 0.0)) return;  // pinned or held; at or behind the eye
    vec3 ndc = clip.xyz / clip.w;
    if (ndc.z < -1.0 || ndc.z > 1.0) return;
    vec2 d = (ndc.xy * 0.5 + 0.5) * screen.xy - finger.xy;  // drag.cpp to_screen, minus the finger
    float r2 = dot(d, d);
    if (!(r2 <= finger.z)) return;
    gl_Position = vec4(finger.w, 0.0, 2.0 * (r2 / finger.z) - 1.0, 1.0);  // window depth r^2 / radius^2
    v_pick = uvec4(uint(gl_VertexID), floatBitsToUint(ndc.z), uint(screen.z), 0u);
}
#endif

#ifdef DRAPE_PASS_GRAB
uniform highp usampler2D u_pick_target;  // texel (slot, 0): what DRAPE_PASS_PICK wrote
uniform highp usampler2D u_info;    // per particle (.w: inverse mass bits when not grabbed)
// Per slot: A, B with the target at NDC depth z = (A.xyz + z B.xyz) / (A.w + z B.w) (the finger
// unprojected, in local coordinates); (state, pick serial, 0, 0), state 0 none, 1 held where it
// is, 2 held under the finger, 3 released at this step.
uniform vec4 u_grab[3 * DRAPE_GRABS];
in vec3 a_ktarget;                  // pin target as the CPU has it
out vec4 v_x;
out vec3 v_target;

void main() {
    v_x = a_x;
    v_target = a_ktarget;
    for (int s = 0; s < DRAPE_GRABS; ++s) {
        vec4 slot = u_grab[3 * s + 2];
        if (slot.x == 0.0) continue;
        uvec4 pick = texelFetch(u_pick_target, ivec2(s, 0), 0);
        if (float(pick.z) != slot.y || int(pick.x) != gl_VertexID) continue;  // another pick, or none found
        if (slot.x == 3.0) {
            // Cloth::grab_release: the inverse mass it has when not grabbed; its displacement
            // (velocity) is kept
            int width = textureSize(u_info, 0).x;
            v_x.w = uintBitsToFloat(texelFetch(u_info, ivec2(gl_VertexID % width, gl_VertexID / width), 0).w);
            continue;
        }
        v_x.w = 0.0;
        v_target = a_x.xyz;  // Cloth::grab: held where it is
        if (slot.x == 2.0) {  // Cloth::grab_move: under the finger at the depth it was picked at
            float z = uintBitsToFloat(pick.y);
            vec4 a = u_grab[3 * s], b = u_grab[3 * s + 1];
            v_target = (a.xyz + z * b.xyz) / (a.w + z * b.w);
        }
    }
}
#endif
