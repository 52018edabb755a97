// Double-precision reference for the benchmark: static equilibrium of a spring grid (the same
// 12-neighbour stencil, rest lengths, masses and pins as a drape grid cloth) by Newton's method
// on the total energy E(x) = sum_s k_s/2 (|x_i - x_j| - L_s)^2 - sum_i m_i g.x_i, with a sparse
// LDL^T of the (projected, positive semi-definite) Hessian and a backtracking line search.
// Independent of the library: it only knows the stencil documented in drape.h.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
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
inline std::vector<RefSpring> grid_springs(uint32_t cols, uint32_t rows, double du, double dv, const double k[3]) {
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
                out.push_back({r * cols + c, uint32_t(rr) * cols + uint32_t(cc), k[o.g], std::sqrt(dx * dx + dy * dy)});
            }
    return out;
}

/// Largest |strain| over the springs at positions x, leaving out those of stiffness bend_k (drape's
/// max_strain covers the structural and shear springs).
inline double max_strain(const std::vector<double>& x, const std::vector<RefSpring>& springs, double bend_k) {
    double worst = 0;
    for (const RefSpring& s : springs) {
        if (s.k == bend_k) continue;
        const double d[3] = {x[3 * s.i] - x[3 * s.j], x[3 * s.i + 1] - x[3 * s.j + 1], x[3 * s.i + 2] - x[3 * s.j + 2]};
        worst = std::max(worst, std::fabs(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / s.rest - 1));
    }
    return worst;
}

/// Minimises the energy from x (3 doubles per particle, updated in place). mass[i] = 0 pins i.
/// Returns the final max-norm of the gradient over free particles (N).
inline double solve_static(std::vector<double>& x, const std::vector<double>& mass, const std::vector<RefSpring>& springs,
                           const double g[3], int max_newton = 200) {
    const int n = int(mass.size());
    std::vector<int> dof(n, -1);
    int nd = 0;
    for (int i = 0; i < n; ++i)
        if (mass[i] > 0) dof[i] = 3 * nd++;
    nd *= 3;  // unknowns: xyz of every free particle
    auto energy = [&](const std::vector<double>& p) {
        double e = 0;
        for (const RefSpring& s : springs) {
            double d[3] = {p[3 * s.i] - p[3 * s.j], p[3 * s.i + 1] - p[3 * s.j + 1], p[3 * s.i + 2] - p[3 * s.j + 2]};
            double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            e += 0.5 * s.k * (l - s.rest) * (l - s.rest);
        }
        for (int i = 0; i < n; ++i)
            if (mass[i] > 0) e -= mass[i] * (g[0] * p[3 * i] + g[1] * p[3 * i + 1] + g[2] * p[3 * i + 2]);
        return e;
    };
    double gnorm = INFINITY;
    for (int it = 0; it < max_newton; ++it) {
        Eigen::VectorXd grad = Eigen::VectorXd::Zero(nd);
        std::vector<Eigen::Triplet<double>> trip;
        trip.reserve(springs.size() * 36);
        for (int i = 0; i < n; ++i)
            if (dof[i] >= 0)
                for (int a = 0; a < 3; ++a) grad[dof[i] + a] -= mass[i] * g[a];
        for (const RefSpring& s : springs) {
            Eigen::Vector3d d(x[3 * s.i] - x[3 * s.j], x[3 * s.i + 1] - x[3 * s.j + 1], x[3 * s.i + 2] - x[3 * s.j + 2]);
            double l = d.norm();
            Eigen::Vector3d u = d / l;
            Eigen::Vector3d f = s.k * (l - s.rest) * u;  // dE/dx_i
            // Hessian block k [u u^T + max(0, 1 - L/l)(I - u u^T)]: the geometric part is dropped
            // for compressed springs so the matrix stays positive semi-definite (projected Newton).
            Eigen::Matrix3d uu = u * u.transpose();
            Eigen::Matrix3d h = s.k * (uu + std::max(0.0, 1.0 - s.rest / l) * (Eigen::Matrix3d::Identity() - uu));
            int di = dof[s.i], dj = dof[s.j];
            for (int a = 0; a < 3; ++a) {
                if (di >= 0) grad[di + a] += f[a];
                if (dj >= 0) grad[dj + a] -= f[a];
                for (int b = 0; b < 3; ++b) {
                    if (di >= 0) trip.emplace_back(di + a, di + b, h(a, b));
                    if (dj >= 0) trip.emplace_back(dj + a, dj + b, h(a, b));
                    if (di >= 0 && dj >= 0) {
                        trip.emplace_back(di + a, dj + b, -h(a, b));
                        trip.emplace_back(dj + a, di + b, -h(a, b));
                    }
                }
            }
        }
        gnorm = grad.lpNorm<Eigen::Infinity>();
        if (gnorm < 1e-11) break;
        Eigen::SparseMatrix<double> H(nd, nd);
        H.setFromTriplets(trip.begin(), trip.end());
        // A tiny diagonal shift keeps the factorisation defined where the projected matrix is
        // singular (out-of-plane directions of a planar, unstretched patch).
        for (int k = 0; k < nd; ++k) H.coeffRef(k, k) += 1e-9 * (1.0 + H.coeff(k, k));
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
        if (ldlt.info() != Eigen::Success) break;
        Eigen::VectorXd step = ldlt.solve(-grad);
        const double e0 = energy(x);
        const double slope = grad.dot(step);
        double t = 1.0;
        std::vector<double> trial(x);
        for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
            for (int i = 0; i < n; ++i)
                if (dof[i] >= 0)
                    for (int a = 0; a < 3; ++a) trial[3 * i + a] = x[3 * i + a] + t * step[dof[i] + a];
            if (energy(trial) <= e0 + 1e-4 * t * slope + 1e-13 * std::fabs(e0) || ls == 39) break;
        }
        x.swap(trial);
    }
    return gnorm;
}

}  // namespace bench
