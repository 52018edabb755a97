#include "backend/cpu/implicit_solve.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <numeric>
#include <type_traits>

#include "backend/cpu/kernels_simd.h"
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#elif defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace drape {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Entries of the Cholesky factor of the symmetric pattern a in its own order: the symbolic analysis
/// alone (elimination tree and column counts; SimplicialLLT keeps the counts protected).
size_t factor_entries(const SparseMatrix& a) {
    struct Symbolic : Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> {
        size_t entries(const SparseMatrix& m) {
            analyzePattern(m);
            return size_t(m_nonZerosPerCol.sum());
        }
    };
    return Symbolic().entries(a);
}

/// Per slot of the neighbour table, the particle between a bend spring's ends that A routes it through
/// (see ImplicitSolve::factor), or -1: one that is the other end of a structural or shear spring of both.
std::vector<int> bend_middles(const NeighbourTable& nb, const drape_params& params) {
    std::vector<int> via(nb.group.size(), -1);
    if (!(params.stiffness[DRAPE_GROUP_BEND] > 0)) return via;
    const uint32_t n = uint32_t(nb.count.size());
    auto short_spring = [&](uint32_t a, uint32_t b) {  // a structural or shear spring joins a and b
        for (uint32_t s = 0; s < nb.count[a]; ++s) {
            const size_t slot = size_t(a) * nb.slots + s;
            if (nb.index[slot] == b && nb.group[slot] < DRAPE_GROUP_BEND) return true;
        }
        return false;
    };
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < nb.count[i]; ++s) {
            const size_t slot = size_t(i) * nb.slots + s;
            if (nb.group[slot] != DRAPE_GROUP_BEND) continue;
            for (uint32_t t = 0; t < nb.count[i] && via[slot] < 0; ++t) {
                const size_t to = size_t(i) * nb.slots + t;
                if (nb.group[to] < DRAPE_GROUP_BEND && short_spring(nb.index[to], nb.index[slot])) via[slot] = int(nb.index[to]);
            }
        }
    return via;
}

/// for_each_spring_coefficient over the springs whose other end j is free (has a factor row), but those
/// routed through a middle (via); returns the sum of their k.
template <class Fn>
double for_each_coupling(const NeighbourTable& nb, const drape_params& params, const std::vector<int>& row,
                         const std::vector<int>& via, uint32_t i, double kd_h, Fn&& fn) {
    double sum = 0;
    for_each_spring_coefficient(nb, params.stiffness, kd_h, i, [&](uint32_t j, double k, size_t slot) {
        if (via[slot] >= 0) return;
        sum += k;
        if (row[j] >= 0) fn(j, k);
    });
    return sum;
}

using Lanes = ImplicitSolve::Lanes;

Lanes lanes(const glm::vec4& r) { return {{r.x, r.y, r.z, 0.0f}}; }
glm::vec3 vec3(const Lanes& a) { return glm::vec3(a.v[0], a.v[1], a.v[2]); }

// Four lanes in one SIMD register where there is one (SSE or NEON intrinsics; a plain array
// elsewhere). A SIMD multiply or add rounds each lane as a scalar one does, so the lanes hold the
// bits the scalar code would. GCC 12 kept plain four-lane loops scalar or vectorised them across
// entries, hence the intrinsics.
#if defined(__SSE2__) || defined(_M_X64)
using Reg = __m128;
Reg load(const Lanes& a) { return _mm_loadu_ps(a.v); }
void store(Lanes& a, Reg r) { _mm_storeu_ps(a.v, r); }
Reg mul(Reg a, Reg b) { return _mm_mul_ps(a, b); }
Reg add(Reg a, Reg b) { return _mm_add_ps(a, b); }
Reg sub(Reg a, Reg b) { return _mm_sub_ps(a, b); }
Reg splat(float x) { return _mm_set1_ps(x); }
template <int K>
Reg lane(Reg v) {  // lane K in all four (pshufd: no copy of v first, as shufps needs)
    return _mm_castsi128_ps(_mm_shuffle_epi32(_mm_castps_si128(v), _MM_SHUFFLE(K, K, K, K)));
}
#elif defined(__ARM_NEON)
using Reg = float32x4_t;
Reg load(const Lanes& a) { return vld1q_f32(a.v); }
void store(Lanes& a, Reg r) { vst1q_f32(a.v, r); }
Reg mul(Reg a, Reg b) { return vmulq_f32(a, b); }
Reg add(Reg a, Reg b) { return vaddq_f32(a, b); }
Reg sub(Reg a, Reg b) { return vsubq_f32(a, b); }
Reg splat(float x) { return vdupq_n_f32(x); }
template <int K>
Reg lane(Reg v) {
    return vdupq_laneq_f32(v, K);
}
#else
using Reg = Lanes;
Reg load(const Lanes& a) { return a; }
void store(Lanes& a, Reg r) { a = r; }
template <class Op>
Reg lanewise(Reg a, Reg b, Op op) {
    for (int l = 0; l < 4; ++l) a.v[l] = op(a.v[l], b.v[l]);
    return a;
}
Reg mul(Reg a, Reg b) { return lanewise(a, b, [](float x, float y) { return x * y; }); }
Reg add(Reg a, Reg b) { return lanewise(a, b, [](float x, float y) { return x + y; }); }
Reg sub(Reg a, Reg b) { return lanewise(a, b, [](float x, float y) { return x - y; }); }
Reg splat(float x) { return {{x, x, x, x}}; }
template <int K>
Reg lane(Reg v) {
    return splat(v.v[K]);
}
#endif

