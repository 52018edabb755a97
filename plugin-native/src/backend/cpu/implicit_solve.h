// The IMPLICIT model's solve of one substep (CpuCloth::implicit_substep): minimise Phi
// (kernels::implicit_residual) by nonlinear preconditioned conjugate gradients on the force
// residual r = -grad Phi. The preconditioner is additive, P^-1 = A^-1 + D^-1 (+ G Hc^-1 G^T from
// the second iteration on, + P_1 V P_1^T, see below):
// - A = M/h^2 + sum_springs (k + kd/h) (e_i - e_j)(e_i - e_j)^T over the free particles (kinematic
//   ones enter only through the residual; Projective Dynamics' constant matrix, Bouaziz et al.
//   2014), factored once by a sparse Cholesky. A bend spring i-j enters as 2k on each half of its
//   path through the middle particle m (i-m, m-j), which A already couples: k (x_i - x_j)^2 <=
//   2k ((x_i - x_m)^2 + (x_m - x_j)^2), so A still bounds the spring's share (the plain step below
//   still lowers Phi), and for smooth modes the two agree. The factor then keeps the pattern of the
//   structural and shear springs alone: half the entries (65^2: 240,067 -> 120,056; 129^2: 1.31 M ->
//   0.62 M), a separator of one row instead of two, 15 / 18.5 % fewer instructions a step at rest at
//   65^2 / 129^2 and 14 % in the falling 64^2 sheet (callgrind), the same rest errors. Lumping them onto the diagonal instead (2k on
//   i and on j) made A too stiff for the smoothest modes: the 256^2 sheet hanging from two corners
//   took 4x as long a step. It is right for the stiff smooth modes (rigid
//   motion, the stretch of a hanging cloth) but charges every spring's k in all directions, where
//   the true (clamped) Hessian H charges k along the spring and only the tension T = k max(0,
//   1 - L/l) across it: modes that bend or swing the cloth are nearly mass-dominated in H and
//   stiff in A, so P = A alone left them to CG, ~sqrt(k/T) iterations. With a few, the default
//   fell in slow motion (bench part 'fall', 17^2 sheet from two corners, fall 0.74 / 0.28 as far
//   as MASS_SPRING at 2e4 / 1e5 N/m), and a taut sheet's sag swung at rest by 0.1-1 % for good
//   (the fall's energy kept by modes the solve barely touched).
// - D: per free particle its 3x3 block of H at the solve's first iterate, M/h^2 plus per spring
//   (k + kd/h) n n^T + T (I - n n^T), built by the first residual pass (kernels::implicit_residual
//   <true>): ~h^2/m where A^-1 is ~0 (motion across the springs), ~0 where A^-1 is right (along
//   stiff springs). Fall then 0.97 / 0.76. At rest a solve keeps the previous solve's D (see solve).
// - G Hc^-1 G^T: H restricted to the rigid motions of a few patches (coarse_space.h). A cloth
//   swinging about its pins or folding turns its springs without stretching them, a motion
//   coordinated over the whole cloth that A charges every spring's k and per-particle D cannot
//   make; CG took it in ~sqrt(k/T) iterations. Built only when a solve needs a second iteration
//   (in motion), so a cloth at rest costs what it did. Fall 1.01 / 1.01 (largest vertex distance
//   from MASS_SPRING over the size 0.035 / 0.075, was 0.43 / 0.83; 33^2: 0.13 / 0.14, was 0.87 /
//   1.25), for ~20 % more work a step in motion.
// - P_1 V P_1^T: the coarse levels (coarse_space.h, CoarseLevels), translations of small cells with
//   one V-cycle on H, assembled in the second iteration, and from the first in a solve after one
//   that used them and not its whole budget (see solve): a taut sheet's smooth out-of-plane waves,
//   which the patches are too coarse to show, cost nearly their mass alone in H while D charges
//   them the tension and A the stiffness; with a few iterations they kept ringing at the user's
//   default drag (65^2 sheet: 4.6e-4 of the displacement after 5.5 s, exact implicit Euler 1.2e-6).
// Step lengths come from H (kernels::implicit_curvature), except for a 1-iteration budget, which
// takes the plain step d += A^-1 r without D (see solve). They are cut where a step would shorten a
// stretched spring below kStepFloor of its rest length: far from equilibrium H at the step's start
// does not see a spring turn over, and the first step of a free cloth let go 10 times stretched
// (bench part 'stress', S5) folded its corners into their neighbours, which 4 iterations could not
// undo (max strain after the first frame 0.99 at 2 x 4; converged implicit Euler 0.43, cut 0.40). A
// spring already shorter than its rest length is never limited, so no solve stalls on one; in the
// bench's motion and at rest the cut never acts (the same bits). With D the taut sheets settle without
// refactoring A at rest with its springs' tension (which the library did until D came: 56 bytes per
// factor entry, 611 ms per 129^2 refactor).
// The fixed point is r = 0, the exact equilibrium, whatever the preconditioner.
//
// The factor's rows are ordered by a one-level nested dissection: two parts that share no spring,
// each in its own minimum-degree (AMD) order, then the separator between them. L is then block
// lower triangular, so each part's forward and back substitution runs on its own thread and only
// the separator's rows are serial; the order and the arithmetic do not depend on the thread
// count, so CPU_THREADED gives the same bits as CPU.
#pragma once

