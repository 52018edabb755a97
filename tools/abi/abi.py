# The one description of Drape's C ABI data: enums, structs and their fields (type, unit, default,
# range, doc). tools/abi/generate.py turns it into
#   - the enum and struct blocks of plugin-native/include/drape/drape.h (between GENERATED markers),
#   - the C# twins unity-package/Runtime/Core/Enums.cs and Structs.cs,
#   - the layout probe tests/dotnet/LayoutProbe/drape_layout_probe.c,
#   - plugin-native/src/core/abi_tables.h: shipped struct sizes, defaults, range validation,
#   - the GLES uniform block (UNIFORM_BLOCK, at the end): its GLSL declaration in the shaders
#     (between GENERATED markers) and its C++ twin plugin-native/src/backend/gles/sim_uniforms.h.
# Edit here, then run `python3 tools/abi/generate.py`; `--check` (a ctest) fails on stale output.
#
# Field types: u32, i32, f32, and arrays of them as "f32[3]"; "const f32*", "const u32*" pointers.
# A field's `rev` is the struct revision that added it: 0 for fields in the first shipped layout.
# Every revision's size is a size the library accepts in struct_size (missing tail = defaults).
# Ranges: (lo, hi); `lo_open` / `hi_open` exclude the bound; `norm` checks the vector's length.

ABI_VERSION = 1


def enum(c, cs, doc, values, cs_type="uint", cs_prefix=None):
    return dict(c=c, cs=cs, doc=doc, values=values, cs_type=cs_type, cs_prefix=cs_prefix)


def field(name, type, doc="", unit=None, default=None, range=None, lo_open=False, hi_open=False, norm=False,
          enum=None, cs=None, cs_type=None, rev=0, check=True):
    return dict(name=name, type=type, doc=doc, unit=unit, default=default, range=range, lo_open=lo_open,
                hi_open=hi_open, norm=norm, enum=enum, cs=cs, cs_type=cs_type, rev=rev, check=check)


def struct(c, cs, doc, fields, direction="in", serializable=False, validate=False):
    """direction: "in" (read by the library) or "out" (written by it)."""
    return dict(c=c, cs=cs, doc=doc, fields=[field("struct_size", "u32")] + fields, direction=direction,
                serializable=serializable, validate=validate)