/// a minus (plus: kAdd) lane k of v times y[k] for k < W, k ascending, each product and sum rounded.
template <int W, bool kAdd = false>
Reg update(Reg a, Reg v, const Reg* y) {
    a = kAdd ? add(a, mul(lane<0>(v), y[0])) : sub(a, mul(lane<0>(v), y[0]));
    if constexpr (W > 1) a = kAdd ? add(a, mul(lane<1>(v), y[1])) : sub(a, mul(lane<1>(v), y[1]));
    if constexpr (W > 2) a = kAdd ? add(a, mul(lane<2>(v), y[2])) : sub(a, mul(lane<2>(v), y[2]));
    if constexpr (W > 3) a = kAdd ? add(a, mul(lane<3>(v), y[3])) : sub(a, mul(lane<3>(v), y[3]));
    return a;
}

/// Forward substitution's share of a group's W columns (values y) in its shared rows [b, e):
/// t[row - base] minus (plus: kAdd) value times y, column by column in ascending order, as
/// gathering along each row subtracted them.
template <int W, bool kAdd>
void scatter(Lanes* t, uint32_t base, const Reg* y, const uint32_t* rows, const Lanes* value, uint32_t b, uint32_t e) {
    for (uint32_t k = b; k < e; ++k) {
        Lanes& ti = t[rows[k] - base];
        store(ti, update<W, kAdd>(load(ti), load(value[k]), y));
    }
}

/// Back substitution's share of a group's shared rows [b, e), last first, in the W columns' sums
/// acc: acc[k] minus lane k of the row's values times its y.
template <int W>
void gather(Reg* acc, const Lanes* y, const uint32_t* rows, const Lanes* value, uint32_t b, uint32_t e) {
    for (uint32_t k = e; k-- > b;) {
        const Reg yi = load(y[rows[k]]);
        const Reg v = load(value[k]);
        acc[0] = sub(acc[0], mul(lane<0>(v), yi));
        if constexpr (W > 1) acc[1] = sub(acc[1], mul(lane<1>(v), yi));
        if constexpr (W > 2) acc[2] = sub(acc[2], mul(lane<2>(v), yi));
        if constexpr (W > 3) acc[3] = sub(acc[3], mul(lane<3>(v), yi));
    }
}

/// fn(std::integral_constant<int, W>) for W = width (1 to ImplicitSolve::kGroupWidth).
template <class Fn>
void with_width(uint32_t width, Fn&& fn) {
    static_assert(ImplicitSolve::kGroupWidth == 4, "one case per width");
    switch (width) {
        case 1: fn(std::integral_constant<int, 1>()); break;
        case 2: fn(std::integral_constant<int, 2>()); break;
        case 3: fn(std::integral_constant<int, 3>()); break;
        default: fn(std::integral_constant<int, 4>()); break;
    }
}

}  // namespace

bool ImplicitSolve::inputs_changed(const drape_params& params, const Particle* x, uint32_t n) {
    const size_t size = 4 + size_t(n);
    bool changed = key_.size() != size;
    key_.resize(size);
    auto set = [&](size_t k, float v) {
        if (key_[k] != v) changed = true;
        key_[k] = v;
    };
    for (int g = 0; g < DRAPE_GROUP_COUNT; ++g) set(size_t(g), params.stiffness[g]);
    set(3, params.damping);
    for (uint32_t i = 0; i < n; ++i) set(4 + i, x[i].w);
    return changed;
}

