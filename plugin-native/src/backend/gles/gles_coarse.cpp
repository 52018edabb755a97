#include "backend/gles/gles_coarse.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace drape::gles {
namespace {

/// A symmetric scalar matrix in rows: diagonal and the off-diagonal entries (column, value).
struct Rows {
    std::vector<double> diag;
    std::vector<std::vector<std::pair<uint32_t, double>>> off;
    std::vector<bool> free;  ///< takes part (level 0: not pinned)
};

Rows fine_matrix(const NeighbourTable& nb, const std::vector<float>& w, const float stiffness[DRAPE_GROUP_COUNT],
                 float damping, float h) {
    const uint32_t n = uint32_t(nb.count.size());
    Rows a;
    a.diag.assign(n, 0.0);
    a.off.resize(n);
    a.free.assign(n, false);
    for (uint32_t i = 0; i < n; ++i) {
        if (!(w[i] > 0)) continue;
        a.free[i] = true;
        a.diag[i] = 1.0 / (double(w[i]) * h * h) +  // the springs along their length (jacobi_step's block)
                    for_each_spring_coefficient(nb, stiffness, double(damping) / h, i, [&](uint32_t j, double k, size_t) {
                        if (w[j] > 0) a.off[i].push_back({j, -k});
                    });
    }
    return a;
}

/// Greedy aggregation over the graph of `a`: each node not yet taken seeds an aggregate and adds the
/// untaken neighbour most strongly tied to it, up to kAggregateSize; a seed left alone joins the
/// neighbouring aggregate it is most strongly tied to (up to kMaxMembers). Returns the parent of
/// every node (kNoNode where not free) and the aggregate count.
uint32_t aggregate(const Rows& a, std::vector<uint32_t>& parent) {
    const uint32_t n = uint32_t(a.diag.size());
    parent.assign(n, kNoNode);
    std::vector<uint32_t> size;
    std::vector<double> tie(n, 0.0);  // strength of each candidate's tie to the aggregate being built
    std::vector<uint32_t> candidates;
    for (uint32_t seed = 0; seed < n; ++seed) {
        if (!a.free[seed] || parent[seed] != kNoNode) continue;
        const uint32_t g = uint32_t(size.size());
        parent[seed] = g;
        size.push_back(1);
        candidates.clear();
        auto add_ties = [&](uint32_t i) {
            for (const auto& [j, v] : a.off[i]) {
                if (parent[j] != kNoNode) continue;
                if (tie[j] == 0.0) candidates.push_back(j);
                tie[j] += -v;
            }
        };
        add_ties(seed);
        while (size[g] < kAggregateSize) {
            uint32_t best = kNoNode;
            for (uint32_t j : candidates)
                if (parent[j] == kNoNode && (best == kNoNode || tie[j] > tie[best])) best = j;
            if (best == kNoNode) break;
            parent[best] = g;
            ++size[g];
            add_ties(best);
        }
        for (uint32_t j : candidates) tie[j] = 0.0;
        if (size[g] > 1) continue;
        // Alone: join the most strongly tied neighbouring aggregate with room.
        uint32_t join = kNoNode;
        double strongest = 0;
        for (const auto& [j, v] : a.off[seed])
            if (parent[j] != kNoNode && parent[j] != g && size[parent[j]] < kMaxMembers && -v > strongest) {
                strongest = -v;
                join = parent[j];
            }
        if (join != kNoNode) {
            parent[seed] = join;
            ++size[join];
            size.pop_back();
        }
    }
    return uint32_t(size.size());
}

/// A_c = P^T A P for the piecewise constant P of `parent`.
Rows galerkin(const Rows& a, const std::vector<uint32_t>& parent, uint32_t count) {
    Rows c;
    c.diag.assign(count, 0.0);
    c.off.resize(count);
    c.free.assign(count, true);
    std::vector<std::vector<std::pair<uint32_t, double>>> raw(count);
    for (uint32_t i = 0; i < uint32_t(a.diag.size()); ++i) {
        const uint32_t p = parent[i];
        if (p == kNoNode) continue;
        c.diag[p] += a.diag[i];
        for (const auto& [j, v] : a.off[i]) {
            const uint32_t q = parent[j];
            if (q == p)
                c.diag[p] += v;
            else if (q != kNoNode)
                raw[p].push_back({q, v});
        }
    }
    for (uint32_t p = 0; p < count; ++p) {
        std::sort(raw[p].begin(), raw[p].end());
        for (const auto& e : raw[p]) {
            if (!c.off[p].empty() && c.off[p].back().first == e.first)
                c.off[p].back().second += e.second;
            else
                c.off[p].push_back(e);
        }
    }
    return c;
}

/// Inverse of a small symmetric positive definite matrix (Gauss-Jordan, no pivoting needed).
std::vector<double> dense_inverse(const Rows& a) {
    const size_t n = a.diag.size();
    std::vector<double> m(n * n, 0.0), inv(n * n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        m[i * n + i] = a.diag[i];
        inv[i * n + i] = 1.0;
        for (const auto& [j, v] : a.off[i]) m[i * n + j] = v;
    }
    for (size_t c = 0; c < n; ++c) {
        const double p = 1.0 / m[c * n + c];
        for (size_t k = 0; k < n; ++k) {
            m[c * n + k] *= p;
            inv[c * n + k] *= p;
        }
        for (size_t r = 0; r < n; ++r) {
            if (r == c) continue;
            const double f = m[r * n + c];
            if (f == 0.0) continue;
            for (size_t k = 0; k < n; ++k) {
                m[r * n + k] -= f * m[c * n + k];
                inv[r * n + k] -= f * inv[c * n + k];
            }
        }
    }
    return inv;
}

uint32_t bits(float f) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
}

}  // namespace

