// Double-precision reference for the benchmark: static equilibrium of a spring grid (the same
// 12-neighbour stencil, rest lengths, masses and pins as a drape grid cloth) by Newton's method
// on the total energy E(x) = sum_s k_s/2 (|x_i - x_j| - L_s)^2 - sum_i m_i g.x_i, with a sparse
// LDL^T of the (projected, positive semi-definite) Hessian and a backtracking line search.
// Independent of the library: it only knows the stencil documented in drape.h.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace bench {

struct RefSpring {
    uint32_t i, j;
    double k, rest;
};

/// Springs of a cols x rows grid with spacing du, dv (drape.h: structural (+-1,0),(0,+-1);
/// shear (+-1,+-1); bend (+-2,0),(0,+-2)); stiffness per group, groups with k = 0 left out.
inline std::vector<RefSpring> grid_springs(uint32_t cols, uint32_t rows, double du, double dv,
                                           const double k[3]) {
    struct Off {
        int dc, dr, g;
    };
    static const Off offs[] = {{1, 0, 0}, {0, 1, 0}, {1, 1, 1}, {-1, 1, 1}, {2, 0, 2}, {0, 2, 2}};
    std::vector<RefSpring> out;
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t c = 0; c < cols; ++c)
            for (const Off& o : offs) {
                int cc = int(c) + o.dc, rr = int(r) + o.dr;
                if (cc < 0 || cc >= int(cols) || rr >= int(rows) || k[o.g] <= 0) continue;
                double dx = o.dc * du, dy = o.dr * dv;
                out.push_back(
                    {r * cols + c, uint32_t(rr) * cols + uint32_t(cc), k[o.g], std::sqrt(dx * dx + dy * dy)});
            }
    return out;
}

/// Largest |strain| over the springs at positions x, leaving out those of stiffness bend_k (drape's
/// max_strain covers the structural and shear springs).
inline double max_strain(const std::vector<double>& x, const std::vector<RefSpring>& springs, double bend_k) {
    double worst = 0;
    for (const RefSpring& s : springs) {
        if (s.k == bend_k) continue;
        const double d[3] = {x[3 * s.i] - x[3 * s.j], x[3 * s.i + 1] - x[3 * s.j + 1],
                             x[3 * s.i + 2] - x[3 * s.j + 2]};
        worst = std::max(worst, std::fabs(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / s.rest - 1));
    }
    return worst;
}

/// A start for the Newton solve of a fine n x n grid from the solution of a coarser m x m grid of
/// the same cloth (rows of the same extent): the coarse displacement from its rest pose,
/// interpolated bilinearly at each fine vertex's (u, v), added to the fine rest pose `x`. Solving
/// 17^2, 33^2, ... in turn this way leaves a few Newton iterations per size instead of tens from
/// a flat start.
inline void add_coarse_displacement(std::vector<double>& x, uint32_t n, const std::vector<double>& coarse,
                                    const std::vector<double>& coarse_rest, uint32_t m) {
    for (uint32_t r = 0; r < n; ++r)
        for (uint32_t c = 0; c < n; ++c) {
            const double u = double(c) * (m - 1) / (n - 1), v = double(r) * (m - 1) / (n - 1);
            const uint32_t c0 = std::min(uint32_t(u), m - 2), r0 = std::min(uint32_t(v), m - 2);
            const double fu = u - c0, fv = v - r0;
            const double w[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
            const uint32_t at[4] = {r0 * m + c0, r0 * m + c0 + 1, (r0 + 1) * m + c0, (r0 + 1) * m + c0 + 1};
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < 4; ++k)
                    x[3 * (size_t(r) * n + c) + a] +=
                        w[k] * (coarse[3 * size_t(at[k]) + a] - coarse_rest[3 * size_t(at[k]) + a]);
        }
}

