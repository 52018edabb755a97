#include "backend/cpu/implicit_solve.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace drape {

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

void ImplicitSolve::factor(const NeighbourTable& nb, const drape_params& params, const Particle* x,
                           uint32_t n, float h) {
    // Rows of the free particles; kinematic ones enter only through the residual.
    std::vector<int> row(n, -1);
    free_.clear();
    for (uint32_t i = 0; i < n; ++i)
        if (x[i].w != 0.0f) {
            row[i] = int(free_.size());
            free_.push_back(i);
        }
    const double kd_h = double(params.damping) / h;
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(free_.size() * (nb.slots + 1));
    for (uint32_t i : free_) {
        double diag = 1.0 / (double(x[i].w) * h * h);
        for (uint32_t s = 0; s < nb.count[i]; ++s) {
            const uint8_t g = nb.group[size_t(i) * nb.slots + s];
            if (g >= DRAPE_GROUP_COUNT || !(params.stiffness[g] > 0)) continue;
            const double k = params.stiffness[g] + kd_h;
            diag += k;
            const int j = row[nb.index[size_t(i) * nb.slots + s]];
            if (j >= 0) entries.emplace_back(row[i], j, -k);
        }
        entries.emplace_back(row[i], row[i], diag);
    }
    const int m = int(free_.size());
    Eigen::SparseMatrix<double> a(m, m);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(a);  // AMD ordering
    // L in float, compressed columns with the diagonal first (Eigen's order); rows of the solve are
    // in the factor's permuted order: free particle f is row perm[f].
    const Eigen::SparseMatrix<double>& l = llt.matrixL().nestedExpression();
    col_.assign(l.outerIndexPtr(), l.outerIndexPtr() + m + 1);
    row_.assign(l.innerIndexPtr(), l.innerIndexPtr() + l.nonZeros());
    value_.assign(l.valuePtr(), l.valuePtr() + l.nonZeros());
    perm_.resize(m);
    for (int f = 0; f < m; ++f) perm_[f] = uint32_t(llt.permutationP().indices()[f]);
    rhs_.resize(m);
    h_ = h;
}

void ImplicitSolve::apply(const Particle* residual, Particle* iterate) {
    const uint32_t m = uint32_t(free_.size());
    for (uint32_t f = 0; f < m; ++f) rhs_[perm_[f]] = glm::vec3(residual[free_[f]]);
    solve_in_place(rhs_.data());
    for (uint32_t f = 0; f < m; ++f) iterate[free_[f]] += Particle(rhs_[perm_[f]], 0.0f);
}

void ImplicitSolve::solve_in_place(glm::vec3* y) const {
    // L L^T y' = y: forward by columns, then backward (three right-hand sides in one pass each).
    const uint32_t m = uint32_t(perm_.size());
    for (uint32_t j = 0; j < m; ++j) {
        const glm::vec3 yj = y[j] / value_[col_[j]];
        y[j] = yj;
        for (uint32_t k = col_[j] + 1; k < col_[j + 1]; ++k) y[row_[k]] -= value_[k] * yj;
    }
    for (uint32_t j = m; j-- > 0;) {
        glm::vec3 yj = y[j];
        for (uint32_t k = col_[j] + 1; k < col_[j + 1]; ++k) yj -= value_[k] * y[row_[k]];
        y[j] = yj / value_[col_[j]];
    }
}

}  // namespace drape