ENUMS = [
    enum("drape_status", "Status", "", cs_type="int", cs_prefix="DRAPE_", values=[
        ("DRAPE_OK", 0, ""),
        ("DRAPE_ERROR_NULL_POINTER", 1, "a required pointer was NULL"),
        ("DRAPE_ERROR_INVALID_HANDLE", 2, "handle is not a live object of the right kind"),
        ("DRAPE_ERROR_STRUCT_SIZE", 3, "struct_size is none of the sizes this library has shipped"),
        ("DRAPE_ERROR_INVALID_ENUM", 4, "enum value out of range"),
        ("DRAPE_ERROR_INVALID_ARGUMENT", 5, "a size, count or value is out of its allowed range"),
        ("DRAPE_ERROR_NOT_FINITE", 6, "a float input was NaN or infinite"),
        ("DRAPE_ERROR_INDEX_OUT_OF_RANGE", 7, "a vertex or triangle index is out of range"),
        ("DRAPE_ERROR_DEGENERATE_MESH", 8, "zero-area or repeated-index triangle, or no edges"),
        ("DRAPE_ERROR_BUFFER_TOO_SMALL", 9, "caller memory/layout cannot hold the output"),
        ("DRAPE_ERROR_BACKEND_UNAVAILABLE", 10, "backend not compiled in or not usable here"),
        ("DRAPE_ERROR_UNSTABLE", 11, "step diverged; the last good state was restored"),
        ("DRAPE_ERROR_OUT_OF_MEMORY", 12, ""),
        ("DRAPE_ERROR_GL", 13, "OpenGL ES error (message carries the GL log)"),
        ("DRAPE_ERROR_INTERNAL", 14, ""),
    ]),
    enum("drape_backend", "Backend", "", cs_prefix="DRAPE_BACKEND_", values=[
        ("DRAPE_BACKEND_CPU", 0, "one thread, deterministic (same input -> same bits)"),
        ("DRAPE_BACKEND_CPU_THREADED", 1, "the world's worker pool; same results as CPU"),
        ("DRAPE_BACKEND_GLES", 2, "OpenGL ES 3.0 transform feedback"),
    ]),
    enum("drape_model", "Model", "", cs_prefix="DRAPE_MODEL_", values=[
        ("DRAPE_MODEL_MASS_SPRING", 0, "Hooke springs + damping, Verlet (paper eq. 1-3)"),
        ("DRAPE_MODEL_PBD", 1, "stretch constraints, stiffness in [0,1] (paper eq. 4-8)"),
        ("DRAPE_MODEL_XPBD", 2, "compliance = 1/stiffness in physical units, one Jacobi pass per iteration. "
                                "Rests softer than its springs with few iterations"),
        ("DRAPE_MODEL_IMPLICIT", 3, "implicit Euler on the same springs (N/m): exact force residual, solved by "
                                    "conjugate gradients on a prefactored sparse Cholesky (CPU) or by block-Jacobi "
                                    "passes with Chebyshev acceleration (GLES); rests exactly at the springs' "
                                    "equilibrium whatever the budget (GLES stretches more in motion, and lags behind "
                                    "implicit Euler in motion when stiff)"),
        ("DRAPE_MODEL_AUTO", 4, "the default: IMPLICIT on every backend, which rests at the springs' equilibrium. "
                                "A cloth stores the model it resolved to (drape_cloth_get_params reports it)"),
    ]),
    enum("drape_group", "Group", "Spring / constraint groups of the 12-neighbour stencil (grid) or of a mesh.",
         cs_prefix="DRAPE_GROUP_", values=[
             ("DRAPE_GROUP_STRUCTURAL", 0, "grid: (+-1,0),(0,+-1); mesh: triangle edges"),
             ("DRAPE_GROUP_SHEAR", 1, "grid: (+-1,+-1); mesh: none"),
             ("DRAPE_GROUP_BEND", 2, "grid: (+-2,0),(0,+-2); mesh: vertices opposite each edge"),
             ("DRAPE_GROUP_COUNT", 3, ""),
         ]),
    enum("drape_collider_shape", "ColliderShape", "", cs_prefix="DRAPE_COLLIDER_", values=[
        ("DRAPE_COLLIDER_SPHERE", 0, "size[0] = radius (> 0)"),
        ("DRAPE_COLLIDER_CAPSULE", 1, "size[0] = radius (> 0), size[1] = half length (>= 0) of the segment along "
                                      "local y between the cap centres (Unity: max(0, height/2 - radius))"),
        ("DRAPE_COLLIDER_BOX", 2, "size = half extents (each > 0), oriented by rotation"),
        ("DRAPE_COLLIDER_PLANE", 3, "infinite; local +y (rotation applied to (0,1,0)) points to the free side, "
                                    "position is a point on it; size ignored"),
    ]),
    enum("drape_stage", "Stage", "Stages of a CPU step, in order (drape_stats.stage_ms).", cs_prefix="DRAPE_STAGE_",
         values=[
             ("DRAPE_STAGE_BEGIN", 0, "plan substeps, back up the state, the step's spring factors"),
             ("DRAPE_STAGE_PREDICT", 1, "inertial prediction (PBD, XPBD)"),
             ("DRAPE_STAGE_SOLVE", 2, "the model's solve (MASS_SPRING: its Verlet step; IMPLICIT: with its "
                                      "prediction)"),
             ("DRAPE_STAGE_TETHER", 3, "tethers (max_stretch > 0 and pinned vertices)"),
             ("DRAPE_STAGE_SELF_COLLIDE", 4, "self-collision (when enabled)"),
             ("DRAPE_STAGE_COLLIDE", 5, "touch drag and colliders (when there are any)"),
             ("DRAPE_STAGE_VERIFY", 6, "finite positions and runaway strain (the strain statistics are computed when read)"),
             ("DRAPE_STAGE_FINISH", 7, "rollback or commit: colliders advance, sleep check, recentre"),
             ("DRAPE_STAGE_COUNT", 8, ""),
         ]),
]

