#include "backend/cpu/coarse_space.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "backend/cpu/kernels_simd.h"

namespace drape {

namespace {

/// S(o) v = o x v.
glm::mat3 cross_matrix(const glm::vec3& o) { return glm::mat3(0, o.z, -o.y, -o.z, 0, o.x, o.y, -o.x, 0); }

/// In place, the lower part of the m x m row-major a becomes its Cholesky factor; false if a is not
/// positive definite (or m is 0).
bool dense_cholesky(double* a, uint32_t m) {
    for (uint32_t j = 0; j < m; ++j) {
        double* row_j = &a[size_t(j) * m];
        double d = row_j[j];
        for (uint32_t k = 0; k < j; ++k) d -= row_j[k] * row_j[k];
        if (!(d > 0)) return false;
        d = std::sqrt(d);
        row_j[j] = d;
        for (uint32_t i = j + 1; i < m; ++i) {
            double* row_i = &a[size_t(i) * m];
            double s = row_i[j];
            for (uint32_t k = 0; k < j; ++k) s -= row_i[k] * row_j[k];
            row_i[j] = s / d;
        }
    }
    return m > 0;
}

/// fn(begin, end) over [0, count) in pool->size() contiguous ranges, one per thread, or in one call
/// without a pool; fn's result per item must not depend on the split.
template <class Fn>
void over_ranges(ThreadPool* pool, uint32_t count, Fn&& fn) {
    if (!pool || pool->size() == 1) {
        fn(0u, count);
        return;
    }
    const uint32_t threads = pool->size();
    pool->run_on_all([&](uint32_t t) {
        fn(uint32_t(uint64_t(count) * t / threads), uint32_t(uint64_t(count) * (t + 1) / threads));
    });
}

/// b = (L L^T)^-1 b with dense_cholesky's L.
void dense_solve(const double* l, double* b, uint32_t m) {
    for (uint32_t i = 0; i < m; ++i) {
        double s = b[i];
        for (uint32_t k = 0; k < i; ++k) s -= l[size_t(i) * m + k] * b[k];
        b[i] = s / l[size_t(i) * m + i];
    }
    for (uint32_t i = m; i-- > 0;) {
        double s = b[i];
        for (uint32_t k = i + 1; k < m; ++k) s -= l[size_t(k) * m + i] * b[k];
        b[i] = s / l[size_t(i) * m + i];
    }
}

}  // namespace

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


void CoarseSpace::assemble(const kernels::SubstepContext& c, const Particle* start, const Particle* disp,
                           const kernels::SpringFrames& frames, uint32_t p) {
    // Row block p of Hc = G^T H G. With G_i = [I | -S(o_i)] (a translation t and rotation w move
    // particle i by t + w x o_i; o_i is x_i minus its patch's reference point, the patch's first
    // particle: any point spans the same rigid motions) and K_ij a spring's 3x3 block of H:
    // - mass:  G_i^T (m_i/h^2) G_i;
    // - a spring inside the patch moves only with the rotation, by -S(x_i - x_j) w; n is along
    //   x_i - x_j, so it adds T S(d)^T S(d) = T (|d|^2 I - d d^T) (T: its tension across; summed as
    //   sum T |d|^2 and sum T d d^T, symmetric, and added once);
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
    kernels::SymMat3 inside;  // the springs inside the patch: sum T d d^T, and in inside_tt sum T |d|^2
    float inside_tt = 0.0f;
    glm::mat3 move[kMaxPatches], turn[kMaxPatches];  // per patch q: sum of K_ij and of -K_ij S(o_j)
    for (uint32_t k = start_[p]; k < start_[p + 1]; ++k) {
        const uint32_t i = member_[k];
        const glm::vec3 xi = pos(i), oi = xi - ref[p];
        offset_[i] = oi;
        glm::mat3 own(inv_h2 / disp[i].w);  // masses, and springs leaving the patch
        uint32_t touched = 0;                // patches q != p with springs from i (bit q)
        kernels::for_active_slots(c, i, [&](uint32_t s, uint32_t j, float, float k) {
            const float across = frames.across(s, i);
            if (patch_[j] == int32_t(p)) {
                if (j > i) {
                    const glm::vec3 d = xi - pos(j);
                    inside.add_outer(across, d);
                    inside_tt += across * glm::dot(d, d);
                }
                return;
            }
            const glm::mat3 kij = kernels::glsl::implicit_spring_block(frames.n(s, i), k, kd_h, across);
            own += kij;
            if (patch_[j] < 0) return;  // kinematic: G_j = 0
            const uint32_t q = uint32_t(patch_[j]);
            const glm::vec3 xj = pos(j);
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
    const glm::vec3& o = inside.off;
    self_rr += glm::mat3(inside_tt) -
               glm::mat3(inside.diag.x, o.x, o.y, o.x, inside.diag.y, o.z, o.y, o.z, inside.diag.z);
    add(p, self_tt, self_tr, glm::transpose(self_tr), self_rr);
}

bool CoarseSpace::factor() { return dense_cholesky(matrix_.data(), dofs()); }

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
    dense_solve(matrix_.data(), rhs_.data(), dofs());
    for (uint32_t i = 0; i < dofs(); ++i) motion_[i] = float(rhs_[i]);
}

namespace {

CoarseLevels::Block block(const kernels::SymMat3& m) {
    return {{m.diag.x, m.diag.y, m.diag.z, m.off.x, m.off.y, m.off.z}};
}

glm::dmat3 matrix(const CoarseLevels::Block& b) {
    const double* v = b.v;
    return glm::dmat3(v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2]);
}

/// Index of column b in a row's sorted columns [begin, end) (it is there).
uint32_t find_column(const std::vector<uint32_t>& col, uint32_t begin, uint32_t end, uint32_t b) {
    return uint32_t(std::lower_bound(col.begin() + begin, col.begin() + end, b) - col.begin());
}

constexpr uint32_t kLanes = 4;  ///< nodes per group of the V-cycle's float copy (CoarseLevels::Level)

/// y = B x for the four nodes' symmetric blocks b (per component four lanes: xx, yy, zz, xy, xz, yz) and
/// x, four lanes each; y -= B x when kSubtract. Each lane does the same float operations in the same
/// order on either path.
template <bool kSubtract>
void block_product(const float* b, const float* x, float* y) {
#if DRAPE_SIMD
    using kernels::simd::F4;
    F4 c[6], v[3], out[3];
    std::memcpy(c, b, sizeof c);
    std::memcpy(v, x, sizeof v);
    std::memcpy(out, y, sizeof out);
    const F4 p[3] = {c[0] * v[0] + c[3] * v[1] + c[4] * v[2], c[3] * v[0] + c[1] * v[1] + c[5] * v[2],
                     c[4] * v[0] + c[5] * v[1] + c[2] * v[2]};
    for (int k = 0; k < 3; ++k) out[k] = kSubtract ? out[k] - p[k] : p[k];
    std::memcpy(y, out, sizeof out);
#else
    for (uint32_t l = 0; l < kLanes; ++l) {
        const float* c = b + l;
        const float v0 = x[l], v1 = x[kLanes + l], v2 = x[2 * kLanes + l];
        const float p[3] = {c[0] * v0 + c[12] * v1 + c[16] * v2, c[12] * v0 + c[4] * v1 + c[20] * v2,
                            c[16] * v0 + c[20] * v1 + c[8] * v2};
        for (uint32_t k = 0; k < 3; ++k) y[k * kLanes + l] = kSubtract ? y[k * kLanes + l] - p[k] : p[k];
    }
#endif
}

/// The four records at idx as x, y and z, four lanes each (out[3 * kLanes]).
void gather_lanes(const kernels::Particle* p, const uint32_t* idx, float* out) {
#if DRAPE_SIMD
    const kernels::simd::V3 v = kernels::simd::gather(p, idx);
    std::memcpy(out, &v, 3 * kLanes * sizeof(float));
#else
    for (uint32_t l = 0; l < kLanes; ++l)
        for (int k = 0; k < 3; ++k) out[k * kLanes + l] = p[idx[l]][k];
#endif
}

}  // namespace

void CoarseLevels::build(const Topology& topo, const Particle* x) {
    const uint32_t n = topo.particle_count;
    const NeighbourTable& nb = topo.nbr;
    levels_.clear();
    cell_.assign(n, -1);
    // Cell size: twice the mean structural rest length, so level 1 holds about 2 x 2 particles.
    double spacing = 0;
    uint32_t springs = 0;
    glm::vec3 lo(INFINITY);
    for (uint32_t i = 0; i < n; ++i) {
        if (x[i].w == 0.0f) continue;
        lo = glm::min(lo, topo.rest_position[i]);
        for (uint32_t s = 0; s < nb.count[i]; ++s)
            if (nb.group[size_t(i) * nb.slots + s] == DRAPE_GROUP_STRUCTURAL) {
                spacing += nb.rest[size_t(i) * nb.slots + s];
                ++springs;
            }
    }
    if (springs == 0 || !(spacing > 0)) return;
    const float cell = float(2.0 * spacing / springs);
    // Integer cell coordinates, a quarter cell off so that a grid's rows fall inside cells, not on
    // their borders; each level halves them. Nodes are numbered in the order of their first particle.
    std::vector<glm::ivec3> coord;
    std::map<std::array<int, 3>, uint32_t> node_of;
    auto node = [&](const glm::ivec3& k) {
        const auto [it, added] = node_of.insert({{k.x, k.y, k.z}, uint32_t(coord.size())});
        if (added) coord.push_back(k);
        return it->second;
    };
    for (uint32_t i = 0; i < n; ++i)
        if (x[i].w != 0.0f)
            cell_[i] = int32_t(node(glm::ivec3(glm::floor((topo.rest_position[i] - lo) / cell + 0.25f))));
    levels_.emplace_back();
    levels_[0].count = uint32_t(coord.size());
    member_start_.assign(levels_[0].count + 1, 0);
    for (uint32_t i = 0; i < n; ++i)
        if (cell_[i] >= 0) ++member_start_[cell_[i] + 1];
    for (uint32_t a = 0; a < levels_[0].count; ++a) member_start_[a + 1] += member_start_[a];
    member_.resize(member_start_.back());
    std::vector<uint32_t> fill(member_start_.begin(), member_start_.end() - 1);
    for (uint32_t i = 0; i < n; ++i)
        if (cell_[i] >= 0) member_[fill[cell_[i]]++] = i;
    // Level 1's pattern: the cells its members' springs reach.
    std::vector<std::vector<uint32_t>> reach(levels_[0].count);
    for (uint32_t i = 0; i < n; ++i)
        if (cell_[i] >= 0)
            for (uint32_t s = 0; s < nb.count[i]; ++s) {
                const int32_t b = cell_[nb.index[size_t(i) * nb.slots + s]];
                if (b >= 0 && b != cell_[i]) reach[cell_[i]].push_back(uint32_t(b));
            }
    // Coarser levels until kCoarsestNodes; each level's pattern is its finer level's, merged.
    while (true) {
        Level& level = levels_.back();
        level.row_start.assign(1, 0);
        level.col.clear();
        for (std::vector<uint32_t>& cols : reach) {
            std::sort(cols.begin(), cols.end());
            cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
            level.col.insert(level.col.end(), cols.begin(), cols.end());
            level.row_start.push_back(uint32_t(level.col.size()));
        }
        level.diag.assign(level.count, Block());
        level.off.assign(level.col.size(), Block());
        level.diag_inv.assign(level.count, Block());
        const uint32_t padded = (level.count + kLanes - 1) / kLanes * kLanes;
        for (std::vector<Particle>* v : {&level.r, &level.e, &level.t}) v->assign(padded, Particle(0.0f));
        if (level.count <= kCoarsestNodes) break;
        const std::vector<glm::ivec3> fine = std::move(coord);
        coord.clear();
        node_of.clear();
        level.parent.resize(level.count);
        for (uint32_t a = 0; a < level.count; ++a) level.parent[a] = node(fine[a] >> 1);
        if (coord.size() == level.count) break;  // no coarser
        std::vector<std::vector<uint32_t>> coarse(coord.size());
        for (uint32_t a = 0; a < level.count; ++a)
            for (uint32_t e = level.row_start[a]; e < level.row_start[a + 1]; ++e)
                if (level.parent[level.col[e]] != level.parent[a])
                    coarse[level.parent[a]].push_back(level.parent[level.col[e]]);
        reach = std::move(coarse);
        levels_.emplace_back();
        Level& next = levels_.back();
        next.count = uint32_t(coord.size());
        const Level& below = levels_[levels_.size() - 2];
        next.child_start.assign(next.count + 1, 0);
        for (uint32_t a = 0; a < below.count; ++a) ++next.child_start[below.parent[a] + 1];
        for (uint32_t p = 0; p < next.count; ++p) next.child_start[p + 1] += next.child_start[p];
        next.child.resize(below.count);
        std::vector<uint32_t> put(next.child_start.begin(), next.child_start.end() - 1);
        for (uint32_t a = 0; a < below.count; ++a) next.child[put[below.parent[a]]++] = a;
    }
    levels_.back().parent.clear();
    for (size_t l = 0; l + 1 < levels_.size(); ++l) {  // the V-cycle's float copy (the coarsest is solved densely)
        Level& level = levels_[l];
        level.width = 1;
        for (uint32_t a = 0; a < level.count; ++a)
            level.width = std::max(level.width, 1 + level.row_start[a + 1] - level.row_start[a]);
        const uint32_t groups = uint32_t(level.r.size()) / kLanes;
        level.cycle_col.resize(size_t(groups) * level.width * kLanes);
        for (uint32_t a = 0; a < groups * kLanes; ++a)
            for (uint32_t s = 0; s < level.width; ++s) {
                const uint32_t e = a < level.count ? level.row_start[a] + s - 1 : 0;
                const bool off = s > 0 && a < level.count && e < level.row_start[a + 1];
                level.cycle_col[(size_t(a / kLanes) * level.width + s) * kLanes + a % kLanes] = off ? level.col[e] : a;
            }
        level.cycle_block.assign(size_t(groups) * level.width * 6 * kLanes, 0.0f);
        level.cycle_inv.assign(size_t(groups) * 6 * kLanes, 0.0f);
    }
    const Level& first = levels_[0];
    slot_off_.assign(size_t(n) * nb.slots, kInside);
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < nb.count[i] && cell_[i] >= 0; ++s) {
            const uint32_t a = uint32_t(cell_[i]);
            const int32_t b = cell_[nb.index[size_t(i) * nb.slots + s]];
            int32_t& to = slot_off_[size_t(i) * nb.slots + s];
            if (b < 0)
                to = kKinematic;
            else if (b != int32_t(a))
                to = int32_t(find_column(first.col, first.row_start[a], first.row_start[a + 1], uint32_t(b)));
        }
    const uint32_t m = 3 * levels_.back().count;
    dense_.assign(size_t(m) * m, 0.0);
    dense_rhs_.assign(m, 0.0);
}

void CoarseLevels::assemble_node(const kernels::SubstepContext& c, const Particle* disp,
                                 const kernels::SpringFrames& frames, uint32_t a) {
    // Row a of H_1 = P_1^T H P_1: per member i its mass over h^2 and, per spring to a particle j outside
    // the cell, its block K_ij on the diagonal and -K_ij at j's cell (none to a kinematic j). A spring
    // inside the cell moves with it: no share.
    Level& level = levels_[0];
    const float kd_h = c.damping / c.h;
    const float inv_h2 = 1.0f / (c.h * c.h);
    for (uint32_t e = level.row_start[a]; e < level.row_start[a + 1]; ++e) level.off[e] = Block();
    kernels::SymMat3 diag;  // float: the same sums as the residual's blocks
    for (uint32_t m = member_start_[a]; m < member_start_[a + 1]; ++m) {
        const uint32_t i = member_[m];
        const int32_t* to = &slot_off_[size_t(i) * c.slots];
        diag.diag += inv_h2 / disp[i].w;
        kernels::for_active_slots(c, i, [&](uint32_t s, uint32_t, float, float k) {
            if (to[s] == kInside) return;
            const float across = frames.across(s, i);
            kernels::SymMat3 kij;  // glsl::implicit_spring_block
            kij.add_outer(kernels::glsl::implicit_block_along(k, kd_h, across), frames.n(s, i));
            kij.diag += across;
            diag.diag += kij.diag;
            diag.off += kij.off;
            if (to[s] >= 0) level.off[uint32_t(to[s])].add(block(kij), -1);
        });
    }
    level.diag[a] = block(diag);
}

bool CoarseLevels::factor(ThreadPool* pool) {
    if (levels_.empty()) return false;
    // H_l+1 = P^T H_l P, row by row of H_l+1 (rows on different threads): its children's blocks, in
    // ascending order; a block between two children to the diagonal. Each child's smoother inverse
    // on the way.
    for (size_t l = 0; l + 1 < levels_.size(); ++l) {
        Level& fine = levels_[l];
        Level& coarse = levels_[l + 1];
        over_ranges(fine.count >= kMinParallelNodes ? pool : nullptr, coarse.count, [&](uint32_t begin, uint32_t end) {
            for (uint32_t p = begin; p < end; ++p) {
                Block& diag = coarse.diag[p] = Block();
                const uint32_t row = coarse.row_start[p], row_end = coarse.row_start[p + 1];
                std::fill(coarse.off.begin() + row, coarse.off.begin() + row_end, Block());
                for (uint32_t c = coarse.child_start[p]; c < coarse.child_start[p + 1]; ++c) {
                    const uint32_t a = coarse.child[c];
                    diag.add(fine.diag[a]);
                    for (uint32_t e = fine.row_start[a]; e < fine.row_start[a + 1]; ++e) {
                        const uint32_t q = fine.parent[fine.col[e]];
                        if (q == p)
                            diag.add(fine.off[e]);
                        else
                            coarse.off[find_column(coarse.col, row, row_end, q)].add(fine.off[e]);
                    }
                    const glm::dmat3 inv = glm::inverse(matrix(fine.diag[a]));
                    fine.diag_inv[a] = {{inv[0][0], inv[1][1], inv[2][2], inv[1][0], inv[2][0], inv[2][1]}};
                }
            }
        });
    }
    for (size_t l = 0; l + 1 < levels_.size(); ++l) {  // the V-cycle's float copy
        Level& level = levels_[l];
        auto put = [&](std::vector<float>& to, size_t group_entry, uint32_t lane, const Block& b) {
            for (int k = 0; k < 6; ++k) to[(group_entry * 6 + k) * kLanes + lane] = float(b.v[k]);
        };
        for (uint32_t a = 0; a < level.count; ++a) {
            const size_t g = a / kLanes;
            const uint32_t lane = a % kLanes;
            put(level.cycle_block, g * level.width, lane, level.diag[a]);
            for (uint32_t e = level.row_start[a]; e < level.row_start[a + 1]; ++e)
                put(level.cycle_block, g * level.width + 1 + (e - level.row_start[a]), lane, level.off[e]);
            put(level.cycle_inv, g, lane, level.diag_inv[a]);
        }
    }
    const Level& last = levels_.back();
    const uint32_t m = 3 * last.count;
    std::fill(dense_.begin(), dense_.end(), 0.0);
    auto put = [&](uint32_t a, uint32_t b, const Block& block) {
        const glm::dmat3 full = matrix(block);
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row) dense_[size_t(3 * a + row) * m + 3 * b + col] = full[col][row];
    };
    for (uint32_t a = 0; a < last.count; ++a) {
        put(a, a, last.diag[a]);
        for (uint32_t e = last.row_start[a]; e < last.row_start[a + 1]; ++e) put(a, last.col[e], last.off[e]);
    }
    return dense_cholesky(dense_.data(), m);
}

