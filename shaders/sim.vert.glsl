#version 300 es
// Drape GLES 3.0 simulation passes (transform feedback, one vertex = one particle).
// Mirrors plugin-native/src/backend/cpu/kernels.h: the maths per particle and spring is substep.h,
// shared with it; the loops over springs and the record reads are kept in step by hand.
//
// State (as on the CPU, see the top of kernels.h): position x and displacement d over the last
// substep (velocity * h_prev), two buffers of one vec4 record per particle (xyz + w inverse mass).
//
// Variants by #define (inserted after #version by the backend; glslangValidator checks each):
//   DRAPE_PASS_MASS_SPRING   kernels::mass_spring_step (paper eq. 1-3), plus Cloth::step's
//                            placement of kinematic particles. Two outputs (separate transform-
//                            feedback buffers): v_x new positions, v_d new displacements
//   DRAPE_PASS_PREDICT       kernels::predict<DRAPE_DASHPOT> (PBD / XPBD prediction), plus Cloth::
//                            step's kinematic displacement; writes displacement iterate records
//                            v_d (xyz = displacement from the substep start) [+ zeroed lambdas]
//   DRAPE_PASS_CONSTRAINT    kernels::constraint_iteration<DRAPE_XPBD, DRAPE_COMMIT>: v_d
//                            [+ v_lambda*] (interleaved)
//   DRAPE_COMMIT             last iteration: two outputs (separate buffers), v_x positions
//                            start + displacement and v_d displacements (lambdas are not kept:
//                            the next prediction resets them)
//   DRAPE_IMPLICIT           predict for IMPLICIT (kernels::implicit_predict): writes the first
//                            iterate v_d (inertia and drag), v_prev (the same) and the target v_target
//   DRAPE_PASS_IMPLICIT      one iteration of IMPLICIT's solve on GLES: a block-Jacobi step on the
//                            implicit Euler objective (kernels::implicit_residual's Phi; per
//                            particle a 3x3 block like its Hessian's, see jacobi_step),
//                            accelerated by Chebyshev (Wang 2015); iterate records (v_d, v_prev,
//                            v_target). With DRAPE_COMMIT: two outputs, v_x = start +
//                            displacement and v_d
//   DRAPE_PROLONG            with DRAPE_PASS_IMPLICIT: the iteration first adds the coarse correction
//                            of each particle's aggregate (level 1) to its iterate and previous
//                            iterate (own and neighbours' alike)
//   DRAPE_PASS_COARSE        one pass of the coarse correction (gles_coarse.h; one vertex per node of
//                            a level, v_d = (vec3, 0)): DRAPE_COARSE_RESTRICT sums the force residual
//                            of each level-1 node's particles at the iterate; DRAPE_COARSE_DOWN smooths
//                            level l's residual once (Jacobi from 0) and sums what it leaves over each
//                            level-(l+1) node's members; DRAPE_COARSE_SOLVE multiplies the coarsest
//                            residual by the dense inverse; DRAPE_COARSE_UP is level l's smoothed
//                            correction plus its parent's (a V-cycle, one smoothing on the way down)
//   DRAPE_PASS_TETHER        kernels::tether after the solve of a substep (only compiled and run
//                            when the cloth has tethers: max_stretch > 0 and kinematic particles).
//                            Two outputs like MASS_SPRING: v_x, v_d. Own x and d as attributes,
//                            the anchor's position from u_x; anchor index and length per particle
//                            as attributes (uploaded when the tethers change)
//   DRAPE_PASS_INTERACT      Cloth::interaction_substep after the solve (and tethers): touch drag
//                            (DRAPE_DRAG: Cloth::drag_cpu_copy's offset, evaluated here from the
//                            touches and views in uniforms, first substep only) then
//                            kernels::collide against DRAPE_SHAPES colliders
//                            (0: no collision code). Two outputs like MASS_SPRING: v_x, v_d
//   DRAPE_PASS_MOVE          RigidMove (core/interaction.h) of the whole state: owner transform
//                            (Cloth::move_state) and re-centring (Cloth::shift_origin: identity
//                            rotation, to = -shift). Two outputs like MASS_SPRING: v_x, v_d
//   DRAPE_PASS_STILL         the sleep check (Cloth::interaction_end_step) drawn, not fed back:
//                            particles whose last substep displacement exceeds the threshold
//                            land on the 1x1 target, the others are clipped; an occlusion query
//                            counts them (no output, rasterizer on)
//   DRAPE_DRAG_VIEWS         capacity of u_drag_views (drape_cloth_drag calls per step)
//   DRAPE_MAX_TOUCHES        capacity of u_touches (touches per step)
//   DRAPE_SHAPES             capacity of u_shapes (colliders, DRAPE_COLLIDER_VEC4 each: layout.h)
//   DRAPE_DASHPOT            predict with PBD's explicit dashpots
//   DRAPE_XPBD               constraint pass is XPBD (lambdas ride in the iterate record), else PBD
//   DRAPE_KINEMATIC          some particles have w = 0: place them on their pin path
//   DRAPE_RECORD             vec4s per displacement-iterate record (predict output, constraint
//                            input/output): 1, or 1 + DRAPE_LAMBDA_VEC4 for XPBD. State records
//                            (x, d) are always one vec4.
//   DRAPE_LAMBDA_VEC4        XPBD: vec4s of lambdas per record (slots rounded up to 4)
//   DRAPE_SLOTS              neighbour-table row length
//
// Data: particle records xyzw (w = inverse mass) come in as attributes (own particle) and as
// texels of highp RGBA32F textures (neighbours; texel j for state records, j*DRAPE_RECORD for
// iterate records). The neighbour table is a RGBA32UI texture, texel i*DRAPE_SLOTS+s = (index,
// floatBitsToUint(rest), group, 0); the particle table texel i = (neighbour count, active springs,
// 0, 0). All textures are DRAPE_TEX_WIDTH texels wide (row-major).
#if !defined(DRAPE_PASS_MASS_SPRING) && !defined(DRAPE_PASS_PREDICT) && !defined(DRAPE_PASS_CONSTRAINT) && \
    !defined(DRAPE_PASS_IMPLICIT) && !defined(DRAPE_PASS_COARSE) && !defined(DRAPE_PASS_TETHER) && !defined(DRAPE_PASS_INTERACT) && !defined(DRAPE_PASS_MOVE) && \
    !defined(DRAPE_PASS_STILL)
