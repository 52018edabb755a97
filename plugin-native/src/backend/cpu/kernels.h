// Per-particle kernels of one substep, each over a range [begin, end) of particles.
//
// Every kernel is a gather: particle i reads its own record and its neighbours' records from
// input buffers and writes only its own record to an output buffer (Jacobi style, the paper's
// per-vertex formulation). That is what a GLES vertex shader with transform feedback can do, so
// shaders/sim.vert.glsl mirrors these functions, and any split of the range over threads gives
// the same bits. The maths per particle and spring is shaders/substep.h, shared with it.
//
// Records are 16 bytes: xyz + w inverse mass (1/kg; 0 = pinned/kinematic). The state of a
// particle is two records: its position x and its displacement d over the last substep (the
// velocity times h_prev). Keeping d instead of the previous position matters in float: with many
// small substeps g h^2 is below half an ulp of a position of a few metres, so x - prev would lose
// gravity entirely (a stiff mass-spring cloth at y = 10 m would never fall); d keeps it exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "backend/cpu/glsl.h"  // glsl::direction, spring_force, ... (shaders/substep.h)
#include "core/params.h"
#include "core/topology.h"

namespace drape::kernels {

using Particle = glm::vec4;

/// Per-substep constants for each spring group. Derived from drape_params and h.
struct GroupConstants {
    float stiffness[DRAPE_GROUP_COUNT];   ///< MASS_SPRING: k, N/m. PBD: fraction per iteration
    float compliance[DRAPE_GROUP_COUNT];  ///< XPBD: alpha~ = 1/(k h^2); 0 when k is 0 (group off)
    float damping_ratio[DRAPE_GROUP_COUNT]; ///< XPBD: gamma = alpha~ * (h^2 kd) / h = kd/(k h)
    bool active[DRAPE_GROUP_COUNT];       ///< stiffness > 0
};

/// Everything a substep needs, as plain pointers (no ownership).
struct SubstepContext {
    const uint32_t* nbr_index;
    const float* nbr_rest;
    const uint8_t* nbr_group;
    const uint32_t* nbr_count;
    const uint32_t* active_count;  ///< active springs per particle (Jacobi row sums)
    uint32_t slots;
    // Column-major copies of the table for the constraint iteration: slot s of particle i at
    // s * stride + i, so four consecutive particles' slot s are contiguous (kernels_simd.h).
    uint32_t stride;               ///< particle count
    const uint32_t* col_index;
    const float* col_rest;
    const uint8_t* col_group;
    float* lambda;                 ///< XPBD multipliers, one per slot, column-major (both ends keep
                                   ///< equal copies); NULL when there is one iteration per substep
                                   ///< (they start at 0 and are never read again)
    GroupConstants groups;
    glm::vec3 gravity, wind;
    float air_drag;
    float damping;                 ///< kd, N*s/m
    float h;                       ///< substep, s
    float h_prev;                  ///< previous substep, s (velocity = d / h_prev)
    float h_ratio;                 ///< h / h_prev: exactly 1 for equal substeps, so steady
                                   ///< motion is not rescaled by a rounded 1/h each substep
    float accel_h;                 ///< (h + h_prev_for_accel)/2: h, or h/2 on the first step
};

inline bool active_slot(const SubstepContext& c, size_t slot) {
    uint8_t g = c.nbr_group[slot];
    return g < DRAPE_GROUP_COUNT && c.groups.active[g];
}

/// Calls fn(s, j, rest, k) for each active spring of particle i: its slot s in i's row, the particle
/// at its other end, its rest length (m) and stiffness (N/m). Row-major table: a particle's springs
/// are contiguous.
template <class Fn>
inline void for_active_slots(const SubstepContext& c, uint32_t i, Fn&& fn) {
    const size_t row = size_t(i) * c.slots;
    for (uint32_t s = 0; s < c.nbr_count[i]; ++s) {
        const size_t slot = row + s;
        if (active_slot(c, slot)) fn(s, c.nbr_index[slot], c.nbr_rest[slot], c.groups.stiffness[c.nbr_group[slot]]);
    }
}

/// for_active_slots without the slot: fn(j, rest, k) (its own loop: through for_active_slots the
/// curvature pass took 0.3 % more instructions).
template <class Fn>
inline void for_active_springs(const SubstepContext& c, uint32_t i, Fn&& fn) {
    const size_t row = size_t(i) * c.slots;
    for (uint32_t s = 0; s < c.nbr_count[i]; ++s) {
        const size_t slot = row + s;
        if (active_slot(c, slot)) fn(c.nbr_index[slot], c.nbr_rest[slot], c.groups.stiffness[c.nbr_group[slot]]);
    }
}

/// IMPLICIT: per slot, its spring as the last residual pass that wrote them saw it at its iterate:
/// the direction n of x_i - x_j and the tension across (glsl::implicit_tension, clamped), which is
/// all a spring's block of H needs (glsl::implicit_spring_block). The coarse space and levels
/// assemble their matrices from them instead of computing every direction again
/// (implicit_solve.cpp). Column-major like SubstepContext::col_index, four rows of `stride` per
/// slot (n.x, n.y, n.z, across), so four consecutive particles' values are one SIMD store.
struct SpringFrames {
    float* v = nullptr;  ///< 4 * slots * stride floats
    uint32_t stride = 0;
    float* at(uint32_t s, uint32_t row) const { return v + (size_t(s) * 4 + row) * stride; }
    glm::vec3 n(uint32_t s, uint32_t i) const { return glm::vec3(at(s, 0)[i], at(s, 1)[i], at(s, 2)[i]); }
    float across(uint32_t s, uint32_t i) const { return at(s, 3)[i]; }
};

/// IMPLICIT: per particle the springs implicit_curvature counts from it (each spring once: from its
/// lower-indexed end, or from its free end when the other is kinematic; none from a kinematic
/// particle), in its slot order. Column-major like SubstepContext::col_index (slot s of particle i at
/// s * stride + i); slots past a particle's count have k = 0, rest length 1 and its own index.
struct CountedSprings {
    const uint32_t* count = nullptr;
    const uint32_t* index = nullptr;
    const float* rest = nullptr;
    const float* k = nullptr;  ///< N/m
};

/// glsl::direction with the length through a pointer (the IMPLICIT kernels' form).
inline glm::vec3 direction(const glm::vec3& d, float* len) { return glsl::direction(d, *len); }

/// glsl::external_accel with this substep's gravity, drag and wind.
inline glm::vec3 external_accel(const SubstepContext& c, const glm::vec3& v) {
    return glsl::external_accel(c.gravity, c.air_drag, c.wind, v);
}

/// MASS_SPRING (paper eq. 1-3): Hooke force plus a dashpot along each spring, then a Verlet step
/// d' = d h/h_prev + a h (h + h_prev)/2, x' = x + d' (variable-step Verlet in displacement form;
/// exact for constant acceleration when the first step uses h/2, see accuracy.md R1).
inline void mass_spring_step(const SubstepContext& c, const Particle* x, const Particle* d, Particle* x_out,
                             Particle* d_out, uint32_t begin, uint32_t end) {
    const float inv_hp = 1.0f / c.h_prev;
    for (uint32_t i = begin; i < end; ++i) {
        const glm::vec3 xi(x[i]);
        const float wi = x[i].w;
        if (wi == 0.0f) {
            x_out[i] = x[i];
            d_out[i] = Particle(0.0f);
            continue;
        }
        const glm::vec3 vi = glm::vec3(d[i]) * inv_hp;
        glm::vec3 force(0.0f);
        for_active_springs(c, i, [&](uint32_t j, float rest, float k) {
            force += glsl::spring_force(xi - glm::vec3(x[j]), vi - glm::vec3(d[j]) * inv_hp, rest, k, c.damping);
        });
        const glm::vec3 a = wi * force + external_accel(c, vi);
        const glm::vec3 dn = glsl::verlet_displacement(glm::vec3(d[i]), c.h_ratio, a, c.h, c.accel_h);
        x_out[i] = Particle(xi + dn, wi);
        d_out[i] = Particle(dn, wi);
    }
}

/// PBD / XPBD prediction: the inertial displacement of this substep under external forces,
/// d' = d h/h_prev + a h (h + h_prev)/2, written as a displacement record; multipliers reset.
/// Position-based substeps then work on displacements from the substep start, not on absolute
/// positions, for the same float reason as the state (see the top of this file).
/// kDashpot (PBD, which has no compliance to carry damping): explicit dashpots along the springs,
/// kd limited per spring to 1/(h (wi ci + wj cj)) so the explicit update cannot overshoot.
template <bool kDashpot>
inline void predict(const SubstepContext& c, const Particle* x, const Particle* d, Particle* out,
                    uint32_t begin, uint32_t end) {
    const float inv_hp = 1.0f / c.h_prev;
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = x[i].w;
        glm::vec3 dn(0.0f);
        if (wi != 0.0f) {
            const glm::vec3 vi = glm::vec3(d[i]) * inv_hp;
            glm::vec3 a = external_accel(c, vi);
            if (kDashpot) {
                const glm::vec3 xi(x[i]);
                glm::vec3 force(0.0f);
                for_active_springs(c, i, [&](uint32_t j, float, float) {
                    force += glsl::dashpot_force(xi - glm::vec3(x[j]), vi - glm::vec3(d[j]) * inv_hp, c.damping, c.h,
                                                 wi, float(c.active_count[i]), x[j].w, float(c.active_count[j]));
                });
                a += wi * force;
            }
            dn = glsl::verlet_displacement(glm::vec3(d[i]), c.h_ratio, a, c.h, c.accel_h);
        }
        out[i] = Particle(dn, wi);
    }
    if (c.lambda)  // column-major: one contiguous run per slot
        for (uint32_t s = 0; s < c.slots; ++s)
            std::fill(c.lambda + size_t(s) * c.stride + begin, c.lambda + size_t(s) * c.stride + end, 0.0f);
}

