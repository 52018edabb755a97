// A cloth: cooked topology + parameters + run-time state behind the interface every backend
// implements, and the world that owns cloths and the worker pool. The C ABI (src/api) validates
// every input before it reaches these classes.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "backend/cpu/thread_pool.h"
#include "core/description.h"
#include "core/interaction.h"  // colliders, drag, owner, sleep
#include "core/params.h"
#include "core/self_collision.h"  // self-collision
#include "core/topology.h"
#include "drape/drape.h"

namespace drape {

class World;

/// Outcome of an operation: status plus message (messages travel back to the calling thread).
struct Result {
    drape_status status = DRAPE_OK;
    std::string message;
    bool ok() const { return status == DRAPE_OK; }
};

/// What a cloth can do beyond the core set (a backend refuses the rest with a clear Result).
enum class Feature { ImplicitModel, XpbdModel, Sleep, Grab, Owner, SelfCollision };

/// A cloth: what every backend shares (cooked topology, parameters, masses, pins, colliders,
/// interaction settings and the CPU copy of the state, with the setters that change them) and the
/// interface each backend implements (step, edit, read, stats, output, readback, capabilities).
/// Backends are siblings: backend/cpu/cpu_cloth.h, backend/gles/gles_cloth.h (backend/backends.h
/// creates them); the C ABI calls only this interface.
class Cloth {
public:
    using Particle = glm::vec4;
    /// What a setter does to the particle state: reads it (a backend whose state lives elsewhere
    /// brings it to the CPU copy first, and takes it back after), overwrites it (taken back
    /// after), or leaves it (parameters, pin targets).
    enum class Access { ReadsState, WritesState, NoState };

    Cloth(World& world, drape_backend backend, std::shared_ptr<const Description> description);
    virtual ~Cloth() = default;

    // ---- the backend interface ----
    /// Steps by dt; on divergence restores the state from before the step.
    virtual Result step(float dt) = 0;
    /// Applies a setter (fn, on this cloth's shared part) now, or where the backend's state lives.
    virtual Result edit(Access access, std::function<void(Cloth&)> fn) = 0;
    /// Writes normals and positions per caller vertex, positions in the caller's space relative to
    /// layout.origin. Layout and size already validated.
    virtual Result read(const drape_vertex_layout& layout, void* dst) = 0;
    virtual Result stats(drape_stats* out) = 0;
    /// Output target: GL buffer name (0 = none) with a layout already validated by the API.
    virtual Result set_output(uint32_t gl_buffer, const drape_vertex_layout& layout) = 0;
    /// Explicit readback of state held outside the CPU copy.
    virtual Result readback() = 0;
    /// OK, or why this backend cannot do it.
    virtual Result supports(Feature feature) const = 0;
    /// True when the world may step it on a pool thread next to other cloths.
    virtual bool steps_on_pool_thread() const = 0;

    World& world() const { return world_; }
    drape_backend backend() const { return backend_; }
    const Topology& topology() const { return topo_; }
    const Description& description() const { return *desc_; }
    /// Cloths sharing this one's description, this one included.
    uint32_t description_users() const { return uint32_t(desc_.use_count()); }
    const drape_params& params() const { return params_; }
    bool is_pinned(uint32_t vertex) const { return pinned_[topo_.vertex_to_particle[vertex]] != 0; }

    void set_params(const drape_params& p);
    /// Per caller vertex; welded copies take the smallest value.
    void set_inverse_masses(const float* inverse_masses);
    void set_pins(const drape_pin* pins, uint32_t count);
    void release_pins(const uint32_t* vertices, uint32_t count);
    void set_positions(const float* xyz);
    void set_velocities(const float* xyz);

    // ---- colliders, sleep, touch drag, grabs, owner (defined in core/interaction.cpp) ----
    void set_colliders(const drape_collider* colliders, uint32_t count);
    void set_sleep(float threshold, float time);
    void wake();
    bool asleep() const { return ix_.asleep; }
    /// True if these pins would move or newly pin a vertex (a reason to wake).
    bool pins_change(const drape_pin* pins, uint32_t count) const;
    /// Touch drag for the next step (paper eq. 9): here through edit(), computed from the CPU copy
    /// (drag_cpu_copy); a backend may evaluate it where its state lives.
    virtual Result drag(const drape_view& view, std::vector<drape_touch> touches);
    /// The drag offsets of these touches from the CPU copy's positions, for the next step.
    void drag_cpu_copy(const drape_view& view, const drape_touch* touches, uint32_t count);
    /// Caller vertex grabbed, or UINT32_MAX if no free vertex lies within pick_radius px: here
    /// from the CPU copy; a backend may pick where its state lives (then DRAPE_GRAB_ON_GPU).
    virtual uint32_t grab(const drape_view& view, uint32_t touch_id, const float position[2], float pick_radius);
    virtual bool grab_move(const drape_view& view, uint32_t touch_id, const float position[2]);
    virtual void grab_release(uint32_t touch_id);
    void set_owner(const drape_owner& owner);
    uint64_t collide_tests() const { return ix_.collide_tests; }
    void set_self_collision(bool enabled, float thickness, float friction);
    const SelfCollision& self_collision() const { return sc_; }
    uint32_t grab_count() const { return uint32_t(ix_.grabs.size()); }
    bool grabbing(uint32_t touch_id) const {
        for (const Grab& g : ix_.grabs)
            if (g.touch_id == touch_id) return true;
        return false;
    }

