// Per-particle maths of a substep: Verlet prediction, MASS_SPRING and PBD dashpot forces, the PBD and
// XPBD constraint updates, the IMPLICIT prediction, spring force and Hessian block, and tethers, for
// the CPU kernels (backend/cpu/kernels.h, implicit_solve.cpp) and the GLES simulation passes
// (sim.vert.glsl), written once in the common subset of glm and GLSL (as collide_shape.h: C++
// includes it through backend/cpu/glsl.h). What stays on each side is where the records come from
// (arrays or textures) and the loops over springs.
#ifndef DRAPE_SHADERS_SUBSTEP_H
#define DRAPE_SHADERS_SUBSTEP_H

#ifdef GL_ES
#define DRAPE_OUT(T) out T
#define DRAPE_INLINE
#endif

// Rotation of v by unit quaternion q = (x, y, z, w), as glm's quat * vec3 (glm/detail/type_quat.inl).
DRAPE_INLINE vec3 quat_rotate(vec4 q, vec3 v) {
    vec3 u = vec3(q.x, q.y, q.z);
    vec3 uv = cross(u, v);
    vec3 uuv = cross(u, uv);
    return v + ((uv * q.w) + uuv) * 2.0f;
}

DRAPE_INLINE vec4 quat_conjugate(vec4 q) { return vec4(-q.x, -q.y, -q.z, q.w); }

// A rigid motion of the whole state (owner transform, re-centring: core/interaction.h RigidMove):
// position x goes to rot * (x - pivot) + to (a displacement turns with quat_rotate(rot, d)).
DRAPE_INLINE vec3 rigid_move(vec4 rot, vec3 pivot, vec3 to, vec3 x) { return quat_rotate(rot, x - pivot) + to; }

// Unit vector and length of d; zero vector for a zero-length spring (no direction, no force).
DRAPE_INLINE vec3 direction(vec3 d, DRAPE_OUT(float) len) {
    len = sqrt(dot(d, d));
    return len > 0.0f ? d * (1.0f / len) : vec3(0.0f);
}

// External acceleration (m/s^2) at velocity v: gravity plus linear air drag towards the wind.
DRAPE_INLINE vec3 external_accel(vec3 gravity, float air_drag, vec3 wind, vec3 v) {
    return gravity + air_drag * (wind - v);
}

// A kinematic (pinned) particle's position at a fraction `along` of the step: on the straight line
// from where it started the step to its pin target.
DRAPE_INLINE vec3 kinematic_path(vec3 start, vec3 target, float along) { return start + (target - start) * along; }

// Variable-step Verlet in displacement form (paper eq. 3): this substep's displacement
// d' = d h/h_prev + a h (h + h_prev)/2 from the last one's d, with h_ratio = h/h_prev and
// accel_h = (h + h_prev)/2 (h/2 on the first step: exact for constant acceleration, accuracy.md R1).
DRAPE_INLINE vec3 verlet_displacement(vec3 d, float h_ratio, vec3 a, float h, float accel_h) {
    return d * h_ratio + a * (h * accel_h);
}

// MASS_SPRING force (N) on particle i from one spring (paper eq. 1-2): Hooke's k (len - rest) plus a
// dashpot kd on the relative velocity, both along the spring. xij = x_i - x_j, vij = v_i - v_j.
DRAPE_INLINE vec3 spring_force(vec3 xij, vec3 vij, float rest, float k, float kd) {
    float len;
    vec3 n = direction(xij, len);
    return (-k * (len - rest) - kd * dot(vij, n)) * n;
}

// PBD's explicit dashpot (N) on particle i along one spring (PBD has no compliance to carry damping):
// kd limited to 1/(h (wi ci + wj cj)), ci and cj the two ends' active springs, so that the explicit
// update cannot overshoot.
DRAPE_INLINE vec3 dashpot_force(vec3 xij, vec3 vij, float kd, float h, float wi, float ci, float wj, float cj) {
    float len;
    vec3 n = direction(xij, len);
    float limit = 1.0f / (h * (wi * ci + wj * cj));
    return -(min(kd, limit) * dot(vij, n)) * n;
}

// Jacobi scaling of one constraint's update: 1 / (1 + theta R), R = the constraint's off-diagonal row
// sum over its diagonal in J W J^T + alpha~ (with |cos| <= 1, so it holds in any pose); theta =
// coupling (kJacobiCoupling). An uncoupled constraint gets the full update; for theta > 1/2 the
// scaled Jacobi iteration converges (2P - A is diagonally dominant).
DRAPE_INLINE float jacobi_scale(float wi, float wj, uint ci, uint cj, float diag, float gamma_factor, float coupling) {
    float off = gamma_factor * (wi * float(ci - 1u) + wj * float(cj - 1u));
    return 1.0f / (1.0f + coupling * off / diag);
}

// Factor of one spring's Jacobi update, symmetric in i and j. XPBD (Macklin 2016 eq. 18, damping as
// eq. 26): 1/diag, diag = (1 + gamma)(wi + wj) + alpha~, times jacobi_scale.
DRAPE_INLINE float xpbd_coefficient(float wi, float wj, uint ci, uint cj, float alpha, float gamma, float coupling) {
    float diag = (1.0f + gamma) * (wi + wj) + alpha;
    return jacobi_scale(wi, wj, ci, cj, diag, 1.0f + gamma, coupling) / diag;
}

