#include "backend/cpu/coarse_space.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace drape {

void CoarseSpace::build(const Topology& topo, const Particle* x) {
    const uint32_t n = topo.particle_count;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i = 0; i < n; ++i)
        if (x[i].w != 0.0f) {
            lo = glm::min(lo, topo.rest_position[i]);
            hi = glm::max(hi, topo.rest_position[i]);
        }
    const glm::vec3 extent = glm::max(hi - lo, glm::vec3(0.0f));
    const float longest = std::max(extent.x, std::max(extent.y, extent.z));
    int cells[3];
    for (int a = 0; a < 3; ++a) cells[a] = longest > 0 && extent[a] >= 0.25f * longest ? kCellsPerAxis : 1;
    std::vector<int32_t> cell_patch(size_t(cells[0]) * cells[1] * cells[2], -1);
    patch_.assign(n, -1);
    uint32_t patches = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (x[i].w == 0.0f) continue;
        size_t cell = 0;
        for (int a = 0; a < 3; ++a) {
            const int k = cells[a] == 1 ? 0
                                        : std::min(cells[a] - 1,
                                                   int((topo.rest_position[i][a] - lo[a]) / extent[a] * float(cells[a])));
            cell = cell * size_t(cells[a]) + size_t(k);
        }
        if (cell_patch[cell] < 0) cell_patch[cell] = int32_t(patches++);
        patch_[i] = cell_patch[cell];
    }
    start_.assign(patches + 1, 0);
    for (uint32_t i = 0; i < n; ++i)
        if (patch_[i] >= 0) ++start_[patch_[i] + 1];
    for (uint32_t p = 0; p < patches; ++p) start_[p + 1] += start_[p];
    member_.resize(start_[patches]);
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (uint32_t i = 0; i < n; ++i)
        if (patch_[i] >= 0) member_[fill[patch_[i]]++] = i;
    offset_.assign(n, glm::vec3(0.0f));
    matrix_.assign(size_t(dofs()) * dofs(), 0.0);
    rhs_.assign(dofs(), 0.0);
    motion_.assign(dofs(), 0.0f);
}

namespace {

/// S(o) v = o x v.
glm::mat3 cross_matrix(const glm::vec3& o) { return glm::mat3(0, o.z, -o.y, -o.z, 0, o.x, o.y, -o.x, 0); }

}  // namespace