#define DRAPE_PASS_MASS_SPRING 1
#endif
#ifndef DRAPE_SLOTS
#define DRAPE_SLOTS 12
#endif
#ifndef DRAPE_LAMBDA_VEC4
#define DRAPE_LAMBDA_VEC4 3
#endif
#ifndef DRAPE_RECORD
#define DRAPE_RECORD 1
#endif
#ifndef DRAPE_DRAG_VIEWS
#define DRAPE_DRAG_VIEWS 4
#endif
#ifndef DRAPE_MAX_TOUCHES
#define DRAPE_MAX_TOUCHES 16
#endif
#ifndef DRAPE_SHAPES
#define DRAPE_SHAPES 0
#endif
#include "layout.h"

precision highp float;
precision highp int;

uniform highp sampler2D u_x;        // MASS_SPRING, PREDICT, TETHER: positions x; CONSTRAINT: displacement iterate
uniform highp sampler2D u_aux;      // MASS_SPRING, PREDICT: displacements d; CONSTRAINT: substep start x
uniform highp usampler2D u_nbr;     // neighbour table
uniform highp usampler2D u_info;    // per particle (count, active)

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
// This substep's numbers (computed on the CPU as Cloth::step does, so the shader sees the same bits):
// x = 1 / h_prev, y = h / h_prev (SubstepContext::h_ratio), z = accel_h, w = kinematic path fraction
// at the end of the substep.
uniform vec4 u_substep;
#ifdef DRAPE_PASS_MOVE
// RigidMove: x -> rot * (x - pivot) + to; d turns with rot (keep_velocity 1) or is zeroed (0).
uniform vec4 u_move_rot;             // quaternion (x, y, z, w)
uniform vec3 u_move_pivot;
uniform vec3 u_move_to;
uniform float u_move_keep_velocity;
#endif
#ifdef DRAPE_PASS_STILL
uniform float u_still_limit2;        // (sleep threshold * h_prev)^2, m^2
#endif
#ifdef DRAPE_PASS_IMPLICIT
// x: Chebyshev weight of this iteration, y: under-relaxation gamma of the Jacobi step
// (gles_cloth.cpp implicit_chebyshev).
uniform vec2 u_chebyshev;
in vec4 a_prev;                     // own previous iterate (displacement)
in vec4 a_target;                   // own target y (kernels::implicit_predict)
#endif
#if defined(DRAPE_PASS_COARSE) || defined(DRAPE_PROLONG)
// Coarse table (RGBA32UI) and vectors (RGBA32F: residuals R_l, corrections e_l), gles_coarse.h.
uniform highp usampler2D u_coarse_table;
uniform highp sampler2D u_coarse_vec;
// Texel offsets of this pass (gles_cloth.cpp run_coarse), whole numbers in float.
uniform vec4 u_coarse;
#endif

