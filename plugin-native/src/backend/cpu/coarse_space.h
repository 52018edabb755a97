// IMPLICIT's coarse space: the rigid motions of a few patches of the cloth, the second level of
// the solve's preconditioner (implicit_solve.h). A cloth swinging about its pins, or folding
// between two halves, turns its springs without stretching them: the spring Hessian H charges
// that only the masses and the tension across the springs, but the constant matrix A charges
// every spring its k in all directions, and per-particle blocks cannot make a motion coordinated
// over the whole cloth, so CG was left with it (bench part 'fall': the default fell 0.76 as far as
// MASS_SPRING at 1e5 N/m). The preconditioner adds z += G Hc^-1 G^T r, with G the patches'
// translations and small rotations (6 columns each) and Hc = G^T H G, assembled at the solve's
// iterate and factored densely (two-level additive Schwarz with rigid-body modes per aggregate as
// the coarse space, as in smoothed aggregation for elasticity: Vanek, Mandel and Brezina 1996).
// Patches are cells of the rest positions' bounding box, kCellsPerAxis along each axis that is at
// least a quarter of the longest.
#pragma once

#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "backend/cpu/kernels.h"
#include "core/topology.h"

namespace drape {

class CoarseSpace {
  public:
    using Particle = kernels::Particle;

    /// Patches over the free particles (x[i].w != 0). Allocates.
    void build(const Topology& topo, const Particle* x);
    uint32_t patch_count() const { return uint32_t(start_.size()) - 1; }

    // One solve's use, in this order; the per-patch calls may run on different threads.
    /// Patch p's rows of Hc at start + disp (H as kernels::implicit_curvature clamps it, plus the
    /// masses over h^2).
    void assemble(const kernels::SubstepContext& c, const Particle* start, const Particle* disp, uint32_t p);
    /// Factors Hc (Cholesky); false if it is not positive definite (then it must not be used).
    bool factor();
    /// Patch p's share of G^T r.
    void restrict_residual(const Particle* r, uint32_t p);
    /// a = Hc^-1 G^T r.
    void solve();
    /// The correction at particle i, G_i a (0 on kinematic particles).
    glm::vec3 at(uint32_t i) const {
        if (patch_[i] < 0) return glm::vec3(0.0f);
        const float* a = &motion_[size_t(patch_[i]) * kDof];
        return glm::vec3(a[0], a[1], a[2]) + glm::cross(glm::vec3(a[3], a[4], a[5]), offset_[i]);
    }

  private:
    static constexpr uint32_t kDof = 6;         ///< per patch: a translation and a rotation
    static constexpr int kCellsPerAxis = 2;     ///< see the file comment
    uint32_t dofs() const { return patch_count() * kDof; }

    std::vector<int32_t> patch_;     ///< per particle its patch, -1 if kinematic
    std::vector<uint32_t> start_;    ///< patch p's particles: member_[start_[p] .. start_[p + 1])
    std::vector<uint32_t> member_;
    std::vector<glm::vec3> offset_;  ///< per particle, x_i minus its patch's first particle, at assemble
    std::vector<double> matrix_;     ///< Hc, then its Cholesky factor (dense, row-major, lower part)
    std::vector<double> rhs_;        ///< G^T r, then Hc^-1 G^T r
    std::vector<float> motion_;      ///< Hc^-1 G^T r per patch: translation, rotation
};

}  // namespace drape
