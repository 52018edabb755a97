// Run-time state of what a cloth interacts with: colliders, touch drag, grabs, the
// owner transform, and sleeping. Owned by Cloth (member ix_); the Cloth member functions that use
// it are defined in core/interaction.cpp. A step calls skip_step_asleep() first and
// interaction_end_step() when done; the CPU step's collide stage (backend/cpu/cpu_collide.cpp)
// applies drag and colliders after each substep's solve.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
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

/// Axis-aligned bounds (empty until something is added).
struct Aabb {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    void add(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void add(const glm::vec3& p, float r) {
        lo = glm::min(lo, p - r);
        hi = glm::max(hi, p + r);
    }
    bool overlaps(const Aabb& o) const {
        return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
    }
};

/// World bounds of a (non-plane) shape at one transform, grown by its margin.
inline void add_shape_bounds(Aabb& b, const CollideShape& s, const glm::vec3& pos, const glm::quat& rot) {
    if (s.shape == DRAPE_COLLIDER_SPHERE) {
        b.add(pos, s.size.x + s.margin);
    } else if (s.shape == DRAPE_COLLIDER_CAPSULE) {
        const glm::vec3 axis = rot * glm::vec3(0, s.size.y, 0);
        b.add(pos + axis, s.size.x + s.margin);
        b.add(pos - axis, s.size.x + s.margin);
    } else {  // box: |R| * half extents
        const glm::mat3 r = glm::mat3_cast(rot);
        const glm::vec3 e(std::fabs(r[0].x) * s.size.x + std::fabs(r[1].x) * s.size.y + std::fabs(r[2].x) * s.size.z,
                          std::fabs(r[0].y) * s.size.x + std::fabs(r[1].y) * s.size.y + std::fabs(r[2].y) * s.size.z,
                          std::fabs(r[0].z) * s.size.x + std::fabs(r[1].z) * s.size.y + std::fabs(r[2].z) * s.size.z);
        b.lo = glm::min(b.lo, pos - e - s.margin);
        b.hi = glm::max(b.hi, pos + e + s.margin);
    }
}

/// Lowest signed height of the box's corners above a plane (normal n through point p).
inline float lowest_above_plane(const Aabb& b, const glm::vec3& p, const glm::vec3& n) {
    const glm::vec3 corner(n.x >= 0 ? b.lo.x : b.hi.x, n.y >= 0 ? b.lo.y : b.hi.y, n.z >= 0 ? b.lo.z : b.hi.z);
    return glm::dot(corner - p, n);
}

/// Whether the shape over the substep (its start and end transforms, grown by its margin) may
/// touch a cloth within these bounds.
inline bool touches(const Aabb& cloth, const CollideShape& s) {
    if (s.shape == DRAPE_COLLIDER_PLANE)
        return lowest_above_plane(cloth, s.pos0, s.rot0 * glm::vec3(0, 1, 0)) < s.margin ||
               lowest_above_plane(cloth, s.pos1, s.rot1 * glm::vec3(0, 1, 0)) < s.margin;
    Aabb b;
    add_shape_bounds(b, s, s.pos0, s.rot0);
    add_shape_bounds(b, s, s.pos1, s.rot1);
    return b.overlaps(cloth);
}

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
