// Per-cloth parameters: validation, defaults, and the per-group constants a (sub)step uses.
#pragma once

#include <string>

#include "drape/drape.h"

namespace drape {

/// Defaults documented in drape.h (from tools/abi/abi.py).
drape_params default_params();

/// `p` with DRAPE_MODEL_AUTO replaced by the model a cloth runs for it on every backend: IMPLICIT,
/// the one that rests at the springs' equilibrium; any other model is kept.
drape_params resolve_model(drape_params p);

/// Empty string when valid; otherwise what is wrong (status in *status).
std::string validate_params(const drape_params& p, drape_status* status);

/// Substeps used by default for the position-based models ("small steps", Macklin et al. 2019:
/// at equal cost substeps x iterations, 16 x 1 beat 4 x 4 on every scene of tests/bench:
/// E2 0.070 vs 0.101 on the two-corner cloth, 0.039 vs 0.147 on the R4 chain).
constexpr uint32_t kAutoSubstepsPositionBased = 16;
/// Upper bound on substeps per step, automatic or given (drape.h).
constexpr uint32_t kMaxSubsteps = DRAPE_MAX_SUBSTEPS;
constexpr uint32_t kMaxIterations = DRAPE_MAX_ITERATIONS;
/// IMPLICIT defaults: substeps, and the most conjugate-gradient iterations a substep may take (it
/// stops once converged, see kImplicitTolerance): the cheapest budget that passes the rest-state
/// tests and settles the taut stiff sheet within 2.5 % in 10 s (tests/native/test_rest_state.cpp).
constexpr uint32_t kAutoSubstepsImplicit = 2;
/// Automatic budget near a moving collider: substeps so that no collider travels more than this share
/// of its smallest size (sphere/capsule radius, box half extent, plus margin) per substep. A collider
/// that overtakes a whole ring of vertices in one substep leaves the springs between them across it
/// (contact is per vertex): the default IMPLICIT (2 substeps) let a sphere at 1 radius per substep
/// through a cloth; at 0.5 none got through at 2 to 20 radii per frame (test_collision.cpp).
constexpr float kColliderTravelPerSubstep = 0.5f;
/// IMPLICIT's automatic substeps while the cloth is near a collider with friction (a stopgap, on the
/// CPU; GLES: 32 substeps, below). The collision pass's position-based friction moves a contact
/// back along the surface after the solve by what the solve moved it, up to mu times its push into
/// the collider, stretching the springs the solve had balanced; the work grows like the substep to
/// the fourth power per substep. At 2 substeps a cloth dropped on a sphere (21^2, 0.1 kg, friction 1)
/// went from 1.5 J to 17 J at the impact and kept gaining up to 6 J at rest on it, and a cloth over a
/// box corner (33^2, friction 1) gained 11 J at rest. At 8 they gained 0.03 J and 0.7 J, at 16 0.004
/// and 0.02 J (friction 0.05 to 1; the drop never above its 1.47 J at the start). Friction inside the
/// solve would be the real fix (tried: tests/bench/README.md, "IMPLICIT with a frictional collider").
constexpr uint32_t kFrictionSubstepsImplicit = 16;
/// IMPLICIT's automatic substeps while the cloth is near a frictionless collider that is not a plane
/// (on the CPU, like the above). The solve holds a contact on the surface normal the last collision
/// pass found; a particle just off an edge or a curve has none, and at 2 substeps the springs pulled
/// such particles deep into the collider (8.6 mm in one substep at a box edge, margin 1 cm), the pass
/// pushed them out, and the next solve turned the strain into motion. Cloths laid over a box corner,
/// a lying capsule and a sphere (33^2, 0.2 kg, 49 / 35 / 35 placements: the collider's size and the
/// cloth's offset varied) gained more than 0.1 J above their lowest total energy in 43 / 15 / 8 of
/// them, at most 143 J (the box corner launched the cloth: strain 2.5 in one step) / 1.4 / 0.37 J. At
/// 8 substeps of kContactIterationsImplicit iterations at most 0.025 / 0.001 / 0.0015 J. Fewer did not
/// do: with 4 iterations the cloth stuck on the frictionless box corner in 5 (4 substeps), 2 (8) of
/// the 49 placements; 4 x 8 stuck in 1 and gained up to 0.09 J. A plane has no edge: 2 substeps gain
/// nothing there.
constexpr uint32_t kContactSubstepsImplicit = 8;
/// IMPLICIT's automatic iteration budget in those substeps (both above). The contacts the pass moves
/// after each solve start the next one away from its minimum; at 4 iterations the 21^2 cloth draped
/// on a sphere with friction 0.5 kept ~300 of its 441 vertices above 1 cm/s (the hanging edges up to
/// 0.3 m/s) for 20 s; at 8 it comes to rest like MASS_SPRING (none above 1 cm/s, 5 mm/s at most).
constexpr uint32_t kContactIterationsImplicit = 8;
constexpr uint32_t kAutoIterationsImplicit = 4;
/// IMPLICIT: a substep's solve stops after a step that released less than kImplicitTolerance^2
/// times the kinetic energy of the substep's predicted motion (backend/cpu/implicit_solve.cpp), so
/// that a cloth at rest costs one iteration. 1e-2 and 3e-2 stopped too early for taut sheets (the
/// 33^2 stiff curtain and the heavy-vertex sheet missed 0.5 %, the taut stiff sheet 2.5 %); 3e-3
/// left the 33^2 sheet at 3.6e-3 of its 5e-3 bound, 1e-3 at 2.3e-3, still one iteration at rest.
/// 5e-4 since the solve gives back what rounding the positions took (the release at rest at 129^2
/// fell from 0.9-1.5 to 0.009 of 1e-3's): the 65^2 taut sheet at the user's drag then settles to
/// 1.1e-4 of its displacement at 4.5-5 s (1.75e-4 at 1e-3), still one iteration at rest.
constexpr float kImplicitTolerance = 5e-4f;
/// IMPLICIT on GLES: iterations of block Jacobi + Chebyshev per substep (gles_cloth.cpp), each one
/// pass, and the longest automatic substep, s (16 substeps at 60 Hz, 96 at 10 Hz). A local
/// iteration reaches less of a substep's answer the longer the substep (the condition of its matrix
/// grows with h^2), so many short substeps with few passes follow motion better than few long ones
/// with many: 33^2 sheet dropped from two corners, rms distance from a converged CPU IMPLICIT run
/// over the first second, before the coarse level (gles_coarse.h): 2 x 8 0.29 m, 16 x 2 0.19 m,
/// 16 x 3 0.12 m (XPBD 16 x 1: 0.15 m), 32 x 1 worse than 16 x 1. With it (its first version), at
/// 2e3 / 1e5 N/m structural: 16 x 3 0.029 / 0.18 m, 16 x 2 0.027 / 0.24 m, 8 x 3 0.070 / 0.39 m,
/// 4 x 6 0.10 / 0.46 m. Long frame steps keep the substep and cost the same per simulated second.
/// With the coarse levels as they are now (rms from CPU IMPLICIT 32 x 64, llvmpipe), two passes beat
/// three: 2e3 N/m 16 x 2 0.023 m, 16 x 3 0.025 m; 1e5 N/m 40 x 2 0.054 m, 40 x 3 0.058 m, 48 x 2
/// 0.041 m, 48 x 3 0.051 m (the 65^2 curtain: 5.3e-5 of its largest displacement after 2 s at
/// 16 x 2, 4.6e-5 at 16 x 3; R13's bound is 5e-3).
constexpr uint32_t kAutoIterationsImplicitGles = 2;
constexpr float kMaxAutoSubstepImplicitGles = 1.0f / 960.0f;
/// GLES IMPLICIT's longest automatic substep while a collider that is not a plane may reach the cloth
/// (GlesCloth::tethered_reach: the positions live on the GPU). Its few block-Jacobi passes do not see the
/// contacts the collision pass then makes; at 1/960 s a 33^2 cloth (0.2 kg) laid over a frictionless
/// box gained up to 1.3 J above its lowest total energy (9 placements: box half sizes 0.2-0.35 m,
/// cloth offsets 0-0.2 m) and one resting centred on the box never settled (strain 10-30 %); with
/// friction 1 up to 0.57 J; a capsule 0.045 J, a sphere 0.15 J. At 1/1920 s (32 x 2 at 60 Hz):
/// box 0.057 J (friction 1: 0.093 J), capsule 0.051 J, sphere 0.004 J; 24 x 2 still 0.27 J, 16 x 6
/// 0.38 J, 24 x 3 0.14 J. The friction tests' sphere drop (friction 1) gained 0.039 J after its
/// impact and crept 5.7 mm in 2 s at 1/960 s, 0.0001 J and 0 at 1/1920 s. Projecting every pass's
/// iterate out of the colliders instead did worse (box up to 3 J, sphere 0.72 J, and frictionless
/// cloths stuck on the box), as did no coarse level (6 J).
constexpr float kMaxContactSubstepImplicitGles = 1.0f / 1920.0f;
/// Slack (m) added to the tethers' reach when GLES decides whether a collider may touch the cloth
/// (GlesCloth::tethered_reach): rounding, and a tether pass that leaves a particle a hair beyond its length.
constexpr float kTetherReachPad = 0.01f;
/// GLES IMPLICIT on cloth much stiffer along its grid lines than across them (structural over
/// shear stiffness r above the default's 2): the soft modes are then in-plane shear and swing, which
/// block Jacobi sees as stiff (a particle's block holds the structural springs) and the constant
/// coarse matrices charge at the structural stiffness (gles_coarse.h), so each substep's passes
/// reach less of its answer. More, shorter substeps (the mass term m/h^2 grows against the
/// springs) recover it: the automatic substep is kMaxAutoSubstepImplicitGles / (r / 2)^(1/4), at
/// most kMaxStiffSubstepFactorGles times shorter (the cost grows with the substeps). 33^2 sheet
/// dropped from two corners, 1e5 / 1e3 N/m (r = 100: 43 substeps at 60 Hz), rms from CPU IMPLICIT
/// 32 x 64 over the first second: 16 x 2 0.21 m, 24 x 2 0.13 m, 32 x 2 0.075 m, 40 x 2 0.054 m,
/// 43 x 2 0.044 m, 48 x 2 0.041 m, 64 x 2 0.033 m (XPBD 16 x 1: 0.15 m); 1e4 / 1e3 N/m (r = 10: 24 substeps): 16 x 3
/// 0.045 m, 24 x 2 0.031 m (XPBD 0.14 m). 1e6 / 1e3 N/m (r = 1000: 76 substeps, the cap 5 just above
/// (r / 2)^(1/4) = 4.7): 40 x 2 (the cap 2.5) 0.26 m and max strain 0.41, 64 x 2 0.14 m, 76 x 2 0.107 m
/// and 0.025 (XPBD 0.145 m, 0.89). Coarse matrices of H assembled on the GPU in every substep (3 x 3
/// blocks at the iterate, Galerkin, exact coarsest solve: tension-aware, as the CPU's CoarseLevels)
/// did worse per GL call: at 40 x 2 0.15-0.26 m, max strain up to 0.99 from the fold on, 1.65 times
/// the calls. Triangle meshes have no shear group (their edges carry the shear): no change there.
constexpr float kMaxStiffSubstepFactorGles = 5.0f;
/// IMPLICIT: relative change of the substep beyond which its matrix is refactored (any matrix
/// gives the exact rest state; a stale one only converges more slowly).
constexpr float kImplicitRefactor = 0.25f;
/// Frame step assumed before the first step (for work done ahead of it), s.
constexpr float kDefaultH = 1.0f / 60.0f;
/// Fraction of the explicit stability limit used when MASS_SPRING picks substeps itself.
constexpr float kStabilitySafety = 0.9f;
/// Jacobi coupling weight theta (shaders/substep.h jacobi_scale); convergent for theta > 1/2.
constexpr float kJacobiCoupling = 0.6f;
/// XPBD's per-group constants for a substep h (Macklin et al. 2016), as both backends hand them to
/// the shared maths: compliance alpha~ = 1/(k h^2) and damping ratio gamma = kd/(k h) (eq. 26); 0
/// where the group is off (k = 0).
inline float xpbd_compliance(float k, float h) { return k > 0 ? 1.0f / (k * h * h) : 0.0f; }
inline float xpbd_damping_ratio(float k, float kd, float h) { return k > 0 ? kd / (k * h) : 0.0f; }
/// Verlet's acceleration factor of a substep (shaders/substep.h verlet_displacement): (h + h_prev)/2,
/// or h/2 on a cloth's first step (exact for constant acceleration, accuracy.md R1).
inline float verlet_accel_h(float h, float h_prev, bool first) { return first ? 0.5f * h : 0.5f * (h + h_prev); }
/// MASS_SPRING's explicit stability bound for one particle (accuracy.md, "cruder" form, valid in
/// any pose): w^2 <= 2 w_i sum_j k_ij; with the dashpots' c = 2 w_i sum kd, Verlet needs
/// h^2 w^2 + 2 h c <= 4, times kStabilitySafety^2. The largest such substep h, s (INFINITY when
/// nothing bounds it: no active spring or no inverse mass).
float mass_spring_max_substep(float inverse_mass, float stiffness_sum, float damping, uint32_t active_springs);

/// GLES IMPLICIT's substeps of at most h_max each in a step of dt, in [1, kMaxSubsteps] (ceil, less
/// 1e-3: 1/60 s over 1/960 s is 16, not 17 by rounding).
uint32_t gles_implicit_substeps(float dt, float h_max);
/// Substeps a step of dt uses on `backend`: params.substeps if set; else MASS_SPRING: ceil(dt / h_max)
/// (h_max from mass_spring_max_substep, the tightest particle), PBD/XPBD:
/// kAutoSubstepsPositionBased, IMPLICIT: kAutoSubstepsImplicit on the CPU, substeps of at most
/// kMaxAutoSubstepImplicitGles (shorter for stiff structural springs, see kMaxStiffSubstepFactorGles;
/// spring_count: the topology's per group) on GLES; always in [1, kMaxSubsteps].
uint32_t substeps_for(const drape_params& p, drape_backend backend, float h_max,
                      const uint32_t spring_count[DRAPE_GROUP_COUNT], float dt);

struct Topology;
struct StabilityEstimate {
    uint32_t substeps;          ///< what a step of dt uses
    uint32_t stable_substeps;   ///< fewest within the explicit bound (MASS_SPRING), 1 otherwise
    float max_stable_substep;   ///< s; 0 = no explicit bound
};
/// For a cloth with this topology (cooked masses, no pins) and parameters.
StabilityEstimate estimate_stability(const Topology& topo, const drape_params& p, drape_backend backend, float dt);

/// A cloth farther than this from its origin (Cloth::origin; any axis, m) is re-centred: local
/// coordinates stay within a few metres, where float resolution is about 5e-7 m. A cloth created
/// within it of the caller's origin starts with origin 0 (same arithmetic as simulating in the
/// caller's space).
constexpr float kRecentreDistance = 4.0f;

/// Strain beyond which a step counts as diverged ("runaway strain", accuracy.md).
constexpr float kRunawayStrain = 10.0f;

}  // namespace drape