void ImplicitSolve::factor(const Topology& topo, const drape_params& params, const Particle* x, float h) {
    const uint32_t n = topo.particle_count;
    const NeighbourTable& nb = topo.nbr;
    const double kd_h = double(params.damping) / h;
    // Free particles; kinematic ones enter only through the residual. row: factor row, -1 if kinematic.
    std::vector<int> row(n, -1);
    const std::vector<int> via = bend_middles(nb, params);
    std::vector<uint32_t> free;
    for (uint32_t i = 0; i < n; ++i)
        if (x[i].w != 0.0f) {
            row[i] = 0;
            free.push_back(i);
        }
    // Dissection: halve the free particles along an axis of their rest positions (ties by index),
    // then move every particle of the second half that has a spring into the first into the
    // separator. part: 0, 1, or kParts for the separator. The axis: of those at least half as wide as
    // the widest (so the separator stays short), the one whose halves differ least from the halves of
    // the index order (ties: x, y, z), in the direction in which the index grows. The particle passes
    // split the index range between the threads (over_blocks; part p runs on thread p), so each thread
    // then has the same particles there as in the substitutions. Split across the index order, half of
    // the r and z that a thread reads were written in the other core's cache (a square grid split by
    // columns: 553 of r's 1056 cache lines per pass at 65^2; by rows 57).
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i : free) {
        lo = glm::min(lo, topo.rest_position[i]);
        hi = glm::max(hi, topo.rest_position[i]);
    }
    const glm::vec3 extent = hi - lo;
    const float widest = std::max(extent.x, std::max(extent.y, extent.z));
    const size_t half = free.size() / 2;
    std::vector<uint32_t> by_axis, split;
    size_t fewest = SIZE_MAX;
    int split_axis = 0;
    for (int axis = 0; axis < 3; ++axis) {
        if (extent[axis] < 0.5f * widest) continue;
        by_axis = free;
        std::stable_sort(by_axis.begin(), by_axis.end(), [&](uint32_t a, uint32_t b) {
            return topo.rest_position[a][axis] < topo.rest_position[b][axis];
        });
        // In the second half along the axis, the lower half by index (free is in index order).
        auto misplaced = [&] {
            size_t count = 0;
            for (size_t f = half; f < by_axis.size(); ++f) count += by_axis[f] < free[half];
            return count;
        };
        size_t other = misplaced();
        if (2 * other > by_axis.size() - half) {  // the index runs against the axis
            std::reverse(by_axis.begin(), by_axis.end());
            other = misplaced();
        }
        if (other < fewest) fewest = other, split_axis = axis, split.swap(by_axis);
    }
    std::vector<uint8_t> part(n, 0);
    for (size_t f = half; f < split.size(); ++f) part[split[f]] = 1;
    for (uint32_t i : free)
        for_each_coupling(nb, params, row, via, i, kd_h, [&](uint32_t j, double) {
            if (part[i] == 1 && part[j] == 0) part[i] = kParts;
            if (part[i] == 0 && part[j] == 1) part[j] = kParts;
        });
    // Each part (and the separator) in its own AMD order, parts first: rows in particle_. AMD breaks
    // ties by the members' labels, and the part's factor came out up to 10 % larger or smaller with the
    // same members labelled in another order (a grid's half labelled by rows or by columns), so each
    // part takes the labelling, by index or sorted along the cut, whose order gives it the smaller
    // factor (counted symbolically).
    const int cut_axis = split_axis == 0   ? (extent.y >= extent.z ? 1 : 2)
                         : split_axis == 1 ? (extent.x >= extent.z ? 0 : 2)
                                           : (extent.x >= extent.y ? 0 : 1);
    particle_.clear();
    std::vector<int> local(n, -1);
    for (int p = 0; p <= kParts; ++p) {
        begin_[p] = uint32_t(particle_.size());
        std::vector<uint32_t> members, best;
        for (uint32_t i : free)
            if (part[i] == p) members.push_back(i);
        size_t fewest_entries = SIZE_MAX;
        for (bool along_cut : {false, true}) {
            if (along_cut)
                std::stable_sort(members.begin(), members.end(), [&](uint32_t a, uint32_t b) {
                    return topo.rest_position[a][cut_axis] < topo.rest_position[b][cut_axis];
                });
            for (int k = 0; k < int(members.size()); ++k) local[members[k]] = k;
            std::vector<Eigen::Triplet<double>> pattern;
            for (uint32_t i : members) {
                pattern.emplace_back(local[i], local[i], 1.0);
                for_each_coupling(nb, params, row, via, i, kd_h, [&](uint32_t j, double) {
                    if (part[j] == p) pattern.emplace_back(local[i], local[j], 1.0);
                });
            }
            SparseMatrix sub(int(members.size()), int(members.size()));
            sub.setFromTriplets(pattern.begin(), pattern.end());
            Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
            Eigen::AMDOrdering<int>()(sub, order);  // order.indices()[k]: the member placed k-th
            std::vector<int> rank(members.size());
            for (int k = 0; k < int(members.size()); ++k) rank[order.indices()[k]] = k;
            for (Eigen::Triplet<double>& t : pattern)
                t = Eigen::Triplet<double>(rank[t.row()], rank[t.col()], 1.0);
            sub.setFromTriplets(pattern.begin(), pattern.end());
            const size_t entries = factor_entries(sub);
            if (entries >= fewest_entries) continue;
            fewest_entries = entries;
            best.clear();
            for (int k = 0; k < int(members.size()); ++k) best.push_back(members[order.indices()[k]]);
        }
        particle_.insert(particle_.end(), best.begin(), best.end());
    }
    begin_[kParts + 1] = uint32_t(particle_.size());
    const int m = int(particle_.size());
    for (int r = 0; r < m; ++r) row[particle_[r]] = r;

    // L from Eigen's factor of A in that order (no further ordering), kept by rows for the
    // substitutions, in float.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(size_t(m) * (nb.slots + 1));
    for (uint32_t i : free) {
        double diag = 1.0 / (double(x[i].w) * h * h) +
                      for_each_coupling(nb, params, row, via, i, kd_h, [&](uint32_t j, double k) {
                          entries.emplace_back(row[i], row[j], -k);
                      });
        // A bend spring i-j routed through its middle m: 2k on i-m here, 2k on m-j from j's row (or here,
        // if j is kinematic and has none).
        for_each_spring_coefficient(nb, params.stiffness, kd_h, i, [&](uint32_t j, double k, size_t slot) {
            const int mid = via[slot];
            if (mid < 0) return;
            diag += 2.0 * k;
            if (row[mid] < 0) return;
            entries.emplace_back(row[i], row[mid], -2.0 * k);
            entries.emplace_back(row[mid], row[i], -2.0 * k);
            entries.emplace_back(row[mid], row[mid], row[j] >= 0 ? 2.0 * k : 4.0 * k);
        });
        entries.emplace_back(row[i], row[i], diag);
    }
    SparseMatrix a(m, m);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> llt(a);
    const SparseMatrix& l = llt.matrixL().nestedExpression();  // by columns, the diagonal first
    // L by groups (supernodes of at most kGroupWidth columns, none across a part's end): column j
    // joins column j - 1's group when column j - 1's rows are j and then column j's.
    const int* outer = l.outerIndexPtr();
    const int* inner = l.innerIndexPtr();
    const double* value = l.valuePtr();
    auto joins = [&](int j) {  // column j may join column j - 1's group
        const int below = outer[j] - outer[j - 1] - 1;  // column j - 1's rows below its diagonal
        return below == outer[j + 1] - outer[j] && below > 0 && inner[outer[j - 1] + 1] == j &&
               std::equal(inner + outer[j - 1] + 2, inner + outer[j], inner + outer[j] + 1);
    };
    inv_diag_.resize(m);
    for (int j = 0; j < m; ++j) inv_diag_[j] = float(1.0 / value[outer[j]]);
    group_.clear();
    group_row_.clear();
    group_value_.clear();
    group_tri_.clear();
    const uint32_t sep = begin_[kParts];
    for (int p = 0; p <= kParts; ++p) {
        part_group_[p] = uint32_t(group_.size());
        for (uint32_t j = begin_[p]; j < begin_[p + 1];) {
            Group g{j, 1, uint32_t(group_row_.size()), 0, 0};
            while (g.width < kGroupWidth && j + g.width < begin_[p + 1] && joins(int(j + g.width))) ++g.width;
            const int last = int(j + g.width - 1);
            for (uint32_t k = 0; k < kGroupWidth; ++k) {  // the run's own triangle: L[j + k][j + kk], kk < k
                Lanes t{};
                for (uint32_t kk = 0; kk < k && k < g.width; ++kk) t.v[kk] = float(value[outer[j + kk] + 1 + (k - kk - 1)]);
                group_tri_.push_back(t);
            }
            for (int e = outer[last] + 1; e < outer[last + 1]; ++e) {
                const uint32_t r = uint32_t(inner[e]);
                assert(p == kParts || r >= sep || (r >= begin_[p] && r < begin_[p + 1]));  // the dissection holds
                Lanes v{};
                for (uint32_t k = 0; k < g.width; ++k)
                    v.v[k] = float(value[outer[j + k] + 1 + (g.width - 1 - k) + (e - outer[last] - 1)]);
                group_row_.push_back(r);
                group_value_.push_back(v);
                if (r < sep || p == kParts) g.part_end = uint32_t(group_row_.size());
            }
            g.end = uint32_t(group_row_.size());
            if (g.part_end < g.rows) g.part_end = g.rows;
            group_.push_back(g);
            j += g.width;
        }
    }
    part_group_[kParts + 1] = uint32_t(group_.size());
    h_ = h;
    const uint32_t sep_count = uint32_t(m) - sep;
    y_.resize(m);
    // Each part's sums in its own cache lines (64 bytes, 4 records; a line apart): the parts scatter
    // into them at once, and two cores writing one line pass it back and forth (false sharing).
    sep_stride_ = (sep_count + 3) / 4 * 4 + 4;
    sep_sum_.resize(size_t(sep_stride_) * kParts);
    for (std::vector<Particle>* v : {&r_, &r_prev_, &z_, &p_}) v->assign(n, Particle(0.0f));
    block_inv_.assign(n, kernels::SymMat3());
    carry_.assign(n, glm::vec3(0.0f));
    carried_.assign(n, glm::vec3(0.0f));
    col_k_.assign(size_t(n) * nb.slots, 0.0f);
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < nb.count[i]; ++s) {
            const uint8_t g = nb.group[size_t(i) * nb.slots + s];
            if (g < DRAPE_GROUP_COUNT && params.stiffness[g] > 0) col_k_[size_t(s) * n + i] = params.stiffness[g];
        }
    // The curvature pass's springs (kernels::CountedSprings), about half of the table: each once.
    uint32_t most = 0;
    counted_count_.assign(n, 0);
    auto counted = [&](uint32_t i, uint32_t s) {
        const size_t slot = size_t(i) * nb.slots + s;
        const uint32_t j = nb.index[slot];
        return x[i].w != 0.0f && col_k_[size_t(s) * n + i] > 0 && !(j < i && x[j].w != 0.0f);
    };
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t s = 0; s < nb.count[i]; ++s) counted_count_[i] += counted(i, s);
        most = std::max(most, counted_count_[i]);
    }
    counted_index_.resize(size_t(most) * n);
    counted_rest_.assign(size_t(most) * n, 1.0f);
    counted_k_.assign(size_t(most) * n, 0.0f);
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t t = 0;
        for (uint32_t s = 0; s < nb.count[i]; ++s)
            if (counted(i, s)) {
                const size_t slot = size_t(i) * nb.slots + s, to = size_t(t++) * n + i;
                counted_index_[to] = nb.index[slot];
                counted_rest_[to] = nb.rest[slot];
                counted_k_[to] = col_k_[size_t(s) * n + i];
            }
        for (; t < most; ++t) counted_index_[size_t(t) * n + i] = i;
    }
    frames_.assign(size_t(n) * nb.slots * 4, 0.0f);
    in_contact_.reserve(n);
    held_.assign(n, glm::vec3(0.0f));
    block_sum_.assign((n + kBlock - 1) / kBlock, 0.0);
    block_shrink_.assign(block_sum_.size(), 0.0f);
    coarse_.build(topo, x);
    levels_.build(topo, x);
    levels_fresh_ = false;
    blocks_fresh_ = false;
}