#include <algorithm>
#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "backend/cpu/coarse_space.h"
#include "backend/cpu/kernels.h"
#include "backend/cpu/thread_pool.h"
#include "core/topology.h"
#include "drape/drape.h"

namespace drape {

class ImplicitSolve {
  public:
    using Particle = kernels::Particle;
    /// Columns of L the substitutions take at once at most (a group: one SIMD register of values
    /// per shared row).
    static constexpr uint32_t kGroupWidth = 4;
    /// x, y, z and a lane kept 0: the substitutions take an entry's three axes in one SIMD multiply
    /// and subtract (implicit_solve.cpp, scatter and gather).
    struct Lanes {
        float v[4];
    };

    /// True when stiffness, damping or an inverse mass (x[i].w) differ from those of the last
    /// factor (or there is none): the matrix must be rebuilt. Remembers the new values.
    bool inputs_changed(const drape_params& params, const Particle* x, uint32_t n);
    /// Forgets the inputs, so that the next inputs_changed is true.
    void clear() { key_.clear(); }
    /// Positions or velocities were set from outside: the rounding carried over (see solve), the
    /// coarse levels and D kept from earlier solves belong to the old state.
    void state_set() {
        std::fill(carry_.begin(), carry_.end(), glm::vec3(0.0f));
        std::fill(carried_.begin(), carried_.end(), glm::vec3(0.0f));
        levels_fresh_ = false;
        blocks_fresh_ = false;
    }

    /// Builds and factors A for substep h; particles with x[i].w == 0 are kinematic. Allocates.
    void factor(const Topology& topo, const drape_params& params, const Particle* x, float h);
    /// Substep the factor was built for, s (0: none yet).
    float h() const { return h_; }

    /// Conjugate-gradient iterations on the substep's displacements d = iterate (the first iterate
    /// on entry, 0 on kinematic particles), from target and start (see kernels::implicit_residual),
    /// until converged (the preconditioned residual r.z below tolerance^2 times the energy scale of
    /// the substep's predicted motion) or max_iterations; returns the iterations taken. pool: the
    /// threads to use, or null for the calling thread alone (same bits). contact_normal (or null):
    /// per particle the outward normal of a frictionless collider it touched in the previous
    /// substep, else 0. The solve does not move such a particle inwards (its residual and search
    /// directions lose their inward part, Baraff and Witkin 1998 sec. 5.3) while it is pulled inwards
    /// and has not moved outwards in this solve (n . d <= 0); once off the surface it is free: held there too,
    /// the steps pushed it out with nothing pulling it back, and that move became velocity (a cloth
    /// sliding on a frictionless sphere went from 1.1 to 4.7 J, launched upwards). The springs then pull its
    /// neighbours and slide it along the surface, instead of pressing it into the collider for the
    /// collision pass to undo, which held a frictionless cloth on a box edge. Frictional contacts are
    /// left to the collision pass, whose friction grows with that push. Does not allocate.
    uint32_t solve(const kernels::SubstepContext& c, const Particle* start, Particle* target, Particle* iterate,
                   uint32_t max_iterations, float tolerance, ThreadPool* pool, const glm::vec3* contact_normal);