in vec4 a_x;                        // own record: position x (MS, PREDICT) / displacement iterate
in vec4 a_aux;                      // own: displacement d (MS, PREDICT, TETHER) or substep start x (CONSTRAINT)
#ifdef DRAPE_DRAG
// Touch drag (paper eq. 9) of the drape_cloth_drag calls since the last step (GlesCloth::drag),
// records as layout.h says, touches in call order; the share is 1 / substeps.
uniform vec4 u_drag_views[DRAPE_DRAG_VIEWS * DRAPE_DRAG_VIEW_VEC4];
uniform vec4 u_touches[DRAPE_MAX_TOUCHES * DRAPE_TOUCH_VEC4];
uniform int u_touch_count;
#endif
#if DRAPE_SHAPES > 0
// kernels::CollideShape per collider (layout.h), interpolated for this substep on the CPU exactly
// as CpuCloth::collide.
uniform vec4 u_shapes[DRAPE_SHAPES * DRAPE_COLLIDER_VEC4];
uniform int u_shape_count;
#endif
#ifdef DRAPE_PASS_TETHER
in uint a_tether_anchor;            // Cloth::tether_anchor_
in float a_tether_length;           // Cloth::tether_length_ (< 0: no tether)
#endif
#ifdef DRAPE_KINEMATIC
in vec3 a_kstart;                   // position at the start of the step
in vec3 a_ktarget;                  // pin target at the end of the step
#endif

#if defined(DRAPE_IMPLICIT) || (defined(DRAPE_PASS_IMPLICIT) && !defined(DRAPE_COMMIT))
out vec4 v_prev;                    // the iterate this pass started from
out vec4 v_target;                  // target y, passed on
#endif
#if defined(DRAPE_PASS_MASS_SPRING) || defined(DRAPE_COMMIT) || defined(DRAPE_PASS_TETHER) || \
    defined(DRAPE_PASS_INTERACT) || defined(DRAPE_PASS_MOVE)
out vec4 v_x;                       // new position record
#endif
out vec4 v_d;                       // new displacement (state or iterate) record
#if defined(DRAPE_XPBD) && (defined(DRAPE_PASS_PREDICT) || (defined(DRAPE_PASS_CONSTRAINT) && !defined(DRAPE_COMMIT)))
#if DRAPE_LAMBDA_VEC4 >= 1
out vec4 v_lambda0;
#endif
#if DRAPE_LAMBDA_VEC4 >= 2
out vec4 v_lambda1;
#endif
#if DRAPE_LAMBDA_VEC4 >= 3
out vec4 v_lambda2;
#endif
#if DRAPE_LAMBDA_VEC4 >= 4
out vec4 v_lambda3;
#endif
#if DRAPE_LAMBDA_VEC4 >= 5
out vec4 v_lambda4;
#endif
#if DRAPE_LAMBDA_VEC4 >= 6
out vec4 v_lambda5;
#endif
#if DRAPE_LAMBDA_VEC4 >= 7
out vec4 v_lambda6;
#endif
#if DRAPE_LAMBDA_VEC4 >= 8
out vec4 v_lambda7;
#endif
#if DRAPE_LAMBDA_VEC4 > DRAPE_MAX_LAMBDA_VEC4  // the v_lambda* above and a_lambda* below
#error "more than 32 neighbour slots is not supported by the GLES backend"
#endif
#endif

#if defined(DRAPE_XPBD) && defined(DRAPE_PASS_CONSTRAINT)
#if DRAPE_LAMBDA_VEC4 >= 1
in vec4 a_lambda0;
#endif
#if DRAPE_LAMBDA_VEC4 >= 2
in vec4 a_lambda1;
#endif
#if DRAPE_LAMBDA_VEC4 >= 3
in vec4 a_lambda2;
#endif
#if DRAPE_LAMBDA_VEC4 >= 4
in vec4 a_lambda3;
#endif
#if DRAPE_LAMBDA_VEC4 >= 5
in vec4 a_lambda4;
#endif
#if DRAPE_LAMBDA_VEC4 >= 6
in vec4 a_lambda5;
#endif
#if DRAPE_LAMBDA_VEC4 >= 7
in vec4 a_lambda6;
#endif
#if DRAPE_LAMBDA_VEC4 >= 8
in vec4 a_lambda7;
#endif
#endif

ivec2 texel(int t) { return ivec2(t % DRAPE_TEX_WIDTH, t / DRAPE_TEX_WIDTH); }
#if defined(DRAPE_PASS_CONSTRAINT) || defined(DRAPE_PASS_IMPLICIT) || defined(DRAPE_COARSE_RESTRICT)
vec4 fetch_x(int j) { return texelFetch(u_x, texel(j * DRAPE_RECORD), 0); }  // iterate record
#else
vec4 fetch_x(int j) { return texelFetch(u_x, texel(j), 0); }                 // state record
#endif
vec4 fetch_aux(int j) { return texelFetch(u_aux, texel(j), 0); }             // state record
uvec4 fetch_nbr(int slot) { return texelFetch(u_nbr, texel(slot), 0); }
uvec4 fetch_info(int i) { return texelFetch(u_info, texel(i), 0); }

