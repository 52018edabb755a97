/*
 * Drape: cloth simulation for games. The public C ABI (C99).
 *
 * Contents, by topic: 1 lifecycle (status, versions, worlds); 2 cloth (creation, masses, pins,
 * state, stepping, sleeping); 3 parameters (models, stiffness, substeps, stability estimate);
 * 4 output (reading positions and normals, info, statistics); 5 collision (colliders,
 * self-collision); 6 interaction (touch drag, grabs, owner transform); 7 GPU (GLES backend);
 * 8 Unity (render event).
 *
 * Rules:
 *  - every function returns a drape_status; results come back through out-pointers;
 *  - on failure drape_last_error() holds a thread-local, human-readable message and the object
 *    the call was made on is unchanged;
 *  - handles (drape_world*, drape_cloth*) are opaque pointer-sized ids (slot index + generation),
 *    not addresses: a destroyed object's handle is refused (DRAPE_ERROR_INVALID_HANDLE) by every
 *    call, from any thread, even after its slot is reused; a world handle is never a cloth handle;
 *  - structs shared with C# name their twin; a test checks size and field offsets. The enum and
 *    struct blocks between GENERATED markers come from tools/abi/abi.py (one description of
 *    type, unit, default, range and doc for each field; do not edit them here).
 *
 * struct_size (versioning): every struct starts with it. A struct can grow at its end (a new
 * "revision"); the library accepts every size it has shipped:
 *  - structs passed in: set struct_size = sizeof the struct you compiled against. An older
 *    revision's size is accepted and the fields it lacks take their documented defaults; any
 *    other size is DRAPE_ERROR_STRUCT_SIZE.
 *  - structs filled by the library (drape_stats, drape_self_collision_desc, drape_stability):
 *    set struct_size likewise; the library writes that revision's fields only.
 *    drape_cloth_get_info, drape_cloth_get_params and drape_params_default, which ABI 1 callers
 *    were not asked to prepare, read any size the library never shipped (0, garbage) as the
 *    first revision's; all three set struct_size to the size written.
 *
 * Threading: a world and the cloths in it may be used from one thread at a time (any thread;
 * hand over with the usual synchronisation, e.g. a join or a mutex). Different worlds may be used
 * from different threads at the same time. Functions taking no world or cloth (drape_abi_version,
 * drape_last_error, *_default, drape_estimate_stability) may be called from any thread at any
 * time. drape_last_error() is per thread. The CPU_THREADED backend runs its own workers only
 * inside drape_world_step / drape_cloth_step (and spreads a world's CPU cloths over them); they
 * are idle when the call returns. GL: a GLES cloth is used only on the thread whose EGL context
 * created it, with that context current (immediate use), or its GL work runs on Unity's render
 * thread (see 7 GPU); CPU cloths never touch GL. Checked under ThreadSanitizer:
 * tests/native/test_threading.cpp (.ci/hardening.sh tsan).
 *
 * Units: metres, kilograms, seconds. Positions are in simulation (world) space.
 */
#ifndef DRAPE_DRAPE_H
#define DRAPE_DRAPE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#  if defined(DRAPE_BUILDING_LIBRARY)
#    define DRAPE_API __declspec(dllexport)
#  else
#    define DRAPE_API __declspec(dllimport)
#  endif
#else
#  define DRAPE_API __attribute__((visibility("default")))
#endif

/* ================================ 1. Lifecycle ================================================ */

/** Bumped on any incompatible change of this header (growing a struct at its end is compatible). */
#define DRAPE_ABI_VERSION 1

/** Longest step, s: drape_world_step / drape_cloth_step refuse dt > DRAPE_MAX_DT. */
#define DRAPE_MAX_DT 1.0f
/** Shortest step that does anything, s: 0 < dt < DRAPE_MIN_DT is accepted (DRAPE_OK) and is a
 *  no-op (nothing moves; pending pin moves, drag and collider motion wait for the next step). */
#define DRAPE_MIN_DT 1e-6f

/* GENERATED BEGIN drape_status */
/* C# twin: Drape.Core.Status. */
typedef enum drape_status {
    DRAPE_OK = 0,
    DRAPE_ERROR_NULL_POINTER = 1, /**< a required pointer was NULL */
    DRAPE_ERROR_INVALID_HANDLE = 2, /**< handle is not a live object of the right kind */
    DRAPE_ERROR_STRUCT_SIZE = 3, /**< struct_size is none of the sizes this library has shipped */
    DRAPE_ERROR_INVALID_ENUM = 4, /**< enum value out of range */
    DRAPE_ERROR_INVALID_ARGUMENT = 5, /**< a size, count or value is out of its allowed range */
    DRAPE_ERROR_NOT_FINITE = 6, /**< a float input was NaN or infinite */
    DRAPE_ERROR_INDEX_OUT_OF_RANGE = 7, /**< a vertex or triangle index is out of range */
    DRAPE_ERROR_DEGENERATE_MESH = 8, /**< zero-area or repeated-index triangle, or no edges */
    DRAPE_ERROR_BUFFER_TOO_SMALL = 9, /**< caller memory/layout cannot hold the output */
    DRAPE_ERROR_BACKEND_UNAVAILABLE = 10, /**< backend not compiled in or not usable here */
    DRAPE_ERROR_UNSTABLE = 11, /**< step diverged; the last good state was restored */
    DRAPE_ERROR_OUT_OF_MEMORY = 12,
    DRAPE_ERROR_GL = 13, /**< OpenGL ES error (message carries the GL log) */
    DRAPE_ERROR_INTERNAL = 14
} drape_status;
/* GENERATED END drape_status */

