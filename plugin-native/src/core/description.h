// The cooked description of a cloth: everything derived only from its input (grid or mesh bytes
// and total mass): topology, rest lengths, masses, the neighbour table and its column-major copy.
// Immutable once cooked and held by shared_ptr<const>: cloths of one world cooked from identical
// input share one (World::describe); each cloth keeps its own settings and state.
#pragma once

#include <cstdint>
#include <vector>

#include "core/topology.h"

namespace drape {

struct Description {
    Description(Topology cooked, uint32_t id_in_world);

    const uint32_t id;  ///< unique among the descriptions its world has cooked
    const Topology topology;
    /// Column-major copy of topology.nbr for the CPU constraint iteration (backend/cpu/kernels.h):
    /// slot s of particle i at [s * particle_count + i].
    std::vector<uint32_t> col_index;
    std::vector<float> col_rest;
    std::vector<uint8_t> col_group;
};

}  // namespace drape
