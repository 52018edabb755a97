#include "core/cloth.h"

#include <algorithm>
#include <chrono>
#include <queue>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "backend/cpu/kernels.h"
#include "backend/cpu/kernels_simd.h"

namespace drape {

Cloth::Cloth(World& world, drape_backend backend, Topology topology)
    : world_(world), backend_(backend), topo_(std::move(topology)), params_(default_params()) {
    const uint32_t n = topo_.particle_count;
    base_inverse_mass_.resize(n);
    for (uint32_t i = 0; i < n; ++i) base_inverse_mass_[i] = 1.0f / topo_.mass[i];
    pinned_.assign(n, 0);
    kinematic_target_.assign(topo_.rest_position.begin(), topo_.rest_position.end());
    for (auto& b : buffers_) b.resize(n);
    for (uint32_t i = 0; i < n; ++i) buffers_[cur_][i] = Particle(topo_.rest_position[i], 0.0f);
    lambda_.assign(size_t(n) * topo_.nbr.slots, 0.0f);
    target_.resize(n);
    slot_coef_.assign(size_t(n) * topo_.nbr.slots, 0.0f);
    const NeighbourTable& nb = topo_.nbr;
    col_index_.resize(nb.index.size());
    col_rest_.resize(nb.rest.size());
    col_group_.resize(nb.group.size());
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t s = 0; s < nb.slots; ++s) {
            col_index_[size_t(s) * n + i] = nb.index[size_t(i) * nb.slots + s];
            col_rest_[size_t(s) * n + i] = nb.rest[size_t(i) * nb.slots + s];
            col_group_[size_t(s) * n + i] = nb.group[size_t(i) * nb.slots + s];
        }
    active_count_.resize(n);
    kinematic_.reserve(n);
    kinematic_start_.resize(n);
    backup_cur_.resize(n);
    backup_disp_.resize(n);
    partials_.resize(world.pool().size());
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
        buffers_[cur_][i].w = buffers_[disp_][i].w = w;
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
        h_max = std::min(h_max, mass_spring_max_substep(buffers_[cur_][i].w, ksum, params_.damping, active));
    }
    ms_h_max_ = h_max;
    // IMPLICIT: refactor now (not in step, which must not allocate) when what the matrix depends
    // on changed: effective masses (which particles are kinematic, masses), stiffness, damping.
    if (params_.model == DRAPE_MODEL_IMPLICIT) {
        if (implicit_.inputs_changed(params_, buffers_[cur_].data(), n) || implicit_.h() == 0)
            factor_implicit(last_h_ > 0 ? last_h_ : kDefaultH / float(kAutoSubstepsImplicit));
    } else {
        implicit_.clear();
    }
    if (kinematic_ != tethered_kinematic_) rebuild_tethers();
    for (uint32_t i = 0; i < n; ++i)
        tether_length_[i] = tether_rest_[i] < 0 ? -1.0f : tether_rest_[i] * (1.0f + params_.max_stretch);
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

void Cloth::set_params(const drape_params& p) {
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
            kinematic_target_[i] = glm::vec3(buffers_[cur_][i]);  // held where it is
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
        kinematic_target_[i] = glm::vec3(buffers_[cur_][i]);
    }
    refresh_derived();
}

void Cloth::set_positions(const float* xyz) {
    wake();
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        const glm::vec3 p(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        buffers_[cur_][i] = Particle(p, buffers_[cur_][i].w);
        buffers_[disp_][i] = Particle(glm::vec3(0.0f), buffers_[cur_][i].w);
        if (buffers_[cur_][i].w == 0.0f) kinematic_target_[i] = p;
    }
    fresh_ = true;
}

void Cloth::set_velocities(const float* xyz) {
    wake();
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        if (buffers_[cur_][i].w == 0.0f) continue;  // kinematic particles follow their targets
        const glm::vec3 vel(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        buffers_[disp_][i] = Particle(vel * h_prev_, buffers_[cur_][i].w);
    }
    fresh_ = true;
}

uint32_t Cloth::substeps_for(float dt) const { return drape::substeps_for(params_, ms_h_max_, dt); }