/* GENERATED BEGIN drape_backend */
/* C# twin: Drape.Core.Backend. */
typedef enum drape_backend {
    DRAPE_BACKEND_CPU = 0, /**< one thread, deterministic (same input -> same bits) */
    DRAPE_BACKEND_CPU_THREADED = 1, /**< the world's worker pool; same results as CPU */
    DRAPE_BACKEND_GLES = 2 /**< OpenGL ES 3.0 transform feedback */
} drape_backend;
/* GENERATED END drape_backend */

typedef struct drape_world drape_world;
typedef struct drape_cloth drape_cloth;

/* GENERATED BEGIN drape_world_desc */
/* C# twin: Drape.Core.WorldDesc. */
typedef struct drape_world_desc {
    uint32_t struct_size;
    uint32_t thread_count; /**< workers for CPU_THREADED including the caller; 0 = hardware count. Range [0,
                                256]. Default 0 */
    uint32_t profile_stages; /**< 1: CPU steps time each stage into drape_stats.stage_ms (a clock read at each
                                  stage's start and end); 0: no timing. Range [0, 1]. Default 0. Added in
                                  struct revision 1 (older sizes still accepted) */
} drape_world_desc;
/* GENERATED END drape_world_desc */

DRAPE_API uint32_t drape_abi_version(void);
/** Human-readable message for the last failure on this thread ("" if none). Never NULL. */
DRAPE_API const char* drape_last_error(void);
/** *out_available = 1 if cloths with this backend can be created now. */
DRAPE_API drape_status drape_backend_available(uint32_t backend, uint32_t* out_available);

DRAPE_API drape_status drape_world_create(const drape_world_desc* desc, drape_world** out_world);
/** Destroys the world and every cloth still in it (their handles become invalid). */
DRAPE_API drape_status drape_world_destroy(drape_world* world);
/** Steps every cloth of the world by dt seconds (0 < dt <= DRAPE_MAX_DT; below DRAPE_MIN_DT a
 *  no-op). Returns the first failure; the other cloths are still stepped. */
DRAPE_API drape_status drape_world_step(drape_world* world, float dt);

/* ================================ 2. Cloth ==================================================== */
/* Limits: at most 4194304 (2^22) vertices per cloth; coordinates within 1e6 m; total mass in
 * (0, 1e6] kg. */

/* GENERATED BEGIN drape_cloth_desc */
/* C# twin: Drape.Core.ClothDesc. Common to grid and mesh creation. */
typedef struct drape_cloth_desc {
    uint32_t struct_size;
    uint32_t backend; /**< drape_backend. Default CPU */
    float total_mass; /**< kg, spread over vertices by area. Range (0, 1e6]. Default 1 */
} drape_cloth_desc;
/* GENERATED END drape_cloth_desc */

/* GENERATED BEGIN drape_grid_desc */
/* C# twin: Drape.Core.GridDesc. Vertex (c, r) is at origin + axis_u*width*c/(columns-1) +
 * axis_v*height*r/(rows-1); caller vertex index = r*columns + c. */
typedef struct drape_grid_desc {
    uint32_t struct_size;
    uint32_t columns; /**< vertices per row, >= 1 (columns*rows >= 2) */
    uint32_t rows; /**< >= 1 */
    float width; /**< m, > 0 */
    float height; /**< m, > 0 */
    float origin[3]; /**< m, position of vertex (0,0) */
    float axis_u[3]; /**< unit direction of increasing column; all zero = +x */
    float axis_v[3]; /**< unit direction of increasing row; all zero = -z */
} drape_grid_desc;
/* GENERATED END drape_grid_desc */

/* GENERATED BEGIN drape_mesh_desc */
/* C# twin: Drape.Core.MeshDesc. Vertices closer than weld_distance are simulated as one (Unity splits
 * vertices at UV seams) and written back to every copy on output. The arrays are read during the create call
 * only. */
typedef struct drape_mesh_desc {
    uint32_t struct_size;
    uint32_t vertex_count; /**< >= 3 */
    const float* positions; /**< vertex_count * 3 floats */
    uint32_t index_count; /**< multiple of 3, >= 3 */
    const uint32_t* indices; /**< triangle list */
    float weld_distance; /**< m, >= 0; 0 welds only bit-identical positions */
} drape_mesh_desc;
/* GENERATED END drape_mesh_desc */

DRAPE_API drape_status drape_cloth_create_grid(drape_world* world, const drape_cloth_desc* desc,
                                               const drape_grid_desc* grid, drape_cloth** out_cloth);
DRAPE_API drape_status drape_cloth_create_mesh(drape_world* world, const drape_cloth_desc* desc,
                                               const drape_mesh_desc* mesh, drape_cloth** out_cloth);
DRAPE_API drape_status drape_cloth_destroy(drape_cloth* cloth);

/** Steps one cloth by dt seconds (0 < dt <= DRAPE_MAX_DT; below DRAPE_MIN_DT a no-op).
 *  DRAPE_ERROR_UNSTABLE: the step diverged and the state was rolled back; pin and grab moves
 *  asked for before it are kept and made by the next step. */
DRAPE_API drape_status drape_cloth_step(drape_cloth* cloth, float dt);

/** Per caller vertex, >= 0 and finite; 0 pins the vertex where it is. Welded copies take the
 *  smallest value given for them. count must equal the vertex count. */
