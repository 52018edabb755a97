#include "core/cloth.h"

#include <algorithm>
#include <queue>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace drape {

Description::Description(Topology cooked, uint32_t id_in_world) : id(id_in_world), topology(std::move(cooked)) {
    const uint32_t n = topology.particle_count;
    const NeighbourTable& nb = topology.nbr;
    col_index.resize(nb.index.size());
    col_rest.resize(nb.rest.size());
    col_group.resize(nb.group.size());
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < nb.slots; ++s) {
            col_index[size_t(s) * n + i] = nb.index[size_t(i) * nb.slots + s];
            col_rest[size_t(s) * n + i] = nb.rest[size_t(i) * nb.slots + s];
            col_group[size_t(s) * n + i] = nb.group[size_t(i) * nb.slots + s];
        }
}

Cloth::Cloth(World& world, drape_backend backend, std::shared_ptr<const Description> description)
    : world_(world), backend_(backend), desc_(std::move(description)), topo_(desc_->topology),
      params_(resolve_model(default_params())) {
    const uint32_t n = topo_.particle_count;
    base_inverse_mass_.resize(n);
    for (uint32_t i = 0; i < n; ++i) base_inverse_mass_[i] = 1.0f / topo_.mass[i];
    pinned_.assign(n, 0);
    kinematic_target_.assign(topo_.rest_position.begin(), topo_.rest_position.end());
    x_.resize(n);
    d_.resize(n);
    for (uint32_t i = 0; i < n; ++i) x_[i] = Particle(topo_.rest_position[i], 0.0f);
    active_count_.resize(n);
    kinematic_.reserve(n);
    tether_anchor_.assign(n, 0);
    tether_rest_.assign(n, -1.0f);
    tether_length_.assign(n, -1.0f);
    normals_.resize(n);
    stats_.struct_size = sizeof(drape_stats);
    refresh_derived();
}

void Cloth::refresh_derived() {
    const uint32_t n = topo_.particle_count;
    const NeighbourTable& nb = topo_.nbr;
    // Effective inverse masses into the state; list the kinematic particles.
    kinematic_.clear();
    for (uint32_t i = 0; i < n; ++i) {
        float w = pinned_[i] ? 0.0f : base_inverse_mass_[i];
        x_[i].w = d_[i].w = w;
        if (w == 0.0f) kinematic_.push_back(i);
    }
    // Active springs per particle, and the explicit stability bound (mass_spring_max_substep,
    // core/params.h; drape_estimate_stability runs the same on a cooked topology).
    float h_max = INFINITY;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t active = 0;
        float ksum = 0;
        for (uint32_t s = 0; s < nb.count[i]; ++s) {
            uint8_t g = nb.group[size_t(i) * nb.slots + s];
            if (params_.stiffness[g] > 0) {
                ++active;
                ksum += params_.stiffness[g];
            }
        }
        active_count_[i] = active;
        h_max = std::min(h_max, mass_spring_max_substep(x_[i].w, ksum, params_.damping, active));
    }
    ms_h_max_ = h_max;
    if (kinematic_ != tethered_kinematic_) rebuild_tethers();
    for (uint32_t i = 0; i < n; ++i)
        tether_length_[i] = tether_rest_[i] < 0 ? -1.0f : tether_rest_[i] * (1.0f + params_.max_stretch);
    refresh_backend();
}

void Cloth::rebuild_tethers() {
    // Multi-source Dijkstra from every kinematic particle over the structural and shear springs
    // (rest lengths as edge weights): the geodesic rest distance along the cloth, which is what a
    // hanging cloth can at most stretch out to.
    const uint32_t n = topo_.particle_count;
    const NeighbourTable& nb = topo_.nbr;
    std::fill(tether_rest_.begin(), tether_rest_.end(), -1.0f);
    using Item = std::pair<float, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    std::vector<float> dist(n, INFINITY);
    for (uint32_t k : kinematic_) {
        dist[k] = 0;
        tether_anchor_[k] = k;
        queue.push({0.0f, k});
    }
    while (!queue.empty()) {
        const auto [di, i] = queue.top();
        queue.pop();
        if (di > dist[i]) continue;
        tether_rest_[i] = di;
        const size_t row = size_t(i) * nb.slots;
        for (uint32_t s = 0; s < nb.count[i]; ++s) {
            if (nb.group[row + s] == DRAPE_GROUP_BEND) continue;
            const uint32_t j = nb.index[row + s];
            const float dj = di + nb.rest[row + s];
            if (dj < dist[j]) {
                dist[j] = dj;
                tether_anchor_[j] = tether_anchor_[i];
                queue.push({dj, j});
            }
        }
    }
    tethered_kinematic_ = kinematic_;
}

void Cloth::set_params(const drape_params& given) {
    const drape_params p = resolve_model(given);
    if (std::memcmp(&p, &params_, sizeof p) != 0) wake();
    params_ = p;
    refresh_derived();
}

