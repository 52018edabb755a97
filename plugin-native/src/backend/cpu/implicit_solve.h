// The IMPLICIT model's linear solve: A = M/h^2 + sum_springs (k + kd/h) (e_i - e_j)(e_i - e_j)^T
// over the free particles (kinematic ones enter only through the residual), factored once by a
// sparse Cholesky and applied to the residual of each iteration (CpuCloth::implicit_substep).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "backend/cpu/kernels.h"
#include "core/topology.h"
#include "drape/drape.h"

namespace drape {

class ImplicitSolve {
  public:
    using Particle = kernels::Particle;

    /// True when stiffness, damping or an inverse mass (x[i].w) differ from those of the last
    /// factor (or there is none): the matrix must be rebuilt. Remembers the new values.
    bool inputs_changed(const drape_params& params, const Particle* x, uint32_t n);
    /// Forgets the inputs, so that the next inputs_changed is true.
    void clear() { key_.clear(); }

    /// Builds and factors A for substep h; particles with x[i].w == 0 are kinematic. Allocates.
    void factor(const NeighbourTable& nb, const drape_params& params, const Particle* x, uint32_t n, float h);
    /// Substep the factor was built for, s (0: none yet).
    float h() const { return h_; }

    /// iterate[i] += (A^-1 r)_i for every free particle i, r = residual. Does not allocate.
    void apply(const Particle* residual, Particle* iterate);

  private:
    void solve_in_place(glm::vec3* y) const;

    float h_ = 0;
    std::vector<float> key_;           ///< stiffness, damping and inverse masses it was built from
    std::vector<uint32_t> free_;       ///< particle of each free row, in particle order
    std::vector<uint32_t> perm_;       ///< factor row of free particle f
    std::vector<uint32_t> col_, row_;  ///< Cholesky factor L, compressed columns, diagonal first
    std::vector<float> value_;
    std::vector<glm::vec3> rhs_;  ///< scratch, one per free row
};

}  // namespace drape