/// Per-spring factor of a Jacobi update (glsl::xpbd_coefficient, glsl::pbd_coefficient), computed
/// once per step (it depends on h, the masses and the active springs, none of which change between
/// substeps); 0 for inactive springs and padding. Column-major like `lambda`; symmetric in i and j.
template <bool kXpbd>
inline void spring_coefficients(const SubstepContext& c, const Particle* x, float* coef, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = x[i].w;
        const size_t row = size_t(i) * c.slots;
        for (uint32_t s = 0; s < c.slots; ++s) {
            const size_t slot = row + s;
            const size_t col = size_t(s) * c.stride + i;
            float& k = coef[col];
            k = 0.0f;
            if (s >= c.nbr_count[i] || !active_slot(c, slot) || wi == 0.0f) continue;
            const uint32_t j = c.nbr_index[slot];
            const uint8_t g = c.nbr_group[slot];
            const uint32_t ci = c.active_count[i], cj = c.active_count[j];
            k = kXpbd ? glsl::xpbd_coefficient(wi, x[j].w, ci, cj, c.groups.compliance[g], c.groups.damping_ratio[g],
                                               kJacobiCoupling)
                      : glsl::pbd_coefficient(wi, x[j].w, ci, cj, c.groups.stiffness[g], kJacobiCoupling);
        }
    }
}

