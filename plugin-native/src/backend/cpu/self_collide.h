// Self-collision kernels: particle-particle contacts found through a spatial hash.
//
// The cloth is a set of particles of radius thickness/2: two particles that are not neighbours in
// the rest mesh are kept at least `thickness` apart, position-based, once per substep after the
// solve (the contact maths, with the hashed grid's bucket, is shaders/self_contact.h, shared with
// the GLES self-collide pass; counting-sort layout as in Mueller's "Ten minute physics" 15).
//
// Candidates: a Verlet list (pairs closer than thickness + skin when it was built) rebuilt only
// when some particle has moved by more than skin/2 relative to the cloth's mean motion since, so
// no pair missing from the list can have come within thickness along its path (triangle
// inequality); a cloth at rest or moving as a whole keeps its list. Built from a hashed grid.
//
// Like kernels.h the correction is a gather: particle i reads the positions x and substep
// displacements d (substep start = x - d) of itself and its candidates, and writes only its own
// correction, the mean of its pair corrections (Jacobi with constraint averaging, Bender et al.
// "Position-based simulation methods", 2015, section 4.2.3). A separate pass applies the
// corrections to x and to d (so the velocity follows). The hash is built serially in particle
// order, so the candidates' order, and hence every sum, is the same for any split over threads.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "backend/cpu/glsl.h"  // glsl::self_contact, self_bucket (shaders/self_contact.h)

namespace drape::kernels {

/// Cells are clamped to +-kSelfCellLimit per axis, so cell coordinates (and their +-1
/// neighbours) fit an int32 for any position, NaN included (those land in one far cell; such a
/// step is rolled back by the verify pass anyway).
constexpr float kSelfCellLimit = 1e9f;

/// Integer cell of a point for cells of size 1/inv_cell.
inline glm::ivec3 self_cell(const glm::vec3& p, float inv_cell) {
    auto axis = [&](float v) {
        const float q = std::floor(v * inv_cell);
        return int32_t(std::fmin(std::fmax(q, -kSelfCellLimit), kSelfCellLimit));  // fmax(NaN, a) = a
    };
    return glm::ivec3(axis(p.x), axis(p.y), axis(p.z));
}

/// Bucket of a cell in a table of mask+1 (a power of two) buckets.
inline uint32_t self_bucket(const glm::ivec3& c, uint32_t mask) { return glsl::self_bucket(c, mask); }

/// The hash as the gather reads it (built by CpuCloth::self_collide, backend/cpu/cpu_collide.cpp).
struct SelfHash {
    float inv_cell;               ///< 1 / cell size (1/m); cell size = list radius
    uint32_t mask;                ///< buckets - 1
    const uint32_t* bucket_start; ///< mask+2 entries: particles of bucket b are entries[start[b], start[b+1])
    const uint32_t* entries;      ///< particle indices, ascending within a bucket
    const glm::ivec3* cell;       ///< per particle: its cell (tells apart cells sharing a bucket)
};

/// Contact parameters.
struct SelfContact {
    float thickness;      ///< m, distance kept between non-neighbour particles
    float list_radius;    ///< m, candidate lists hold the pairs closer than this (thickness + skin)
    float exclude_rest2;  ///< m^2, pairs closer than this in the rest mesh never collide
    float friction;       ///< Coulomb coefficient, >= 0
    const glm::vec3* rest;      ///< rest positions (topology)
    const uint32_t* nbr_index;  ///< neighbour table: pairs sharing a spring never collide
    const uint32_t* nbr_count;
    uint32_t slots;
};

/// Candidate lists (a Verlet list, as in molecular dynamics): for each particle i in [begin, end),
/// calls emit(i, k, j) for the k-th particle j closer than list_radius to i that may collide with it
/// (not i, no shared spring, not closer than sqrt(exclude_rest2) at rest), then done(i, count).
/// Cell size of the hash = list_radius, so the 27 cells around i's cell hold every candidate; the
/// order is the hash's (fixed by the serial build), whatever the split over threads.
template <class Emit, class Done>
inline void self_candidates(const SelfContact& c, const SelfHash& h, const glm::vec4* x, uint32_t begin,
                            uint32_t end, Emit&& emit, Done&& done) {
    const float r2 = c.list_radius * c.list_radius;
    for (uint32_t i = begin; i < end; ++i) {
        const glm::vec3 xi(x[i]), ri = c.rest[i];
        const glm::ivec3 ci = h.cell[i];
        const uint32_t* row = c.nbr_index + size_t(i) * c.slots;
        const uint32_t row_count = c.nbr_count[i];
        uint32_t k = 0;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 cell = ci + glm::ivec3(dx, dy, dz);
                    const uint32_t b = self_bucket(cell, h.mask);
                    for (uint32_t e = h.bucket_start[b]; e < h.bucket_start[b + 1]; ++e) {
                        const uint32_t j = h.entries[e];
                        if (j == i || h.cell[j] != cell) continue;  // self, or another cell in this bucket
                        const glm::vec3 xij = xi - glm::vec3(x[j]);
                        if (!(glm::dot(xij, xij) < r2)) continue;
                        const glm::vec3 rij = ri - c.rest[j];
                        if (glm::dot(rij, rij) < c.exclude_rest2) continue;
                        bool spring = false;
                        for (uint32_t s = 0; s < row_count && !spring; ++s) spring = row[s] == j;
                        if (spring) continue;
                        emit(i, k, j);
                        ++k;
                    }
                }
        done(i, k);
    }
}

/// Writes corr[i] for particles [begin, end): the mean of particle i's pair corrections over its
/// candidates list[start[i], start[i+1]) (zero for kinematic particles and particles without
/// contact). Returns the number of contacts found (each pair counted from both ends).
inline uint32_t self_collide_gather(const SelfContact& c, const uint32_t* start, const uint32_t* list,
                                    const glm::vec4* x, const glm::vec4* d, glm::vec3* corr, uint32_t begin,
                                    uint32_t end) {
    uint32_t contacts_total = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const float wi = x[i].w;
        glm::vec3 sum(0.0f);
        uint32_t contacts = 0;
        if (wi != 0.0f) {
            const glm::vec3 xi(x[i]), di(d[i]);
            for (uint32_t e = start[i]; e < start[i + 1]; ++e) {
                const uint32_t j = list[e];
                const glm::vec3 xij = xi - glm::vec3(x[j]);
                const glm::vec3 dij = di - glm::vec3(d[j]);
                const float share = wi / (wi + x[j].w);
                glm::vec3 dxi;
                if (!glsl::self_contact(xij, dij, c.thickness, share, c.friction, i < j ? 1.0f : -1.0f, dxi)) continue;
                sum += dxi;
                ++contacts;
            }
        }
        corr[i] = contacts ? sum * (1.0f / float(contacts)) : glm::vec3(0.0f);
        contacts_total += contacts;
    }
    return contacts_total;
}

/// x += corr and d += corr (the substep start stays where it was, so the velocity d/h includes
/// the push) for particles [begin, end).
inline void self_collide_apply(const glm::vec3* corr, glm::vec4* x, glm::vec4* d, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const glm::vec3 c = corr[i];
        if (c == glm::vec3(0.0f)) continue;
        x[i] += glm::vec4(c, 0.0f);
        d[i] += glm::vec4(c, 0.0f);
    }
}

}  // namespace drape::kernels