DRAPE_API drape_status drape_cloth_set_inverse_masses(drape_cloth* cloth, const float* inverse_masses,
                                                      uint32_t count);

/* GENERATED BEGIN drape_pin */
/* C# twin: Drape.Core.Pin. Pins a caller vertex (inverse mass 0) at a target; pinning again moves it (the
 * move is spread over the next step's substeps). */
typedef struct drape_pin {
    uint32_t struct_size;
    uint32_t vertex; /**< caller vertex index */
    float position[3]; /**< m, target */
} drape_pin;
/* GENERATED END drape_pin */

/** Pins (or moves already pinned) vertices; see drape_pin. */
DRAPE_API drape_status drape_cloth_set_pins(drape_cloth* cloth, const drape_pin* pins, uint32_t count);
/** Releases pins: the vertices get back the inverse mass they had before pinning. */
DRAPE_API drape_status drape_cloth_release_pins(drape_cloth* cloth, const uint32_t* vertices, uint32_t count);
/** Teleports vertices (count*3 floats, caller order) and zeroes velocities. Rest lengths keep. */
DRAPE_API drape_status drape_cloth_set_positions(drape_cloth* cloth, const float* positions, uint32_t count);
/** Sets velocities (count*3 floats, caller order, m/s). */
DRAPE_API drape_status drape_cloth_set_velocities(drape_cloth* cloth, const float* velocities, uint32_t count);

/* Sleeping, on every backend. A GLES cloth checks its motion on the GPU without waiting for it (an
 * occlusion query per step, its result asked for at a later step): it falls asleep at the first
 * step after the result of a still step arrives (usually the next: the same state as a CPU cloth,
 * one step call later), and while asleep its steps make no GL call. drape_stats.sleeping of a GLES
 * cloth is current after a step or readback in immediate mode. */
/* GENERATED BEGIN drape_sleep_desc */
/* C# twin: Drape.Core.SleepDesc. A cloth whose fastest particle stays below `threshold` for `time` seconds of
 * steps falls asleep: its velocities are zeroed and drape_cloth_step returns at once without touching the
 * state. Colliders, pins, drag, grab, owner transform, parameters, masses, positions or velocities that
 * change wake it. Default: threshold 0 (never sleeps). */
typedef struct drape_sleep_desc {
    uint32_t struct_size;
    float threshold; /**< m/s, 0 = never sleep. Typical 0.01. Range [0, 100]. Default 0 */
    float time; /**< s, how long motion must stay below threshold. Typical 1. Range [0, 100]. Default 0 */
} drape_sleep_desc;
/* GENERATED END drape_sleep_desc */

DRAPE_API drape_status drape_cloth_set_sleep(drape_cloth* cloth, const drape_sleep_desc* desc);
/** Wakes the cloth (it sleeps again after `time` seconds of stillness). */
DRAPE_API drape_status drape_cloth_wake(drape_cloth* cloth);

/* ================================ 3. Parameters =============================================== */

/** Most substeps a step uses, automatic or given (params.substeps). MASS_SPRING whose stability
 *  bound asks for more is stepped with DRAPE_MAX_SUBSTEPS and may diverge (DRAPE_ERROR_UNSTABLE,
 *  rolled back): drape_estimate_stability tells beforehand. */
#define DRAPE_MAX_SUBSTEPS 1000
/** Most solver iterations per substep (params.iterations). */
#define DRAPE_MAX_ITERATIONS 1000

/* GENERATED BEGIN drape_model */
/* C# twin: Drape.Core.Model. */
typedef enum drape_model {
    DRAPE_MODEL_MASS_SPRING = 0, /**< Hooke springs + damping, Verlet (paper eq. 1-3) */
    DRAPE_MODEL_PBD = 1, /**< stretch constraints, stiffness in [0,1] (paper eq. 4-8) */
    DRAPE_MODEL_XPBD = 2, /**< compliance = 1/stiffness in physical units, one Jacobi pass per iteration.
                               Rests softer than its springs with few iterations */
    DRAPE_MODEL_IMPLICIT = 3, /**< implicit Euler on the same springs (N/m): exact force residual, solved by
                                   conjugate gradients on a prefactored sparse Cholesky (CPU) or by
                                   block-Jacobi passes with Chebyshev acceleration (GLES); rests exactly at
                                   the springs' equilibrium whatever the budget (GLES stretches more in
                                   motion, and lags behind implicit Euler in motion when stiff) */
    DRAPE_MODEL_AUTO = 4 /**< the default: IMPLICIT on every backend, which rests at the springs' equilibrium.
                              A cloth stores the model it resolved to (drape_cloth_get_params reports it) */
} drape_model;
/* GENERATED END drape_model */

/* GENERATED BEGIN drape_group */
/* C# twin: Drape.Core.Group. Spring / constraint groups of the 12-neighbour stencil (grid) or of a mesh. */
typedef enum drape_group {
    DRAPE_GROUP_STRUCTURAL = 0, /**< grid: (+-1,0),(0,+-1); mesh: triangle edges */
    DRAPE_GROUP_SHEAR = 1, /**< grid: (+-1,+-1); mesh: none */
    DRAPE_GROUP_BEND = 2, /**< grid: (+-2,0),(0,+-2); mesh: vertices opposite each edge */
    DRAPE_GROUP_COUNT = 3
} drape_group;
/* GENERATED END drape_group */

