// The CPU step's contact stages (backend/cpu/cpu_cloth.h): touch drag and colliders (a broad
// phase, then kernels::collide in collide.h), and self-collision (a spatial hash, kernels in
// self_collide.h). Both work on the committed positions of a substep.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "backend/cpu/collide.h"
#include "backend/cpu/cpu_cloth.h"
#include "backend/cpu/self_collide.h"
#include "core/profile.h"

namespace drape::cpu {
namespace {

/// The cloth's bounds over a step of dt: its positions, grown by its fastest particle's travel over
/// the step (its last substep's displacement d scaled to dt).
Aabb step_bounds(const std::vector<kernels::Particle>& x, const std::vector<kernels::Particle>& d, float h_prev,
                 float dt) {
    Aabb cloth;
    float reach = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        cloth.add(glm::vec3(x[i]));
        reach = std::max(reach, glm::length(glm::vec3(d[i])));
    }
    if (h_prev > 0) reach *= dt / h_prev;
    cloth.lo -= reach;
    cloth.hi += reach;
    return cloth;
}

}  // namespace

uint32_t CpuCloth::collider_substeps(float dt, bool& contact_near) const {
    // Near: the collider's bounds over the step touch the cloth's over the step (step_bounds).
    const Aabb cloth = step_bounds(x_, d_, h_prev_, dt);
    uint32_t needed = 1;
    contact_near = false;
    for (const ColliderState& c : ix_.colliders) {
        const float travel = glm::length(c.pos_end - c.pos_start);
        const bool moving = c.shape != DRAPE_COLLIDER_PLANE && travel != 0;  // a plane cannot be passed around
        const bool contact = fine_ready_ && contact_substeps_for(c) > 0;
        if (!moving && !contact) continue;
        if (!touches(cloth, c.at_substep(0, 1))) continue;
        contact_near = contact_near || contact;
        if (!moving) continue;
        const float smallest =
            (c.shape == DRAPE_COLLIDER_BOX ? std::min({c.size.x, c.size.y, c.size.z}) : c.size.x) + c.margin;
        const float s_needed = std::ceil(travel / (kColliderTravelPerSubstep * smallest));
        needed = std::max(needed, s_needed >= float(kMaxSubsteps) ? kMaxSubsteps : uint32_t(s_needed));
    }
    return needed;
}

uint32_t CpuCloth::self_collision_substeps(float dt) const {
    const uint32_t n = topo_.particle_count;
    glm::vec3 mean(0.0f);
    for (uint32_t i = 0; i < n; ++i) mean += glm::vec3(d_[i]);
    mean /= float(n);
    float fastest = 0;
    for (uint32_t i = 0; i < n; ++i) fastest = std::max(fastest, glm::length(glm::vec3(d_[i]) - mean));
    const float s = std::ceil(fastest * (dt / h_prev_) / (kSelfMoveLimit * sc_.thickness));
    return s < 1 ? 1u : s >= float(kMaxSubsteps) ? kMaxSubsteps : uint32_t(s);
}

void CpuCloth::collide(uint32_t sub) {
    ProfileScope scope(profile_, DRAPE_STAGE_COLLIDE);
    const uint32_t substeps = substeps_;
    const uint32_t n = topo_.particle_count;
    Particle* x = x_.data();
    Particle* d = d_.data();  // this substep's displacement: start = x - d

    // Touch drag: 1/substeps of the step's displacement in the first substep gives the vertex
    // the finger's velocity (offset / dt); inertia carries it the rest of the way, so a free
    // vertex ends the step displaced by exactly the offset. (Adding a share in every substep
    // would accumulate: 1/S + 2/S + ... = (S+1)/2 times the offset.)
    if (sub == 0 && !ix_.drag_particles.empty()) {
        const float part = 1.0f / float(substeps);
        for (uint32_t i : ix_.drag_particles)
            if (x[i].w != 0.0f) {
                x[i] += Particle(ix_.drag_offset[i] * part, 0.0f);
                d[i] += Particle(ix_.drag_offset[i] * part, 0.0f);
            }
    }

    if (ix_.colliders.empty()) return;
    // Broad phase: colliders at this substep (host's previous -> new transform, interpolated)
    // against the bounds of the cloth's substep start and end positions.
    Aabb cloth;
    for (uint32_t i = 0; i < n; ++i) {
        cloth.add(glm::vec3(x[i]));
        cloth.add(glm::vec3(x[i]) - glm::vec3(d[i]));
    }
    shapes_.clear();
    for (const ColliderState& c : ix_.colliders) {
        const CollideShape s = c.at_substep(sub, substeps);
        if (touches(cloth, s)) shapes_.push_back(s);
    }
    if (shapes_.empty()) return;
    ix_.collide_tests += uint64_t(n) * shapes_.size();
    const CollideShape* shapes = shapes_.data();
    const uint32_t count = uint32_t(shapes_.size());
    glm::vec3* normal = params_.model == DRAPE_MODEL_IMPLICIT ? contact_normal_.data() : nullptr;
    for_particles([&](uint32_t b, uint32_t e) { kernels::collide(shapes, count, x, d, normal, b, e); });
    contact_fresh_ = normal != nullptr;
}

void CpuCloth::self_collide() {
    ProfileScope scope(profile_, DRAPE_STAGE_SELF_COLLIDE);
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

}  // namespace drape::cpu