void CoarseSpace::assemble(const kernels::SubstepContext& c, const Particle* start, const Particle* disp, uint32_t p) {
    // Row block p of Hc = G^T H G. With G_i = [I | -S(o_i)] (a translation t and rotation w move
    // particle i by t + w x o_i; o_i is x_i minus its patch's reference point, the patch's first
    // particle: any point spans the same rigid motions) and K_ij a spring's 3x3 block of H:
    // - mass:  G_i^T (m_i/h^2) G_i;
    // - a spring inside the patch moves only with the rotation, by -S(x_i - x_j) w; n is along
    //   x_i - x_j, so it adds T S(d)^T S(d) = T (|d|^2 I - d d^T) (T: its tension across);
    // - a spring to a kinematic particle or another patch q: G_i^T K_ij G_i to block pp, and, from
    //   this end, -G_i^T K_ij G_j to block pq (q's rows take the other end's share).
    constexpr uint32_t kMaxPatches = kCellsPerAxis * kCellsPerAxis * kCellsPerAxis;
    const uint32_t m = dofs(), patches = patch_count();
    auto pos = [&](uint32_t i) { return glm::vec3(start[i]) + glm::vec3(disp[i]); };
    glm::vec3 ref[kMaxPatches];
    for (uint32_t q = 0; q < patches; ++q) ref[q] = pos(member_[start_[q]]);
    double* rows = &matrix_[size_t(p) * kDof * m];
    std::fill(rows, rows + size_t(kDof) * m, 0.0);
    // rows' 6x6 block at column block q += [[tt, tr], [rt, rr]].
    auto add = [&](uint32_t q, const glm::mat3& tt, const glm::mat3& tr, const glm::mat3& rt, const glm::mat3& rr) {
        double* block = rows + size_t(q) * kDof;
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row) {
                block[size_t(row) * m + col] += double(tt[col][row]);
                block[size_t(row) * m + 3 + col] += double(tr[col][row]);
                block[size_t(3 + row) * m + col] += double(rt[col][row]);
                block[size_t(3 + row) * m + 3 + col] += double(rr[col][row]);
            }
    };
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    glm::mat3 self_tt(0.0f), self_tr(0.0f), self_rr(0.0f);  // block pp (its rt is tr^T)
    glm::mat3 move[kMaxPatches], turn[kMaxPatches];  // per patch q: sum of K_ij and of -K_ij S(o_j)
    for (uint32_t k = start_[p]; k < start_[p + 1]; ++k) {
        const uint32_t i = member_[k];
        const glm::vec3 xi = pos(i), oi = xi - ref[p];
        offset_[i] = oi;
        glm::mat3 own(inv_h2 / disp[i].w);  // masses, and springs leaving the patch
        uint32_t touched = 0;                // patches q != p with springs from i (bit q)
        kernels::for_active_springs(c, i, [&](uint32_t j, float rest, float k) {
            const glm::vec3 xj = pos(j), d = xi - xj;
            float len;
            const glm::vec3 n = kernels::direction(d, &len);
            const float across = kernels::glsl::implicit_tension(len, rest, k, false);
            if (patch_[j] == int32_t(p)) {
                if (j > i) self_rr += across * (glm::mat3(glm::dot(d, d)) - glm::outerProduct(d, d));
                return;
            }
            const glm::mat3 kij = kernels::glsl::implicit_spring_block(n, k, kd_h, across);
            own += kij;
            if (patch_[j] < 0) return;  // kinematic: G_j = 0
            const uint32_t q = uint32_t(patch_[j]);
            if (!(touched & (1u << q))) {
                touched |= 1u << q;
                move[q] = turn[q] = glm::mat3(0.0f);
            }
            move[q] += kij;
            turn[q] -= kij * cross_matrix(xj - ref[q]);
        });
        const glm::mat3 s = cross_matrix(oi), own_r = -(own * s);
        self_tt += own;
        self_tr += own_r;
        self_rr += s * own_r;
        for (uint32_t q = 0; q < patches; ++q)
            if (touched & (1u << q)) add(q, -move[q], -turn[q], -(s * move[q]), -(s * turn[q]));
    }
    add(p, self_tt, self_tr, glm::transpose(self_tr), self_rr);
}

bool CoarseSpace::factor() {
    const uint32_t m = dofs();
    for (uint32_t j = 0; j < m; ++j) {
        double* row_j = &matrix_[size_t(j) * m];
        double d = row_j[j];
        for (uint32_t k = 0; k < j; ++k) d -= row_j[k] * row_j[k];
        if (!(d > 0)) return false;
        d = std::sqrt(d);
        row_j[j] = d;
        for (uint32_t i = j + 1; i < m; ++i) {
            double* row_i = &matrix_[size_t(i) * m];
            double s = row_i[j];
            for (uint32_t k = 0; k < j; ++k) s -= row_i[k] * row_j[k];
            row_i[j] = s / d;
        }
    }
    return m > 0;
}

void CoarseSpace::restrict_residual(const Particle* r, uint32_t p) {
    double* out = &rhs_[size_t(p) * kDof];
    std::fill(out, out + kDof, 0.0);
    for (uint32_t k = start_[p]; k < start_[p + 1]; ++k) {
        const uint32_t i = member_[k];
        const glm::vec3 ri(r[i]), torque = glm::cross(offset_[i], ri);
        for (int a = 0; a < 3; ++a) {
            out[a] += double(ri[a]);
            out[3 + a] += double(torque[a]);
        }
    }
}

void CoarseSpace::solve() {
    const uint32_t m = dofs();
    for (uint32_t i = 0; i < m; ++i) {
        double s = rhs_[i];
        for (uint32_t k = 0; k < i; ++k) s -= matrix_[size_t(i) * m + k] * rhs_[k];
        rhs_[i] = s / matrix_[size_t(i) * m + i];
    }
    for (uint32_t i = m; i-- > 0;) {
        double s = rhs_[i];
        for (uint32_t k = i + 1; k < m; ++k) s -= matrix_[size_t(k) * m + i] * rhs_[k];
        rhs_[i] = s / matrix_[size_t(i) * m + i];
        motion_[i] = float(rhs_[i]);
    }
}

}  // namespace drape