/// One PBD (paper eq. 7-8, stiffness k per iteration) or XPBD (Macklin 2016 eq. 18 with the
/// damping term of eq. 26) Jacobi iteration on displacements `disp` from the substep start
/// `start`; writes displacements to `out` and, with kCommit (the last iteration), also the new
/// positions start + displacement to `x_out`. `coef` from spring_coefficients (0 for inactive
/// springs, which then contribute nothing). Symmetric in i and j, so both copies of each lambda
/// stay equal.
template <bool kXpbd, bool kCommit>
inline void constraint_iteration(const SubstepContext& c, const float* coef, const Particle* disp,
                                 const Particle* start, Particle* out, Particle* x_out, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = disp[i].w;
        const glm::vec3 di(disp[i]);
        const glm::vec3 si(start[i]);
        glm::vec3 dx(0.0f);
        if (wi != 0.0f) {
            const uint32_t count = c.nbr_count[i];
            for (uint32_t s = 0; s < count; ++s) {
                const size_t slot = size_t(s) * c.stride + i;
                const uint32_t j = c.col_index[slot];
                const glm::vec3 dij = di - glm::vec3(disp[j]);
                float len;
                const glm::vec3 n = direction((si - glm::vec3(start[j])) + dij, &len);
                const float constraint = len - c.col_rest[slot];
                float dl;
                if (kXpbd) {
                    const uint8_t g = c.col_group[slot];
                    // Without stored multipliers (one iteration per substep) lambda is 0 here:
                    // -C - 0 is -C exactly, so skipping the term changes no bit.
                    const float lambda = c.lambda ? c.lambda[slot] : 0.0f;
                    dl = glsl::xpbd_delta(constraint, c.groups.compliance[g], lambda, c.groups.damping_ratio[g], n, dij,
                                          coef[slot]);
                    if (c.lambda) c.lambda[slot] = lambda + dl;
                } else {
                    dl = -constraint * coef[slot];
                }
                dx += (wi * dl) * n;
            }
        }
        const glm::vec3 dn = di + dx;
        out[i] = Particle(dn, wi);
        if (kCommit) x_out[i] = Particle(si + dn, wi);
    }
}

