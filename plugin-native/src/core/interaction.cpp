// Cloth's interaction with the world and the user: colliders, self-collision setting, sleeping,
// touch drag (paper eq. 9), pick-and-hold grabs and the owner transform. The C ABI (src/api) has
// validated every input. The backends' steps call skip_step_asleep and interaction_end_step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "backend/cpu/glsl.h"  // touch_weight
#include "core/cloth.h"
#include "core/drag.h"

namespace drape {
namespace {

/// Normalised lerp along the shorter arc: accurate enough across one frame's substeps.
glm::quat nlerp(const glm::quat& a, glm::quat b, float t) {
    if (glm::dot(a, b) < 0) b = -b;
    return glm::normalize(a * (1.0f - t) + b * t);
}

glm::quat to_quat(const float q[4]) { return glm::normalize(glm::quat(q[3], q[0], q[1], q[2])); }

}  // namespace

// ---- colliders ------------------------------------------------------------------------------

void Cloth::set_colliders(const drape_collider* colliders, uint32_t count) {
    std::vector<ColliderState> next(count);
    bool changed = count != ix_.colliders.size();
    for (uint32_t k = 0; k < count; ++k) {
        const drape_collider& in = colliders[k];
        ColliderState& c = next[k];
        c.id = in.id;
        c.shape = in.shape;
        c.size = glm::vec3(in.size[0], in.size[1], in.size[2]);
        if (c.shape == DRAPE_COLLIDER_SPHERE) c.size.y = c.size.z = 0;
        if (c.shape == DRAPE_COLLIDER_CAPSULE) c.size.z = 0;
        if (c.shape == DRAPE_COLLIDER_PLANE) c.size = glm::vec3(0);
        c.margin = in.margin;
        c.friction = in.friction;
        c.pos_end = glm::vec3(in.position[0], in.position[1], in.position[2]);
        c.rot_end = to_quat(in.rotation);
        c.pos_start = c.pos_end;
        c.rot_start = c.rot_end;
        const ColliderState* old = nullptr;
        for (const ColliderState& o : ix_.colliders)
            if (o.id == c.id) old = &o;
        if (old) {  // moves from where it was at the last call (its current transform)
            c.pos_start = old->pos_end;
            c.rot_start = old->rot_end;
            changed = changed || old->shape != c.shape || old->size != c.size || old->margin != c.margin ||
                      old->friction != c.friction || old->pos_end != c.pos_end || old->rot_end != c.rot_end;
        } else {
            changed = true;
        }
    }
    ix_.colliders.swap(next);
    if (changed) wake();
    refresh_colliders();
}

// ---- self-collision (the CPU step's stage: backend/cpu/cpu_collide.cpp) ---------------------

void Cloth::set_self_collision(bool enabled, float thickness, float friction) {
    if (enabled != sc_.enabled || (enabled && (thickness != sc_.thickness || friction != sc_.friction))) wake();
    if (thickness != sc_.thickness) sc_.list_valid = false;
    sc_.enabled = enabled;
    sc_.thickness = thickness;
    sc_.friction = friction;
}

// ---- sleeping -------------------------------------------------------------------------------

void Cloth::set_sleep(float threshold, float time) {
    ix_.sleep_threshold = threshold;
    ix_.sleep_time = time;
    wake();
}

void Cloth::wake() {
    ++ix_.wakes;
    ix_.asleep = false;
    ix_.still_time = 0;
    stats_.sleeping = 0;
}

bool Cloth::pins_change(const drape_pin* pins, uint32_t count) const {
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = topo_.vertex_to_particle[pins[k].vertex];
        if (!pinned_[i] || kinematic_target_[i] != glm::vec3(pins[k].position[0], pins[k].position[1], pins[k].position[2]))
            return true;
    }
    return false;
}

bool Cloth::skip_step_asleep() {
    if (!ix_.asleep) return false;
    // Asleep: no work at all; the state (and hence every output) stays bit-identical.
    stats_.substeps = 0;
    stats_.step_ms = 0;
    std::fill_n(stats_.stage_ms, DRAPE_STAGE_COUNT, 0.0f);
    stats_.sleeping = 1;
    return true;
}

void Cloth::advance_interaction() {
    for (ColliderState& c : ix_.colliders) {
        c.pos_start = c.pos_end;
        c.rot_start = c.rot_end;
    }
    for (uint32_t i : ix_.drag_particles) ix_.drag_marked[i] = 0;
    ix_.drag_particles.clear();
    stats_.sleeping = 0;
}

