// constraint_iteration and implicit_residual (kernels.h) on four particles at once: SSE on x86-64,
// NEON on arm64.
//
// Each lane does exactly the scalar kernel's float operations in the same order (IEEE add, mul,
// div and sqrt are correctly rounded in every lane, and no multiply-add is contracted), so
// results are bit-identical to kernels::constraint_iteration and the GLES mirror still matches.
// Lanes past their particle's spring count read the padding slots, whose factor is 0, and add
// nothing.
// The maths of direction, xpbd_delta and the implicit spring terms (shaders/substep.h) is written
// out again here in vector form: the shared functions take one particle's vec3s, these four lanes'
// components.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "backend/cpu/kernels.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#define DRAPE_SIMD 1
#elif defined(__ARM_NEON) && defined(__aarch64__)
#include <arm_neon.h>
#define DRAPE_SIMD 1
#else
#define DRAPE_SIMD 0
#endif

namespace drape::kernels {

#if DRAPE_SIMD
namespace simd {

typedef float F4 __attribute__((vector_size(16)));
typedef int32_t I4 __attribute__((vector_size(16)));

inline F4 max4(F4 a, F4 b) {  // a or b where either is NaN: the callers pass none
#if defined(__SSE2__)
    return F4(_mm_max_ps(__m128(a), __m128(b)));
#else
    return F4(vmaxq_f32(float32x4_t(a), float32x4_t(b)));
#endif
}

inline F4 sqrt4(F4 v) {
#if defined(__SSE2__)
    return F4(_mm_sqrt_ps(__m128(v)));
#else
    return F4(vsqrtq_f32(float32x4_t(v)));
#endif
}

struct V3 {
    F4 x, y, z;
};

// Component-wise x, y, z of four records.
inline V3 gather(const Particle* p, const uint32_t idx[4]) {
    V3 r;
#if defined(__SSE2__)
    __m128 a = _mm_loadu_ps(&p[idx[0]].x), b = _mm_loadu_ps(&p[idx[1]].x);
    __m128 c = _mm_loadu_ps(&p[idx[2]].x), d = _mm_loadu_ps(&p[idx[3]].x);
    _MM_TRANSPOSE4_PS(a, b, c, d);
    r.x = F4(a), r.y = F4(b), r.z = F4(c);
#else
    for (int l = 0; l < 4; ++l) {
        r.x[l] = p[idx[l]].x;
        r.y[l] = p[idx[l]].y;
        r.z[l] = p[idx[l]].z;
    }
#endif
    return r;
}

}  // namespace simd
#endif

template <bool kXpbd, bool kCommit>
inline void constraint_iteration_simd(const SubstepContext& c, const float* coef, const Particle* disp,
                                      const Particle* start, Particle* out, Particle* x_out, uint32_t begin,
                                      uint32_t end) {
#if DRAPE_SIMD
    using simd::F4;
    using simd::I4;
    using simd::V3;
    uint32_t i = begin;
    for (; i + 4 <= end; i += 4) {
        const uint32_t self[4] = {i, i + 1, i + 2, i + 3};
        const V3 di = simd::gather(disp, self);
        const V3 si = simd::gather(start, self);
        F4 wi;
        uint32_t max_count = 0;
        for (int l = 0; l < 4; ++l) {
            wi[l] = disp[i + l].w;
            max_count = c.nbr_count[i + l] > max_count ? c.nbr_count[i + l] : max_count;
        }
        V3 dx{F4{0, 0, 0, 0}, F4{0, 0, 0, 0}, F4{0, 0, 0, 0}};
        for (uint32_t s = 0; s < max_count; ++s) {
            const size_t base = size_t(s) * c.stride + i;  // four consecutive slots (column-major)
            uint32_t j[4];
            F4 rest, k, lambda = {0, 0, 0, 0}, alpha = {0, 0, 0, 0}, gamma = {0, 0, 0, 0};
            std::memcpy(j, c.col_index + base, sizeof j);
            std::memcpy(&rest, c.col_rest + base, sizeof rest);
            std::memcpy(&k, coef + base, sizeof k);
            if (kXpbd) {
                if (c.lambda) std::memcpy(&lambda, c.lambda + base, sizeof lambda);
                // Per-group constants by lane (padding group: 0), without a per-slot array.
                const I4 g = {c.col_group[base], c.col_group[base + 1], c.col_group[base + 2], c.col_group[base + 3]};
                const F4 zero4 = {0, 0, 0, 0};
                for (int gr = 0; gr < DRAPE_GROUP_COUNT; ++gr) {
                    const I4 is = g == I4{gr, gr, gr, gr};
                    alpha = is ? zero4 + c.groups.compliance[gr] : alpha;
                    gamma = is ? zero4 + c.groups.damping_ratio[gr] : gamma;
                }
            }
            const V3 dj = simd::gather(disp, j);
            const V3 sj = simd::gather(start, j);
            const V3 dij{di.x - dj.x, di.y - dj.y, di.z - dj.z};
            const V3 d{(si.x - sj.x) + dij.x, (si.y - sj.y) + dij.y, (si.z - sj.z) + dij.z};
            const F4 len = simd::sqrt4(d.x * d.x + d.y * d.y + d.z * d.z);
            const F4 one = {1, 1, 1, 1};
            const F4 zero = {0, 0, 0, 0};
            const F4 inv = len > zero ? one / len : zero;  // direction(): zero for a zero length
            const V3 n{d.x * inv, d.y * inv, d.z * inv};
            const F4 constraint = len - rest;
            F4 dl;
            if (kXpbd) {
                const F4 ndot = n.x * dij.x + n.y * dij.y + n.z * dij.z;
                dl = (-constraint - alpha * lambda - gamma * ndot) * k;
                // Padding slots hold lambda 0 and get dl 0 (their factor is 0).
                if (c.lambda) {
                    const F4 updated = lambda + dl;
                    std::memcpy(c.lambda + base, &updated, sizeof updated);
                }
            } else {
                dl = -constraint * k;
            }
            const F4 wdl = wi * dl;
            dx.x += wdl * n.x;
            dx.y += wdl * n.y;
            dx.z += wdl * n.z;
        }
        for (int l = 0; l < 4; ++l) {
            // Kinematic lanes: every factor of theirs is 0, so dx is 0 as in the scalar kernel.
            const glm::vec3 dn(di.x[l] + (wi[l] != 0.0f ? dx.x[l] : 0.0f), di.y[l] + (wi[l] != 0.0f ? dx.y[l] : 0.0f),
                               di.z[l] + (wi[l] != 0.0f ? dx.z[l] : 0.0f));
            out[i + l] = Particle(dn, wi[l]);
            if (kCommit) x_out[i + l] = Particle(glm::vec3(si.x[l], si.y[l], si.z[l]) + dn, wi[l]);
        }
    }
    constraint_iteration<kXpbd, kCommit>(c, coef, disp, start, out, x_out, i, end);
#else
    constraint_iteration<kXpbd, kCommit>(c, coef, disp, start, out, x_out, begin, end);
#endif
}

/// implicit_residual on four particles at once: the springs in SIMD lanes, each lane's sums in the
/// scalar kernel's order, then per particle its inertia, r.p and block inverse as the scalar kernel
/// does them: the same bits. col_k: per slot (column-major) its spring's stiffness, 0 where inactive
/// or padding; a spring a lane does not have adds exactly 0 to its sums (a sum that starts at +0
/// never becomes -0, so adding +-0 leaves it as it is). kFrames: also the springs' SpringFrames (in
/// the lanes of a particle's padding slots too, where nothing reads them).
template <bool kBlocks = false, bool kFrames = false>
inline double implicit_residual_simd(const SubstepContext& c, const float* col_k, const Particle* disp,
                                     const Particle* target, const Particle* start, const Particle* p,
                                     Particle* residual, uint32_t begin, uint32_t end,
                                     SymMat3* block_inv = nullptr, const SpringFrames& frames = {}) {
    double rp = 0;
    uint32_t i = begin;
#if DRAPE_SIMD
    using simd::F4;
    using simd::I4;
    using simd::V3;
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    const F4 zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    for (; i + 4 <= end; i += 4) {
        const uint32_t self[4] = {i, i + 1, i + 2, i + 3};
        const V3 di = simd::gather(disp, self);
        const V3 si = simd::gather(start, self);
        F4 wi, iso = zero;
        uint32_t max_count = 0;
        for (int l = 0; l < 4; ++l) {
            wi[l] = disp[i + l].w;
            if (kBlocks && wi[l] != 0.0f) iso[l] = inv_h2 / wi[l];
            max_count = c.nbr_count[i + l] > max_count ? c.nbr_count[i + l] : max_count;
        }
        V3 r{zero, zero, zero}, diag{zero, zero, zero}, off{zero, zero, zero};
        for (uint32_t s = 0; s < max_count; ++s) {
            const size_t base = size_t(s) * c.stride + i;  // four consecutive slots (column-major)
            uint32_t j[4];
            F4 rest, k;
            std::memcpy(j, c.col_index + base, sizeof j);
            std::memcpy(&rest, c.col_rest + base, sizeof rest);
            std::memcpy(&k, col_k + base, sizeof k);
            const I4 on = k > zero;
            const V3 dj = simd::gather(disp, j);
            const V3 sj = simd::gather(start, j);
            const V3 dij{di.x - dj.x, di.y - dj.y, di.z - dj.z};
            const V3 d{(si.x - sj.x) + dij.x, (si.y - sj.y) + dij.y, (si.z - sj.z) + dij.z};
            const F4 len = simd::sqrt4(d.x * d.x + d.y * d.y + d.z * d.z);
            const F4 inv = len > zero ? one / len : zero;  // direction(): zero for a zero length
            const V3 n{d.x * inv, d.y * inv, d.z * inv};
            // glsl::implicit_spring_force
            const F4 f = F4(I4(-(k * (len - rest) + kd_h * (n.x * dij.x + n.y * dij.y + n.z * dij.z))) & on);
            r.x += f * n.x;
            r.y += f * n.y;
            r.z += f * n.z;
            if (kBlocks || kFrames) {
                // glsl::implicit_tension (clamped), implicit_block_along, SymMat3::add_outer
                const F4 t = one - rest / len;
                const F4 across = len > zero ? k * (zero < t ? t : zero) : zero;
                if (kFrames) {
                    const F4 rows[4] = {n.x, n.y, n.z, across};
                    for (uint32_t row = 0; row < 4; ++row)
                        std::memcpy(frames.at(s, row) + i, &rows[row], sizeof(F4));
                }
                if (kBlocks) {
                    iso += across;  // 0 where k is
                    const F4 along = F4(I4(k + kd_h - across) & on);
                    const V3 a{along * n.x, along * n.y, along * n.z};
                    diag.x += a.x * n.x;
                    diag.y += a.y * n.y;
                    diag.z += a.z * n.z;
                    off.x += a.x * n.y;
                    off.y += a.x * n.z;
                    off.z += a.y * n.z;
                }
            }
        }
        for (int l = 0; l < 4; ++l) {
            glm::vec3 rl(0.0f);
            if (wi[l] != 0.0f) {
                rl = glm::vec3(r.x[l], r.y[l], r.z[l]) -
                     (glm::vec3(di.x[l], di.y[l], di.z[l]) - glm::vec3(target[i + l])) * (inv_h2 / wi[l]);
                if (p) rp += double(glm::dot(rl, glm::vec3(p[i + l])));
                if (kBlocks) {
                    SymMat3 nn{glm::vec3(diag.x[l], diag.y[l], diag.z[l]), glm::vec3(off.x[l], off.y[l], off.z[l])};
                    nn.diag += iso[l];
                    block_inv[i + l] = nn.inverse();
                }
            } else if (kBlocks) {
                block_inv[i + l] = SymMat3();
            }
            residual[i + l] = Particle(rl, wi[l]);
        }
    }
#endif
    // The rest one by one, each particle's r.p added in order as the scalar kernel adds it.
    for (; i < end; ++i)
        rp += implicit_residual<kBlocks, kFrames>(c, disp, target, start, p, residual, i, i + 1, block_inv,
                                                  frames);
    return rp;
}

/// implicit_curvature (and its *shrink) on four particles at once, over the springs it counts
/// (springs): in SIMD lanes, each lane's sum in the scalar kernel's slot order (a padding slot adds
/// exactly +0: e never is -0), the particles' sums in order: the same bits.
inline double implicit_curvature_simd(const SubstepContext& c, const CountedSprings& springs, const Particle* disp,
                                      const Particle* start, const Particle* p, uint32_t begin, uint32_t end,
                                      float floor, float* shrink) {
    double sum = 0;
    uint32_t i = begin;
#if DRAPE_SIMD
    using simd::F4;
    using simd::I4;
    using simd::V3;
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    const F4 zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    F4 rate = zero;
    for (; i + 4 <= end; i += 4) {
        const uint32_t self[4] = {i, i + 1, i + 2, i + 3};
        const V3 di = simd::gather(disp, self);
        const V3 si = simd::gather(start, self);
        const V3 pi = simd::gather(p, self);
        const V3 xi{si.x + di.x, si.y + di.y, si.z + di.z};
        F4 e = zero;
        uint32_t max_count = 0;
        for (int l = 0; l < 4; ++l) {
            const float wi = disp[i + l].w;
            if (wi != 0.0f) e[l] = (pi.x[l] * pi.x[l] + pi.y[l] * pi.y[l] + pi.z[l] * pi.z[l]) * (inv_h2 / wi);
            max_count = springs.count[i + l] > max_count ? springs.count[i + l] : max_count;
        }
        for (uint32_t s = 0; s < max_count; ++s) {
            const size_t base = size_t(s) * c.stride + i;  // four consecutive slots (column-major)
            uint32_t j[4];
            F4 rest, k;
            std::memcpy(j, springs.index + base, sizeof j);
            std::memcpy(&rest, springs.rest + base, sizeof rest);
            std::memcpy(&k, springs.k + base, sizeof k);
            const I4 on = k > zero;
            const V3 dj = simd::gather(disp, j);
            const V3 sj = simd::gather(start, j);
            const V3 pj = simd::gather(p, j);
            const V3 d{xi.x - (sj.x + dj.x), xi.y - (sj.y + dj.y), xi.z - (sj.z + dj.z)};
            const F4 len = simd::sqrt4(d.x * d.x + d.y * d.y + d.z * d.z);
            const F4 inv = len > zero ? one / len : zero;  // direction(): zero for a zero length
            const V3 n{d.x * inv, d.y * inv, d.z * inv};
            const V3 dp{pi.x - pj.x, pi.y - pj.y, pi.z - pj.z};
            const F4 along = n.x * dp.x + n.y * dp.y + n.z * dp.z;
            const F4 t = one - rest / len;  // glsl::implicit_tension (clamped)
            const F4 across = len > zero ? k * (zero < t ? t : zero) : zero;
            const F4 term = (k + kd_h) * along * along + across * ((dp.x * dp.x + dp.y * dp.y + dp.z * dp.z) - along * along);
            e += F4(I4(term) & on);
            // 0 where the spring is not stretched (padding slots have rest > len = 0); not positive
            // where p does not shorten it.
            const F4 shortens = -along / (len - floor * rest);
            rate = simd::max4(rate, F4(I4(shortens) & (len >= rest)));
        }
        for (int l = 0; l < 4; ++l)
            if (disp[i + l].w != 0.0f) sum += double(e[l]);
    }
    for (int l = 0; l < 4; ++l) *shrink = std::max(*shrink, rate[l]);
#endif
    for (; i < end; ++i) sum += implicit_curvature(c, disp, start, p, i, i + 1, floor, shrink);
    return sum;
}

/// The CPU step's runaway check (CpuCloth::verify): true if a spring of particles [begin, end) has
/// |x_i - x_j|^2 above col_limit (per slot, column-major; +inf where unchecked, padding included) or
/// a NaN length. Four particles at once; each spring is seen from both ends.
inline bool overstretched(const SubstepContext& c, const float* col_limit, const Particle* x, uint32_t begin,
                          uint32_t end) {
    uint32_t i = begin;
#if DRAPE_SIMD
    using simd::F4;
    using simd::I4;
    using simd::V3;
    I4 over = {0, 0, 0, 0};
    for (; i + 4 <= end; i += 4) {
        const uint32_t self[4] = {i, i + 1, i + 2, i + 3};
        const V3 xi = simd::gather(x, self);
        uint32_t max_count = 0;
        for (int l = 0; l < 4; ++l) max_count = c.nbr_count[i + l] > max_count ? c.nbr_count[i + l] : max_count;
        for (uint32_t s = 0; s < max_count; ++s) {
            const size_t base = size_t(s) * c.stride + i;
            uint32_t j[4];
            F4 limit;
            std::memcpy(j, c.col_index + base, sizeof j);
            std::memcpy(&limit, col_limit + base, sizeof limit);
            const V3 xj = simd::gather(x, j);
            const V3 d{xi.x - xj.x, xi.y - xj.y, xi.z - xj.z};
            over |= ~(d.x * d.x + d.y * d.y + d.z * d.z <= limit);
        }
    }
    if (over[0] | over[1] | over[2] | over[3]) return true;
#endif
    for (; i < end; ++i)
        for (uint32_t s = 0; s < c.nbr_count[i]; ++s) {
            const size_t slot = size_t(s) * c.stride + i;
            const glm::vec3 d = glm::vec3(x[i]) - glm::vec3(x[c.col_index[slot]]);
            if (!(glm::dot(d, d) <= col_limit[slot])) return true;
        }
    return false;
}

}  // namespace drape::kernels