/* GENERATED BEGIN drape_params */
/* C# twin: Drape.Core.Params. Settable at any time; drape_params_default fills the defaults. */
typedef struct drape_params {
    uint32_t struct_size;
    uint32_t model; /**< drape_model. Default AUTO */
    float stiffness[3]; /**< per drape_group. MASS_SPRING, XPBD, IMPLICIT: N/m per spring (0 = group off);
                             PBD: fraction in [0,1] per iteration. Range [0, 1e9]. Default 2000, 1000, 200 */
    float damping; /**< N*s/m, along each spring (eq. 2; XPBD: constraint damping; IMPLICIT: implicit
                        dashpot). Range [0, 1e6]. Default 0.05 */
    float gravity[3]; /**< m/s^2. Length <= 10000. Default (0, -9.81, 0) */
    float wind[3]; /**< m/s, air velocity. Length <= 10000. Default (0, 0, 0) */
    float air_drag; /**< 1/s, a += air_drag*(wind - v). Range [0, 1000]. Default 0.1 */
    uint32_t substeps; /**< per step; 0 = automatic (MASS_SPRING: from the stability bound, see
                            drape_estimate_stability; PBD, XPBD: 16 "small steps"; IMPLICIT: 2, on GLES one
                            per 1/960 s of the step (up to 5 times as many for structural springs much stiffer
                            than shear ones); on CPU backends more while a collider near the cloth moves over
                            half its size per substep, or with self-collision a particle over a quarter of the
                            thickness). Automatic or given, at most DRAPE_MAX_SUBSTEPS. Range [0,
                            DRAPE_MAX_SUBSTEPS]. Default 0 */
    uint32_t iterations; /**< solver iterations per substep (PBD, XPBD, IMPLICIT; IMPLICIT on the CPU: at
                              most, fewer once converged); 0 = automatic (IMPLICIT: 4, on GLES 2; PBD and
                              XPBD: 1). Range [0, DRAPE_MAX_ITERATIONS]. Default 0 */
    float max_stretch; /**< tethers (long-range attachments, Kim et al. 2012): every particle stays within (1
                            + max_stretch) x its rest distance along the cloth to the nearest pinned particle.
                            Fraction; 0 = off. Range [0, 100]. Default 0.1 */
} drape_params;
/* GENERATED END drape_params */

/** Fills every field with its default and struct_size (see "struct_size" above). */
DRAPE_API drape_status drape_params_default(drape_params* out_params);
/** Errors: NULL_POINTER, STRUCT_SIZE, INVALID_ENUM (model), NOT_FINITE, INVALID_ARGUMENT (a field
 *  out of its range; PBD stiffness above 1). Takes effect at the next step. */
DRAPE_API drape_status drape_cloth_set_params(drape_cloth* cloth, const drape_params* params);
/** The cloth's parameters (see "struct_size" above for out_params->struct_size). */
DRAPE_API drape_status drape_cloth_get_params(const drape_cloth* cloth, drape_params* out_params);

/* GENERATED BEGIN drape_stability */
/* C# twin: Drape.Core.StabilityEstimate. What drape_estimate_stability says about a cloth before it exists:
 * the substeps a step of dt would use and the explicit stability bound behind MASS_SPRING's automatic choice
 * (the same computation a cloth runs when its parameters or masses change). */
typedef struct drape_stability {
    uint32_t struct_size;
    uint32_t substeps; /**< substeps a step of dt uses with these parameters (params.substeps, or the
                            automatic choice, capped at DRAPE_MAX_SUBSTEPS) */
    uint32_t stable_substeps; /**< fewest substeps that keep MASS_SPRING within its explicit stability bound
                                   h*omega_max < 2 (with the library's safety factor), not capped (UINT32_MAX
                                   if beyond); 1 for PBD and XPBD */
    float max_stable_substep; /**< s, MASS_SPRING: largest stable substep h (the tightest particle); 0 when
                                   nothing bounds it (PBD, XPBD, no active spring) */
    uint32_t stable; /**< 1 if substeps >= stable_substeps */
} drape_stability;
/* GENERATED END drape_stability */

/** Stability estimate for a cloth that is not (yet) created: the cloth desc and exactly one of
 *  grid or mesh (the other NULL) as for creation, the parameters, and a step dt (as for
 *  drape_cloth_step). Runs the computation the cloth itself runs (area-weighted masses, springs
 *  per particle, no pins: pinning only removes particles from the bound). Validation and errors
 *  as for drape_cloth_create_* and drape_cloth_set_params; the backend need not be available. */
DRAPE_API drape_status drape_estimate_stability(const drape_cloth_desc* desc, const drape_grid_desc* grid,
                                                const drape_mesh_desc* mesh, const drape_params* params, float dt,
                                                drape_stability* out_estimate);

/* ================================ 4. Output =================================================== */

/* GENERATED BEGIN drape_vertex_layout */
/* C# twin: Drape.Core.VertexLayout. Output goes to dst + i*stride + offset for caller vertex i. */
typedef struct drape_vertex_layout {
    uint32_t struct_size;
    uint32_t stride; /**< bytes between vertices, >= 12, multiple of 4 */
    int32_t position_offset; /**< bytes, multiple of 4, or -1 = do not write */
    int32_t normal_offset; /**< bytes, multiple of 4, or -1 = do not write */
    float origin[3]; /**< m, positions are written relative to this point of simulation space (position -
                          origin, computed in double): far from the world origin, write around a point near
                          the cloth (the renderer's transform, a floating origin) to keep float precision.
                          Must be 0 for drape_cloth_set_output_buffer. Default (0, 0, 0). Added in struct
                          revision 1 (older sizes still accepted) */
} drape_vertex_layout;
/* GENERATED END drape_vertex_layout */