// kernels::active_slot: a group is on where its stiffness is
bool active_group(uint g) { return g < uint(DRAPE_GROUP_COUNT) && u_stiffness[g] > 0.0; }

#include "substep.h"  // direction, spring_force, xpbd_delta, ...: the CPU kernels' maths

#ifdef DRAPE_PASS_CONSTRAINT
// The particle a constraint pass solves for: displacement iterate d, substep start s, inverse
// mass w, active springs c, first neighbour-table slot and used slots (0 when kinematic).
struct Own {
    vec3 d;
    vec3 s;
    float w;
    uint c;
    int row;
    int count;
};

// One slot of kernels::constraint_iteration: adds the slot's correction to dx and returns its
// lambda after the update (XPBD; PBD passes and ignores 0). Slots past the particle's count and
// inactive groups change nothing.
float solve_slot(Own o, int s, float lambda, inout vec3 dx) {
    if (s >= o.count) return lambda;
    uvec4 nb = fetch_nbr(o.row + s);
    uint g = nb.z;
    if (!active_group(g)) return lambda;
    int j = int(nb.x);
    vec4 rj = fetch_x(j);
    float wj = rj.w;
    vec3 dij = o.d - rj.xyz;
    float len;
    vec3 n = direction((o.s - fetch_aux(j).xyz) + dij, len);
    float constraint = len - uintBitsToFloat(nb.y);
    // The CPU's factor (kernels::spring_coefficients), here per slot and iteration.
#ifdef DRAPE_XPBD
    float coef =
        xpbd_coefficient(o.w, wj, o.c, fetch_info(j).y, u_compliance[g], u_damping_ratio[g], u_jacobi_coupling);
    float dl = xpbd_delta(constraint, u_compliance[g], lambda, u_damping_ratio[g], n, dij, coef);
#else
    float dl = -constraint * pbd_coefficient(o.w, wj, o.c, fetch_info(j).y, u_stiffness[g], u_jacobi_coupling);
#endif
    dx += (o.w * dl) * n;
    return lambda + dl;
}

#ifdef DRAPE_XPBD
// Slots 4q .. 4q+3 in order, their lambdas in one vec4. Lambdas live in vec4 attributes and
// varyings with constant component names, never in a local array indexed by the slot: softpipe
// (and mobile compilers of the same kind) read such an array wrongly (XPBD drifted 1e-4 m from
// the CPU in two steps of a 16x16 sheet), and vertex-stage local arrays are a weak spot of
// mobile GLES compilers.
vec4 solve_slots4(Own o, int q, vec4 lambda, inout vec3 dx) {
    lambda.x = solve_slot(o, 4 * q, lambda.x, dx);
    lambda.y = solve_slot(o, 4 * q + 1, lambda.y, dx);
    lambda.z = solve_slot(o, 4 * q + 2, lambda.z, dx);
    lambda.w = solve_slot(o, 4 * q + 3, lambda.w, dx);
    return lambda;
}
#endif
#endif

#if defined(DRAPE_PASS_COARSE) || defined(DRAPE_PROLONG)
uvec4 fetch_table(int t) { return texelFetch(u_coarse_table, texel(t), 0); }
vec3 fetch_vec(int t) { return texelFetch(u_coarse_vec, texel(t), 0).xyz; }
#endif
#ifdef DRAPE_PROLONG
// The coarse correction of particle j's aggregate (u_coarse: x particles' info, y level 1's
// corrections); 0 where it does not move (w 0: pinned or held) or has no aggregate.
vec3 correction(int j, float w) {
    uint parent = fetch_table(int(u_coarse.x) + j).z;
    return w != 0.0 && parent != DRAPE_NO_NODE ? fetch_vec(int(u_coarse.y) + int(parent)) : vec3(0.0);
}
#endif

#if defined(DRAPE_PASS_IMPLICIT) || defined(DRAPE_COARSE_RESTRICT)
// Neighbour j's iterate, with its coarse correction in the iteration that adds it.
vec3 neighbour_iterate(int j) {
    vec4 r = fetch_x(j);
#ifdef DRAPE_PROLONG
    return r.xyz + correction(j, r.w);
#else
    return r.xyz;
#endif
}