/// What a Newton solve took (solve_static's optional out-parameter).
struct SolveStats {
    int newton = 0, factorisations = 0, cg = 0;  ///< iterations, LDL^T factorisations, CG iterations
};

/// Minimises the energy from x (3 doubles per particle, updated in place). mass[i] = 0 pins i.
/// Returns the final max-norm of the gradient over free particles (N); it stops below 1e-11 N.
///
/// Each Newton step solves with the exact Hessian when it is positive definite (near the minimum,
/// so convergence ends quadratic) and otherwise with the projected one (compressed springs'
/// geometric part dropped). Projected alone converged linearly (x0.85 per iteration) on a sheet
/// whose equilibrium has compressed springs: 112 iterations at 33^2.
///
/// The step comes from conjugate gradients to 1e-6 of the gradient's norm, preconditioned by a
/// sparse LDL^T of the Hessian at an earlier iterate, refactorised only when CG needs about a
/// factorisation's work: from a start interpolated from the size below the Hessian changes
/// little over the solve, and one factorisation of a 257^2 grid (198k unknowns) takes minutes
/// (Eigen's simplicial LDL^T, the only one here) while a CG iteration takes about a second.
///
/// The Hessian's sparsity pattern is that of the spring list, the same every iteration: it is
/// built and ordered (Eigen's analyzePattern, AMD) once, and each iteration only refills the
/// values through per-spring slots and factorises numerically. Re-analysing per iteration made
/// the 129^2 sheet take minutes.
inline double solve_static(std::vector<double>& x, const std::vector<double>& mass,
                           const std::vector<RefSpring>& springs, const double g[3], SolveStats* stats = nullptr,
                           int max_newton = 200) {
    const int n = int(mass.size());
    std::vector<int> dof(n, -1);
    int nd = 0;
    for (int i = 0; i < n; ++i)
        if (mass[i] > 0) dof[i] = 3 * nd++;
    nd *= 3;  // unknowns: xyz of every free particle
    auto energy = [&](const std::vector<double>& p) {
        double e = 0;
        for (const RefSpring& s : springs) {
            double d[3] = {p[3 * s.i] - p[3 * s.j], p[3 * s.i + 1] - p[3 * s.j + 1],
                           p[3 * s.i + 2] - p[3 * s.j + 2]};
            double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            e += 0.5 * s.k * (l - s.rest) * (l - s.rest);
        }
        for (int i = 0; i < n; ++i)
            if (mass[i] > 0) e -= mass[i] * (g[0] * p[3 * i] + g[1] * p[3 * i + 1] + g[2] * p[3 * i + 2]);
        return e;
    };
    // Pattern: the diagonal blocks of free particles and both off-diagonal blocks of each spring
    // between two free particles. slot[s][b] is the value index of entry (a, c) = (b / 3, b % 3)
    // of the spring's block ii, jj, ij or ji (-1 where a particle is pinned).
    Eigen::SparseMatrix<double> H(nd, nd);
    {
        std::vector<Eigen::Triplet<double>> trip;
        trip.reserve(springs.size() * 36 + size_t(nd));
        for (int k = 0; k < nd; ++k) trip.emplace_back(k, k, 0.0);
        for (const RefSpring& s : springs) {
            const int di = dof[s.i], dj = dof[s.j];
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) {
                    if (di >= 0) trip.emplace_back(di + a, di + b, 0.0);
                    if (dj >= 0) trip.emplace_back(dj + a, dj + b, 0.0);
                    if (di >= 0 && dj >= 0) {
                        trip.emplace_back(di + a, dj + b, 0.0);
                        trip.emplace_back(dj + a, di + b, 0.0);
                    }
                }
        }
        H.setFromTriplets(trip.begin(), trip.end());
        H.makeCompressed();
    }
    auto index_of = [&](int row, int col) {  // value index of (row, col), which is in the pattern
        const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
        const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
        return int(std::lower_bound(begin, end, row) - H.innerIndexPtr());
    };
    std::vector<std::array<int, 36>> slot(springs.size());
    for (size_t k = 0; k < springs.size(); ++k) {
        const int di = dof[springs[k].i], dj = dof[springs[k].j];
        for (int b = 0; b < 9; ++b) {
            const int a = b / 3, c = b % 3;
            slot[k][b] = di >= 0 ? index_of(di + a, di + c) : -1;
            slot[k][9 + b] = dj >= 0 ? index_of(dj + a, dj + c) : -1;
            slot[k][18 + b] = di >= 0 && dj >= 0 ? index_of(di + a, dj + c) : -1;
            slot[k][27 + b] = di >= 0 && dj >= 0 ? index_of(dj + a, di + c) : -1;
        }
    }
    std::vector<int> diagonal(static_cast<size_t>(nd));
    for (int k = 0; k < nd; ++k) diagonal[size_t(k)] = index_of(k, k);
    // The preconditioner P: H's entries between equal axes (row and column dof % 3 equal), so
    // its LDL^T falls apart into three grids of one unknown per particle. from[k]: H's value
    // index of P's k-th value (both in column order).
    Eigen::SparseMatrix<double> P(nd, nd);
    std::vector<int> from;
    {
        std::vector<Eigen::Triplet<double>> trip;
        for (int col = 0; col < nd; ++col)
            for (int k = H.outerIndexPtr()[col]; k < H.outerIndexPtr()[col + 1]; ++k)
                if (H.innerIndexPtr()[k] % 3 == col % 3) {
                    trip.emplace_back(H.innerIndexPtr()[k], col, 0.0);
                    from.push_back(k);
                }
        P.setFromTriplets(trip.begin(), trip.end());
        P.makeCompressed();
    }
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    ldlt.analyzePattern(P);
    double* value = H.valuePtr();

    double gnorm = INFINITY;
    std::vector<double> trial(x);
    Eigen::VectorXd grad(nd);
    // Gradient into grad and Hessian into H's values, at x.
    auto assemble = [&](bool projected) {
        grad.setZero();
        std::fill(value, value + H.nonZeros(), 0.0);
        for (int i = 0; i < n; ++i)
            if (dof[i] >= 0)
                for (int a = 0; a < 3; ++a) grad[dof[i] + a] -= mass[i] * g[a];
        for (size_t k = 0; k < springs.size(); ++k) {
            const RefSpring& s = springs[k];
            Eigen::Vector3d d(x[3 * s.i] - x[3 * s.j], x[3 * s.i + 1] - x[3 * s.j + 1],
                              x[3 * s.i + 2] - x[3 * s.j + 2]);
            double l = d.norm();
            Eigen::Vector3d u = d / l;
            Eigen::Vector3d f = s.k * (l - s.rest) * u;  // dE/dx_i
            // Hessian block k [u u^T + (1 - L/l)(I - u u^T)]; projected, the geometric part is
            // dropped for compressed springs so the matrix stays positive semi-definite.
            Eigen::Matrix3d uu = u * u.transpose();
            const double geometric = 1.0 - s.rest / l;
            Eigen::Matrix3d h = s.k * (uu + (projected ? std::max(0.0, geometric) : geometric) *
                                                (Eigen::Matrix3d::Identity() - uu));
            int di = dof[s.i], dj = dof[s.j];
            for (int a = 0; a < 3; ++a) {
                if (di >= 0) grad[di + a] += f[a];
                if (dj >= 0) grad[dj + a] -= f[a];
            }
            for (int b = 0; b < 9; ++b) {
                const double hb = h(b / 3, b % 3);
                if (slot[k][b] >= 0) value[slot[k][b]] += hb;
                if (slot[k][9 + b] >= 0) value[slot[k][9 + b]] += hb;
                if (slot[k][18 + b] >= 0) value[slot[k][18 + b]] -= hb;
                if (slot[k][27 + b] >= 0) value[slot[k][27 + b]] -= hb;
            }
        }
        // A tiny diagonal shift keeps the factorisation defined where the projected matrix is
        // singular (out-of-plane directions of a planar, unstretched patch).
        for (int k = 0; k < nd; ++k) value[diagonal[size_t(k)]] += 1e-9 * (1.0 + value[diagonal[size_t(k)]]);
    };
    SolveStats st;
    // CG iterations allowed before refactorising: about what a factorisation costs, counted as
    // sum over L's columns of count^2 flops, against 2 nnz(L) + nnz(H) per CG iteration.
    int max_cg = 0;
    // The preconditioner: H as assembled (exact, or projected where the exact one is not
    // positive definite), factorised.
    auto factor = [&] {
        auto factorize = [&] {
            ++st.factorisations;
            for (size_t k = 0; k < from.size(); ++k) P.valuePtr()[k] = value[from[k]];
            ldlt.factorize(P);
        };
        factorize();
        if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 0) {
            assemble(true);
            factorize();
        }
        const auto& L = ldlt.matrixL().nestedExpression();
        double cost = 0;
        for (int c = 0; c < nd; ++c) cost += std::pow(double(L.outerIndexPtr()[c + 1] - L.outerIndexPtr()[c]), 2);
        max_cg = int(std::clamp(cost / (2.0 * L.nonZeros() + H.nonZeros()), 2.0, 1000.0));
        return ldlt.info() == Eigen::Success;
    };
    // H step = -grad by CG preconditioned with P's factor, to 1e-6 of |grad|: its iterations,
    // -1 on a direction of non-positive curvature (H not positive definite), limit + 1 if not
    // converged within limit.
    Eigen::VectorXd step(nd), r(nd), z(nd), p(nd), hp(nd);
    auto pcg = [&](int limit) {
        step.setZero();
        r = -grad;
        z = ldlt.solve(r);
        p = z;
        double rz = r.dot(z);
        const double tol = 1e-6 * grad.norm();
        for (int k = 1; k <= limit; ++k) {
            ++st.cg;
            hp.noalias() = H * p;
            const double php = p.dot(hp);
            if (!(php > 0)) return -1;
            step += (rz / php) * p;
            r -= (rz / php) * hp;
            if (r.norm() <= tol) return k;
            z = ldlt.solve(r);
            const double rz1 = r.dot(z);
            p = z + (rz1 / rz) * p;
            rz = rz1;
        }
        return limit + 1;
    };
    // The step with the exact Hessian, or the projected one where the exact one is not positive
    // definite; CG's iterations.
    auto newton_step = [&](int limit) {
        const int k = pcg(limit);
        if (k >= 0) return k;
        assemble(true);
        return pcg(limit);
    };
    constexpr int kMaxCg = 10000;
    int fresh = 0;  // CG iterations of the step right after the last factorisation
    for (int it = 0; it < max_newton; ++it) {
        assemble(false);
        gnorm = grad.lpNorm<Eigen::Infinity>();
        if (gnorm < 1e-11) break;
        ++st.newton;
        int k = it > 0 ? newton_step(fresh + max_cg) : -1;
        if (k < 0 || k > fresh + max_cg) {  // no factor yet, or a stale one: factorise this H
            if (!factor()) break;
            fresh = k = newton_step(kMaxCg);
            if (k < 0 || k > kMaxCg) break;
        }
        const double e0 = energy(x);
        const double slope = grad.dot(step);
        double t = 1.0;
        for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
            for (int i = 0; i < n; ++i)
                if (dof[i] >= 0)
                    for (int a = 0; a < 3; ++a) trial[3 * i + a] = x[3 * i + a] + t * step[dof[i] + a];
            if (energy(trial) <= e0 + 1e-4 * t * slope + 1e-13 * std::fabs(e0) || ls == 39) break;
        }
        x.swap(trial);
    }
    if (stats) *stats = st;
    return gnorm;
}

}  // namespace bench