/// A symmetric 3x3 matrix in 6 floats (a mat3 takes 9): the IMPLICIT solve's per-particle blocks.
struct SymMat3 {
    glm::vec3 diag{0.0f};  ///< xx, yy, zz
    glm::vec3 off{0.0f};   ///< xy, xz, yz

    /// += s n n^T
    void add_outer(float s, const glm::vec3& n) {
        const glm::vec3 a = s * n;
        diag += a * n;
        off += glm::vec3(a.x * n.y, a.x * n.z, a.y * n.z);
    }
    glm::vec3 operator*(const glm::vec3& v) const {
        return diag * v + glm::vec3(off.x * v.y + off.y * v.z, off.x * v.x + off.z * v.z, off.y * v.x + off.z * v.y);
    }
    /// The inverse by cofactors (the matrix must be invertible; the blocks are positive definite).
    SymMat3 inverse() const {
        const float a = diag.x, b = diag.y, c = diag.z, d = off.x, e = off.y, f = off.z;
        const glm::vec3 cof_diag(b * c - f * f, a * c - e * e, a * b - d * d);
        const glm::vec3 cof_off(e * f - d * c, d * f - e * b, d * e - a * f);
        const float inv_det = 1.0f / (a * cof_diag.x + d * cof_off.x + e * cof_off.y);
        return {cof_diag * inv_det, cof_off * inv_det};
    }
};

/// IMPLICIT prediction (glsl::implicit_predict): the target y = d h/h_prev + a h (h + h_prev)/2
/// (inertia and external forces, as predict<false>) and the first iterate d h/h_prev plus the air
/// drag's share (inertia and drag, so that at rest it is exactly 0: see implicit_residual).
inline void implicit_predict(const SubstepContext& c, const Particle* x, const Particle* d, Particle* target,
                             Particle* first, uint32_t begin, uint32_t end) {
    const float inv_hp = 1.0f / c.h_prev;
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = x[i].w;
        glm::vec3 inertia(0.0f), y(0.0f);
        if (wi != 0.0f) {
            const glm::vec3 v = glm::vec3(d[i]) * inv_hp;
            y = glsl::implicit_predict(glm::vec3(d[i]), c.h_ratio, external_accel(c, v), -c.air_drag * v, c.h,
                                       c.accel_h, inertia);
        }
        target[i] = Particle(y, wi);
        first[i] = Particle(inertia, wi);
    }
}

/// IMPLICIT model: one substep is implicit Euler (Baraff and Witkin 1998), posed as minimising
///   Phi(d) = sum_i |d_i - y_i|^2 / (2 w_i h^2) + sum_springs k/2 (|x_i - x_j| - L)^2
/// (plus a dashpot kd along each spring) over the substep's displacements d, x = start + d. This
/// kernel writes the force residual  r_i = -grad_i Phi = F_i - (d_i - y_i) / (w_i h^2)  (N; 0 for
/// kinematic particles); CpuCloth::implicit_substep turns it into a step with a prefactored global
/// solve. Any iteration of the form d += P^-1 r has grad Phi = 0 as its fixed point: at rest the
/// first iterate is d = 0 (implicit_predict) and y = h^2 g, so a substep that stays at rest is
/// one where the spring forces balance m g exactly, the springs' own equilibrium, whatever the
/// iteration count (one Jacobi iteration of XPBD rests softer than its springs).
/// Returns sum_i r_i . p_i over the range in double (the conjugate-gradient solve's line search
/// needs it; 0 when p is null), so that no second pass reads r.
/// kBlocks: also writes block_inv[i], the inverse of particle i's 3x3 block of the clamped Hessian of
/// Phi (implicit_curvature's H): I/(w_i h^2) plus its springs' blocks (glsl::implicit_spring_block,
/// summed as iso I + sum along n n^T in symmetric form); 0 for kinematic particles. The springs'
/// directions are at hand here, so the blocks cost no pass of their own.
/// kFrames: also writes each spring's direction and tension to frames (SpringFrames).
template <bool kBlocks = false, bool kFrames = false>
inline double implicit_residual(const SubstepContext& c, const Particle* disp, const Particle* target,
                                const Particle* start, const Particle* p, Particle* residual, uint32_t begin,
                                uint32_t end, SymMat3* block_inv = nullptr, const SpringFrames& frames = {}) {
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    double rp = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = disp[i].w;
        glm::vec3 r(0.0f);
        if (wi != 0.0f) {
            const glm::vec3 di(disp[i]);
            const glm::vec3 si(start[i]);
            float iso = inv_h2 / wi;
            SymMat3 nn;  // sum of along n n^T
            for_active_slots(c, i, [&](uint32_t s, uint32_t j, float rest, float k) {
                const glm::vec3 dij = di - glm::vec3(disp[j]);
                float len;
                const glm::vec3 n = direction((si - glm::vec3(start[j])) + dij, &len);
                r += glsl::implicit_spring_force(n, len, dij, rest, k, kd_h);
                if (kBlocks || kFrames) {
                    const float across = glsl::implicit_tension(len, rest, k, false);
                    if (kBlocks) {
                        iso += across;
                        nn.add_outer(glsl::implicit_block_along(k, kd_h, across), n);
                    }
                    if (kFrames)
                        for (int row = 0; row < 4; ++row) frames.at(s, row)[i] = row < 3 ? n[row] : across;
                }
            });
            r -= (di - glm::vec3(target[i])) * (inv_h2 / wi);
            if (p) rp += double(glm::dot(r, glm::vec3(p[i])));
            if (kBlocks) {
                nn.diag += iso;
                block_inv[i] = nn.inverse();
            }
        } else if (kBlocks) {
            block_inv[i] = SymMat3();
        }
        residual[i] = Particle(r, wi);
    }
    return rp;
}