/** Writes positions and/or normals of every caller vertex into dst (dst_size bytes). */
DRAPE_API drape_status drape_cloth_read(const drape_cloth* cloth, const drape_vertex_layout* layout,
                                        void* dst, size_t dst_size);

/* GENERATED BEGIN drape_cloth_info */
/* C# twin: Drape.Core.ClothInfo. */
typedef struct drape_cloth_info {
    uint32_t struct_size;
    uint32_t vertex_count; /**< caller vertices (before welding) */
    uint32_t particle_count; /**< simulated particles (after welding) */
    uint32_t spring_count[3]; /**< springs/constraints per drape_group */
    uint32_t triangle_count; /**< 0 for a grid with a single row or column */
    uint32_t backend; /**< drape_backend */
    uint32_t description_id; /**< its cooked description (topology, rest lengths, masses): cloths of one world
                                  created from identical input (the same grid or mesh bytes and total_mass)
                                  share one and report the same id. Added in struct revision 1 (older sizes
                                  still accepted) */
    uint32_t description_users; /**< cloths using that description, this one included. Added in struct
                                     revision 1 (older sizes still accepted) */
} drape_cloth_info;
/* GENERATED END drape_cloth_info */

/** Sizes of the cloth (see "struct_size" above for out_info->struct_size). */
DRAPE_API drape_status drape_cloth_get_info(const drape_cloth* cloth, drape_cloth_info* out_info);

/* GENERATED BEGIN drape_stage */
/* C# twin: Drape.Core.Stage. Stages of a CPU step, in order (drape_stats.stage_ms). */
typedef enum drape_stage {
    DRAPE_STAGE_BEGIN = 0, /**< plan substeps, back up the state, the step's spring factors */
    DRAPE_STAGE_PREDICT = 1, /**< inertial prediction (PBD, XPBD) */
    DRAPE_STAGE_SOLVE = 2, /**< the model's solve (MASS_SPRING: its Verlet step; IMPLICIT: with its
                                prediction) */
    DRAPE_STAGE_TETHER = 3, /**< tethers (max_stretch > 0 and pinned vertices) */
    DRAPE_STAGE_SELF_COLLIDE = 4, /**< self-collision (when enabled) */
    DRAPE_STAGE_COLLIDE = 5, /**< touch drag and colliders (when there are any) */
    DRAPE_STAGE_VERIFY = 6, /**< finite positions and runaway strain (the strain statistics are computed when
                                 read) */
    DRAPE_STAGE_FINISH = 7, /**< rollback or commit: colliders advance, sleep check, recentre */
    DRAPE_STAGE_COUNT = 8
} drape_stage;
/* GENERATED END drape_stage */

/* GENERATED BEGIN drape_stats */
/* C# twin: Drape.Core.Stats. Describes the last step. */
typedef struct drape_stats {
    uint32_t struct_size;
    float step_ms; /**< ms, wall time of the last step */
    uint32_t substeps; /**< substeps used by the last step */
    uint32_t iterations; /**< iterations per substep used by the last step (IMPLICIT: the most any substep
                              took) */
    float max_strain; /**< max over structural+shear springs of |l/L0 - 1| */
    float rms_strain;
    float kinetic_energy; /**< J */
    float potential_energy; /**< J, gravity relative to y = 0 */
    float elastic_energy; /**< J, springs (MASS_SPRING, XPBD, IMPLICIT); 0 for PBD */
    uint32_t non_finite; /**< 1 if the last step produced NaN/Inf (and was rolled back) */
    uint32_t unstable_steps; /**< steps rolled back since creation */
    uint32_t sleeping; /**< 1 if the cloth is asleep (drape_sleep_desc): steps do no work. Added in struct
                            revision 1 (older sizes still accepted) */
    float stage_ms[8]; /**< ms, wall time of each drape_stage in the last step, summed over its substeps; 0
                            unless a CPU cloth's world profiles stages (drape_world_desc.profile_stages).
                            Added in struct revision 2 (older sizes still accepted) */
} drape_stats;
/* GENERATED END drape_stats */

/** Statistics of the last step; out_stats->struct_size must be a size drape_stats has shipped. */
DRAPE_API drape_status drape_cloth_get_stats(const drape_cloth* cloth, drape_stats* out_stats);

/* ================================ 5. Collision ================================================ */
/* On a GLES cloth colliders run on the GPU like on the CPU (a collision pass per substep,
 * compiled only while the cloth has colliders; it tests every collider, as the cloth's bounds are
 * on the GPU). Self-collision too: a hash pass and a collide pass per substep, made and run only
 * while it is on. */

/** Most colliders one cloth takes (drape_cloth_set_colliders). */
#define DRAPE_MAX_COLLIDERS 64

/* GENERATED BEGIN drape_collider_shape */
/* C# twin: Drape.Core.ColliderShape. */
typedef enum drape_collider_shape {
    DRAPE_COLLIDER_SPHERE = 0, /**< size[0] = radius (> 0) */
    DRAPE_COLLIDER_CAPSULE = 1, /**< size[0] = radius (> 0), size[1] = half length (>= 0) of the segment along
                                     local y between the cap centres (Unity: max(0, height/2 - radius)) */
    DRAPE_COLLIDER_BOX = 2, /**< size = half extents (each > 0), oriented by rotation */
    DRAPE_COLLIDER_PLANE = 3 /**< infinite; local +y (rotation applied to (0,1,0)) points to the free side,
                                  position is a point on it; size ignored */
} drape_collider_shape;
/* GENERATED END drape_collider_shape */