uint32_t Cloth::iterations_for() const {
    if (params_.iterations > 0) return params_.iterations;
    return params_.model == DRAPE_MODEL_IMPLICIT ? kAutoIterationsImplicit : 1;
}

template <class KinematicAt>
void Cloth::implicit_substep(kernels::SubstepContext& c, const KinematicAt& kinematic_at) {
    // Target y into target_, inertia as the first iterate into spare2; then each iteration
    // d += A^-1 r, r = kernels::implicit_residual, A = M/h^2 + sum_springs (k + kd/h) (e_i - e_j)
    // (e_i - e_j)^T over the free particles: Projective Dynamics' constant matrix (Bouaziz et al.
    // 2014), prefactored, as the preconditioner of the exact force residual. A bounds the spring
    // Hessian (k n n^T + k (1 - L/l)(I - n n^T) <= k I), so every iteration lowers Phi; it solves
    // the linear part (rigid motion, stretch of a hanging cloth) in one iteration, which local
    // Jacobi-type sweeps need O(n) iterations for; and the fixed point is the exact equilibrium
    // whatever A is (kernels::implicit_residual), so A is refactored only when it drifts far.
    Particle* cur = buffers_[cur_].data();
    Particle* disp = buffers_[disp_].data();
    Particle* target = target_.data();
    Particle* iterate = buffers_[spare2_].data();
    Particle* residual = buffers_[spare_].data();
    for_particles([&](uint32_t b, uint32_t e) { kernels::implicit_predict(c, cur, disp, target, iterate, b, e); });
    for (uint32_t k : kinematic_) target[k] = iterate[k] = Particle(kinematic_at(k) - glm::vec3(cur[k]), 0.0f);
    if (!(std::fabs(implicit_.h() / c.h - 1.0f) < kImplicitRefactor)) factor_implicit(c.h);  // dt changed a lot
    const uint32_t iterations = iterations_for();
    for (uint32_t it = 0; it < iterations; ++it) {
        for_particles([&](uint32_t b, uint32_t e) { kernels::implicit_residual(c, iterate, target, cur, residual, b, e); });
        implicit_.apply(residual, iterate);
    }
    // Commit: positions start + d into the old displacement buffer, d becomes the state.
    for_particles([&](uint32_t b, uint32_t e) {
        for (uint32_t i = b; i < e; ++i) disp[i] = Particle(glm::vec3(cur[i]) + glm::vec3(iterate[i]), cur[i].w);
    });
    const int old_cur = cur_;
    cur_ = disp_;
    disp_ = spare2_;
    spare2_ = old_cur;
}

void Cloth::factor_implicit(float h) {
    implicit_.factor(topo_.nbr, params_, buffers_[cur_].data(), topo_.particle_count, h);
}

template <class Fn>
void Cloth::for_particles(Fn&& fn) {
    if (backend_ == DRAPE_BACKEND_CPU_THREADED)
        world_.pool().parallel_for(topo_.particle_count, fn);
    else
        fn(0u, topo_.particle_count);
}

// Far from the caller's origin floats lose the cloth's detail (1e4 m: 1 mm steps), so positions
// are held relative to origin_; once the cloth has drifted kRecentreDistance (core/params.h) from
// it, origin_ moves by whole metres and every held position (state, pin targets, colliders, owner, the
// self-collision reference) shifts back by the same exact amount.
void Cloth::recentre() {
    const glm::vec3 x0 = glm::vec3(buffers_[cur_][0]);
    if (!(std::fabs(x0.x) > kRecentreDistance || std::fabs(x0.y) > kRecentreDistance ||
          std::fabs(x0.z) > kRecentreDistance))
        return;
    const glm::vec3 shift = glm::round(x0);
    origin_ += glm::dvec3(shift);
    for (Particle& p : buffers_[cur_]) p = Particle(glm::vec3(p) - shift, p.w);
    for (glm::vec3& t : kinematic_target_) t -= shift;
    for (ColliderState& c : ix_.colliders) {
        c.pos_start -= shift;
        c.pos_end -= shift;
    }
    ix_.owner_pos -= shift;
    for (glm::vec3& b : sc_.built) b -= shift;
}