// The force residual r_i = -grad_i Phi (see jacobi_step) at the iterate and the block D_i.
vec3 implicit_residual(int row, int count, vec3 di, vec3 si, vec3 yi, float wi, out mat3 block) {
    float kd_h = u_damping / u_h;
    float mass_h2 = 1.0 / (wi * u_h * u_h);
    vec3 r = (yi - di) * mass_h2;
    block = mat3(mass_h2);
    for (int s = 0; s < count; ++s) {
        uvec4 nb = fetch_nbr(row + s);
        if (!active_group(nb.z)) continue;
        int j = int(nb.x);
        vec3 dij = di - neighbour_iterate(j);
        float len;
        vec3 n = direction((si - fetch_aux(j).xyz) + dij, len);
        float k = u_stiffness[nb.z];
        float rest = uintBitsToFloat(nb.y);
        r += implicit_spring_force(n, len, dij, rest, k, kd_h);
        block += implicit_spring_block(n, k, kd_h, implicit_tension(len, rest, k, true));
    }
    return r;
}
#endif

#ifdef DRAPE_PASS_IMPLICIT
// The block-Jacobi step of particle i (free) on Phi(d) = sum_i |d_i - y_i|^2 / (2 w_i h^2) +
// sum_springs k/2 (|x_i - x_j| - L)^2 + dashpots (kernels::implicit_residual): the force residual
// r_i = -grad_i Phi and a 3x3 block D_i like Phi's Hessian block H_ii, but with each spring's
// transverse stiffness k (1 - L/l) taken by its magnitude (implicit_tension, magnitude true): D_i is
// positive definite, and since a spring's term in H is at most twice its share of the two blocks,
// H <= 2 D: the damped iteration converges for the linearised problem. (Dropping a compressed
// spring's negative transverse term instead, as the CPU's blocks do, let a stiff cloth hanging from
// two corners oscillate at 150 % strain.) Returns D_i^-1 r_i. Neighbours' iterates from u_x, their
// substep start from u_aux.
vec3 jacobi_step(int row, int count, vec3 di, vec3 si, vec3 yi, float wi) {
    mat3 block;
    vec3 r = implicit_residual(row, count, di, si, yi, wi, block);
    return inverse(block) * r;
}
#endif

#ifdef DRAPE_PASS_COARSE
#ifdef DRAPE_COARSE_RESTRICT
// Particle i's force residual at the iterate (0 for a pinned or held particle, or no member).
vec3 member_residual(uint i) {
    if (i == DRAPE_NO_NODE) return vec3(0.0);
    int p = int(i);
    vec4 rec = fetch_x(p);
    if (rec.w == 0.0) return vec3(0.0);
    vec3 yi = texelFetch(u_x, texel(p * DRAPE_RECORD + 2), 0).xyz;  // the record's target
    mat3 block;
    return implicit_residual(p * DRAPE_SLOTS, int(fetch_info(p).x), rec.xyz, fetch_aux(p).xyz, yi, rec.w, block);
}
#define DRAPE_MEMBER_TERM member_residual
#endif
#ifdef DRAPE_COARSE_DOWN
// What one Jacobi smoothing from 0 leaves of level l's residual at node c: R_c - sum_j A_cj w R_j / A_jj
// (the table's entries hold A_cj / A_jj). u_coarse: x members, y level l's info, z its residuals.
vec3 smoothed_residual(uint c) {
    if (c == DRAPE_NO_NODE) return vec3(0.0);
    int node = int(c);
    int residuals = int(u_coarse.z);
    vec3 res = (1.0 - DRAPE_COARSE_WEIGHT) * fetch_vec(residuals + node);
    uvec4 info = fetch_table(int(u_coarse.y) + node);
    for (int e = 0; e < int(info.y); ++e) {
        uvec4 entry = fetch_table(int(info.x) + e);
        res -= (DRAPE_COARSE_WEIGHT * uintBitsToFloat(entry.y)) * fetch_vec(residuals + int(entry.x));
    }
    return res;
}
#define DRAPE_MEMBER_TERM smoothed_residual
#endif
#ifdef DRAPE_MEMBER_TERM
// Sum over node c's members (u_coarse.x: the members' table texels, filled from the first). The
// loop stops at the first empty texel: most aggregates fill one, and a SIMD batch of nodes (llvmpipe,
// GPU warps) whose nodes all did skips the second's terms.
vec3 sum_members(int c) {
    vec3 sum = vec3(0.0);
    for (int q = 0; q < DRAPE_MAX_MEMBERS / 4; ++q) {
        uvec4 m = fetch_table(int(u_coarse.x) + (DRAPE_MAX_MEMBERS / 4) * c + q);
        if (m.x == DRAPE_NO_NODE) break;
        sum += DRAPE_MEMBER_TERM(m.x) + DRAPE_MEMBER_TERM(m.y) + DRAPE_MEMBER_TERM(m.z) + DRAPE_MEMBER_TERM(m.w);
    }
    return sum;
}
#endif
#endif

