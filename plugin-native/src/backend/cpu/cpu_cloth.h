// CPU backend: a Cloth stepped on the CPU, single-threaded (DRAPE_BACKEND_CPU) or over the world's
// pool (DRAPE_BACKEND_CPU_THREADED, bit-identical to single-threaded). The state is the shared CPU
// copy (Cloth::x_, d_) plus two scratch buffers; the four buffers' roles rotate (swapped, never
// copied). Kernels: backend/cpu/kernels.h.
#pragma once

#include <vector>

#include "backend/cpu/collide.h"
#include "backend/cpu/implicit_solve.h"
#include "backend/cpu/kernels.h"
#include "core/cloth.h"

namespace drape::cpu {

class CpuCloth final : public Cloth {
public:
    CpuCloth(World& world, drape_backend backend, std::shared_ptr<const Description> description);

    Result step(float dt) override;
    Result edit(Access access, std::function<void(Cloth&)> fn) override;
    Result read(const drape_vertex_layout& layout, void* dst) override;
    Result stats(drape_stats* out) override;
    Result set_output(uint32_t gl_buffer, const drape_vertex_layout& layout) override;
    Result readback() override { return {}; }  // the CPU copy is the state
    Result supports(Feature) const override { return {}; }
    bool steps_on_pool_thread() const override { return backend_ == DRAPE_BACKEND_CPU; }

private:
    // ---- the step: one function per stage (drape_stage), in the order step() runs them ----
    /// Plans substeps and iterations, backs up the state for a rollback, sets the step's constants.
    void begin(float dt);
    /// The substep's constants; PBD/XPBD: inertial prediction and kinematic targets. `along`:
    /// share of the step the kinematic particles have moved by the substep's end.
    void predict(float along);
    /// The model's solve of one substep (MASS_SPRING: its whole Verlet step; IMPLICIT: predict too).
    void solve(float along);
    /// kernels::tether (max_stretch > 0 and kinematic particles).
    void tether();
    /// Self-collision (cpu_collide.cpp).
    void self_collide();
    /// Touch drag (first substep) and colliders (cpu_collide.cpp).
    void collide(uint32_t sub);
    /// Substeps the automatic budget needs for the colliders that move near the cloth this step
    /// (kColliderTravelPerSubstep; 1 if none, cpu_collide.cpp). contact_near: whether a collider with
    /// friction, or one that is not a plane, is near (its bounds over the step against the cloth's,
    /// grown by the fastest particle's travel): IMPLICIT then takes contact_substeps_ substeps.
    uint32_t collider_substeps(float dt, bool& contact_near) const;
    /// Substeps the automatic budget needs with self-collision on: no particle moves more than
    /// kSelfMoveLimit thicknesses per substep relative to the cloth's mean motion, at its last
    /// substep's velocity (cpu_collide.cpp).
    uint32_t self_collision_substeps(float dt) const;
    struct VerifyPartial {
        bool finite, runaway;
    };
    /// Finite positions and runaway strain over all particles.
    VerifyPartial verify();
    /// Statistics (the strain's when read); rolls back a failed step, or commits (interaction bookkeeping, recentre).
    Result finish(float dt, const VerifyPartial& total);

    void refresh_backend() override;
    void recentre();  // moves origin_ near the cloth, shifting every held position
    glm::vec3 kinematic_position(uint32_t k, float along) const;
    /// fn(begin, end) over the particles: split over the world's pool (CPU_THREADED) or one call.
    template <class Fn>
    void for_particles(Fn&& fn) {
        if (backend_ == DRAPE_BACKEND_CPU_THREADED)
            world_.pool().parallel_for(topo_.particle_count, fn);
        else
            fn(0u, topo_.particle_count);
    }

    // The step being taken (begin).
    float* profile_ = nullptr;  ///< stats_.stage_ms while the world profiles stages, else nullptr
    kernels::SubstepContext ctx_{};
    uint32_t substeps_ = 0, iterations_ = 0;
    uint32_t implicit_iterations_ = 0;  ///< IMPLICIT: most iterations a substep took (it stops when converged)
    float h_ = 0;  ///< substep, s

    // Scratch buffers (their roles rotate with x_ and d_).
    std::vector<Particle> spare_, spare2_;
    std::vector<float> lambda_;
    // IMPLICIT model (implicit_substep): the substep's inertial target and the prefactored
    // matrix (backend/cpu/implicit_solve.h).
    std::vector<Particle> target_;
    /// IMPLICIT: per particle the normal of the frictionless collider the last collision pass moved
    /// it out of (0: none), for the next substep's solve; contact_fresh_ says the last substep wrote it.
    std::vector<glm::vec3> contact_normal_;
    bool contact_fresh_ = false;
    ImplicitSolve implicit_;
    /// IMPLICIT's solve at contact_substeps_ a step while a collider that needs them is near
    /// (collider_substeps), factored outside the step (refresh_contacts): in A built for the planned
    /// substep (dt/2) the mass term is too small by (planned / actual substep)^2, and with 8 substeps
    /// on it (16 times) 4 iterations let the cloth slide off a sphere with friction 1.
    ImplicitSolve implicit_fine_;
    /// IMPLICIT's substeps near collider c: kFrictionSubstepsImplicit with friction, else
    /// kContactSubstepsImplicit if it is not a plane, else 0 (none needed).
    static uint32_t contact_substeps_for(const ColliderState& c);
    uint32_t contact_substeps_ = 0;  ///< the most contact_substeps_for gives over the colliders
    bool fine_ready_ = false;  ///< implicit_fine_ is factored for these params and contact_substeps_
    const ImplicitSolve* implicit_last_ = nullptr;  ///< the solve the last substep used
    float last_dt_ = 0;  ///< step of the last step, s (0: none yet)
    void refresh_colliders() override;
    void refresh_contacts();  ///< contact_substeps_ for the colliders, implicit_fine_ factored for them when stale
    template <class KinematicAt>
    void implicit_substep(kernels::SubstepContext& c, const KinematicAt& kinematic_at);
    void factor_implicit(float h);
    float last_h_ = 0;  ///< substep of the last step, s (0: none yet)
    std::vector<float> slot_coef_;  ///< per-spring Jacobi factor of the current step (kernels.h)
    /// Per slot, column-major: the largest squared length verify lets its spring reach (+inf: unchecked).
    std::vector<float> col_limit_;

    std::vector<glm::vec3> kinematic_start_;  ///< kinematic particles' positions at the start of the step

    /// Colliders that may touch the cloth this substep (capacity DRAPE_MAX_COLLIDERS: kept).
    std::vector<CollideShape> shapes_;

    // Rollback copy and per-thread verify partials (allocated once).
    std::vector<Particle> backup_x_, backup_d_;
    float backup_h_prev_ = 1.0f;
    bool backup_fresh_ = true;
    std::vector<VerifyPartial> partials_;
};

}  // namespace drape::cpu