CoarseHierarchy cook_coarse(const NeighbourTable& nb, const std::vector<float>& inverse_mass,
                            const float stiffness[DRAPE_GROUP_COUNT], float damping, float h, uint32_t tex_width) {
    CoarseHierarchy out;
    std::vector<Rows> mats{fine_matrix(nb, inverse_mass, stiffness, damping, h)};
    std::vector<std::vector<uint32_t>> parents;  // parents[l]: level l -> level l + 1
    auto free_count = [](const Rows& a) { return uint32_t(std::count(a.free.begin(), a.free.end(), true)); };
    while (free_count(mats.back()) > kCoarsestNodes) {
        std::vector<uint32_t> parent;
        const uint32_t count = aggregate(mats.back(), parent);
        if (count * 5 > free_count(mats.back()) * 4) break;  // stalled (a graph without ties)
        mats.push_back(galerkin(mats.back(), parent, count));
        parents.push_back(std::move(parent));
    }
    if (parents.empty() || mats.back().diag.size() > 4 * kCoarsestNodes)
        return out;  // none, or stalled large
    const uint32_t levels = uint32_t(mats.size());
    // Table layout: per level its node info and (l >= 1) members, then the entries, then the dense inverse.
    std::vector<uint32_t>& t = out.table;
    auto texel = [&t]() {
        t.insert(t.end(), 4, 0u);
        return uint32_t(t.size() / 4 - 1);
    };
    out.levels.resize(levels);
    uint32_t rows = 0;  // of the vector buffer
    for (uint32_t l = 0; l < levels; ++l) {
        CoarseLevel& L = out.levels[l];
        L.count = uint32_t(mats[l].diag.size());
        if (l == 0) continue;
        L.residual = rows * tex_width;
        rows += (L.count + tex_width - 1) / tex_width;
        L.correction = rows * tex_width;
        rows += (L.count + tex_width - 1) / tex_width;
    }
    out.vector_texels = rows * tex_width;
    for (uint32_t l = 0; l < levels; ++l) {
        CoarseLevel& L = out.levels[l];
        L.info = uint32_t(t.size() / 4);
        for (uint32_t c = 0; c < L.count; ++c) {
            const uint32_t at = texel();
            t[4 * at + 2] = l + 1 < levels ? parents[l][c] : kNoNode;
            t[4 * at + 3] = bits(float(mats[l].diag[c]));
        }
        if (l == 0) continue;
        L.members = uint32_t(t.size() / 4);
        const size_t first = t.size();
        t.insert(t.end(), size_t(L.count) * kMaxMembers, kNoNode);
        std::vector<uint32_t> filled(L.count, 0);
        for (uint32_t i = 0; i < out.levels[l - 1].count; ++i) {
            const uint32_t p = parents[l - 1][i];
            if (p != kNoNode) t[first + size_t(p) * kMaxMembers + filled[p]++] = i;
        }
    }
    // Off-diagonal entries of the levels the down pass smooths (1 .. levels - 2), each scaled by the
    // diagonal of its column: value A_cj / A_jj.
    for (uint32_t l = 1; l + 1 < levels; ++l) {
        const Rows& a = mats[l];
        for (uint32_t c = 0; c < out.levels[l].count; ++c) {
            const uint32_t info = out.levels[l].info + c;
            t[4 * info] = uint32_t(t.size() / 4);
            t[4 * info + 1] = uint32_t(a.off[c].size());
            for (const auto& [j, v] : a.off[c]) {
                const uint32_t at = texel();
                t[4 * at] = j;
                t[4 * at + 1] = bits(float(v / a.diag[j]));
            }
        }
    }
    const std::vector<double> inv = dense_inverse(mats.back());
    out.dense = uint32_t(t.size() / 4);
    for (double v : inv) t[4 * texel()] = bits(float(v));
    return out;
}

}  // namespace drape::gles