Result Cloth::step(float dt) {
    if (skip_step_asleep()) return {};  // asleep -> no work (core/interaction.cpp)
    const auto t0 = std::chrono::steady_clock::now();
    const uint32_t n = topo_.particle_count;
    const NeighbourTable& nb = topo_.nbr;
    const uint32_t substeps = substeps_for(dt);
    const float h = dt / float(substeps);
    last_h_ = h;
    const drape_model model = drape_model(params_.model);

    std::memcpy(backup_cur_.data(), buffers_[cur_].data(), n * sizeof(Particle));
    std::memcpy(backup_disp_.data(), buffers_[disp_].data(), n * sizeof(Particle));
    const float backup_h_prev = h_prev_;
    const bool backup_fresh = fresh_;
    for (uint32_t k : kinematic_) kinematic_start_[k] = glm::vec3(buffers_[cur_][k]);

    kernels::SubstepContext c{};
    c.nbr_index = nb.index.data();
    c.nbr_rest = nb.rest.data();
    c.nbr_group = nb.group.data();
    c.nbr_count = nb.count.data();
    c.active_count = active_count_.data();
    c.slots = nb.slots;
    c.stride = n;
    c.col_index = col_index_.data();
    c.col_rest = col_rest_.data();
    c.col_group = col_group_.data();
    const uint32_t iterations = iterations_for();
    c.lambda = model == DRAPE_MODEL_XPBD && iterations > 1 ? lambda_.data() : nullptr;
    for (int g = 0; g < DRAPE_GROUP_COUNT; ++g) {
        const float k = params_.stiffness[g];
        c.groups.stiffness[g] = k;
        c.groups.active[g] = k > 0;
        c.groups.compliance[g] = k > 0 ? 1.0f / (k * h * h) : 0.0f;
        c.groups.damping_ratio[g] = k > 0 ? params_.damping / (k * h) : 0.0f;
    }
    c.gravity = glm::vec3(params_.gravity[0], params_.gravity[1], params_.gravity[2]);
    c.wind = glm::vec3(params_.wind[0], params_.wind[1], params_.wind[2]);
    c.air_drag = params_.air_drag;
    c.damping = params_.damping;
    c.h = h;
    if (model == DRAPE_MODEL_XPBD)
        for_particles([&](uint32_t b, uint32_t e) {
            kernels::spring_coefficients<true>(c, buffers_[cur_].data(), slot_coef_.data(), b, e);
        });
    else if (model == DRAPE_MODEL_PBD)
        for_particles([&](uint32_t b, uint32_t e) {
            kernels::spring_coefficients<false>(c, buffers_[cur_].data(), slot_coef_.data(), b, e);
        });

    for (uint32_t sub = 0; sub < substeps; ++sub) {
        c.h_prev = h_prev_;
        c.h_ratio = h / h_prev_;
        c.accel_h = fresh_ ? 0.5f * h : 0.5f * (h + h_prev_);
        Particle* cur = buffers_[cur_].data();
        Particle* disp = buffers_[disp_].data();
        Particle* spare = buffers_[spare_].data();
        Particle* spare2 = buffers_[spare2_].data();
        // Kinematic particles move along a straight line from their start to their target.
        const float along = float(sub + 1) / float(substeps);
        auto kinematic_at = [&](uint32_t k) {
            return kinematic_start_[k] + (kinematic_target_[k] - kinematic_start_[k]) * along;
        };
        if (model == DRAPE_MODEL_IMPLICIT) {
            implicit_substep(c, kinematic_at);
        } else if (model == DRAPE_MODEL_MASS_SPRING) {
            for_particles([&](uint32_t b, uint32_t e) { kernels::mass_spring_step(c, cur, disp, spare, spare2, b, e); });
            for (uint32_t k : kinematic_) {
                spare[k] = Particle(kinematic_at(k), 0.0f);
                spare2[k] = Particle(glm::vec3(spare[k]) - glm::vec3(cur[k]), 0.0f);
            }
            std::swap(cur_, spare_);
            std::swap(disp_, spare2_);
        } else {
            // predict: displacements into spare; iterate spare <-> spare2; the last iteration
            // also writes positions, into the displacement buffer (free after predict).
            if (model == DRAPE_MODEL_PBD && params_.damping > 0)
                for_particles([&](uint32_t b, uint32_t e) { kernels::predict<true>(c, cur, disp, spare, b, e); });
            else
                for_particles([&](uint32_t b, uint32_t e) { kernels::predict<false>(c, cur, disp, spare, b, e); });
            for (uint32_t k : kinematic_) spare[k] = Particle(kinematic_at(k) - glm::vec3(cur[k]), 0.0f);
            int in = spare_, out = spare2_;
            const bool xpbd = model == DRAPE_MODEL_XPBD;
            const float* coef = slot_coef_.data();
            for (uint32_t it = 0; it < iterations; ++it) {
                const bool last = it + 1 == iterations;
                Particle* src = buffers_[in].data();
                Particle* dst = buffers_[out].data();
                for_particles([&](uint32_t b, uint32_t e) {
                    using kernels::constraint_iteration_simd;
                    if (xpbd && last) constraint_iteration_simd<true, true>(c, coef, src, cur, dst, disp, b, e);
                    else if (xpbd) constraint_iteration_simd<true, false>(c, coef, src, cur, dst, nullptr, b, e);
                    else if (last) constraint_iteration_simd<false, true>(c, coef, src, cur, dst, disp, b, e);
                    else constraint_iteration_simd<false, false>(c, coef, src, cur, dst, nullptr, b, e);
                });
                std::swap(in, out);
            }
            // Positions went to the old displacement buffer, displacements to `in`.
            const int old_cur = cur_;
            cur_ = disp_;
            disp_ = in;
            spare_ = old_cur;
            spare2_ = out;
        }
        if (params_.max_stretch > 0 && !kinematic_.empty()) {
            Particle* x = buffers_[cur_].data();
            Particle* d = buffers_[disp_].data();
            for_particles([&](uint32_t b, uint32_t e) {
                kernels::tether(tether_anchor_.data(), tether_length_.data(), x, d, b, e);
            });
        }
        if (sc_.enabled) self_collision_substep();  // self-collision (core/self_collision.cpp)
        // touch drag + colliders on the committed positions (core/interaction.cpp)
        if (!ix_.colliders.empty() || !ix_.drag_particles.empty()) interaction_substep(sub, substeps);
        h_prev_ = h;
        fresh_ = false;
    }

    // Verify: finite positions and no runaway strain; strain statistics on the way.
    const Particle* x = buffers_[cur_].data();
    auto verify = [&](uint32_t t, uint32_t b, uint32_t e) {
        VerifyPartial p{true, 0, 0, 0, 0};
        for (uint32_t i = b; i < e; ++i) {
            if (!(std::isfinite(x[i].x) && std::isfinite(x[i].y) && std::isfinite(x[i].z))) p.finite = false;
            const size_t row = size_t(i) * nb.slots;
            for (uint32_t s = 0; s < nb.count[i]; ++s) {
                const uint32_t j = nb.index[row + s];
                const uint8_t g = nb.group[row + s];
                if (j < i || !(params_.stiffness[g] > 0) || !(nb.rest[row + s] > 0)) continue;
                const float strain = glm::length(glm::vec3(x[i]) - glm::vec3(x[j])) / nb.rest[row + s] - 1.0f;
                const float a = std::fabs(strain);
                if (!(a <= p.max_strain_all)) p.max_strain_all = a;  // also catches NaN
                if (g != DRAPE_GROUP_BEND) {
                    p.max_strain = std::max(p.max_strain, a);
                    p.sum_sq += strain * strain;
                    ++p.count;
                }
            }
        }
        partials_[t] = p;
    };
    const uint32_t parts = backend_ == DRAPE_BACKEND_CPU_THREADED ? world_.pool().size() : 1;
    if (parts == 1) {
        verify(0, 0, n);
    } else {
        world_.pool().run_on_all([&](uint32_t t) {
            verify(t, uint32_t(uint64_t(n) * t / parts), uint32_t(uint64_t(n) * (t + 1) / parts));
        });
    }
    VerifyPartial total{true, 0, 0, 0, 0};
    for (uint32_t t = 0; t < parts; ++t) {
        total.finite = total.finite && partials_[t].finite;
        if (!(partials_[t].max_strain_all <= total.max_strain_all)) total.max_strain_all = partials_[t].max_strain_all;
        total.max_strain = std::max(total.max_strain, partials_[t].max_strain);
        total.sum_sq += partials_[t].sum_sq;
        total.count += partials_[t].count;
    }

    stats_.substeps = substeps;
    stats_.iterations = model == DRAPE_MODEL_MASS_SPRING ? 1 : iterations;
    stats_.step_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const bool runaway = !(total.max_strain_all <= kRunawayStrain);
    stats_.non_finite = total.finite ? 0 : 1;
    if (!total.finite || runaway) {
        std::memcpy(buffers_[cur_].data(), backup_cur_.data(), n * sizeof(Particle));
        std::memcpy(buffers_[disp_].data(), backup_disp_.data(), n * sizeof(Particle));
        h_prev_ = backup_h_prev;
        fresh_ = backup_fresh;
        // kinematic_target_ keeps the requested pin and grab moves: the next step makes them.
        ++stats_.unstable_steps;
        interaction_end_step(dt, true);
        return {DRAPE_ERROR_UNSTABLE,
                std::string("step diverged (") + (total.finite ? "runaway strain" : "non-finite positions") +
                    " with " + std::to_string(substeps) + " substeps of " + std::to_string(h) +
                    " s); the state before the step was restored. Raise substeps or lower stiffness."};
    }
    stats_.max_strain = total.max_strain;
    stats_.rms_strain = total.count ? std::sqrt(total.sum_sq / float(total.count)) : 0.0f;
    interaction_end_step(dt, false);  // colliders advance, drag consumed, sleep check
    recentre();  // after the step, so a rolled-back step changes nothing
    return {};
}

