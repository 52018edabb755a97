// Run-time state of what a cloth interacts with: colliders, touch drag, grabs, the
// owner transform, and sleeping. Owned by Cloth (member ix_); the Cloth member functions that use
// it are defined in core/interaction.cpp. A step calls skip_step_asleep() first and
// interaction_end_step() when done; the CPU step's collide stage (backend/cpu/cpu_collide.cpp)
// applies drag and colliders after each substep's solve.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "backend/cpu/glsl.h"  // rigid_move (shaders/substep.h)
#include "drape/drape.h"
#include "shaders/layout.h"

namespace drape {

/// One collider during one substep: the collider record of shaders/layout.h (DRAPE_COLLIDER_VEC4
/// vec4s; the GLES backend uploads shape as a float).
struct CollideShape {
    glm::vec3 pos0; float margin;     ///< centre at the substep start (m); margin (m, >= 0)
    glm::vec3 pos1; float friction;   ///< centre at the substep end (m); Coulomb coefficient (>= 0)
    glm::quat rot0;                   ///< orientation at the substep start (unit)
    glm::quat rot1;                   ///< orientation at the substep end (unit)
    glm::vec3 size; uint32_t shape;   ///< drape_collider_shape and its sizes (see drape_collider)
};
static_assert(sizeof(CollideShape) == DRAPE_COLLIDER_VEC4 * sizeof(glm::vec4), "collider record of shaders/layout.h");

/// A collider as the host gave it, plus where it was at the start of the current step.
struct ColliderState {
    uint32_t id, shape;
    glm::vec3 size;
    float margin, friction;
    glm::vec3 pos_start, pos_end;  ///< m
    glm::quat rot_start, rot_end;  ///< unit

    /// Substep `sub` of `substeps`: the previous -> new transform interpolated (position linearly,
    /// rotation by normalised lerp), the last substep ending exactly at the new transform.
    CollideShape at_substep(uint32_t sub, uint32_t substeps) const;
};

/// A rigid motion of the whole particle state (owner transform, re-centring): each position x goes
/// to rot * (x - pivot) + to; displacements turn with rot (keep_velocity) or become zero.
struct RigidMove {
    glm::quat rot{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 pivot{0.0f};
    glm::vec3 to{0.0f};
    bool keep_velocity = true;
    glm::vec4 rot_xyzw() const { return glm::vec4(rot.x, rot.y, rot.z, rot.w); }  ///< as the shaders take it
    glm::vec3 apply(const glm::vec3& x) const { return kernels::glsl::rigid_move(rot_xyzw(), pivot, to, x); }
};

struct Grab {
    uint32_t touch_id;
    uint32_t particle;  ///< the grabbed particle (GLES: the grab's slot; the particle is on the GPU)
    double ndc_z;  ///< depth the vertex was grabbed at
};

struct Interaction {
    // Colliders (drape_cloth_set_colliders).
    std::vector<ColliderState> colliders;

    // Touch drag: displacement per affected particle for the next step, spread over its substeps.
    std::vector<uint32_t> drag_particles;
    std::vector<glm::vec3> drag_offset;  ///< per particle (only entries in drag_particles used)
    std::vector<uint8_t> drag_marked;    ///< per particle: listed in drag_particles

    std::vector<Grab> grabs;

    // Owner transform.
    bool has_owner = false;
    glm::vec3 owner_pos{0.0f};
    glm::quat owner_rot{1.0f, 0.0f, 0.0f, 0.0f};

    // Sleeping.
    float sleep_threshold = 0;  ///< m/s; 0 = never
    float sleep_time = 1;       ///< s
    float still_time = 0;       ///< s of steps below the threshold so far
    bool asleep = false;
    uint32_t wakes = 0;         ///< wake() calls so far (a GPU sleep check issued before one is stale)
    uint64_t collide_tests = 0; ///< particle-collider narrow-phase tests (diagnostics, tests)
};

}  // namespace drape