  private:
    static constexpr uint32_t kMaxHalvings = 8;  ///< of a step along which Phi rose (see solve)
    /// A step may shorten a stretched spring (along its direction) to this share of its rest length at
    /// most (see the file comment).
    static constexpr float kStepFloor = 0.1f;
    static constexpr int kParts = 2;  ///< parts of the nested dissection; the separator follows
    /// Particles per partial sum of a dot product: fixed, so that the order of the sums, and so their
    /// bits, do not depend on the thread count. Small, so that the threads' shares of the blocks are
    /// near equal: with 256, a 65^2 cloth's 17 blocks went 8 / 9 and the worker's residual pass took
    /// 7 % more instructions than the caller's.
    static constexpr uint32_t kBlock = 64;
    /// Blocks a thread takes at a time in over_blocks (ThreadPool::parallel_grains): 256 particles,
    /// ~4 us of the residual pass.
    static constexpr uint32_t kGrain = 4;
    /// pool when it would split the particles (ThreadPool::chunks, the particle passes' rule), else
    /// null: the calling thread alone.
    ThreadPool* parallel(ThreadPool* pool) const {
        return pool && pool->chunks(uint32_t(r_.size())) > 1 ? pool : nullptr;
    }
    /// fn(begin, end) -> double over the particles in blocks of kBlock, each thread taking whole
    /// blocks; returns the blocks' results summed in block order.
    template <class Fn>
    double over_blocks(ThreadPool* pool, Fn&& fn);

    /// fn(k) for k in [0, count) (the coarse space's patches, the coarse levels' level-1 nodes) in
    /// contiguous ranges, range t on thread t (or all on the caller). Both are numbered in the order of
    /// their first particle, so a thread takes about the particles it has in the particle passes (one
    /// item in two on each thread had each read the other core's lines of r and of the iterate).
    template <class Fn>
    void over_items(ThreadPool* pool, uint32_t count, Fn&& fn);

    struct Dots {
        double rz = 0, z_r_prev = 0;  ///< r.z and z.r_prev
    };
    /// z = A^-1 r (+ D^-1 r: with_blocks_) on the free particles (z stays 0 on kinematic ones), with r.z and z.r_prev.
    Dots precondition(const Particle* r, const Particle* r_prev, Particle* z, ThreadPool* pool);
    // The substitutions with L's values (one per entry: A's three axes are equal).
    void forward_part(int p, const Particle* r);
    /// Forward substitution of group g; a part's shares of separator rows go to t[row - base].
    void forward_group(uint32_t g, Lanes* t, uint32_t base);
    void separator(const Particle* r, const Particle* r_prev, Particle* z);
    /// Back substitution over groups [first, last).
    Dots back_substitute(uint32_t first, uint32_t last, const Particle* r, const Particle* r_prev, Particle* z);