template <class Fn>
double ImplicitSolve::over_blocks(ThreadPool* pool, Fn&& fn) {
    const uint32_t n = uint32_t(r_.size()), blocks = uint32_t(block_sum_.size());
    auto run = [&](uint32_t first, uint32_t last) {
        for (uint32_t b = first; b < last; ++b) block_sum_[b] = fn(b * kBlock, std::min(n, (b + 1) * kBlock));
    };
    if (ThreadPool* threads = parallel(pool)) {
        threads->parallel_grains(blocks, kGrain, run);
    } else {
        run(0, blocks);
    }
    double sum = 0;
    for (double s : block_sum_) sum += s;
    return sum;
}

uint32_t ImplicitSolve::solve(const kernels::SubstepContext& c, const Particle* start, Particle* target,
                              Particle* iterate, uint32_t max_iterations, float tolerance, ThreadPool* pool,
                              const glm::vec3* contact_normal) {
    for (uint32_t i : in_contact_) held_[i] = glm::vec3(0.0f);
    in_contact_.clear();
    if (contact_normal)
        for (uint32_t i = 0; i < uint32_t(r_.size()); ++i)
            if (contact_normal[i] != glm::vec3(0.0f)) in_contact_.push_back(i);
    normal_ = in_contact_.empty() ? nullptr : contact_normal;
    // r at the iterate, and r . p when p is given (the line search's slope at the new point); with
    // blocks, also D (block_inv_) there, with frames the springs' frames_. At a contact that holds the
    // particle (pulled inwards, not moved outwards: held_) r loses its inward part (p has none, so
    // r.p loses that part's share).
    const kernels::SpringFrames frames{frames_.data(), c.stride};
    const kernels::CountedSprings counted{counted_count_.data(), counted_index_.data(), counted_rest_.data(),
                                          counted_k_.data()};
    auto residual = [&](const Particle* p, bool blocks = false, bool with_frames = false) {
        double rp = over_blocks(pool, [&](uint32_t b, uint32_t e) {
            if (blocks)
                return kernels::implicit_residual_simd<true>(c, col_k_.data(), iterate, target, start, p, r_.data(), b, e,
                                                             block_inv_.data());
            if (with_frames)
                return kernels::implicit_residual_simd<false, true>(c, col_k_.data(), iterate, target, start, p,
                                                                    r_.data(), b, e, nullptr, frames);
            return kernels::implicit_residual_simd(c, col_k_.data(), iterate, target, start, p, r_.data(), b, e);
        });
        for (uint32_t i : in_contact_) {
            const glm::vec3 n = normal_[i];
            const float inward = glm::dot(glm::vec3(r_[i]), n);
            const bool hold = inward < 0.0f && glm::dot(glm::vec3(iterate[i]), n) <= 0.0f;
            held_[i] = hold ? n : glm::vec3(0.0f);
            if (!hold) continue;
            r_[i] -= Particle(inward * n, 0.0f);
            if (p) rp -= double(inward) * double(glm::dot(n, glm::vec3(p[i])));
        }
        return rp;
    };
    auto move = [&](const std::vector<Particle>& direction, float step) {  // iterate += step direction
        over_blocks(pool, [&](uint32_t b, uint32_t e) {
            for (uint32_t i = b; i < e; ++i) iterate[i] += Particle(step * glm::vec3(direction[i]), 0.0f);
            return 0.0;
        });
    };
    // Converged when a step released less than tolerance^2 times the kinetic energy of the predicted
    // displacement y over the substep, sum m |y|^2 / (2 h^2) (inertia and external forces: at rest,
    // gravity's h^2 g). The step's release is that of one Newton step along p, alpha r.p / 2,
    // measured with the spring Hessian: r.z alone would rate a mode that A makes stiffer than it
    // is (a taut sheet's sag) by A's stiffness and stop long before that mode settles.
    // The same pass adds to target and first iterate what the last commit's rounding took from each
    // position (see the end).
    const float inv_h2 = 1.0f / (c.h * c.h);
    const double load = over_blocks(pool, [&](uint32_t b, uint32_t e) {
        double sum = 0;
        for (uint32_t i = b; i < e; ++i)
            if (target[i].w != 0.0f) {
                const Particle shift(carry_[i] - c.h_ratio * carried_[i], 0.0f);
                target[i] += shift;
                iterate[i] += shift;
                sum += double(glm::dot(glm::vec3(target[i]), glm::vec3(target[i])) * (inv_h2 / target[i].w));
            }
        return sum;
    });
    const double converged_release = double(tolerance) * double(tolerance) * load;
    // A single iteration has no next one to halve an overshoot, so it takes the plain step
    // d += A^-1 r: A alone bounds the clamped Hessian, so that step lowers Phi (D^-1 r with a Newton
    // step length does not: IMPLICIT 1x1 blew up in 5 of the 15 quick S1 cells with it), and it solves
    // the linear part (rigid motion, stretch along the load) at once. Not when A was built for a
    // longer substep (a fast collider added substeps): its mass term is then smaller than the
    // Hessian's.
    const bool plain_step = max_iterations == 1 && h_ < c.h * (1.0f + kImplicitRefactor);
    with_blocks_ = !plain_step;  // D comes with the first residual
    // D as the previous solve built or kept it, when that solve stopped after its first iteration (a
    // cloth at rest or nearly: it has barely moved since) at the same substep length and no collider
    // touched the cloth since: building D was ~8 % of a step at rest (65^2 curtain). At most
    // kKeepBlocks solves in a row, so that a cloth drifting slowly (swinging, turned with its owner)
    // gets it anew. D is only a preconditioner: a stale one changes the directions, not the minimum
    // the solve stops at.
    const bool keep_blocks =
        with_blocks_ && blocks_fresh_ && c.h == blocks_h_ && kept_ < kKeepBlocks && contact_normal == nullptr;
    kept_ = keep_blocks ? kept_ + 1 : 0;
    blocks_h_ = c.h;
    with_coarse_ = false;
    // The coarse levels as an earlier solve assembled them, when the previous solve used them and
    // not its whole budget: a cloth in mild motion or settled (a taut sheet ringing about its rest
    // state) has barely moved since, and its waves get their share from the first step, also in the
    // solves that stop after it (without them there, the 65^2 sheet at the user's drag rang at 2.7e-4
    // of its displacement at 3-4 s and 8.9e-4 at 4.5-5 s). Not after a solve that used the whole
    // budget (falling: the bench's falling sheet went from 0.09-0.11 of its size away from
    // MASS_SPRING to 0.13-0.17 with them).
    with_levels_ = with_blocks_ && levels_fresh_;
    // A second iteration then also keeps the coarse space and levels as they are, up to
    // kReuseSolves solves after their assembly (solves that start with them, one iteration or
    // more: a cloth pulled after a while at rest gets them anew): assembling them was a quarter of a
    // step in mild motion.
    const bool reuse = with_levels_ && reuses_ < kReuseSolves;
    if (reuse) ++reuses_;
    // Preconditioned nonlinear conjugate gradients: the first direction is z = P^-1 r, then
    // Polak-Ribiere (clamped at 0, which restarts on z), each with the step length of one Newton
    // step along the direction, alpha = r.p / p.Hp (Shewchuk 1994, "An introduction to the
    // conjugate gradient method without the agonizing pain", B5). Phi must not rise: by the
    // trapezoid rule along the last step, Phi(new) - Phi(old) = -alpha/2 (r_old.p + r_new.p); if that
    // is positive the step overshot, so it is halved until it is not (at most kMaxHalvings times) and
    // the directions restart. Once was not enough: the Hessian at a flat sheet does not see that moving
    // a pin's neighbour across its spring stretches it, so a stiff sheet's first step can overshoot by
    // orders of magnitude (8^2 at 1e9 N/m, 0.05 s substeps: Phi 0.006 -> 829 J; halved once, 63 J were
    // left in the springs after 4 iterations, where the cloth had 0.006 J to give). Every dot product
    // is fused into a pass that computes one of its factors.
    double rz_prev = 0, rp_prev = 0;
    float alpha = 1;
    uint32_t it = 0;
    while (it < max_iterations) {
        std::swap(r_, r_prev_);
        const bool first = it == 0;
        // Not converged in one iteration, so in motion: from here on the preconditioner adds the
        // coarse space and levels (coarse_space.h), assembled at this iterate from the springs' frames
        // that its residual passes write; a cloth at rest never pays for them.
        const bool second = it == 1 && with_blocks_, assemble = second && !reuse;
        double rp_new = residual(first ? nullptr : p_.data(), first && with_blocks_ && !keep_blocks, assemble);
        bool restart = first;
        if (!first && rp_prev + rp_new < 0) {
            float back = alpha;
            for (uint32_t h = 0; h < kMaxHalvings && rp_prev + rp_new < 0; ++h) {
                back *= 0.5f;
                move(p_, -back);
                rp_new = residual(p_.data(), false, assemble);
            }
            restart = true;
        }
        if (assemble) {
            over_items(pool, coarse_.patch_count(),
                       [&](uint32_t p) { coarse_.assemble(c, start, iterate, frames, p); });
            coarse_ok_ = coarse_.factor();
            over_items(pool, levels_.node_count(), [&](uint32_t a) { levels_.assemble_node(c, iterate, frames, a); });
            with_levels_ = levels_.factor(parallel(pool));
            reuses_ = 0;
        }
        if (second) {
            with_coarse_ = coarse_ok_;
            restart = true;
        }
        const Dots dots = precondition(r_.data(), r_prev_.data(), first ? p_.data() : z_.data(), pool);
        ++it;
        if (!(dots.rz > 0)) break;  // r = 0: at the minimum
        if (plain_step) {
            move(p_, 1.0f);
            break;
        }
        double rp = dots.rz;
        if (!first) {
            double beta = restart ? 0.0 : std::max(0.0, (dots.rz - dots.z_r_prev) / rz_prev);
            if (beta > 0) {
                rp = dots.rz + beta * rp_new;
                if (!(rp > 0)) beta = 0, rp = dots.rz;  // not downhill: restart
            }
            const float b = float(beta);
            over_blocks(pool, [&](uint32_t begin, uint32_t end) {
                for (uint32_t i = begin; i < end; ++i) p_[i] = z_[i] + b * p_[i];
                return 0.0;
            });
        }
        alpha = float(rp / over_blocks(pool, [&](uint32_t begin, uint32_t end) {
                          float& shrink = block_shrink_[begin / kBlock];
                          shrink = 0.0f;
                          return kernels::implicit_curvature_simd(c, counted, iterate, start, p_.data(), begin, end,
                                                                  kStepFloor, &shrink);
                      }));
        const float shrink = *std::max_element(block_shrink_.begin(), block_shrink_.end());
        if (alpha * shrink > 1.0f) alpha = 1.0f / shrink;  // no stretched spring below kStepFloor of its rest length
        move(p_, alpha);
        if (double(alpha) * rp <= converged_release) break;
        rz_prev = dots.rz;
        rp_prev = rp;
    }
    levels_fresh_ = with_levels_ && it < max_iterations;
    blocks_fresh_ = with_blocks_ && it == 1 && it < max_iterations;
    // The caller commits the positions start + d in floats, which rounds each coordinate by up to half
    // a float step (6e-8 m at 1 m): the springs' lengths change by about that, and their forces by k
    // times it, noise that the next solve's first step spent itself undoing (at rest 0.9-1.5 times
    // the tolerance's release at 129^2, growing with the particle count, so every solve took a
    // second iteration there). What the rounding takes (exactly: Knuth's TwoSum) is given back to
    // the next solve's target and first iterate, so that its springs see the unrounded positions
    // (the release at rest at 129^2 fell to 0.009 of the tolerance's), less its share of the
    // displacement that the caller keeps as the velocity (h_ratio times the carry this solve
    // received). What a later stage (collision, tethers) or a setter does to a position leaves the
    // carry stale by at most this half float step, as much as the rounding it replaces.
    over_blocks(pool, [&](uint32_t b, uint32_t e) {
        for (uint32_t i = b; i < e; ++i) {
            if (target[i].w == 0.0f) continue;
            const glm::vec3 a(start[i]), d(iterate[i]), sum = a + d, d_part = sum - a;
            carried_[i] = carry_[i];
            carry_[i] = (a - (sum - d_part)) + (d - d_part);
        }
        return 0.0;
    });
    return it;
}