void Cloth::set_inverse_masses(const float* inverse_masses) {
    wake();
    const uint32_t n = topo_.particle_count;
    std::vector<float> w(n, INFINITY);
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        float& slot = w[topo_.vertex_to_particle[v]];
        slot = std::min(slot, inverse_masses[v]);
    }
    for (uint32_t i = 0; i < n; ++i) {
        if (w[i] == 0.0f && base_inverse_mass_[i] != 0.0f && !pinned_[i])
            kinematic_target_[i] = glm::vec3(x_[i]);  // held where it is
        base_inverse_mass_[i] = w[i];
    }
    refresh_derived();
}

void Cloth::set_pins(const drape_pin* pins, uint32_t count) {
    if (pins_change(pins, count)) wake();
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = topo_.vertex_to_particle[pins[k].vertex];
        pinned_[i] = 1;
        kinematic_target_[i] = glm::vec3(pins[k].position[0], pins[k].position[1], pins[k].position[2]);
    }
    refresh_derived();
}

void Cloth::release_pins(const uint32_t* vertices, uint32_t count) {
    if (count) wake();
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = topo_.vertex_to_particle[vertices[k]];
        pinned_[i] = 0;
        kinematic_target_[i] = glm::vec3(x_[i]);
    }
    refresh_derived();
}

void Cloth::set_positions(const float* xyz) {
    wake();
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        const glm::vec3 p(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        x_[i] = Particle(p, x_[i].w);
        d_[i] = Particle(glm::vec3(0.0f), x_[i].w);
        if (x_[i].w == 0.0f) kinematic_target_[i] = p;
    }
    fresh_ = true;
}

void Cloth::set_velocities(const float* xyz) {
    wake();
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        if (x_[i].w == 0.0f) continue;  // kinematic particles follow their targets
        const glm::vec3 vel(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        d_[i] = Particle(vel * h_prev_, x_[i].w);
    }
    fresh_ = true;
}

uint32_t Cloth::substeps_for(float dt) const { return drape::substeps_for(params_, backend_, ms_h_max_, topo_.spring_count, dt); }

uint32_t Cloth::iterations_for() const {
    if (params_.iterations > 0) return params_.iterations;
    return params_.model == DRAPE_MODEL_IMPLICIT ? kAutoIterationsImplicit : 1;
}

void Cloth::read_cpu_copy(const drape_vertex_layout& layout, void* dst) const {
    const uint32_t n = topo_.particle_count;
    const Particle* x = x_.data();
    auto* bytes = static_cast<uint8_t*>(dst);
    if (layout.normal_offset >= 0) {
        // Area-weighted vertex normals: sum of unnormalised face normals.
        std::fill(normals_.begin(), normals_.end(), glm::vec3(0.0f));
        const auto& tri = topo_.triangles;
        for (size_t k = 0; k + 2 < tri.size(); k += 3) {
            const glm::vec3 p0(x[tri[k]]), p1(x[tri[k + 1]]), p2(x[tri[k + 2]]);
            const glm::vec3 fn = glm::cross(p1 - p0, p2 - p0);
            normals_[tri[k]] += fn;
            normals_[tri[k + 1]] += fn;
            normals_[tri[k + 2]] += fn;
        }
        for (uint32_t i = 0; i < n; ++i) {
            const float len = glm::length(normals_[i]);
            normals_[i] = len > 0 ? normals_[i] / len : glm::vec3(0, 1, 0);
        }
    }
    // Local positions -> the caller's space relative to layout.origin, in double.
    const glm::dvec3 shift = origin_ - glm::dvec3(layout.origin[0], layout.origin[1], layout.origin[2]);
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        uint8_t* rec = bytes + size_t(v) * layout.stride;
        if (layout.position_offset >= 0) {
            const glm::vec3 p = glm::vec3(glm::dvec3(glm::vec3(x[i])) + shift);
            std::memcpy(rec + layout.position_offset, &p, 12);
        }
        if (layout.normal_offset >= 0) std::memcpy(rec + layout.normal_offset, &normals_[i], 12);
    }
}

// Far from the caller's origin floats lose the cloth's detail (1e4 m: 1 mm steps), so positions
// are held relative to origin_; once the cloth has drifted kRecentreDistance (core/params.h) from
// it, origin_ moves by whole metres and every held position (state, pin targets, colliders, owner, the
// self-collision reference) shifts back by the same exact amount.
glm::vec3 Cloth::recentre_shift(const glm::vec3& reference) {
    if (!(std::fabs(reference.x) > kRecentreDistance || std::fabs(reference.y) > kRecentreDistance ||
          std::fabs(reference.z) > kRecentreDistance))
        return glm::vec3(0.0f);
    return glm::round(reference);
}