    /// Substeps a step of dt uses with the current parameters on this cloth's backend.
    uint32_t substeps_for(float dt) const;
    /// Iterations per substep with the current parameters (0 in drape_params = automatic).
    virtual uint32_t iterations_for() const;

    /// The point the cloth's coordinates are measured from, in the caller's space, m. Every
    /// position held by the cloth is relative to it (float precision does not depend on where the
    /// cloth is); the C ABI converts positions in (when an edit is applied, so a GLES cloth whose
    /// render thread re-centres in between still gets them right) and Cloth::read converts them
    /// out. Set at creation; a step moves it in whole metres when the cloth has drifted
    /// (recentre_shift, shift_origin).
    const glm::dvec3& origin() const { return origin_; }
    void set_origin(const glm::dvec3& origin) { origin_ = origin; }

protected:
    /// Positions (caller's space, relative to layout.origin, computed in double) and normals of the
    /// CPU copy per caller vertex.
    void read_cpu_copy(const drape_vertex_layout& layout, void* dst) const;
    /// stats_ plus the energies and strain statistics of the CPU copy.
    void stats_of_cpu_copy(drape_stats* out) const;

    void refresh_derived();  // after params or masses change
    /// The backend's own data derived from params and masses (refresh_derived ends with it).
    virtual void refresh_backend() {}
    /// The backend's own data derived from the colliders (set_colliders ends with it).
    virtual void refresh_colliders() {}
    /// Whole-metre shift that brings `reference` (a local position) back near the origin; zero
    /// while it is within kRecentreDistance (core/params.h) on every axis.
    static glm::vec3 recentre_shift(const glm::vec3& reference);
    /// Moves the particle state rigidly (owner transform): here the CPU copy; a backend whose state
    /// lives elsewhere moves that too.
    virtual void move_state(const RigidMove& m);
    /// origin_ += shift, every position held here (CPU copy, pin targets, colliders, owner,
    /// self-collision reference) -= shift.
    void shift_origin(const glm::vec3& shift);
    glm::dvec3 origin_{0.0};
    // Step bookkeeping (core/interaction.cpp): asleep -> no step; after a step, colliders advance,
    // drag is consumed (advance_interaction) and the sleep check runs (count_still): on the CPU
    // copy in interaction_end_step, on the GPU for GLES.
    bool skip_step_asleep();
    void interaction_end_step(float dt, bool rolled_back);
    void advance_interaction();
    /// Sleep bookkeeping of a step that was still (fastest particle below the threshold) or not:
    /// true when the cloth falls asleep now (the caller then zeroes the velocities).
    bool count_still(bool still, float dt);
    Interaction ix_;
    SelfCollision sc_;  // setting, and the CPU step's hash storage

    World& world_;
    const drape_backend backend_;
    const std::shared_ptr<const Description> desc_;
    const Topology& topo_;  ///< desc_->topology
    drape_params params_;

    // CPU copy of the run-time state: positions x_ and displacements over the last substep d_
    // (see backend/cpu/kernels.h), one record per particle.
    std::vector<Particle> x_, d_;
    float h_prev_ = 1.0f;   ///< previous substep; velocity = disp / h_prev
    bool fresh_ = true;     ///< next substep is the first since positions/velocities were set

    // Masses and pins.
    std::vector<float> base_inverse_mass_;   ///< per particle, before pinning
    std::vector<uint8_t> pinned_;            ///< explicit pin (drape_cloth_set_pins)
    std::vector<glm::vec3> kinematic_target_;///< where a particle with w = 0 goes this step
    std::vector<uint32_t> kinematic_;        ///< particles with w = 0

    // Tethers: nearest kinematic particle along the cloth and that rest distance (-1: none);
    // rebuilt only when the set of kinematic particles changes (moving pins keeps them).
    void rebuild_tethers();
    std::vector<uint32_t> tether_anchor_;
    std::vector<float> tether_rest_, tether_length_;
    std::vector<uint32_t> tethered_kinematic_;  ///< kinematic_ when the tethers were built

    // Derived from params + masses.
    std::vector<uint32_t> active_count_;
    float ms_h_max_ = 0;  ///< MASS_SPRING: largest stable substep from the explicit bound, s

    mutable std::vector<glm::vec3> normals_;
    drape_stats stats_{};
};

class World {
public:
    /// profile_stages: CPU steps time their stages (drape_stats.stage_ms, core/profile.h).
    World(uint32_t threads, bool profile_stages);
    ~World();
    ThreadPool& pool() { return pool_; }
    bool profile_stages() const { return profile_stages_; }
    void add(Cloth* c) { cloths_.push_back(c); }
    void remove(Cloth* c);
    const std::vector<Cloth*>& cloths() const { return cloths_; }
    Result step(float dt);

    /// The cooked description of `key` (the exact input bytes it is cooked from): the one a cloth
    /// of this world already uses, or a new one that cook(topology) fills; nullptr when cook fails
    /// (*result says why).
    std::shared_ptr<const Description> describe(const std::string& key,
                                                const std::function<CookResult(Topology&)>& cook, CookResult* result);

private:
    ThreadPool pool_;
    const bool profile_stages_;
    std::vector<Cloth*> cloths_;
    std::vector<Cloth*> serial_, threaded_;  // per-step scratch, capacity kept
    std::vector<Result> results_;
    std::unordered_map<std::string, std::weak_ptr<const Description>> descriptions_;  ///< by key
    uint32_t descriptions_cooked_ = 0;
};

}  // namespace drape