/* GENERATED BEGIN drape_collider */
/* C# twin: Drape.Core.ColliderDesc. One element of the array given to drape_cloth_set_colliders. */
typedef struct drape_collider {
    uint32_t struct_size;
    uint32_t shape; /**< drape_collider_shape */
    uint32_t id; /**< host's stable id, unique in the array. The collider moves from the transform it had
                      under the same id in the previous call to this one, interpolated across the next step's
                      substeps (no tunnelling); a new id starts at rest */
    float position[3]; /**< m, simulation space */
    float rotation[4]; /**< unit quaternion x, y, z, w (|q| within 1e-3 of 1; renormalised). Default (0, 0, 0,
                            1) */
    float size[3]; /**< m, see drape_collider_shape */
    float margin; /**< m, in [0, 10]: distance kept between the cloth and the surface (cloth thickness plus
                       skin); typical 0.005 */
    float friction; /**< Coulomb coefficient in [0, 10]; 0 = frictionless. Typical 0.3-0.8 */
} drape_collider;
/* GENERATED END drape_collider */

/** Replaces the cloth's colliders (call once per frame with the current transforms; count 0
 *  removes them all). Nothing is checked against the cloth before the next step; with no
 *  colliders, or none whose bounds touch the cloth's, the step does no collision work.
 *  Errors: NULL_POINTER, STRUCT_SIZE (per element), INVALID_ENUM (shape), NOT_FINITE,
 *  INVALID_ARGUMENT (count > DRAPE_MAX_COLLIDERS, sizes (each <= 1e6 m), margin, friction,
 *  duplicate id, non-unit rotation). A change of any collider wakes a sleeping cloth. */
DRAPE_API drape_status drape_cloth_set_colliders(drape_cloth* cloth, const drape_collider* colliders,
                                                 uint32_t count);

/* GENERATED BEGIN drape_self_collision_desc */
/* C# twin: Drape.Core.SelfCollisionDesc. Self-collision: particles of the cloth that are not neighbours in
 * the rest mesh are kept at least `thickness` apart, so a cloth folding onto itself does not pass through
 * itself. Resolved once per substep (after the solve, before colliders) over candidate pairs from a spatial
 * hash, rebuilt only when the cloth has moved enough to need it; pairs that share a spring or lie closer than
 * 1.5 x thickness in the rest mesh never collide, and a pair that passed through each other within a substep
 * is pushed back to the side it came from. It works on particles: with a thickness well below the particle
 * spacing a particle can slip through the middle of a grid cell of another layer; the particle spacing is a
 * good thickness. A particle moving more than one thickness per substep relative to the cloth's mean motion
 * may pass through (raise substeps). Off by default: a cloth without it does no extra work. GLES: the hash is
 * rebuilt every substep (cells of 1.5 x thickness, at most 8 particles per bucket), so a pair moving more
 * than half a thickness per substep relative to each other may pass through. */
typedef struct drape_self_collision_desc {
    uint32_t struct_size;
    uint32_t enabled; /**< 1 = on, 0 = off (default). Default 0 */
    float thickness; /**< m, distance kept between non-neighbour particles: > 0 when enabled (>= 0 when not),
                          at most 1/4 of the diagonal of the cloth's rest bounding box. Typical: the particle
                          spacing. Default 0. Default 0 */
    float friction; /**< Coulomb coefficient between layers in [0, 10]; 0 = frictionless (default). Typical
                         0.1-0.5. Default 0 */
} drape_self_collision_desc;
/* GENERATED END drape_self_collision_desc */

/** Turns self-collision on or off (see drape_self_collision_desc); takes effect at the next step.
 *  Errors: NULL_POINTER, STRUCT_SIZE, NOT_FINITE (thickness, friction), INVALID_ARGUMENT (enabled
 *  not 0/1, thickness or friction out of range). A change wakes a sleeping cloth. On a GLES device
 *  below a limit self-collision needs (13 vertex texture units, ...) the cloth's next step fails with
 *  BACKEND_UNAVAILABLE naming it; the cloth steps again once self-collision is off. */
DRAPE_API drape_status drape_cloth_set_self_collision(drape_cloth* cloth, const drape_self_collision_desc* desc);
/** Current setting (out_desc->struct_size must be set). A new cloth: enabled 0, thickness 0, friction 0. */
DRAPE_API drape_status drape_cloth_get_self_collision(const drape_cloth* cloth, drape_self_collision_desc* out_desc);

/* ================================ 6. Interaction ============================================== */
/* Touch drag runs on every backend. A GLES cloth reads nothing back for it: it keeps the touches
 * and views and its next step's first collision pass evaluates the drag on the GPU, at the
 * positions that step starts from (a CPU cloth: at the positions of the call; the same unless
 * positions change in between); it takes at most 4 drape_cloth_drag calls with 16 touches in all
 * between two steps (more: DRAPE_ERROR_INVALID_ARGUMENT). The owner transform runs on every backend (a GLES cloth moves its GPU state
 * by one transform-feedback pass per changed call, before its next step). Grabs run on every
 * backend. A GLES cloth reads nothing back for them: its next step picks the vertex on the GPU (at
 * the positions that step starts from) and holds it there, so drape_cloth_grab cannot say which
 * vertex it got (DRAPE_GRAB_ON_GPU) nor whether one was within the radius: the touch id holds its
 * grab until released either way (drape_cloth_grab_move is accepted and moves nothing if none was
 * found); moves and releases apply at the next step; a lost GL context drops the picks (the ids
 * hold nothing until grabbed again); tethers stay anchored to the pins (a CPU cloth anchors them
 * to the grabbed vertex too). Limits: 16 touches per drag call, 16 grabs held at once, pick radius
 * in (0, 1e4] px, screen positions within 1e6 px. */