void Cloth::shift_origin(const glm::vec3& shift) {
    origin_ += glm::dvec3(shift);
    for (Particle& p : x_) p = Particle(glm::vec3(p) - shift, p.w);
    for (glm::vec3& t : kinematic_target_) t -= shift;
    for (ColliderState& c : ix_.colliders) {
        c.pos_start -= shift;
        c.pos_end -= shift;
    }
    ix_.owner_pos -= shift;
    for (glm::vec3& b : sc_.built) b -= shift;
}

void Cloth::stats_of_cpu_copy(drape_stats* out) const {
    drape_stats s = stats_;
    // Energies and strain statistics from the current state (computed on demand: a step does not
    // pay for them; one length per spring serves both).
    const Particle* x = x_.data();
    const Particle* d = d_.data();
    const NeighbourTable& nb = topo_.nbr;
    const glm::vec3 g(params_.gravity[0], params_.gravity[1], params_.gravity[2]);
    double kinetic = 0, potential = 0, elastic = 0, strain_sq = 0;
    float max_strain = 0;
    uint32_t strained = 0;  // springs in the strain statistics: structural and shear, active
    for (uint32_t i = 0; i < topo_.particle_count; ++i) {
        const float w = x[i].w;
        if (w > 0) {
            const glm::vec3 v = glm::vec3(d[i]) / h_prev_;
            kinetic += 0.5 * double(glm::dot(v, v)) / w;
            potential -= glm::dot(glm::dvec3(g), origin_ + glm::dvec3(glm::vec3(x[i]))) / w;
        }
        const size_t row = size_t(i) * nb.slots;
        for (uint32_t k = 0; k < nb.count[i]; ++k) {
            const uint32_t j = nb.index[row + k];
            if (j < i) continue;
            const uint8_t group = nb.group[row + k];
            const float rest = nb.rest[row + k];
            const float len = glm::length(glm::vec3(x[i]) - glm::vec3(x[j]));
            if (params_.model != DRAPE_MODEL_PBD) {
                const double stretch = len - rest;
                elastic += 0.5 * params_.stiffness[group] * stretch * stretch;
            }
            if (group == DRAPE_GROUP_BEND || !(params_.stiffness[group] > 0) || !(rest > 0)) continue;
            const float strain = len / rest - 1.0f;
            max_strain = std::max(max_strain, std::fabs(strain));
            strain_sq += double(strain) * strain;
            ++strained;
        }
    }
    s.kinetic_energy = float(kinetic);
    s.potential_energy = float(potential);
    s.elastic_energy = float(elastic);
    s.max_strain = max_strain;
    s.rms_strain = strained ? float(std::sqrt(strain_sq / strained)) : 0.0f;
    *out = s;
}

World::World(uint32_t threads, bool profile_stages) : pool_(threads), profile_stages_(profile_stages) {}

std::shared_ptr<const Description> World::describe(const std::string& key,
                                                   const std::function<CookResult(Topology&)>& cook,
                                                   CookResult* result) {
    *result = {};
    // Forget descriptions no cloth uses any more; reuse a live one cooked from the same bytes.
    for (auto it = descriptions_.begin(); it != descriptions_.end();)
        it = it->second.expired() ? descriptions_.erase(it) : std::next(it);
    auto found = descriptions_.find(key);
    if (found != descriptions_.end()) return found->second.lock();
    Topology topology;
    *result = cook(topology);
    if (result->status != DRAPE_OK) return nullptr;
    auto cooked = std::make_shared<const Description>(std::move(topology), ++descriptions_cooked_);
    descriptions_[key] = cooked;
    return cooked;
}

World::~World() {
    for (Cloth* c : std::vector<Cloth*>(cloths_)) delete c;
}

void World::remove(Cloth* c) { cloths_.erase(std::find(cloths_.begin(), cloths_.end(), c)); }

Result World::step(float dt) {
    // Single-threaded cloths are spread over the pool (one cloth is never split, so each stays
    // deterministic); threaded cloths then use the whole pool one after another. The lists keep
    // their capacity, so steady-state steps do not allocate.
    const uint32_t threads = pool_.size();
    serial_.clear();
    threaded_.clear();
    // GLES cloths need the caller's GL context: stepped on this thread with the threaded ones.
    for (Cloth* c : cloths_) (c->steps_on_pool_thread() ? serial_ : threaded_).push_back(c);
    results_.resize(serial_.size());
    if (threads > 1 && serial_.size() > 1) {
        pool_.run_on_all([&](uint32_t t) {
            for (size_t k = t; k < serial_.size(); k += threads) results_[k] = serial_[k]->step(dt);
        });
    } else {
        for (size_t k = 0; k < serial_.size(); ++k) results_[k] = serial_[k]->step(dt);
    }
    Result first;
    for (const Result& r : results_)
        if (!r.ok() && first.ok()) first = r;
    for (Cloth* c : threaded_) {
        Result r = c->step(dt);
        if (!r.ok() && first.ok()) first = r;
    }
    return first;
}

}  // namespace drape