    float h_ = 0;
    std::vector<float> key_;           ///< stiffness, damping and inverse masses it was built from
    uint32_t begin_[kParts + 2] = {};  ///< factor rows of part p: [begin_[p], begin_[p + 1]); separator last
    std::vector<uint32_t> particle_;   ///< particle of each factor row
    std::vector<float> inv_diag_;      ///< 1 / L_jj
    // The strictly lower part of L by groups: runs of consecutive columns of one part (or the
    // separator) whose rows below the run are the same (supernodes, at most kGroupWidth columns).
    // Column first + k of a group has the rows first + k + 1 .. first + width - 1 (the group's own
    // triangle) and then its shared rows. A part's rows reach only its own columns, so parts run at
    // once. Both substitutions go through a shared row once per group: the forward one subtracts the
    // group's columns from it in turn (the same operations, in the same order, as gathering along
    // the row: the same bits), the back one subtracts it from each column's sum (its own register).
    struct Group {
        uint32_t first, width;  ///< its columns: [first, first + width)
        uint32_t rows, end;     ///< its shared rows: group_row_[rows, end), ascending
        uint32_t part_end;      ///< those in its own part (or the separator) end here; a part's
                                ///< separator rows follow
    };
    std::vector<Group> group_;
    uint32_t part_group_[kParts + 2] = {};  ///< groups of part p: [part_group_[p], part_group_[p + 1]); separator last
    std::vector<uint32_t> group_row_;
    std::vector<Lanes> group_value_;  ///< per shared row: lane k holds L at it and the group's column first + k
    std::vector<Lanes> group_tri_;    ///< kGroupWidth per group: record k, lane kk < k: L[first + k][first + kk]
    std::vector<Lanes> y_;            ///< scratch, one per factor row
    std::vector<Lanes> sep_sum_;      ///< per part and separator row: sum of L_sk y_k over the part's k
    uint32_t sep_stride_ = 0;         ///< part p's sums: sep_sum_[p * sep_stride_ + row - separator's first]
    Dots part_dots_[kParts + 1];      ///< the parts' and the separator's share of the dot products
    std::vector<double> block_sum_;   ///< over_blocks' per-block results
    std::vector<float> block_shrink_;  ///< per block the curvature pass's shrink rate (see solve)
    // Conjugate gradients, one record per particle: residual, the previous one, preconditioned
    // residual and direction.
    std::vector<Particle> r_, r_prev_, z_, p_;
    std::vector<kernels::SymMat3> block_inv_;  ///< per particle the inverse of its block of H (D)
    bool blocks_fresh_ = false;  ///< the next solve may keep block_inv_ (see solve)
    float blocks_h_ = 0;         ///< substep block_inv_ was built for
    static constexpr uint32_t kKeepBlocks = 8;  ///< solves in a row that may keep block_inv_
    uint32_t kept_ = 0;          ///< solves in a row that kept it
    std::vector<glm::vec3> carry_;  ///< per particle what the last commit's rounding took (see solve's end)
    std::vector<glm::vec3> carried_;  ///< carry_ as the last solve received it (in its displacements)
    /// Per slot of the neighbour table, column-major like SubstepContext::col_index, its spring's
    /// stiffness (N/m; 0 where inactive or padding): the residual's springs in SIMD lanes.
    std::vector<float> col_k_;
    // The curvature pass's springs (kernels::CountedSprings).
    std::vector<uint32_t> counted_count_, counted_index_;
    std::vector<float> counted_rest_, counted_k_;
    /// The springs' directions and tensions (kernels::SpringFrames) that the residual pass writes in
    /// the second iteration, for the coarse space and levels.
    std::vector<float> frames_;
    bool with_blocks_ = true;           ///< this solve's preconditioner adds D^-1 r (not a plain 1-iteration step)
    CoarseSpace coarse_;
    bool with_coarse_ = false;          ///< this solve's preconditioner adds the coarse correction
    CoarseLevels levels_;
    bool with_levels_ = false;          ///< this solve's preconditioner adds the coarse levels' correction
    bool levels_fresh_ = false;         ///< the next solve may start with levels_ (see solve)
    bool coarse_ok_ = false;            ///< coarse_ as last assembled is positive definite
    static constexpr uint32_t kReuseSolves = 8;  ///< solves that may reuse coarse_ and levels_ (see solve)
    uint32_t reuses_ = 0;               ///< solves that started with them since they were assembled
    std::vector<uint32_t> in_contact_;       ///< particles with a contact normal in this solve
    const glm::vec3* normal_ = nullptr;  ///< this solve's contact normals, null if none
    std::vector<glm::vec3> held_;        ///< per particle its normal while the contact holds it (see solve), else 0
};

}  // namespace drape
