// Self-collision: the setting and the per-substep pass. The C ABI (src/api) has validated
// the input. Kernels and the method: backend/cpu/self_collide.h.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "backend/cpu/self_collide.h"
#include "core/cloth.h"

namespace drape {

void Cloth::set_self_collision(bool enabled, float thickness, float friction) {
    if (enabled != sc_.enabled || (enabled && (thickness != sc_.thickness || friction != sc_.friction))) wake();
    if (thickness != sc_.thickness) sc_.list_valid = false;
    sc_.enabled = enabled;
    sc_.thickness = thickness;
    sc_.friction = friction;
}

void Cloth::self_collision_substep() {
    const uint32_t n = topo_.particle_count;
    Particle* x = x_.data();
    Particle* d = d_.data();  // this substep's displacement: start = x - d
    SelfCollision& s = sc_;
    const float t = s.thickness;
    if (s.cell.size() != n) {  // first use: size everything once (hash: a power of two >= 2n buckets)
        uint32_t buckets = 1;
        while (buckets < 2 * n) buckets *= 2;
        s.bucket_start.assign(size_t(buckets) + 1, 0);
        s.entries.assign(n, 0);
        s.cell.assign(n, glm::ivec3(0));
        s.list_start.assign(size_t(n) + 1, 0);
        s.list.reserve(size_t(n) * 8);
        s.built.assign(n, glm::vec3(0.0f));
        s.corr.assign(n, glm::vec3(0.0f));
        s.list_valid = false;
    }

    // Is the list still complete? Every particle's offset from where the list was built, at the
    // substep start and end, must lie within skin/2 of the mean offset: then any two particles'
    // relative position changed by at most skin along the whole substep, and a pair that was not
    // listed (farther apart than thickness + skin) never came within thickness.
    bool rebuild = !s.list_valid;
    if (!rebuild) {
        glm::vec3 mean(0.0f);
        for (uint32_t i = 0; i < n; ++i) mean += glm::vec3(x[i]) - s.built[i];
        mean *= 1.0f / float(n);
        float dev2 = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const glm::vec3 e = glm::vec3(x[i]) - s.built[i] - mean;
            const glm::vec3 f = e - glm::vec3(d[i]);
            dev2 = std::fmax(dev2, std::fmax(glm::dot(e, e), glm::dot(f, f)));
        }
        const float half = 0.5f * s.skin;
        rebuild = !(dev2 <= half * half);  // NaN rebuilds too
    }

    const float exclude = kSelfExcludeRest * t;
    kernels::SelfContact contact{};
    contact.thickness = t;
    contact.exclude_rest2 = exclude * exclude;
    contact.friction = s.friction;
    contact.rest = topo_.rest_position.data();
    contact.nbr_index = topo_.nbr.index.data();
    contact.nbr_count = topo_.nbr.count.data();
    contact.slots = topo_.nbr.slots;
    const bool threaded = backend_ == DRAPE_BACKEND_CPU_THREADED;

    if (rebuild) {
        // Skin: twice this substep's motion spread around the mean (the substep start must be
        // covered too), within [kSelfMinSkin, kSelfMaxSkin] thicknesses.
        glm::vec3 mean(0.0f);
        for (uint32_t i = 0; i < n; ++i) mean += glm::vec3(d[i]);
        mean *= 1.0f / float(n);
        float spread2 = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const glm::vec3 v = glm::vec3(d[i]) - mean;
            spread2 = std::fmax(spread2, glm::dot(v, v));
        }
        const float want = 2.0f * std::sqrt(spread2);
        s.skin = std::isfinite(want) ? std::fmin(std::fmax(want, kSelfMinSkin * t), kSelfMaxSkin * t) : kSelfMaxSkin * t;
        contact.list_radius = t + s.skin;

        // Counting sort of the particles into buckets by cell (serial, in particle order: the
        // layout, hence every list's order, does not depend on threads).
        const uint32_t mask = uint32_t(s.bucket_start.size()) - 2;
        const float inv_cell = 1.0f / contact.list_radius;
        std::fill(s.bucket_start.begin(), s.bucket_start.end(), 0u);
        for (uint32_t i = 0; i < n; ++i) {
            s.cell[i] = kernels::self_cell(glm::vec3(x[i]), inv_cell);
            ++s.bucket_start[kernels::self_bucket(s.cell[i], mask) + 1];
        }
        for (size_t b = 1; b < s.bucket_start.size(); ++b) s.bucket_start[b] += s.bucket_start[b - 1];
        for (uint32_t i = 0; i < n; ++i) s.entries[s.bucket_start[kernels::self_bucket(s.cell[i], mask)]++] = i;
        for (size_t b = s.bucket_start.size() - 1; b > 0; --b) s.bucket_start[b] = s.bucket_start[b - 1];
        s.bucket_start[0] = 0;
        const kernels::SelfHash hash{inv_cell, mask, s.bucket_start.data(), s.entries.data(), s.cell.data()};

        // Lists. Threaded: count per particle, offsets, fill (both passes split over the pool).
        // One thread: a single pass appending. Same lists either way.
        uint32_t* start = s.list_start.data();
        s.list_start[0] = 0;
        if (threaded) {
            auto count = [&](uint32_t b, uint32_t e) {
                kernels::self_candidates(contact, hash, x, b, e, [](uint32_t, uint32_t, uint32_t) {},
                                         [&](uint32_t i, uint32_t k) { start[i + 1] = k; });
            };
            world_.pool().parallel_for(n, count);
            for (uint32_t i = 0; i < n; ++i) start[i + 1] += start[i];
            if (s.list.size() < start[n]) s.list.resize(start[n]);
            uint32_t* list = s.list.data();
            auto fill = [&](uint32_t b, uint32_t e) {
                kernels::self_candidates(contact, hash, x, b, e,
                                         [&](uint32_t i, uint32_t k, uint32_t j) { list[start[i] + k] = j; },
                                         [](uint32_t, uint32_t) {});
            };
            world_.pool().parallel_for(n, fill);
        } else {
            s.list.clear();  // keeps its capacity
            kernels::self_candidates(contact, hash, x, 0u, n,
                                     [&](uint32_t, uint32_t, uint32_t j) { s.list.push_back(j); },
                                     [&](uint32_t i, uint32_t) { start[i + 1] = uint32_t(s.list.size()); });
        }
        for (uint32_t i = 0; i < n; ++i) s.built[i] = glm::vec3(x[i]);
        s.list_valid = true;
        ++s.rebuilds;
    }
    contact.list_radius = t + s.skin;

    glm::vec3* corr = s.corr.data();
    const uint32_t* start = s.list_start.data();
    const uint32_t* list = s.list.data();
    auto gather = [&](uint32_t b, uint32_t e) {
        const uint32_t found = kernels::self_collide_gather(contact, start, list, x, d, corr, b, e);
        if (found) s.contacts.fetch_add(found, std::memory_order_relaxed);
    };
    auto apply = [&](uint32_t b, uint32_t e) { kernels::self_collide_apply(corr, x, d, b, e); };
    if (threaded) {
        world_.pool().parallel_for(n, gather);
        world_.pool().parallel_for(n, apply);
    } else {
        gather(0u, n);
        apply(0u, n);
    }
}

}  // namespace drape