void Cloth::read(const drape_vertex_layout& layout, void* dst) const {
    const uint32_t n = topo_.particle_count;
    const Particle* x = buffers_[cur_].data();
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
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        uint8_t* rec = bytes + size_t(v) * layout.stride;
        if (layout.position_offset >= 0) std::memcpy(rec + layout.position_offset, &x[i], 12);
        if (layout.normal_offset >= 0) std::memcpy(rec + layout.normal_offset, &normals_[i], 12);
    }
}

void Cloth::stats(drape_stats* out) const {
    drape_stats s = stats_;
    // Energies from the current state (computed on demand: a step does not pay for them).
    const Particle* x = buffers_[cur_].data();
    const Particle* d = buffers_[disp_].data();
    const NeighbourTable& nb = topo_.nbr;
    const glm::vec3 g(params_.gravity[0], params_.gravity[1], params_.gravity[2]);
    double kinetic = 0, potential = 0, elastic = 0;
    for (uint32_t i = 0; i < topo_.particle_count; ++i) {
        const float w = x[i].w;
        if (w > 0) {
            const glm::vec3 v = glm::vec3(d[i]) / h_prev_;
            kinetic += 0.5 * double(glm::dot(v, v)) / w;
            potential -= glm::dot(glm::dvec3(g), origin_ + glm::dvec3(glm::vec3(x[i]))) / w;
        }
        if (params_.model == DRAPE_MODEL_PBD) continue;
        const size_t row = size_t(i) * nb.slots;
        for (uint32_t k = 0; k < nb.count[i]; ++k) {
            const uint32_t j = nb.index[row + k];
            if (j < i) continue;
            const double stretch = glm::length(glm::vec3(x[i]) - glm::vec3(x[j])) - nb.rest[row + k];
            elastic += 0.5 * params_.stiffness[nb.group[row + k]] * stretch * stretch;
        }
    }
    s.kinetic_energy = float(kinetic);
    s.potential_energy = float(potential);
    s.elastic_energy = float(elastic);
    *out = s;
}

World::World(uint32_t threads) : pool_(threads) {}

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
    for (Cloth* c : cloths_) (c->backend() == DRAPE_BACKEND_CPU ? serial_ : threaded_).push_back(c);
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