STRUCTS = [
    struct("drape_world_desc", "WorldDesc", "", validate=True, fields=[
        field("thread_count", "u32", "workers for CPU_THREADED including the caller; 0 = hardware count",
              range=(0, 256), default=0),
        field("profile_stages", "u32", "1: CPU steps time each stage into drape_stats.stage_ms (a clock read at "
              "each stage's start and end); 0: no timing", range=(0, 1), default=0, rev=1),
    ]),
    struct("drape_cloth_desc", "ClothDesc", "Common to grid and mesh creation.", validate=True, fields=[
        field("backend", "u32", "drape_backend", enum="drape_backend", default="DRAPE_BACKEND_CPU"),
        field("total_mass", "f32", "spread over vertices by area", unit="kg", range=(0, 1e6), lo_open=True,
              default=1.0),
    ]),
    struct("drape_grid_desc", "GridDesc",
           "Vertex (c, r) is at origin + axis_u*width*c/(columns-1) + axis_v*height*r/(rows-1); caller vertex "
           "index = r*columns + c.", [
               field("columns", "u32", "vertices per row, >= 1 (columns*rows >= 2)"),
               field("rows", "u32", ">= 1"),
               field("width", "f32", "> 0", unit="m"),
               field("height", "f32", "> 0", unit="m"),
               field("origin", "f32[3]", "position of vertex (0,0)", unit="m"),
               field("axis_u", "f32[3]", "unit direction of increasing column; all zero = +x"),
               field("axis_v", "f32[3]", "unit direction of increasing row; all zero = -z"),
           ]),
    struct("drape_mesh_desc", "MeshDesc",
           "Vertices closer than weld_distance are simulated as one (Unity splits vertices at UV seams) and "
           "written back to every copy on output. The arrays are read during the create call only.", [
               field("vertex_count", "u32", ">= 3"),
               field("positions", "const f32*", "vertex_count * 3 floats"),
               field("index_count", "u32", "multiple of 3, >= 3"),
               field("indices", "const u32*", "triangle list"),
               field("weld_distance", "f32", ">= 0; 0 welds only bit-identical positions", unit="m"),
           ]),
    struct("drape_params", "Params",
           "Settable at any time; drape_params_default fills the defaults.", serializable=True, validate=True,
           fields=[
               field("model", "u32", "drape_model", enum="drape_model", default="DRAPE_MODEL_AUTO"),
               field("stiffness", "f32[3]",
                     "per drape_group. MASS_SPRING, XPBD, IMPLICIT: N/m per spring (0 = group off); PBD: fraction in [0,1] "
                     "per iteration", cs_type="GroupValues", default=[2000.0, 1000.0, 200.0], range=(0, 1e9)),
               field("damping", "f32", "along each spring (eq. 2; XPBD: constraint damping; IMPLICIT: implicit dashpot)", unit="N*s/m",
                     default=0.05, range=(0, 1e6)),
               field("gravity", "f32[3]", "", unit="m/s^2", default=[0.0, -9.81, 0.0], range=(0, 1e4), norm=True),
               field("wind", "f32[3]", "air velocity", unit="m/s", default=[0.0, 0.0, 0.0], range=(0, 1e4),
                     norm=True),
               field("air_drag", "f32", "a += air_drag*(wind - v)", unit="1/s", default=0.1, range=(0, 1000)),
               field("substeps", "u32",
                     "per step; 0 = automatic (MASS_SPRING: from the stability bound, see drape_estimate_stability; "
                     "PBD, XPBD: 16 \"small steps\"; IMPLICIT: 2, on GLES one per 1/960 s of the step (up to 5 times as many "
                     "for structural springs much stiffer than shear ones); on CPU backends more "
                     "while a collider near the cloth moves over half its size per substep, or with self-collision a "
                     "particle over a quarter of the thickness). Automatic or given, "
                     "at most DRAPE_MAX_SUBSTEPS",
                     default=0, range=(0, "DRAPE_MAX_SUBSTEPS")),
               field("iterations", "u32", "solver iterations per substep (PBD, XPBD, IMPLICIT; IMPLICIT on the CPU: at most, "
                     "fewer once converged); 0 = automatic (IMPLICIT: 4, on GLES 2; PBD and XPBD: 1)", default=0, range=(0, "DRAPE_MAX_ITERATIONS")),
               field("max_stretch", "f32",
                     "tethers (long-range attachments, Kim et al. 2012): every particle stays within "
                     "(1 + max_stretch) x its rest distance along the cloth to the nearest pinned particle. "
                     "Fraction; 0 = off", default=0.1, range=(0, 100)),
           ]),
    struct("drape_vertex_layout", "VertexLayout",
           "Output goes to dst + i*stride + offset for caller vertex i.", [
               field("stride", "u32", "bytes between vertices, >= 12, multiple of 4"),
               field("position_offset", "i32", "bytes, multiple of 4, or -1 = do not write"),
               field("normal_offset", "i32", "bytes, multiple of 4, or -1 = do not write"),
               field("origin", "f32[3]",
                     "positions are written relative to this point of simulation space (position - origin, "
                     "computed in double): far from the world origin, write around a point near the cloth (the "
                     "renderer's transform, a floating origin) to keep float precision. Must be 0 for "
                     "drape_cloth_set_output_buffer", unit="m", default=[0.0, 0.0, 0.0], rev=1),
           ]),
    struct("drape_pin", "Pin",
           "Pins a caller vertex (inverse mass 0) at a target; pinning again moves it (the move is spread over "
           "the next step's substeps).", [
               field("vertex", "u32", "caller vertex index"),
               field("position", "f32[3]", "target", unit="m"),
           ]),
    struct("drape_cloth_info", "ClothInfo", "", direction="out", fields=[
        field("vertex_count", "u32", "caller vertices (before welding)"),
        field("particle_count", "u32", "simulated particles (after welding)"),
        field("spring_count", "u32[3]", "springs/constraints per drape_group", cs_type="GroupCounts"),
        field("triangle_count", "u32", "0 for a grid with a single row or column"),
        field("backend", "u32", "drape_backend", enum="drape_backend"),
        field("description_id", "u32", "its cooked description (topology, rest lengths, masses): cloths of one world "
              "created from identical input (the same grid or mesh bytes and total_mass) share one and report the "
              "same id", rev=1),
        field("description_users", "u32", "cloths using that description, this one included", rev=1),
    ]),
    struct("drape_stats", "Stats", "Describes the last step.", direction="out", fields=[
        field("step_ms", "f32", "wall time of the last step", unit="ms"),
        field("substeps", "u32", "substeps used by the last step"),
        field("iterations", "u32", "iterations per substep used by the last step (IMPLICIT: the most any "
              "substep took)"),
        field("max_strain", "f32", "max over structural+shear springs of |l/L0 - 1|"),
        field("rms_strain", "f32", ""),
        field("kinetic_energy", "f32", "", unit="J"),
        field("potential_energy", "f32", "gravity relative to y = 0", unit="J"),
        field("elastic_energy", "f32", "springs (MASS_SPRING, XPBD, IMPLICIT); 0 for PBD", unit="J"),
        field("non_finite", "u32", "1 if the last step produced NaN/Inf (and was rolled back)"),
        field("unstable_steps", "u32", "steps rolled back since creation"),
        field("sleeping", "u32", "1 if the cloth is asleep (drape_sleep_desc): steps do no work", rev=1),
        field("stage_ms", "f32[8]", "wall time of each drape_stage in the last step, summed over its substeps; "
              "0 unless a CPU cloth's world profiles stages (drape_world_desc.profile_stages)", unit="ms",
              cs_type="StageTimes", rev=2),
    ]),
    struct("drape_collider", "ColliderDesc", "One element of the array given to drape_cloth_set_colliders.", [
        field("shape", "u32", "drape_collider_shape", enum="drape_collider_shape"),
        field("id", "u32",
              "host's stable id, unique in the array. The collider moves from the transform it had under the same "
              "id in the previous call to this one, interpolated across the next step's substeps (no tunnelling); "
              "a new id starts at rest"),
        field("position", "f32[3]", "simulation space", unit="m"),
        field("rotation", "f32[4]", "unit quaternion x, y, z, w (|q| within 1e-3 of 1; renormalised)",
              default=[0.0, 0.0, 0.0, 1.0]),
        field("size", "f32[3]", "see drape_collider_shape", unit="m"),
        field("margin", "f32",
              "in [0, 10]: distance kept between the cloth and the surface (cloth thickness plus skin); typical "
              "0.005", unit="m"),
        field("friction", "f32", "Coulomb coefficient in [0, 10]; 0 = frictionless. Typical 0.3-0.8"),
    ]),
    struct("drape_sleep_desc", "SleepDesc",
           "A cloth whose fastest particle stays below `threshold` for `time` seconds of steps falls asleep: its "
           "velocities are zeroed and drape_cloth_step returns at once without touching the state. Colliders, "
           "pins, drag, grab, owner transform, parameters, masses, positions or velocities that change wake it. "
           "Default: threshold 0 (never sleeps).", validate=True, fields=[
               field("threshold", "f32", "0 = never sleep. Typical 0.01", unit="m/s", range=(0, 100), default=0.0),
               field("time", "f32", "how long motion must stay below threshold. Typical 1", unit="s",
                     range=(0, 100), default=0.0),
           ]),
    struct("drape_view", "View",
           "Matrices are 4x4, column-major (glm, OpenGL and Unity's Matrix4x4 memory order: element (row r, column "
           "c) at [c*4 + r]); OpenGL clip conventions (NDC in [-1,1]^3; Unity: GL.GetGPUProjectionMatrix is not "
           "needed, pass Camera.projectionMatrix).", [
               field("world", "f32[16]", "simulation space -> world (identity if the cloth simulates in world space)"),
               field("view", "f32[16]", "world -> camera", cs="ViewMatrix"),
               field("projection", "f32[16]", "camera -> clip"),
               field("viewport", "f32[2]", "width and height (> 0); screen origin bottom-left", unit="px"),
           ]),
    struct("drape_touch", "TouchPoint",
           "Touch drag, paper eq. 9 (with the exponent's sign restored): c = min(1, A exp(-r^2 / (2 sigma))), r = "
           "screen distance (px) of the vertex from the touch. The vertex's screen position moves by c * motion and "
           "is unprojected at its own depth. As in the paper, sigma divides r^2 directly (it is a variance, px^2), "
           "and A = 200, sigma = 300 px^2 (the paper's constants, interpreted in pixels: in NDC units they would "
           "give the same c everywhere). Drape clamps c to 1 so no vertex outruns the finger: with the defaults the "
           "vertices within sqrt(2 sigma ln A) = 56 px follow the finger fully, c = 0.5 at 60 px, 0.01 at 77 px.",
           validate=True, fields=[
               field("position", "f32[2]", "where the finger was at the previous call (the touch point)", unit="px",
                     range=(-1e6, 1e6), default=[0.0, 0.0]),
               field("motion", "f32[2]", "finger motion since then", unit="px", range=(-1e6, 1e6),
                     default=[0.0, 0.0]),
               field("amplitude", "f32", "A", default=200.0, range=(0, 1e6), lo_open=True),
               field("sigma", "f32", "", unit="px^2", default=300.0, range=(0, 1e12), lo_open=True),
           ]),
    struct("drape_owner", "Owner",
           "The transform of the object the cloth hangs on (character, flag pole), in simulation space. Pinned "
           "vertices move rigidly with it. Free vertices are carried along by (1 - inertia) of the owner's motion "
           "without gaining velocity: inertia 0 simulates the cloth fully in the owner's local space (owner motion "
           "has no inertial effect), 1 fully in world space (the cloth lags and swings as the pins drag it). A "
           "jump of the owner's position by more than teleport_distance moves the whole cloth rigidly with it "
           "(shape kept, velocities zeroed) instead of stretching it across the world.", validate=True, fields=[
               field("position", "f32[3]", "", unit="m", range=(-1e6, 1e6), default=[0.0, 0.0, 0.0]),
               field("rotation", "f32[4]", "unit quaternion x, y, z, w", default=[0.0, 0.0, 0.0, 1.0],
                     check=False),
               field("linear_inertia", "f32", "", range=(0, 1), default=1.0),
               field("angular_inertia", "f32", "", range=(0, 1), default=1.0),
               field("teleport_distance", "f32", "", unit="m", range=(0, 1e6), lo_open=True, default=1.0),
           ]),
    struct("drape_self_collision_desc", "SelfCollisionDesc",
           "Self-collision: particles of the cloth that are not neighbours in the rest mesh are kept at least "
           "`thickness` apart, so a cloth folding onto itself does not pass through itself. Resolved once per "
           "substep (after the solve, before colliders) over candidate pairs from a spatial hash, rebuilt only when "
           "the cloth has moved enough to need it; pairs that share a spring or lie closer than 1.5 x thickness in "
           "the rest mesh never collide, and a pair that passed through each other within a substep is pushed back "
           "to the side it came from. It works on particles: with a thickness well below the particle spacing a "
           "particle can slip through the middle of a grid cell of another layer; the particle spacing is a good "
           "thickness. A particle moving more than one thickness per substep relative to the cloth's mean motion "
           "may pass through (raise substeps). Off by default: a cloth without it does no extra work. GLES: the hash is "
           "rebuilt every substep (cells of 1.5 x thickness, at most 8 particles per bucket), so a pair moving more "
           "than half a thickness per substep relative to each other may pass through.", serializable=True, fields=[
               field("enabled", "u32", "1 = on, 0 = off (default)", default=0),
               field("thickness", "f32",
                     "distance kept between non-neighbour particles: > 0 when enabled (>= 0 when not), at most 1/4 "
                     "of the diagonal of the cloth's rest bounding box. Typical: the particle spacing. Default 0",
                     unit="m", default=0.0),
               field("friction", "f32",
                     "Coulomb coefficient between layers in [0, 10]; 0 = frictionless (default). Typical 0.1-0.5",
                     default=0.0),
           ]),
    struct("drape_stability", "StabilityEstimate",
           "What drape_estimate_stability says about a cloth before it exists: the substeps a step of dt would "
           "use and the explicit stability bound behind MASS_SPRING's automatic choice (the same computation a "
           "cloth runs when its parameters or masses change).", direction="out", fields=[
               field("substeps", "u32",
                     "substeps a step of dt uses with these parameters (params.substeps, or the automatic choice, "
                     "capped at DRAPE_MAX_SUBSTEPS)"),
               field("stable_substeps", "u32",
                     "fewest substeps that keep MASS_SPRING within its explicit stability bound h*omega_max < 2 "
                     "(with the library's safety factor), not capped (UINT32_MAX if beyond); 1 for PBD and XPBD"),
               field("max_stable_substep", "f32",
                     "MASS_SPRING: largest stable substep h (the tightest particle); 0 when nothing bounds it (PBD, "
                     "XPBD, no active spring)", unit="s"),
               field("stable", "u32", "1 if substeps >= stable_substeps"),
           ]),
]