bool Cloth::count_still(bool still, float dt) {
    if (!still || !(ix_.sleep_threshold > 0)) {
        ix_.still_time = 0;
        return false;
    }
    ix_.still_time += dt;
    if (ix_.still_time < ix_.sleep_time) return false;
    ix_.asleep = true;
    stats_.sleeping = 1;
    return true;
}

void Cloth::interaction_end_step(float dt, bool rolled_back) {
    advance_interaction();
    // Still: the fastest particle over the last substep is below the threshold.
    const uint32_t n = topo_.particle_count;
    const Particle* disp = d_.data();
    const float limit = ix_.sleep_threshold * h_prev_;
    const float limit2 = limit * limit;
    bool still = !rolled_back && ix_.sleep_threshold > 0;
    for (uint32_t i = 0; i < n && still; ++i) {
        const glm::vec3 d(disp[i]);
        still = glm::dot(d, d) <= limit2;
    }
    if (count_still(still, dt)) {
        // Fall asleep at rest: velocities zeroed so that waking starts from rest.
        Particle* dw = d_.data();
        for (uint32_t i = 0; i < n; ++i) dw[i] = Particle(glm::vec3(0.0f), dw[i].w);
    }
}

// ---- touch drag and grabs ---------------------------------------------------------------------

Result Cloth::drag(const drape_view& view, std::vector<drape_touch> touches) {
    return edit(Access::ReadsState, [view, t = std::move(touches)](Cloth& c) {
        c.drag_cpu_copy(view, t.data(), uint32_t(t.size()));
    });
}

void Cloth::drag_cpu_copy(const drape_view& view, const drape_touch* touches, uint32_t count) {
    const uint32_t n = topo_.particle_count;
    if (ix_.drag_offset.size() != n) {
        ix_.drag_offset.assign(n, glm::vec3(0.0f));
        ix_.drag_marked.assign(n, 0);
        ix_.drag_particles.reserve(n);
    }
    const ScreenMapping m = make_screen_mapping(view, origin_);
    const Particle* x = x_.data();
    bool moved = false;
    for (uint32_t i = 0; i < n; ++i) {
        if (x[i].w == 0.0f) continue;
        glm::dvec2 px;
        double z;
        if (!to_screen(m, glm::vec3(x[i]), &px, &z)) continue;
        // Several touches: the screen displacements add up (each with its own falloff).
        glm::dvec2 shift(0.0);
        for (uint32_t k = 0; k < count; ++k) {
            const glm::dvec2 d = px - glm::dvec2(touches[k].position[0], touches[k].position[1]);
            const float c = kernels::glsl::touch_weight(float(glm::dot(d, d)), touches[k].amplitude, touches[k].sigma);
            shift += double(c) * glm::dvec2(touches[k].motion[0], touches[k].motion[1]);
        }
        if (shift == glm::dvec2(0.0)) continue;
        const glm::vec3 offset(from_screen(m, px + shift, z) - glm::dvec3(glm::vec3(x[i])));
        if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z)) continue;
        if (!ix_.drag_marked[i]) {
            ix_.drag_marked[i] = 1;
            ix_.drag_offset[i] = glm::vec3(0.0f);
            ix_.drag_particles.push_back(i);
        }
        ix_.drag_offset[i] += offset;
        moved = true;
    }
    if (moved) wake();
}

uint32_t Cloth::grab(const drape_view& view, uint32_t touch_id, const float position[2], float pick_radius) {
    grab_release(touch_id);
    const ScreenMapping m = make_screen_mapping(view, origin_);
    const Particle* x = x_.data();
    const glm::dvec2 touch(position[0], position[1]);
    double best = double(pick_radius) * pick_radius;
    uint32_t best_vertex = std::numeric_limits<uint32_t>::max();
    double best_z = 0;
    for (uint32_t v = 0; v < topo_.vertex_count; ++v) {
        const uint32_t i = topo_.vertex_to_particle[v];
        if (x[i].w == 0.0f) continue;  // pinned or already grabbed
        glm::dvec2 px;
        double z;
        if (!to_screen(m, glm::vec3(x[i]), &px, &z) || z < -1 || z > 1) continue;
        const glm::dvec2 d = px - touch;
        const double r2 = glm::dot(d, d);
        if (r2 <= best) {
            best = r2;
            best_vertex = v;
            best_z = z;
        }
    }
    if (best_vertex == std::numeric_limits<uint32_t>::max()) return best_vertex;
    const uint32_t i = topo_.vertex_to_particle[best_vertex];
    ix_.grabs.push_back({touch_id, i, best_z});
    pinned_[i] = 1;
    kinematic_target_[i] = glm::vec3(x[i]);
    refresh_derived();
    wake();
    return best_vertex;
}

