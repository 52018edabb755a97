// Cooked, immutable description of a cloth: particles, neighbour table, triangles, masses.
// Cooked once at creation (grid or triangle mesh); never touched by a step.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "drape/drape.h"

namespace drape {

/// Neighbour table, one row of `slots` entries per particle (the paper's per-vertex spring list).
/// Row i holds the springs of particle i in [0, count[i]); the rest of the row is padding
/// (index = i, rest = 0, group = kNoGroup). Every spring appears twice, once in each end's row,
/// so a per-particle gather (CPU or a GLES vertex shader) sees all of its springs.
struct NeighbourTable {
    static constexpr uint8_t kNoGroup = 0xff;
    uint32_t slots = 0;               ///< row length (12 for a grid, max valence for a mesh)
    std::vector<uint32_t> index;      ///< particle at the other end
    std::vector<float> rest;          ///< rest length, m
    std::vector<uint8_t> group;       ///< drape_group, or kNoGroup for padding
    std::vector<uint32_t> count;      ///< used slots per particle
};

/// Calls fn(j, k, slot) for every spring of particle i whose group has positive stiffness (slot: its
/// place in the table), with k = stiffness[group] + kd_h, the spring's coefficient in the constant
/// implicit matrix M/h^2 + sum (k + kd/h) that GLES coarsens (the CPU factors it with its bend springs
/// routed through their middles, implicit_solve.h); returns the sum of the k.
template <class Fn>
double for_each_spring_coefficient(const NeighbourTable& nb, const float* stiffness, double kd_h, uint32_t i,
                                   Fn&& fn) {
    double sum = 0;
    for (uint32_t s = 0; s < nb.count[i]; ++s) {
        const size_t slot = size_t(i) * nb.slots + s;
        const uint8_t g = nb.group[slot];
        if (g >= DRAPE_GROUP_COUNT || !(stiffness[g] > 0)) continue;
        const double k = stiffness[g] + kd_h;
        sum += k;
        fn(nb.index[slot], k, slot);
    }
    return sum;
}

struct Topology {
    uint32_t vertex_count = 0;                ///< caller vertices
    uint32_t particle_count = 0;              ///< after welding
    std::vector<uint32_t> vertex_to_particle; ///< caller vertex -> particle
    std::vector<glm::vec3> rest_position;     ///< per particle, m
    std::vector<float> mass;                  ///< per particle, kg (area-weighted share)
    std::vector<uint32_t> triangles;          ///< particle indices, 3 per triangle (for normals)
    NeighbourTable nbr;
    uint32_t spring_count[DRAPE_GROUP_COUNT] = {};
    float extent = 0;                         ///< diagonal of the rest bounding box, m
};

/// Result of cooking: a status and, on failure, the message for drape_last_error().
struct CookResult {
    drape_status status = DRAPE_OK;
    std::string message;
};

/// Grid with the paper's 12-spring stencil. Inputs must already be validated.
Topology cook_grid(const drape_grid_desc& grid, float total_mass);

/// Arbitrary triangle mesh: welds coincident vertices, structural springs on edges, bend springs
/// between the vertices opposite each interior edge. Validates indices and degenerate triangles.
CookResult cook_mesh(const drape_mesh_desc& mesh, float total_mass, Topology& out);

}  // namespace drape