template <class Fn>
void ImplicitSolve::over_items(ThreadPool* pool, uint32_t count, Fn&& fn) {
    if (ThreadPool* threads = parallel(pool)) {
        const uint32_t parts = threads->size();
        threads->run_on_all([&](uint32_t t) {
            for (uint32_t p = count * t / parts; p < count * (t + 1) / parts; ++p) fn(p);
        });
    } else {
        for (uint32_t p = 0; p < count; ++p) fn(p);
    }
}

ImplicitSolve::Dots ImplicitSolve::precondition(const Particle* r, const Particle* r_prev, Particle* z,
                                                ThreadPool* pool) {
    // Parts on their own threads (part p on thread p mod size), or one after the other: the same
    // arithmetic either way. Each part sums its rows' dot products in row order, the separator
    // last; the sums are added in part order.
    ThreadPool* threads = parallel(pool);
    auto each_part = [&](auto&& fn) {
        if (!threads) {
            for (int p = 0; p < kParts; ++p) fn(p);
            return;
        }
        threads->run_on_all([&](uint32_t t) {
            for (int p = 0; p < kParts; ++p)
                if (uint32_t(p) % threads->size() == t) fn(p);
        });
    };
    if (with_coarse_) {
        over_items(pool, coarse_.patch_count(), [&](uint32_t p) { coarse_.restrict_residual(r, p); });
        coarse_.solve();
    }
    if (with_levels_) levels_.apply(r, threads);
    each_part([&](int p) { forward_part(p, r); });
    separator(r, r_prev, z);
    each_part([&](int p) { part_dots_[p] = back_substitute(part_group_[p], part_group_[p + 1], r, r_prev, z); });
    Dots sum;
    for (const Dots& d : part_dots_) {
        sum.rz += d.rz;
        sum.z_r_prev += d.z_r_prev;
    }
    return sum;
}