/** drape_cloth_grab's *out_vertex on a GLES cloth: the vertex is picked on the GPU at the next
 *  step, and not known here (UINT32_MAX - 1; UINT32_MAX: no vertex within the radius, CPU). */
#define DRAPE_GRAB_ON_GPU 0xFFFFFFFEu

/* GENERATED BEGIN drape_view */
/* C# twin: Drape.Core.View. Matrices are 4x4, column-major (glm, OpenGL and Unity's Matrix4x4 memory order:
 * element (row r, column c) at [c*4 + r]); OpenGL clip conventions (NDC in [-1,1]^3; Unity:
 * GL.GetGPUProjectionMatrix is not needed, pass Camera.projectionMatrix). */
typedef struct drape_view {
    uint32_t struct_size;
    float world[16]; /**< simulation space -> world (identity if the cloth simulates in world space) */
    float view[16]; /**< world -> camera */
    float projection[16]; /**< camera -> clip */
    float viewport[2]; /**< px, width and height (> 0); screen origin bottom-left */
} drape_view;
/* GENERATED END drape_view */

/* GENERATED BEGIN drape_touch */
/* C# twin: Drape.Core.TouchPoint. Touch drag, paper eq. 9 (with the exponent's sign restored): c = min(1, A
 * exp(-r^2 / (2 sigma))), r = screen distance (px) of the vertex from the touch. The vertex's screen position
 * moves by c * motion and is unprojected at its own depth. As in the paper, sigma divides r^2 directly (it is
 * a variance, px^2), and A = 200, sigma = 300 px^2 (the paper's constants, interpreted in pixels: in NDC
 * units they would give the same c everywhere). Drape clamps c to 1 so no vertex outruns the finger: with the
 * defaults the vertices within sqrt(2 sigma ln A) = 56 px follow the finger fully, c = 0.5 at 60 px, 0.01 at
 * 77 px. */
typedef struct drape_touch {
    uint32_t struct_size;
    float position[2]; /**< px, where the finger was at the previous call (the touch point). Range [-1e6,
                            1e6]. Default (0, 0) */
    float motion[2]; /**< px, finger motion since then. Range [-1e6, 1e6]. Default (0, 0) */
    float amplitude; /**< A. Range (0, 1e6]. Default 200 */
    float sigma; /**< px^2. Range (0, 1e12]. Default 300 */
} drape_touch;
/* GENERATED END drape_touch */

/** Fills struct_size and the defaults (position, motion 0; A 200; sigma 300). */
DRAPE_API drape_status drape_touch_default(drape_touch* out_touch);
/** Drags the cloth with `count` touches (0..16) seen through `view`; the displacement is spread
 *  over the next step (the dragged vertices get the finger's velocity). Several calls before a
 *  step add up. Kinematic (pinned, grabbed) vertices are not moved. Wakes the cloth if anything moves. */
DRAPE_API drape_status drape_cloth_drag(drape_cloth* cloth, const drape_view* view, const drape_touch* touches,
                                        uint32_t count);
/** Pick-and-hold: grabs the free vertex nearest (on screen) to `position` (px) within
 *  `pick_radius` px and holds it as a moving pin at its current depth. `touch_id` names the grab
 *  (at most 16 at once; grabbing with a live id releases the old one first). *out_vertex = the
 *  caller vertex, or UINT32_MAX if none was within the radius (still DRAPE_OK); on a GLES cloth
 *  DRAPE_GRAB_ON_GPU (see above). */
DRAPE_API drape_status drape_cloth_grab(drape_cloth* cloth, const drape_view* view, uint32_t touch_id,
                                        const float position[2], float pick_radius, uint32_t* out_vertex);
/** Moves a grabbed vertex under the finger at `position` (px), at the depth it was grabbed at;
 *  the move is spread over the next step like a pin move. INVALID_ARGUMENT if touch_id holds nothing
 *  (a GLES cloth: if touch_id was not grabbed). */
DRAPE_API drape_status drape_cloth_grab_move(drape_cloth* cloth, const drape_view* view, uint32_t touch_id,
                                             const float position[2]);
/** Releases a grab (the vertex gets its inverse mass back and keeps its velocity). Unknown id: OK. */
DRAPE_API drape_status drape_cloth_grab_release(drape_cloth* cloth, uint32_t touch_id);

/* GENERATED BEGIN drape_owner */
/* C# twin: Drape.Core.Owner. The transform of the object the cloth hangs on (character, flag pole), in
 * simulation space. Pinned vertices move rigidly with it. Free vertices are carried along by (1 - inertia) of
 * the owner's motion without gaining velocity: inertia 0 simulates the cloth fully in the owner's local space
 * (owner motion has no inertial effect), 1 fully in world space (the cloth lags and swings as the pins drag
 * it). A jump of the owner's position by more than teleport_distance moves the whole cloth rigidly with it
 * (shape kept, velocities zeroed) instead of stretching it across the world. */