// PBD (paper eq. 7-8, a fraction k of the correction per iteration): k/(wi + wj) times jacobi_scale.
DRAPE_INLINE float pbd_coefficient(float wi, float wj, uint ci, uint cj, float k, float coupling) {
    float wsum = wi + wj;
    return k * jacobi_scale(wi, wj, ci, cj, wsum, 1.0f, coupling) / wsum;
}

// XPBD multiplier change of one spring with constraint value C = len - rest and damping along n:
// (-C - alpha~ lambda - gamma n.dij) * coef (PBD's is -C * coef). dij = d_i - d_j, the relative
// displacement over the substep so far.
DRAPE_INLINE float xpbd_delta(float constraint, float alpha, float lambda, float gamma, vec3 n, vec3 dij, float coef) {
    return (-constraint - alpha * lambda - gamma * dot(n, dij)) * coef;
}

// IMPLICIT (kernels::implicit_residual's Phi(d) = sum_i |d_i - y_i|^2 / (2 w_i h^2) + sum_springs
// k/2 (|x_i - x_j| - L)^2 plus a dashpot kd along each spring): the prediction of a substep from the
// last displacement d and the external acceleration a. Returns the target y = d h/h_prev + a h (h +
// h_prev)/2 (verlet_displacement) and sets `first`, the first iterate, to the inertia and `drag`, the
// part of a that slows the particle (-air_drag v): at rest it is exactly 0, so a substep that stays at
// rest is one where the springs balance the external forces exactly. The drag is no force the springs
// balance, so it needs no solve: left to the solve (first = inertia alone), it acted on a motion only as
// far as a few iterations reached that motion, and the smooth out-of-plane waves of a fine taut sheet,
// which the preconditioner barely sees (their Hessian is nearly the mass, its blocks charge them the
// springs' tension), kept swinging for seconds (129^2 sheet on two edges, air_drag 3: 1.8e-3 of the
// displacement after 9 s; now 1.3e-6 after 8 s).
DRAPE_INLINE vec3 implicit_predict(vec3 d, float h_ratio, vec3 a, vec3 drag, float h, float accel_h,
                                   DRAPE_OUT(vec3) first) {
    first = d * h_ratio + drag * (h * accel_h);
    return d * h_ratio + a * (h * accel_h);
}

// IMPLICIT force (N) on particle i from one spring, -grad_i of its share of Phi: Hooke's k (len - rest)
// plus the dashpot kd_h = kd/h on the relative displacement dij = d_i - d_j over the substep, along n
// (n, len: direction of x_i - x_j at the iterate).
DRAPE_INLINE vec3 implicit_spring_force(vec3 n, float len, vec3 dij, float rest, float k, float kd_h) {
    return -(k * (len - rest) + kd_h * dot(n, dij)) * n;
}

// IMPLICIT: a spring's stiffness across itself in the Hessian of Phi, its tension over its length
// k (1 - rest/len) (0 at zero length). Compressed it is negative and the Hessian indefinite: the CPU
// clamps it at 0 (magnitude false: the step lengths need the true curvature where it is positive), the
// GLES block-Jacobi step takes its magnitude (magnitude true: its block must bound the spring's whole
// term, see sim.vert.glsl jacobi_step).
DRAPE_INLINE float implicit_tension(float len, float rest, float k, bool magnitude) {
    if (!(len > 0.0f)) return 0.0f;
    float t = 1.0f - rest / len;
    return k * (magnitude ? abs(t) : max(0.0f, t));
}

// IMPLICIT: a spring's 3x3 block of the Hessian of Phi on x_i (kd_h = kd/h; the dashpot's change of
// direction is left out): (k + kd_h) n n^T along it plus `across` (implicit_tension) (I - n n^T),
// that is implicit_block_along(...) n n^T + across I.
DRAPE_INLINE float implicit_block_along(float k, float kd_h, float across) { return k + kd_h - across; }

DRAPE_INLINE mat3 implicit_spring_block(vec3 n, float k, float kd_h, float across) {
    return implicit_block_along(k, kd_h, across) * outerProduct(n, n) + mat3(across);
}

// Touch drag weight (paper section IV, eq. 9, with the exponent's minus sign restored), clamped to 1 so
// that no vertex moves further than the finger: min(1, A exp(-r^2 / (2 sigma))), r^2 and sigma in px^2.
DRAPE_INLINE float touch_weight(float r2, float amplitude, float sigma) {
    return min(1.0f, amplitude * exp(-r2 / (2.0f * sigma)));
}

// Tether (long-range attachment, Kim, Chentanez and Mueller 2012): particle x (inverse mass w) may be
// at most `limit` from its anchor; beyond that `pull` brings it back onto the sphere. False, with no
// pull, when it is within, kinematic (w = 0) or has no tether (limit < 0).
DRAPE_INLINE bool tether_pull(vec3 x, float w, vec3 anchor, float limit, DRAPE_OUT(vec3) pull) {
    pull = vec3(0.0f);
    if (limit < 0.0f || w == 0.0f) return false;
    float len;
    vec3 n = direction(x - anchor, len);
    if (len <= limit) return false;
    pull = n * (limit - len);
    return true;
}

#endif