void ImplicitSolve::forward_group(uint32_t g, Lanes* t, uint32_t base) {
    // The group's own rows (the earlier columns' shares are in y_ already), then its columns' shares
    // of its shared rows: the part's (or the separator's) in y_, a part's separator rows in t.
    const Group& gr = group_[g];
    const Lanes* tri = &group_tri_[size_t(g) * kGroupWidth];
    Reg y[kGroupWidth];
    for (uint32_t k = 0; k < gr.width; ++k) {
        Reg v = load(y_[gr.first + k]);
        for (uint32_t kk = 0; kk < k; ++kk) v = sub(v, mul(splat(tri[k].v[kk]), y[kk]));
        y[k] = mul(v, splat(inv_diag_[gr.first + k]));
        store(y_[gr.first + k], y[k]);
    }
    with_width(gr.width, [&](auto w) {
        constexpr int W = decltype(w)::value;
        scatter<W, false>(y_.data(), 0, y, group_row_.data(), group_value_.data(), gr.rows, gr.part_end);
        scatter<W, true>(t, base, y, group_row_.data(), group_value_.data(), gr.part_end, gr.end);
    });
}

void ImplicitSolve::forward_part(int p, const Particle* r) {
    // L y = r over the part's rows, and the part's share of each separator row's sum, group by group
    // (the same subtractions in the same order as gathering along each row).
    for (uint32_t row = begin_[p]; row < begin_[p + 1]; ++row) y_[row] = lanes(r[particle_[row]]);
    const uint32_t sep = begin_[kParts], sep_count = begin_[kParts + 1] - sep;
    Lanes* sum = &sep_sum_[size_t(p) * sep_stride_];
    std::fill(sum, sum + sep_count, Lanes{});
    for (uint32_t g = part_group_[p]; g < part_group_[p + 1]; ++g) forward_group(g, sum, sep);
}