#if DRAPE_SHAPES > 0
#include "collide_shape.h"  // collide_moving: the CPU's collision maths
#endif

#ifdef DRAPE_DRAG
// Cloth::drag_cpu_copy at position x, times the share: per call, the touches' screen shifts add up
// and are unprojected at x's depth. offset = from_screen(px + shift, z) - x, written as
// w (D.xyz - x D.w) / (1 + w D.w) with D = inverse * (2 shift / viewport, 0, 0) and w = clip.w
// (no cancellation between two unprojected points in float).
vec3 drag_share(vec3 x) {
    vec3 total = vec3(0.0);
    int k = 0;
    while (k < u_touch_count) {
        int view = int(u_touches[DRAPE_TOUCH_VEC4 * k + 1].z);
        int v = DRAPE_DRAG_VIEW_VEC4 * view;
        mat4 mvp = mat4(u_drag_views[v], u_drag_views[v + 1], u_drag_views[v + 2], u_drag_views[v + 3]);
        mat4 inv = mat4(u_drag_views[v + 4], u_drag_views[v + 5], u_drag_views[v + 6], u_drag_views[v + 7]);
        vec4 screen = u_drag_views[v + 8];
        vec4 clip = mvp * vec4(x, 1.0);
        vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * screen.xy;
        vec2 shift = vec2(0.0);
        for (; k < u_touch_count && int(u_touches[DRAPE_TOUCH_VEC4 * k + 1].z) == view; ++k) {
            vec4 t0 = u_touches[DRAPE_TOUCH_VEC4 * k], t1 = u_touches[DRAPE_TOUCH_VEC4 * k + 1];
            vec2 d = px - t0.xy;
            shift += touch_weight(dot(d, d), t1.x, t1.y) * t0.zw;
        }
        if (!(clip.w > 0.0) || (shift.x == 0.0 && shift.y == 0.0)) continue;  // at or behind the eye
        vec4 dv = inv * vec4(shift * 2.0 / screen.xy, 0.0, 0.0);
        vec3 offset = clip.w * (dv.xyz - x * dv.w) / (1.0 + clip.w * dv.w);
        if (!isinf(offset.x) && !isinf(offset.y) && !isinf(offset.z) && !isnan(offset.x) && !isnan(offset.y) &&
            !isnan(offset.z))
            total += offset * screen.z;
    }
    return total;
}
#endif

#ifdef DRAPE_KINEMATIC
// This substep's end on the pin path (CpuCloth::kinematic_position).
vec3 kinematic_at() { return kinematic_path(a_kstart, a_ktarget, u_substep.w); }
#endif

