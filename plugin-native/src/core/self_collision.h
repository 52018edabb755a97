// Self-collision state of a cloth: the setting and the spatial hash's storage. Owned by
// Cloth (member sc_); Cloth::set_self_collision is defined in core/interaction.cpp. The CPU step's
// self-collide stage (backend/cpu/cpu_collide.cpp, kernels in backend/cpu/self_collide.h) runs
// after each substep's solve and tethers, before drag and colliders, and only when enabled: a
// cloth without self-collision does no extra work.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace drape {

/// Pairs closer than kSelfExcludeRest * thickness in the rest mesh never collide (they are
/// neighbours: at rest they would already be in contact). Pairs sharing a spring never collide.
constexpr float kSelfExcludeRest = 1.5f;
/// Skin of the candidate lists (list radius = thickness + skin): at least kSelfMinSkin and at
/// most kSelfMaxSkin thicknesses, and twice the relative motion of the substep the list is built
/// in. A particle moving more than kSelfMaxSkin/2 thicknesses in one substep relative to the
/// cloth's mean motion may pass through.
constexpr float kSelfMinSkin = 1.0f;
constexpr float kSelfMaxSkin = 2.0f;
/// Automatic budget with self-collision: substeps so that no particle moves more than this many
/// thicknesses per substep relative to the cloth's mean motion. The default IMPLICIT at its 2
/// substeps let a folding cloth pass through itself (154 of 240 mirror pairs on the wrong side,
/// test_self_collision.cpp); at 0.5 64 still did, at 0.25 none.
constexpr float kSelfMoveLimit = 0.25f;
/// Largest thickness accepted, as a fraction of the diagonal of the cloth's rest bounding box.
constexpr float kSelfMaxThicknessFraction = 0.25f;

struct SelfCollision {
    bool enabled = false;
    float thickness = 0;  ///< m
    float friction = 0;   ///< Coulomb coefficient

    // Storage, sized on the first substep with self-collision; afterwards only the candidate
    // list can grow (when a crumpled cloth has more close pairs than ever before).
    std::vector<uint32_t> bucket_start;  ///< hash: buckets + 1
    std::vector<uint32_t> entries;       ///< hash: particles sorted by bucket
    std::vector<glm::ivec3> cell;        ///< hash: per particle
    std::vector<uint32_t> list_start;    ///< candidates of i: list[list_start[i], list_start[i+1])
    std::vector<uint32_t> list;
    std::vector<glm::vec3> built;        ///< positions the list was built at
    std::vector<glm::vec3> corr;         ///< per particle correction of the current substep
    bool list_valid = false;             ///< false: rebuild at the next substep
    float skin = 0;                      ///< m, of the current list
    uint64_t rebuilds = 0;               ///< list builds since creation (diagnostics)
    std::atomic<uint64_t> contacts{0};   ///< contacts found since creation (both ends; diagnostics)

    SelfCollision() = default;
    SelfCollision(const SelfCollision&) = delete;
    SelfCollision& operator=(const SelfCollision&) = delete;
};

}  // namespace drape