void ImplicitSolve::separator(const Particle* r, const Particle* r_prev, Particle* z) {
    // Forward over the separator rows (the parts' shares summed in part order), then backward.
    const uint32_t sep = begin_[kParts], m = begin_[kParts + 1];
    for (uint32_t row = sep; row < m; ++row) {
        Lanes v = lanes(r[particle_[row]]);
        for (int p = 0; p < kParts; ++p)
            for (int l = 0; l < 4; ++l) v.v[l] -= sep_sum_[size_t(p) * sep_stride_ + (row - sep)].v[l];
        y_[row] = v;
    }
    for (uint32_t g = part_group_[kParts]; g < part_group_[kParts + 1]; ++g) forward_group(g, nullptr, 0);
    part_dots_[kParts] = back_substitute(part_group_[kParts], part_group_[kParts + 1], r, r_prev, z);
}

ImplicitSolve::Dots ImplicitSolve::back_substitute(uint32_t first, uint32_t last, const Particle* r,
                                                   const Particle* r_prev, Particle* z) {
    // L^T y' = y over groups [first, last), last first: a column's y' is its y less the shares of the
    // later rows it reaches (its own part's and the separator's, so the separator runs before the
    // parts), in the order in which scattering along the rows subtracted them: the shared rows last
    // first, then the group's own. z takes y' at each row's particle, with its dot products on the
    // way, rows last first.
    Dots dots;
    for (uint32_t g = last; g-- > first;) {
        const Group& gr = group_[g];
        const Lanes* tri = &group_tri_[size_t(g) * kGroupWidth];
        Reg acc[kGroupWidth];
        for (uint32_t k = 0; k < gr.width; ++k) acc[k] = load(y_[gr.first + k]);
        with_width(gr.width, [&](auto w) {
            gather<decltype(w)::value>(acc, y_.data(), group_row_.data(), group_value_.data(), gr.rows, gr.end);
        });
        for (uint32_t k = gr.width; k-- > 0;) {
            for (uint32_t kk = gr.width; --kk > k;) acc[k] = sub(acc[k], mul(splat(tri[kk].v[k]), acc[kk]));
            acc[k] = mul(acc[k], splat(inv_diag_[gr.first + k]));  // y' of the column
            Lanes y;
            store(y, acc[k]);
            y_[gr.first + k] = y;
            const glm::vec3 v = vec3(y);
            const uint32_t i = particle_[gr.first + k];
            glm::vec3 zi = with_blocks_ ? v + block_inv_[i] * glm::vec3(r[i]) : v;  // A^-1 r (+ D^-1 r)
            if (with_coarse_) zi += coarse_.at(i);
            if (with_levels_) zi += levels_.at(i);
            if (normal_) zi -= std::min(0.0f, glm::dot(zi, held_[i])) * held_[i];  // no step inwards at a contact
            z[i] = Particle(zi, 0.0f);
            dots.rz += double(glm::dot(zi, glm::vec3(r[i])));
            dots.z_r_prev += double(glm::dot(zi, glm::vec3(r_prev[i])));
        }
    }
    return dots;
}

}  // namespace drape
