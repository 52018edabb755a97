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
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "backend/cpu/kernels.h"
#include "backend/cpu/thread_pool.h"
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
    /// masses over h^2), its springs' blocks from frames (written by the residual pass at disp).
    void assemble(const kernels::SubstepContext& c, const Particle* start, const Particle* disp,
                  const kernels::SpringFrames& frames, uint32_t p);
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

// IMPLICIT's coarse levels: smooth motions too fine for the patches. A taut sheet's out-of-plane
// waves (a quarter of its width long) cost nearly their mass alone in H, while D charges them the
// springs' tension and A their stiffness, so a few iterations applied only a small share of their
// force and they kept ringing. Translations of small aggregates show them, at little cost: a jump
// across an aggregate's border bends its springs without stretching them, which H charges only their
// tension. The preconditioner adds z += P_1 V(P_1^T r): level 1 groups the free particles in cells
// of about 2 x 2 (twice their rest spacing), level l + 1 the cells of level l 2 x 2, down to
// kCoarsestNodes; H_1 = P_1^T H P_1 and H_l+1 = P^T H_l P (Galerkin, piecewise-constant P) at the
// solve's iterate; V is one symmetric V-cycle (damped block Jacobi before and after the coarser
// level's correction, dense Cholesky at the coarsest): aggregation multigrid (Vanek, Mandel and
// Brezina 1996, without the prolongation smoothing), as GLES does on A (gles_coarse.h).
class CoarseLevels {
  public:
    using Particle = kernels::Particle;
    /// A symmetric 3x3 block in double: xx, yy, zz, xy, xz, yz.
    struct Block {
        double v[6] = {};
        void add(const Block& b, double s = 1) {
            for (int k = 0; k < 6; ++k) v[k] += s * b.v[k];
        }
        glm::dvec3 operator*(const glm::dvec3& x) const {
            return {v[0] * x.x + v[3] * x.y + v[4] * x.z, v[3] * x.x + v[1] * x.y + v[5] * x.z,
                    v[4] * x.x + v[5] * x.y + v[2] * x.z};
        }
    };

    /// Cells and the levels' block patterns over the free particles (x[i].w != 0). Allocates.
    void build(const Topology& topo, const Particle* x);

    // One solve's use, in this order.
    /// Level 1's rows of H at disp (as kernels::implicit_curvature clamps it, plus the masses over
    /// h^2; the springs' blocks from frames, written by the residual pass at disp), node by node
    /// (the nodes may run on different threads), then the coarser levels.
    void assemble_node(const kernels::SubstepContext& c, const Particle* disp,
                       const kernels::SpringFrames& frames, uint32_t a);
    uint32_t node_count() const { return levels_.empty() ? 0 : levels_[0].count; }
    /// The coarser levels, the smoothers' block inverses and the coarsest level's Cholesky factor;
    /// false when there are no levels or a matrix is not positive definite (then it must not be used).
    /// pool: threads for the per-node work (null: the caller alone; the same bits either way).
    bool factor(ThreadPool* pool);
    /// One V-cycle on level 1's share of r (pool as in factor), in float: in double its block products
    /// were ~9 % of a step at rest (65^2 curtain).
    void apply(const Particle* r, ThreadPool* pool);
    /// The correction at particle i (0 on kinematic particles).
    glm::vec3 at(uint32_t i) const { return cell_[i] < 0 ? glm::vec3(0.0f) : glm::vec3(levels_[0].e[cell_[i]]); }

  private:
    static constexpr uint32_t kCoarsestNodes = 32;  ///< solved densely: 96 unknowns, ~30 k multiply-adds
    static constexpr float kSmoothing = 2.0f / 3.0f;  ///< Jacobi weight, below 2 / lambda_max(D_l^-1 H_l)
    /// A level with fewer nodes runs on the caller alone: a pass over it is a few microseconds (a node
    /// costs ~100-250 instructions), about what waking and joining the workers costs.
    static constexpr uint32_t kMinParallelNodes = 256;
    struct Level {
        uint32_t count = 0;
        std::vector<uint32_t> parent;              ///< per node its node on the next level (none on the last)
        std::vector<uint32_t> child_start, child;  ///< node a's nodes on the finer level, ascending: child[child_start[a] ..
                                                   ///< child_start[a + 1]) (none on level 1)
        std::vector<uint32_t> row_start, col;      ///< off-diagonal blocks by rows, columns sorted
        std::vector<Block> diag, off;
        std::vector<Block> diag_inv;               ///< smoother
        // The V-cycle's copy of H_l and the smoother in float, four nodes at once (the last group
        // padded with nodes whose blocks are 0): per group of four and entry (the diagonal first,
        // then the row's off-diagonal blocks, rows shorter than width padded with 0 blocks at the
        // node itself) the four columns, and per component (xx, yy, zz, xy, xz, yz) four lanes.
        uint32_t width = 0;
        std::vector<uint32_t> cycle_col;
        std::vector<float> cycle_block, cycle_inv;
        std::vector<Particle> r, e, t;             ///< residual, correction, scratch (padded to the groups)
    };
    std::vector<Level> levels_;          ///< [0]: level 1 (cells of particles)
    std::vector<int32_t> cell_;          ///< per particle its level-1 node, -1 if kinematic
    std::vector<uint32_t> member_start_, member_;  ///< level-1 node a's particles
    /// Per slot of the neighbour table (row-major), where its spring's -K_ij goes in level 1's
    /// off-diagonal blocks (an index into off), or kInside (both ends in one cell: no share) or
    /// kKinematic (the other end kinematic: the diagonal's share only).
    std::vector<int32_t> slot_off_;
    static constexpr int32_t kInside = -1, kKinematic = -2;
    std::vector<double> dense_;          ///< coarsest H, then its Cholesky factor (row-major, lower)
    std::vector<double> dense_rhs_;
    void cycle(size_t l, ThreadPool* pool);
};

}  // namespace drape