bool Cloth::grab_move(const drape_view& view, uint32_t touch_id, const float position[2]) {
    for (const Grab& g : ix_.grabs) {
        if (g.touch_id != touch_id) continue;
        const ScreenMapping m = make_screen_mapping(view, origin_);
        const glm::vec3 target(from_screen(m, glm::dvec2(position[0], position[1]), g.ndc_z));
        if (!std::isfinite(target.x) || !std::isfinite(target.y) || !std::isfinite(target.z)) return false;
        if (!pinned_[g.particle]) {  // the host released the pin under the grab: hold it again
            pinned_[g.particle] = 1;
            refresh_derived();
        }
        if (target != kinematic_target_[g.particle]) wake();
        kinematic_target_[g.particle] = target;
        return true;
    }
    return false;
}

void Cloth::grab_release(uint32_t touch_id) {
    for (size_t k = 0; k < ix_.grabs.size(); ++k) {
        if (ix_.grabs[k].touch_id != touch_id) continue;
        const uint32_t i = ix_.grabs[k].particle;
        ix_.grabs.erase(ix_.grabs.begin() + long(k));
        pinned_[i] = 0;
        kinematic_target_[i] = glm::vec3(x_[i]);
        refresh_derived();
        wake();
        return;
    }
}

// ---- owner transform --------------------------------------------------------------------------

void Cloth::set_owner(const drape_owner& o) {
    const glm::vec3 pos(o.position[0], o.position[1], o.position[2]);
    const glm::quat rot = to_quat(o.rotation);
    if (!ix_.has_owner) {
        ix_.has_owner = true;
        ix_.owner_pos = pos;
        ix_.owner_rot = rot;
        return;
    }
    if (pos == ix_.owner_pos && rot == ix_.owner_rot) return;
    const glm::vec3 p_old = ix_.owner_pos;
    glm::quat dq = glm::normalize(rot * glm::conjugate(ix_.owner_rot));
    if (dq.w < 0) dq = -dq;
    ix_.owner_pos = pos;
    ix_.owner_rot = rot;
    const RigidMove full{dq, p_old, pos, false};
    if (glm::length(pos - p_old) > o.teleport_distance) {
        // Teleport: the whole cloth (and its pins) jumps rigidly with the owner, at rest.
        move_state(full);
        for (glm::vec3& t : kinematic_target_) t = full.apply(t);
        fresh_ = true;
        wake();
        return;
    }
    // Carried part (1 - inertia) of the motion: applied to every particle's current and previous
    // position (its displacement turns with it), so it adds no velocity. Kinematic targets take the full motion; pins then cover the
    // rest (inertia) over the next step's substeps, dragging the free cloth behind them.
    const glm::quat carry_rot = glm::slerp(glm::quat(1, 0, 0, 0), dq, 1.0f - o.angular_inertia);
    const glm::vec3 carry_move = (pos - p_old) * (1.0f - o.linear_inertia);
    if (o.linear_inertia < 1 || o.angular_inertia < 1) move_state({carry_rot, p_old, p_old + carry_move, true});
    for (uint32_t k : kinematic_) kinematic_target_[k] = full.apply(kinematic_target_[k]);
    wake();
}

void Cloth::move_state(const RigidMove& m) {
    for (uint32_t i = 0; i < topo_.particle_count; ++i) {
        x_[i] = Particle(m.apply(glm::vec3(x_[i])), x_[i].w);
        d_[i] = m.keep_velocity ? Particle(kernels::glsl::quat_rotate(m.rot_xyzw(), glm::vec3(d_[i])), d_[i].w) : Particle(glm::vec3(0.0f), x_[i].w);
    }
}

CollideShape ColliderState::at_substep(uint32_t sub, uint32_t substeps) const {
    const float t0 = float(sub) / float(substeps), t1 = float(sub + 1) / float(substeps);
    const bool last = sub + 1 == substeps;
    CollideShape s;
    s.pos0 = pos_start + (pos_end - pos_start) * t0;
    s.pos1 = last ? pos_end : pos_start + (pos_end - pos_start) * t1;
    s.rot0 = nlerp(rot_start, rot_end, t0);
    s.rot1 = last ? rot_end : nlerp(rot_start, rot_end, t1);
    s.margin = margin;
    s.friction = friction;
    s.size = size;
    s.shape = shape;
    return s;
}

}  // namespace drape