void CoarseLevels::apply(const Particle* r, ThreadPool* pool) {
    Level& level = levels_[0];
    over_ranges(level.count >= kMinParallelNodes ? pool : nullptr, level.count, [&](uint32_t begin, uint32_t end) {
        for (uint32_t a = begin; a < end; ++a) {
            glm::vec3 sum(0.0f);
            for (uint32_t k = member_start_[a]; k < member_start_[a + 1]; ++k) sum += glm::vec3(r[member_[k]]);
            level.r[a] = Particle(sum, 0.0f);
        }
    });
    cycle(0, pool);
}

void CoarseLevels::cycle(size_t l, ThreadPool* pool) {
    // Group by group of kLanes nodes on the pool (each node's value does not depend on the split),
    // except the restriction's sums (a few additions per node) and the coarsest solve.
    Level& level = levels_[l];
    if (l + 1 == levels_.size()) {
        for (uint32_t a = 0; a < level.count; ++a)
            for (int k = 0; k < 3; ++k) dense_rhs_[3 * a + k] = level.r[a][k];
        dense_solve(dense_.data(), dense_rhs_.data(), 3 * level.count);
        for (uint32_t a = 0; a < level.count; ++a)
            level.e[a] = Particle(float(dense_rhs_[3 * a]), float(dense_rhs_[3 * a + 1]), float(dense_rhs_[3 * a + 2]), 0.0f);
        return;
    }
    const uint32_t groups = uint32_t(level.r.size()) / kLanes;
    auto each_group = [&](auto&& fn) {
        over_ranges(level.count >= kMinParallelNodes ? pool : nullptr, groups, [&](uint32_t begin, uint32_t end) {
            for (uint32_t g = begin; g < end; ++g) fn(g);
        });
    };
    auto store = [&](std::vector<Particle>& to, uint32_t g, const float* v) {
        for (uint32_t l = 0; l < kLanes; ++l)
            to[g * kLanes + l] = Particle(v[l], v[kLanes + l], v[2 * kLanes + l], 0.0f);
    };
    // t = r - H_l e
    auto residual = [&](uint32_t g) {
        float t[3 * kLanes], e[3 * kLanes];
        gather_lanes(level.r.data(), &level.cycle_col[size_t(g) * level.width * kLanes], t);  // entry 0: the nodes
        for (uint32_t s = 0; s < level.width; ++s) {
            const size_t entry = size_t(g) * level.width + s;
            gather_lanes(level.e.data(), &level.cycle_col[entry * kLanes], e);
            block_product<true>(&level.cycle_block[entry * 6 * kLanes], e, t);
        }
        store(level.t, g, t);
    };
    // e (+)= kSmoothing D_l^-1 v
    auto smooth = [&](uint32_t g, const std::vector<Particle>& v, bool add) {
        float x[3 * kLanes], y[3 * kLanes];
        gather_lanes(v.data(), &level.cycle_col[size_t(g) * level.width * kLanes], x);
        block_product<false>(&level.cycle_inv[size_t(g) * 6 * kLanes], x, y);
        for (uint32_t l = 0; l < kLanes; ++l) {
            Particle& e = level.e[g * kLanes + l];
            const Particle step(kSmoothing * y[l], kSmoothing * y[kLanes + l], kSmoothing * y[2 * kLanes + l], 0.0f);
            e = add ? e + step : step;
        }
    };
    Level& coarse = levels_[l + 1];
    each_group([&](uint32_t g) { smooth(g, level.r, false); });
    each_group(residual);
    std::fill(coarse.r.begin(), coarse.r.end(), Particle(0.0f));
    for (uint32_t a = 0; a < level.count; ++a) coarse.r[level.parent[a]] += level.t[a];
    cycle(l + 1, pool);
    each_group([&](uint32_t g) {
        for (uint32_t a = g * kLanes; a < std::min(level.count, (g + 1) * kLanes); ++a) level.e[a] += coarse.e[level.parent[a]];
    });
    each_group(residual);
    each_group([&](uint32_t g) { smooth(g, level.t, true); });
}

}  // namespace drape