# ---- Enums the shaders spell ------------------------------------------------------------------------
# generate.py writes their values as #defines (drape.h's names) into shaders/layout.h for GLSL, which
# cannot include drape.h.
SHADER_ENUMS = ["drape_group", "drape_collider_shape"]


# ---- GLES uniform block ---------------------------------------------------------------------------
# What every GLES pass reads that changes only with the parameters, the substep length or the cloth's
# origin: one std140 uniform block shared by all programs (one binding point), uploaded when a value
# changes instead of set per program and pass. generate.py writes its GLSL declaration into each
# shader that reads it (between GENERATED markers) and its C++ twin, the struct drape::gles::<cpp> in
# plugin-native/src/backend/gles/sim_uniforms.h (offsets checked by static_assert, and against the
# driver's layout when a program is linked). Members are
# u_<name> in GLSL. Types: float, int, vec3 (std140: scalars aligned to 4 bytes, vec3 to 16); scalars
# come first so none shares a vec3's last word (a layout some mobile drivers get wrong).

def ufield(name, type, doc="", unit=None):
    return dict(name=name, type=type, doc=doc, unit=unit)


UNIFORM_BLOCK = dict(glsl="DrapeSim", cpp="SimUniforms", binding=0,
                     shaders=["shaders/sim.vert.glsl", "shaders/output.vert.glsl"], fields=[
    ufield("damping", "float", "drape_params.damping (eq. 2; PBD: dashpot)", unit="N*s/m"),
    ufield("air_drag", "float", "drape_params.air_drag", unit="1/s"),
    ufield("h", "float", "substep length", unit="s"),
    ufield("jacobi_coupling", "float", "kJacobiCoupling (core/params.h)"),
    ufield("stiffness", "vec3", "drape_params.stiffness per drape_group (0: group off)"),
    ufield("compliance", "vec3", "XPBD: 1 / (k h^2) per group, 0 where off"),
    ufield("damping_ratio", "vec3", "XPBD: damping / (k h) per group, 0 where off"),
    ufield("gravity", "vec3", "drape_params.gravity", unit="m/s^2"),
    ufield("wind", "vec3", "drape_params.wind", unit="m/s"),
    ufield("origin", "vec3", "Cloth::origin (whole metres: exact in float); the output pass adds it", unit="m"),
])
