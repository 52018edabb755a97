// The coarse levels of IMPLICIT's GLES solve (sim.vert.glsl DRAPE_PASS_COARSE): an aggregation
// multigrid hierarchy of the constant matrix A = M/h^2 + sum over springs (k + kd/h) L_spring, the
// same scalar matrix per axis that the CPU prefactors (backend/cpu/implicit_solve.h). Cooked on the
// CPU when the cloth's substep, springs or masses change, uploaded as one table texture.
//
// Level 0 is the particles; level l+1 groups level l's nodes into aggregates of neighbours (greedy,
// over the matrix's graph, so any mesh works), prolongation piecewise constant, A_{l+1} = P^T A_l P
// (Galerkin). The coarsest level (at most kCoarsestNodes nodes) is solved with its dense inverse.
// Pinned particles take no part: the correction leaves them where their pin says.
#pragma once

#include <cstdint>
#include <vector>

#include "core/topology.h"
#include "shaders/layout.h"

namespace drape::gles {

/// Nodes of the coarsest level at most, solved densely: each of its nodes sums up to this many
/// products in one pass (at most 16384 fetches, a small share of a 33^2 fine pass). 128 rather than
/// 64 leaves out a level (two passes per substep) at 33^2 and 65^2.
constexpr uint32_t kCoarsestNodes = 128;
/// Members an aggregate may have (two RGBA32UI texels of indices); the greedy pass aims at
/// kAggregateSize (2 x 2 on a grid) and merges leftovers into neighbours up to the cap.
constexpr uint32_t kMaxMembers = DRAPE_MAX_MEMBERS;
constexpr uint32_t kAggregateSize = 4;
constexpr uint32_t kNoNode = DRAPE_NO_NODE;
static_assert(kMaxMembers % 4 == 0, "members fill whole texels");

/// Where each level lives in the table texture and the vector buffer (texel offsets).
struct CoarseLevel {
    uint32_t count = 0;    ///< nodes
    uint32_t info = 0;     ///< table: per node (first entry texel, entries, parent at l+1, diag bits)
    uint32_t members = 0;  ///< table (l >= 1): per node kMaxMembers / 4 texels of level l-1 indices
    uint32_t residual = 0, correction = 0;  ///< vector buffer (l >= 1), row-aligned: R_l and e_l
};

struct CoarseHierarchy {
    std::vector<CoarseLevel> levels;  ///< [0] the particles; empty or size 1: no coarse correction
    uint32_t dense = 0;               ///< table: the coarsest level's inverse, count^2 texels (x = bits)
    std::vector<uint32_t> table;      ///< RGBA32UI texels, 4 words each
    uint32_t vector_texels = 0;       ///< vector buffer size, whole rows
    bool active() const { return levels.size() > 1; }
};

/// The hierarchy for a substep h: masses from inverse masses w (0: pinned or kinematic), springs
/// from the neighbour table where stiffness[group] > 0, damping kd along each spring.
CoarseHierarchy cook_coarse(const NeighbourTable& nb, const std::vector<float>& inverse_mass,
                            const float stiffness[DRAPE_GROUP_COUNT], float damping, float h, uint32_t tex_width);

}  // namespace drape::gles