typedef struct drape_owner {
    uint32_t struct_size;
    float position[3]; /**< m. Range [-1e6, 1e6]. Default (0, 0, 0) */
    float rotation[4]; /**< unit quaternion x, y, z, w. Default (0, 0, 0, 1) */
    float linear_inertia; /**< Range [0, 1]. Default 1 */
    float angular_inertia; /**< Range [0, 1]. Default 1 */
    float teleport_distance; /**< m. Range (0, 1e6]. Default 1 */
} drape_owner;
/* GENERATED END drape_owner */

/** Fills struct_size and defaults (identity transform, inertia 1, teleport_distance 1 m). */
DRAPE_API drape_status drape_owner_default(drape_owner* out_owner);
/** Sets the owner transform for this frame. The first call only records it; later calls move
 *  pins and cloth by the change since the previous call (see drape_owner). Wakes on change. */
DRAPE_API drape_status drape_cloth_set_owner(drape_cloth* cloth, const drape_owner* owner);

/* ================================ 7. GPU (DRAPE_BACKEND_GLES) ================================= */
/* A GLES cloth keeps its state in GL buffers of the context that was current when it was created.
 * Immediate use (tests, samples, apps owning the context): create, step, read and destroy with
 * that context current on the calling thread; without one, creation fails with
 * DRAPE_ERROR_BACKEND_UNAVAILABLE and steps with DRAPE_ERROR_BACKEND_UNAVAILABLE.
 * Unity (no context on the main thread, an OpenGLES3 device seen by UnityPluginLoad): calls on the
 * main thread only record; the GL work (creation, queued steps and edits, output, releasing
 * destroyed cloths) runs on the render thread when the event from drape_unity_render_event fires.
 * Errors met there are returned by the cloth's next drape_cloth_step.
 * Steps never read back. drape_cloth_read and drape_cloth_get_stats read the state back (immediate
 * use only: with the context current) and then report what a CPU cloth would: positions, normals,
 * energies, and max/rms strain and non_finite from that read-back state; step_ms is the time to
 * record the GL commands; there is no divergence check or rollback on the GPU (unstable_steps
 * stays 0). Setters that need the current positions (inverse masses, new pins, releasing pins,
 * velocities) read back too.
 * Like a CPU cloth, a GLES cloth simulates relative to its own origin and takes and returns
 * positions in the caller's space (the output buffer too). It re-centres without reading back:
 * from its first pinned vertex's target, or, without pins, from the state last read back. */

/** Output target of a GLES cloth: after every step (and now) the GPU writes positions and/or
 *  normals of every caller vertex into GL buffer `gl_buffer` (Unity: Mesh.GetNativeVertexBufferPtr)
 *  at gl_buffer + i*stride + offset; bytes of the stride outside position/normal are kept.
 *  The buffer must hold vertex_count*stride bytes (checked with glGetBufferParameteriv, also before
 *  each step); stride <= 256. gl_buffer = 0 (layout may be NULL) stops writing. */
DRAPE_API drape_status drape_cloth_set_output_buffer(drape_cloth* cloth, uint32_t gl_buffer,
                                                     const drape_vertex_layout* layout);
/** Copies the GPU state of a GLES cloth to its CPU copy (immediate: now; Unity: at the next render
 *  event). Not needed for drape_cloth_read in immediate use. No-op for CPU cloths. */
DRAPE_API drape_status drape_cloth_readback(drape_cloth* cloth);
/** The GL context(s) of the GLES cloths are gone (EGL context destroyed, Android context loss):
 *  every GLES cloth of every world forgets the names of its GL objects without deleting them (no
 *  GL call is made here; any thread), and so do destroyed cloths whose objects were waiting for
 *  their context. On its next GL work, with a new OpenGL ES 3 context current (immediate use:
 *  the calling thread; Unity: the render event), a cloth builds its programs, buffers and textures
 *  again from its description, settings, pins and colliders as they are then, and its state from
 *  its CPU copy. That copy is the state of the last drape_cloth_readback, drape_cloth_read or
 *  drape_cloth_get_stats that read the GPU, or of the last setter that wrote positions or
 *  velocities, whichever came later: GPU steps after it are lost (the cloth resumes from that
 *  state, with the substep length it had then). To lose nothing, read back before the context
 *  goes; Unity's device shutdown event does this itself. The output buffer (a name in the old
 *  context) is forgotten: set the new one with drape_cloth_set_output_buffer. Until a context is
 *  current, GL work fails with DRAPE_ERROR_BACKEND_UNAVAILABLE; drape_cloth_read returns the CPU
 *  copy. Call it only after the old context is gone or no longer current anywhere; with several
 *  contexts, all GLES cloths start again from their CPU copies. No-op without GLES cloths. */
DRAPE_API drape_status drape_gles_context_lost(void);

/* ================================ 8. Unity ==================================================== */
/* UnityPluginLoad / UnityPluginUnload are exported too (Unity's native plug-in interface). */

/** The render-event callback for GL.IssuePluginEvent / CommandBuffer.IssuePluginEvent and the
 *  event id to pass (reserved from Unity). The event runs every GLES cloth's recorded GL work.
 *  NULL_POINTER (with a message) if either out-pointer is NULL. */
DRAPE_API drape_status drape_unity_render_event(void** out_callback, int32_t* out_event_id);

#ifdef __cplusplus
}
#endif

#endif /* DRAPE_DRAPE_H */