void main() {
#ifdef DRAPE_PASS_MOVE
    v_x = vec4(rigid_move(u_move_rot, u_move_pivot, u_move_to, a_x.xyz), a_x.w);
    v_d = u_move_keep_velocity > 0.0 ? vec4(quat_rotate(u_move_rot, a_aux.xyz), a_aux.w) : vec4(0.0, 0.0, 0.0, a_x.w);
    return;
#elif defined(DRAPE_PASS_STILL)
    gl_PointSize = 1.0;
    gl_Position = dot(a_aux.xyz, a_aux.xyz) > u_still_limit2 ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
    return;
#elif defined(DRAPE_PASS_COARSE)
    int c = gl_VertexID;
#if defined(DRAPE_COARSE_RESTRICT) || defined(DRAPE_COARSE_DOWN)
    v_d = vec4(sum_members(c), 0.0);  // level 1 / level l+1 residual
#elif defined(DRAPE_COARSE_SOLVE)
    // e_c = sum_j (A^-1)_cj R_j; u_coarse: x the inverse's texels, y the residuals, z the node count.
    int count = int(u_coarse.z);
    vec3 e = vec3(0.0);
    for (int j = 0; j < count; ++j)
        e += uintBitsToFloat(fetch_table(int(u_coarse.x) + c * count + j).x) * fetch_vec(int(u_coarse.y) + j);
    v_d = vec4(e, 0.0);
#else  // DRAPE_COARSE_UP: u_coarse: x level l's info, y its residuals, z the parents' corrections
    uvec4 info = fetch_table(int(u_coarse.x) + c);
    vec3 e = (DRAPE_COARSE_WEIGHT / uintBitsToFloat(info.w)) * fetch_vec(int(u_coarse.y) + c);
    if (info.z != DRAPE_NO_NODE) e += fetch_vec(int(u_coarse.z) + int(info.z));
    v_d = vec4(e, 0.0);
#endif
    return;
#else
    int i = gl_VertexID;
    vec3 xi = a_x.xyz;
    float wi = a_x.w;
#ifdef DRAPE_PASS_INTERACT
    v_x = a_x;
    v_d = a_aux;
    if (wi == 0.0) return;  // kinematic: goes where its pin says (no drag, no collision)
    vec3 dd = a_aux.xyz;
#ifdef DRAPE_DRAG
    // CpuCloth::collide, first substep: x and d move by the drag share, from where the particle
    // started the step (x - d: the drag is evaluated where drape_cloth_drag saw the cloth)
    vec3 share = drag_share(xi - dd);
    xi += share;
    dd += share;
#endif
#if DRAPE_SHAPES > 0
    // kernels::collide
    vec3 x_in = xi;
    vec3 si = x_in - dd;
    for (int k = 0; k < u_shape_count; ++k) {
        int r = DRAPE_COLLIDER_VEC4 * k;
        vec4 c0 = u_shapes[r], c1 = u_shapes[r + 1], rot0 = u_shapes[r + 2], rot1 = u_shapes[r + 3];
        vec4 c4 = u_shapes[r + 4];
        vec3 q;
        if (collide_moving(int(c4.w), c4.xyz, c0.w, c1.w, c0.xyz, rot0, c1.xyz, rot1, si, xi, q))
            xi = quat_rotate(rot1, q) + c1.xyz;
    }
    dd += xi - x_in;
#endif
    v_x = vec4(xi, wi);
    v_d = vec4(dd, a_aux.w);
    return;
#endif
#ifdef DRAPE_PASS_TETHER
    // kernels::tether (the CPU updates in place; anchors are kinematic, so they do not move here)
    v_x = a_x;
    v_d = a_aux;
    vec3 pull;
    if (!tether_pull(xi, wi, fetch_x(int(a_tether_anchor)).xyz, a_tether_length, pull)) return;
    v_x = vec4(xi + pull, wi);
    v_d = vec4(a_aux.xyz + pull, a_aux.w);
    return;
#endif
    uvec4 info = fetch_info(i);
    int count = int(info.x);
    int row = i * DRAPE_SLOTS;

#if defined(DRAPE_PASS_MASS_SPRING)
    // kernels::mass_spring_step
    if (wi == 0.0) {
#ifdef DRAPE_KINEMATIC
        // Cloth::step: x = kinematic_at, d = x - x_old
        vec3 at = kinematic_at();
        v_x = vec4(at, 0.0);
        v_d = vec4(at - xi, 0.0);
#else
        v_x = a_x;
        v_d = vec4(0.0);
#endif
        return;
    }
    vec3 vi = a_aux.xyz * u_substep.x;
    vec3 force = vec3(0.0);
    for (int s = 0; s < count; ++s) {
        uvec4 nb = fetch_nbr(row + s);
        if (!active_group(nb.z)) continue;
        int j = int(nb.x);
        vec3 vj = fetch_aux(j).xyz * u_substep.x;
        force += spring_force(xi - fetch_x(j).xyz, vi - vj, uintBitsToFloat(nb.y), u_stiffness[nb.z], u_damping);
    }
    vec3 a = wi * force + external_accel(u_gravity, u_air_drag, u_wind, vi);
    vec3 dn = verlet_displacement(a_aux.xyz, u_substep.y, a, u_h, u_substep.z);
    v_x = vec4(xi + dn, wi);
    v_d = vec4(dn, wi);

#elif defined(DRAPE_PASS_PREDICT)
    // kernels::predict<kDashpot> (kernels::implicit_predict with DRAPE_IMPLICIT)
    vec3 dn = vec3(0.0);
#ifdef DRAPE_IMPLICIT
    vec3 first = vec3(0.0);  // the first iterate of a free particle
#endif
    if (wi != 0.0) {
        vec3 vi = a_aux.xyz * u_substep.x;
        vec3 a = external_accel(u_gravity, u_air_drag, u_wind, vi);
#ifdef DRAPE_IMPLICIT
        dn = implicit_predict(a_aux.xyz, u_substep.y, a, -u_air_drag * vi, u_h, u_substep.z, first);
#else
#ifdef DRAPE_DASHPOT
        vec3 force = vec3(0.0);
        float ci = float(info.y);
        for (int s = 0; s < count; ++s) {
            uvec4 nb = fetch_nbr(row + s);
            if (!active_group(nb.z)) continue;
            int j = int(nb.x);
            vec4 rj = fetch_x(j);
            vec3 vj = fetch_aux(j).xyz * u_substep.x;
            force += dashpot_force(xi - rj.xyz, vi - vj, u_damping, u_h, wi, ci, rj.w, float(fetch_info(j).y));
        }
        a += wi * force;
#endif
        dn = verlet_displacement(a_aux.xyz, u_substep.y, a, u_h, u_substep.z);
#endif
    }
#ifdef DRAPE_KINEMATIC
    // Cloth::step: the kinematic displacement of this substep, kinematic_at - x
    if (wi == 0.0) dn = kinematic_at() - xi;
#endif
    v_d = vec4(dn, wi);
#ifdef DRAPE_IMPLICIT
    // kernels::implicit_predict: dn is the target y; the first iterate is the inertia and drag (at
    // rest exactly 0), kinematic particles their path
    v_d = vec4(wi != 0.0 ? first : dn, wi);
    v_prev = v_d;
    v_target = vec4(dn, wi);
#endif
#ifdef DRAPE_XPBD
#if DRAPE_LAMBDA_VEC4 >= 1
    v_lambda0 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 2
    v_lambda1 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 3
    v_lambda2 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 4
    v_lambda3 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 5
    v_lambda4 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 6
    v_lambda5 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 7
    v_lambda6 = vec4(0.0);
#endif
#if DRAPE_LAMBDA_VEC4 >= 8
    v_lambda7 = vec4(0.0);
#endif
#endif

#elif defined(DRAPE_PASS_IMPLICIT)
    // d' = prev + omega (d + gamma D_i^-1 r - prev): the under-relaxed block-Jacobi step, then
    // Chebyshev's extrapolation from the previous iterate. Its fixed point is r = 0 whatever omega
    // and gamma: the springs' exact equilibrium at rest. Kinematic particles keep their path.
    vec3 di = a_x.xyz;  // own iterate
    vec3 prev = a_prev.xyz;
#ifdef DRAPE_PROLONG
    // The aggregate's correction, added to the iterate and the previous one alike: the Chebyshev
    // recurrence goes on from the corrected pair.
    vec3 e = correction(i, wi);
    di += e;
    prev += e;
#endif
    vec3 dn = di;
    if (wi != 0.0) {
        vec3 jacobi = di + u_chebyshev.y * jacobi_step(row, count, di, a_aux.xyz, a_target.xyz, wi);
        dn = prev + u_chebyshev.x * (jacobi - prev);
    }
    v_d = vec4(dn, wi);
#ifdef DRAPE_COMMIT
    v_x = vec4(a_aux.xyz + dn, wi);
#else
    v_prev = vec4(di, a_x.w);
    v_target = a_target;
#endif

#elif defined(DRAPE_PASS_CONSTRAINT)
    // kernels::constraint_iteration<kXpbd, kCommit>
    Own o = Own(xi, a_aux.xyz, wi, info.y, row, wi != 0.0 ? count : 0);
    vec3 dx = vec3(0.0);
#ifdef DRAPE_XPBD
#if DRAPE_LAMBDA_VEC4 >= 1
    vec4 lambda0 = solve_slots4(o, 0, a_lambda0, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 2
    vec4 lambda1 = solve_slots4(o, 1, a_lambda1, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 3
    vec4 lambda2 = solve_slots4(o, 2, a_lambda2, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 4
    vec4 lambda3 = solve_slots4(o, 3, a_lambda3, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 5
    vec4 lambda4 = solve_slots4(o, 4, a_lambda4, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 6
    vec4 lambda5 = solve_slots4(o, 5, a_lambda5, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 7
    vec4 lambda6 = solve_slots4(o, 6, a_lambda6, dx);
#endif
#if DRAPE_LAMBDA_VEC4 >= 8
    vec4 lambda7 = solve_slots4(o, 7, a_lambda7, dx);
#endif
#else
    for (int s = 0; s < o.count; ++s) solve_slot(o, s, 0.0, dx);
#endif
    vec3 dn = o.d + dx;
    v_d = vec4(dn, wi);
#ifdef DRAPE_COMMIT
    v_x = vec4(o.s + dn, wi);
#endif
#if defined(DRAPE_XPBD) && !defined(DRAPE_COMMIT)
#if DRAPE_LAMBDA_VEC4 >= 1
    v_lambda0 = lambda0;
#endif
#if DRAPE_LAMBDA_VEC4 >= 2
    v_lambda1 = lambda1;
#endif
#if DRAPE_LAMBDA_VEC4 >= 3
    v_lambda2 = lambda2;
#endif
#if DRAPE_LAMBDA_VEC4 >= 4
    v_lambda3 = lambda3;
#endif
#if DRAPE_LAMBDA_VEC4 >= 5
    v_lambda4 = lambda4;
#endif
#if DRAPE_LAMBDA_VEC4 >= 6
    v_lambda5 = lambda5;
#endif
#if DRAPE_LAMBDA_VEC4 >= 7
    v_lambda6 = lambda6;
#endif
#if DRAPE_LAMBDA_VEC4 >= 8
    v_lambda7 = lambda7;
#endif
#endif
#endif
#endif  // DRAPE_PASS_MOVE, DRAPE_PASS_STILL
}