/// IMPLICIT: the curvature p^T H p of Phi (implicit_residual) along p, at disp, over the masses and
/// springs of particles [begin, end) in double. H has each spring's transverse stiffness clamped at
/// 0, so that it is positive definite; per spring, on p_i - p_j, glsl::implicit_spring_block with
/// glsl::implicit_tension(magnitude false): (k + kd/h) n n^T + k max(0, 1 - L/l) (I - n n^T). p^T H p is a sum over springs, so each spring
/// is counted once, from its lower-indexed end (from its free end if the other is kinematic), and
/// no H p is stored. p must be 0 on kinematic particles.
/// Also raises *shrink to the largest rate -n.(p_i - p_j) / (l - floor L) over the springs it counts
/// that are stretched (l >= L) and that p shortens: a step of length alpha along p brings such a
/// spring's length along its direction to floor L where alpha times that rate is 1.
inline double implicit_curvature(const SubstepContext& c, const Particle* disp, const Particle* start,
                                 const Particle* p, uint32_t begin, uint32_t end, float floor, float* shrink) {
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    double sum = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = disp[i].w;
        if (wi == 0.0f) continue;
        const glm::vec3 pi(p[i]);
        const glm::vec3 xi = glm::vec3(start[i]) + glm::vec3(disp[i]);
        float e = glm::dot(pi, pi) * (inv_h2 / wi);
        for_active_springs(c, i, [&](uint32_t j, float rest, float k) {
            if (j < i && disp[j].w != 0.0f) return;  // counted from j
            float len;
            const glm::vec3 n = direction(xi - (glm::vec3(start[j]) + glm::vec3(disp[j])), &len);
            const glm::vec3 dp = pi - glm::vec3(p[j]);
            const float along = glm::dot(n, dp);
            const float across = glsl::implicit_tension(len, rest, k, false);
            e += (k + kd_h) * along * along + across * (glm::dot(dp, dp) - along * along);
            if (len >= rest && along < 0.0f) *shrink = std::max(*shrink, -along / (len - floor * rest));
        });
        sum += double(e);
    }
    return sum;
}

/// Tethers (glsl::tether_pull): particle i may be at most `length[i]` from the kinematic particle
/// `anchor[i]`; its displacement takes the same correction as its position (no velocity away from
/// the anchor). One-sided and local, so it runs after the solve in O(n) and stops the stretch a
/// local solver cannot remove in few passes on a fine cloth. Particles without an anchor have
/// length < 0.
inline void tether(const uint32_t* anchor, const float* length, Particle* x, Particle* d, uint32_t begin,
                   uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const glm::vec3 xi(x[i]);
        glm::vec3 pull;
        if (!glsl::tether_pull(xi, x[i].w, glm::vec3(x[anchor[i]]), length[i], pull)) continue;
        x[i] = Particle(xi + pull, x[i].w);
        d[i] += Particle(pull, 0.0f);
    }
}

}  // namespace drape::kernels
