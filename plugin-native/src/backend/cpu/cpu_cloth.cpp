#include "backend/cpu/cpu_cloth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "backend/cpu/kernels_simd.h"
#include "core/profile.h"

namespace drape::cpu {

CpuCloth::CpuCloth(World& world, drape_backend backend, std::shared_ptr<const Description> description)
    : Cloth(world, backend, std::move(description)) {
    const uint32_t n = topo_.particle_count;
    spare_.resize(n);
    spare2_.resize(n);
    lambda_.assign(size_t(n) * topo_.nbr.slots, 0.0f);
    target_.resize(n);
    contact_normal_.resize(n);
    slot_coef_.assign(size_t(n) * topo_.nbr.slots, 0.0f);
    col_limit_.resize(size_t(n) * topo_.nbr.slots);
    kinematic_start_.resize(n);
    backup_x_.resize(n);
    backup_d_.resize(n);
    shapes_.reserve(DRAPE_MAX_COLLIDERS);
    partials_.resize(world.pool().size());
    refresh_backend();  // the base constructor's refresh_derived ran before this class existed
}

void CpuCloth::refresh_backend() {
    // The runaway check's limit per slot: a spring (1 + kRunawayStrain) times its rest length, squared.
    const NeighbourTable& nb = topo_.nbr;
    const float stretch = (1.0f + kRunawayStrain) * (1.0f + kRunawayStrain);
    for (uint32_t i = 0; i < topo_.particle_count; ++i)
        for (uint32_t s = 0; s < nb.slots; ++s) {
            const size_t slot = size_t(i) * nb.slots + s;
            const bool checked = s < nb.count[i] && nb.group[slot] < DRAPE_GROUP_COUNT &&
                                 params_.stiffness[nb.group[slot]] > 0 && nb.rest[slot] > 0;
            col_limit_[size_t(s) * topo_.particle_count + i] =
                checked ? stretch * (nb.rest[slot] * nb.rest[slot]) : INFINITY;
        }
    // IMPLICIT: refactor now (not in step, which must not allocate) when what the matrix depends
    // on changed: effective masses (which particles are kinematic, masses), stiffness, damping.
    const uint32_t n = topo_.particle_count;
    if (params_.model == DRAPE_MODEL_IMPLICIT) {
        if (implicit_.inputs_changed(params_, x_.data(), n) || implicit_.h() == 0)
            factor_implicit(last_h_ > 0 ? last_h_ : kDefaultH / float(kAutoSubstepsImplicit));
    } else {
        implicit_.clear();
    }
    refresh_contacts();
}

void CpuCloth::refresh_colliders() { refresh_contacts(); }

uint32_t CpuCloth::contact_substeps_for(const ColliderState& c) {
    return c.friction > 0.0f ? kFrictionSubstepsImplicit : c.shape != DRAPE_COLLIDER_PLANE ? kContactSubstepsImplicit : 0u;
}

void CpuCloth::refresh_contacts() {
    contact_substeps_ = 0;
    for (const ColliderState& c : ix_.colliders) contact_substeps_ = std::max(contact_substeps_, contact_substeps_for(c));
    fine_ready_ = contact_substeps_ > 0 && params_.model == DRAPE_MODEL_IMPLICIT && params_.substeps == 0;
    if (!fine_ready_) return;
    const float h = (last_dt_ > 0 ? last_dt_ : kDefaultH) / float(contact_substeps_);
    if (implicit_fine_.inputs_changed(params_, x_.data(), topo_.particle_count) || implicit_fine_.h() == 0 ||
        !(std::fabs(implicit_fine_.h() / h - 1.0f) < kImplicitRefactor))
        implicit_fine_.factor(topo_, params_, x_.data(), h);
}

template <class KinematicAt>
void CpuCloth::implicit_substep(kernels::SubstepContext& c, const KinematicAt& kinematic_at) {
    // Target y into target_, inertia and drag as the first iterate into spare2; then the solve
    // (implicit_solve.h) minimises Phi (kernels::implicit_residual) from there.
    Particle* cur = x_.data();
    Particle* disp = d_.data();
    Particle* target = target_.data();
    Particle* iterate = spare2_.data();
    for_particles([&](uint32_t b, uint32_t e) { kernels::implicit_predict(c, cur, disp, target, iterate, b, e); });
    for (uint32_t k : kinematic_) target[k] = iterate[k] = Particle(kinematic_at(k) - glm::vec3(cur[k]), 0.0f);
    // The finer factor where it fits this substep (collider_substeps), else the planned one.
    const bool fine = fine_ready_ && std::fabs(c.h / implicit_fine_.h() - 1.0f) < kImplicitRefactor;
    ImplicitSolve& implicit = fine ? implicit_fine_ : implicit_;
    if (!fine && !(std::fabs(implicit_.h() / last_h_ - 1.0f) < kImplicitRefactor)) factor_implicit(last_h_);  // dt changed a lot
    if (fresh_ || &implicit != implicit_last_) implicit.state_set();  // what the other one kept is stale
    implicit_last_ = &implicit;
    const uint32_t taken = implicit.solve(c, cur, target, iterate, iterations_, kImplicitTolerance,
                                           backend_ == DRAPE_BACKEND_CPU_THREADED ? &world_.pool() : nullptr,
                                           contact_fresh_ ? contact_normal_.data() : nullptr);
    contact_fresh_ = false;
    implicit_iterations_ = std::max(implicit_iterations_, taken);
    // Commit: positions start + d into the old displacement buffer, d becomes the state.
    for_particles([&](uint32_t b, uint32_t e) {
        for (uint32_t i = b; i < e; ++i) disp[i] = Particle(glm::vec3(cur[i]) + glm::vec3(iterate[i]), cur[i].w);
    });
    x_.swap(d_);
    d_.swap(spare2_);
}

void CpuCloth::factor_implicit(float h) {
    implicit_.factor(topo_, params_, x_.data(), h);
}

// Re-centred from particle 0 (Cloth::recentre_shift).
void CpuCloth::recentre() {
    const glm::vec3 shift = recentre_shift(glm::vec3(x_[0]));
    if (shift != glm::vec3(0.0f)) shift_origin(shift);
}

// The step reads like a table of contents: one function per stage (drape_stage), each run over
// all particles before the next and timed by a profile scope (core/profile.h) when the world
// profiles stages.
Result CpuCloth::step(float dt) {
    if (skip_step_asleep()) return {};  // asleep -> no work (core/interaction.cpp)
    const auto t0 = std::chrono::steady_clock::now();
    profile_ = world_.profile_stages() ? stats_.stage_ms : nullptr;
    if (profile_) std::fill_n(profile_, DRAPE_STAGE_COUNT, 0.0f);
    begin(dt);
    for (uint32_t sub = 0; sub < substeps_; ++sub) {
        const float along = float(sub + 1) / float(substeps_);  // share of the kinematic particles' move
        predict(along);
        solve(along);
        if (params_.max_stretch > 0 && !kinematic_.empty()) tether();
        if (sc_.enabled) self_collide();
        if (!ix_.colliders.empty() || !ix_.drag_particles.empty()) collide(sub);
        h_prev_ = h_;
        fresh_ = false;
    }
    const VerifyPartial total = verify();
    stats_.step_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return finish(dt, total);
}

void CpuCloth::begin(float dt) {
    ProfileScope scope(profile_, DRAPE_STAGE_BEGIN);
    // Plan: substeps and iterations from the parameters; the state backed up for a rollback.
    const uint32_t n = topo_.particle_count;
    substeps_ = substeps_for(dt);
    // IMPLICIT's factor follows the planned substep, not one a passing collider shortened for a
    // frame or two (refactoring allocates and costs many steps).
    last_h_ = dt / float(substeps_);
    last_dt_ = dt;
    bool contact_near = false;
    if (params_.substeps == 0 && !ix_.colliders.empty())
        substeps_ = std::min(kMaxSubsteps, std::max(substeps_, collider_substeps(dt, contact_near)));
    const bool contact = fine_ready_ && contact_near;
    if (contact) substeps_ = std::min(kMaxSubsteps, std::max(substeps_, contact_substeps_));
    if (params_.substeps == 0 && sc_.enabled)
        substeps_ = std::min(kMaxSubsteps, std::max(substeps_, self_collision_substeps(dt)));
    h_ = dt / float(substeps_);
    iterations_ = iterations_for();
    if (contact && params_.iterations == 0) iterations_ = std::max(iterations_, kContactIterationsImplicit);
    implicit_iterations_ = 0;
    for_particles([&](uint32_t b, uint32_t e) {  // on the pool (on the caller alone: ~2 % of a 65^2 1x1 step)
        std::copy(x_.begin() + b, x_.begin() + e, backup_x_.begin() + b);
        std::copy(d_.begin() + b, d_.begin() + e, backup_d_.begin() + b);
    });
    backup_h_prev_ = h_prev_;
    backup_fresh_ = fresh_;
    for (uint32_t k : kinematic_) kinematic_start_[k] = glm::vec3(x_[k]);

    // The step's constants for the kernels.
    const NeighbourTable& nb = topo_.nbr;
    const drape_model model = drape_model(params_.model);
    const float h = h_;
    kernels::SubstepContext& c = ctx_;
    c = kernels::SubstepContext{};
    c.nbr_index = nb.index.data();
    c.nbr_rest = nb.rest.data();
    c.nbr_group = nb.group.data();
    c.nbr_count = nb.count.data();
    c.active_count = active_count_.data();
    c.slots = nb.slots;
    c.stride = n;
    c.col_index = desc_->col_index.data();
    c.col_rest = desc_->col_rest.data();
    c.col_group = desc_->col_group.data();
    c.lambda = model == DRAPE_MODEL_XPBD && iterations_ > 1 ? lambda_.data() : nullptr;
    for (int g = 0; g < DRAPE_GROUP_COUNT; ++g) {
        const float k = params_.stiffness[g];
        c.groups.stiffness[g] = k;
        c.groups.active[g] = k > 0;
        c.groups.compliance[g] = xpbd_compliance(k, h);
        c.groups.damping_ratio[g] = xpbd_damping_ratio(k, params_.damping, h);
    }
    c.gravity = glm::vec3(params_.gravity[0], params_.gravity[1], params_.gravity[2]);
    c.wind = glm::vec3(params_.wind[0], params_.wind[1], params_.wind[2]);
    c.air_drag = params_.air_drag;
    c.damping = params_.damping;
    c.h = h;
    if (model == DRAPE_MODEL_XPBD)
        for_particles([&](uint32_t b, uint32_t e) {
            kernels::spring_coefficients<true>(c, x_.data(), slot_coef_.data(), b, e);
        });
    else if (model == DRAPE_MODEL_PBD)
        for_particles([&](uint32_t b, uint32_t e) {
            kernels::spring_coefficients<false>(c, x_.data(), slot_coef_.data(), b, e);
        });
}

glm::vec3 CpuCloth::kinematic_position(uint32_t k, float along) const {
    return kernels::glsl::kinematic_path(kinematic_start_[k], kinematic_target_[k], along);
}

void CpuCloth::predict(float along) {
    ProfileScope scope(profile_, DRAPE_STAGE_PREDICT);
    // The substep's constants, then PBD/XPBD's inertial prediction: displacements into spare_.
    // (MASS_SPRING predicts inside its one kernel, IMPLICIT inside implicit_substep: both solve.)
    kernels::SubstepContext& c = ctx_;
    c.h_prev = h_prev_;
    c.h_ratio = h_ / h_prev_;
    c.accel_h = verlet_accel_h(h_, h_prev_, fresh_);
    if (params_.model != DRAPE_MODEL_PBD && params_.model != DRAPE_MODEL_XPBD) return;
    Particle* cur = x_.data();
    Particle* disp = d_.data();
    Particle* spare = spare_.data();
    if (params_.model == DRAPE_MODEL_PBD && params_.damping > 0)
        for_particles([&](uint32_t b, uint32_t e) { kernels::predict<true>(c, cur, disp, spare, b, e); });
    else
        for_particles([&](uint32_t b, uint32_t e) { kernels::predict<false>(c, cur, disp, spare, b, e); });
    for (uint32_t k : kinematic_) spare[k] = Particle(kinematic_position(k, along) - glm::vec3(cur[k]), 0.0f);
}

void CpuCloth::solve(float along) {
    ProfileScope scope(profile_, DRAPE_STAGE_SOLVE);
    const kernels::SubstepContext& c = ctx_;
    Particle* cur = x_.data();
    Particle* disp = d_.data();
    if (params_.model == DRAPE_MODEL_IMPLICIT) {
        implicit_substep(ctx_, [&](uint32_t k) { return kinematic_position(k, along); });
    } else if (params_.model == DRAPE_MODEL_MASS_SPRING) {
        Particle* spare = spare_.data();
        Particle* spare2 = spare2_.data();
        for_particles([&](uint32_t b, uint32_t e) { kernels::mass_spring_step(c, cur, disp, spare, spare2, b, e); });
        for (uint32_t k : kinematic_) {
            spare[k] = Particle(kinematic_position(k, along), 0.0f);
            spare2[k] = Particle(glm::vec3(spare[k]) - glm::vec3(cur[k]), 0.0f);
        }
        x_.swap(spare_);
        d_.swap(spare2_);
    } else {
        // Iterate the predicted displacements spare_ <-> spare2_; the last iteration also writes
        // positions, into the displacement buffer (free after predict).
        std::vector<Particle>* in = &spare_;
        std::vector<Particle>* out = &spare2_;
        const bool xpbd = params_.model == DRAPE_MODEL_XPBD;
        const float* coef = slot_coef_.data();
        for (uint32_t it = 0; it < iterations_; ++it) {
            const bool last = it + 1 == iterations_;
            Particle* src = in->data();
            Particle* dst = out->data();
            for_particles([&](uint32_t b, uint32_t e) {
                using kernels::constraint_iteration_simd;
                if (xpbd && last) constraint_iteration_simd<true, true>(c, coef, src, cur, dst, disp, b, e);
                else if (xpbd) constraint_iteration_simd<true, false>(c, coef, src, cur, dst, nullptr, b, e);
                else if (last) constraint_iteration_simd<false, true>(c, coef, src, cur, dst, disp, b, e);
                else constraint_iteration_simd<false, false>(c, coef, src, cur, dst, nullptr, b, e);
            });
            std::swap(in, out);
        }
        // Positions went to the old displacement buffer, displacements to `in`; the old
        // positions become spare_ and the last scratch spare2_.
        x_.swap(d_);
        d_.swap(*in);
        if (in != &spare_) spare_.swap(spare2_);
    }
}

void CpuCloth::tether() {
    ProfileScope scope(profile_, DRAPE_STAGE_TETHER);
    Particle* x = x_.data();
    Particle* d = d_.data();
    const uint32_t* anchor = tether_anchor_.data();
    const float* length = tether_length_.data();
    for_particles([&](uint32_t b, uint32_t e) { kernels::tether(anchor, length, x, d, b, e); });
}

CpuCloth::VerifyPartial CpuCloth::verify() {
    ProfileScope scope(profile_, DRAPE_STAGE_VERIFY);
    // Finite positions and no runaway strain (kernels::overstretched with col_limit_: no root or
    // division per spring). The strain statistics are computed when read (Cloth::stats_of_cpu_copy).
    const uint32_t n = topo_.particle_count;
    const Particle* x = x_.data();
    auto verify_range = [&](uint32_t t, uint32_t b, uint32_t e) {
        VerifyPartial p{true, kernels::overstretched(ctx_, col_limit_.data(), x, b, e)};
        for (uint32_t i = b; i < e; ++i)
            if (!(std::isfinite(x[i].x) && std::isfinite(x[i].y) && std::isfinite(x[i].z))) p.finite = false;
        partials_[t] = p;
    };
    // Split like for_particles (a smaller cloth on the caller alone), one partial per chunk.
    const bool threaded = backend_ == DRAPE_BACKEND_CPU_THREADED;
    const uint32_t parts = threaded ? world_.pool().chunks(n) : 1;
    if (threaded)
        world_.pool().parallel_chunks(n, verify_range);
    else
        verify_range(0, 0, n);
    VerifyPartial total{true, false};
    for (uint32_t t = 0; t < parts; ++t) {
        total.finite = total.finite && partials_[t].finite;
        total.runaway = total.runaway || partials_[t].runaway;
    }
    return total;
}

Result CpuCloth::finish(float dt, const VerifyPartial& total) {
    ProfileScope scope(profile_, DRAPE_STAGE_FINISH);
    // Statistics; on failure the state from before the step comes back, else the step commits.
    const uint32_t n = topo_.particle_count;
    stats_.substeps = substeps_;
    stats_.iterations = params_.model == DRAPE_MODEL_MASS_SPRING ? 1
                        : params_.model == DRAPE_MODEL_IMPLICIT ? implicit_iterations_
                                                                : iterations_;
    stats_.non_finite = total.finite ? 0 : 1;
    if (!total.finite || total.runaway) {
        std::memcpy(x_.data(), backup_x_.data(), n * sizeof(Particle));
        std::memcpy(d_.data(), backup_d_.data(), n * sizeof(Particle));
        h_prev_ = backup_h_prev_;
        fresh_ = backup_fresh_;
        implicit_.state_set();  // what its solves kept belongs to the step rolled back
        implicit_fine_.state_set();
        // kinematic_target_ keeps the requested pin and grab moves: the next step makes them.
        ++stats_.unstable_steps;
        interaction_end_step(dt, true);
        return {DRAPE_ERROR_UNSTABLE,
                std::string("step diverged (") + (total.finite ? "runaway strain" : "non-finite positions") +
                    " with " + std::to_string(substeps_) + " substeps of " + std::to_string(h_) +
                    " s); the state before the step was restored. Raise substeps or lower stiffness."};
    }
    interaction_end_step(dt, false);  // colliders advance, drag consumed, sleep check
    recentre();  // after the step, so a rolled-back step changes nothing
    return {};
}

Result CpuCloth::edit(Access, std::function<void(Cloth&)> fn) {
    fn(*this);
    return {};
}

Result CpuCloth::read(const drape_vertex_layout& layout, void* dst) {
    read_cpu_copy(layout, dst);
    return {};
}

Result CpuCloth::stats(drape_stats* out) {
    stats_of_cpu_copy(out);
    return {};
}

Result CpuCloth::set_output(uint32_t, const drape_vertex_layout&) {
    return {DRAPE_ERROR_INVALID_ARGUMENT,
            "an output GL buffer needs a GLES cloth; use drape_cloth_read for CPU cloths"};
}

}  // namespace drape::cpu
