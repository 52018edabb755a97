/* The C compiler's view of drape.h, for the C# layout parity test (LayoutParityTests.cs).
 * Built into libdrape_layout_probe.so by Drape.Core.Tests.csproj. Every struct of drape.h shared
 * with C# is listed with its size and each field's offset and size, and every enumerator with its
 * value. A field added to a struct but not here still fails the test: the struct size changes. */
#include <stddef.h>
#include <stdint.h>

#include "drape/drape.h"

typedef struct probe_entry {
    const char* name;
    int64_t value;
} probe_entry;

#define STRUCT(t) {#t, (int64_t)sizeof(t)}
#define FIELD(t, f) {#t "." #f, (int64_t)offsetof(t, f)}, {#t "." #f ":size", (int64_t)sizeof(((t*)0)->f)}
#define ENUM(e) {"enum:" #e, (int64_t)(e)}

static const probe_entry k_entries[] = {
    {"DRAPE_ABI_VERSION", DRAPE_ABI_VERSION},

    STRUCT(drape_world_desc),
    FIELD(drape_world_desc, struct_size),
    FIELD(drape_world_desc, thread_count),

    STRUCT(drape_cloth_desc),
    FIELD(drape_cloth_desc, struct_size),
    FIELD(drape_cloth_desc, backend),
    FIELD(drape_cloth_desc, total_mass),

    STRUCT(drape_grid_desc),
    FIELD(drape_grid_desc, struct_size),
    FIELD(drape_grid_desc, columns),
    FIELD(drape_grid_desc, rows),
    FIELD(drape_grid_desc, width),
    FIELD(drape_grid_desc, height),
    FIELD(drape_grid_desc, origin),
    FIELD(drape_grid_desc, axis_u),
    FIELD(drape_grid_desc, axis_v),

    STRUCT(drape_mesh_desc),
    FIELD(drape_mesh_desc, struct_size),
    FIELD(drape_mesh_desc, vertex_count),
    FIELD(drape_mesh_desc, positions),
    FIELD(drape_mesh_desc, index_count),
    FIELD(drape_mesh_desc, indices),
    FIELD(drape_mesh_desc, weld_distance),

    STRUCT(drape_params),
    FIELD(drape_params, struct_size),
    FIELD(drape_params, model),
    FIELD(drape_params, stiffness),
    FIELD(drape_params, damping),
    FIELD(drape_params, gravity),
    FIELD(drape_params, wind),
    FIELD(drape_params, air_drag),
    FIELD(drape_params, substeps),
    FIELD(drape_params, iterations),
    FIELD(drape_params, max_stretch),

    STRUCT(drape_vertex_layout),
    FIELD(drape_vertex_layout, struct_size),
    FIELD(drape_vertex_layout, stride),
    FIELD(drape_vertex_layout, position_offset),
    FIELD(drape_vertex_layout, normal_offset),

    STRUCT(drape_pin),
    FIELD(drape_pin, struct_size),
    FIELD(drape_pin, vertex),
    FIELD(drape_pin, position),

    STRUCT(drape_cloth_info),
    FIELD(drape_cloth_info, struct_size),
    FIELD(drape_cloth_info, vertex_count),
    FIELD(drape_cloth_info, particle_count),
    FIELD(drape_cloth_info, spring_count),
    FIELD(drape_cloth_info, triangle_count),
    FIELD(drape_cloth_info, backend),

    STRUCT(drape_stats),
    FIELD(drape_stats, struct_size),
    FIELD(drape_stats, step_ms),
    FIELD(drape_stats, substeps),
    FIELD(drape_stats, iterations),
    FIELD(drape_stats, max_strain),
    FIELD(drape_stats, rms_strain),
    FIELD(drape_stats, kinetic_energy),
    FIELD(drape_stats, potential_energy),
    FIELD(drape_stats, elastic_energy),
    FIELD(drape_stats, non_finite),
    FIELD(drape_stats, unstable_steps),
    FIELD(drape_stats, sleeping),

    STRUCT(drape_collider),
    FIELD(drape_collider, struct_size),
    FIELD(drape_collider, shape),
    FIELD(drape_collider, id),
    FIELD(drape_collider, position),
    FIELD(drape_collider, rotation),
    FIELD(drape_collider, size),
    FIELD(drape_collider, margin),
    FIELD(drape_collider, friction),

    STRUCT(drape_sleep_desc),
    FIELD(drape_sleep_desc, struct_size),
    FIELD(drape_sleep_desc, threshold),
    FIELD(drape_sleep_desc, time),

    STRUCT(drape_view),
    FIELD(drape_view, struct_size),
    FIELD(drape_view, world),
    FIELD(drape_view, view),
    FIELD(drape_view, projection),
    FIELD(drape_view, viewport),

    STRUCT(drape_touch),
    FIELD(drape_touch, struct_size),
    FIELD(drape_touch, position),
    FIELD(drape_touch, motion),
    FIELD(drape_touch, amplitude),
    FIELD(drape_touch, sigma),

    STRUCT(drape_owner),
    FIELD(drape_owner, struct_size),
    FIELD(drape_owner, position),
    FIELD(drape_owner, rotation),
    FIELD(drape_owner, linear_inertia),
    FIELD(drape_owner, angular_inertia),
    FIELD(drape_owner, teleport_distance),

    STRUCT(drape_self_collision_desc),
    FIELD(drape_self_collision_desc, struct_size),
    FIELD(drape_self_collision_desc, enabled),
    FIELD(drape_self_collision_desc, thickness),
    FIELD(drape_self_collision_desc, friction),

    {"DRAPE_MAX_COLLIDERS", DRAPE_MAX_COLLIDERS},

    ENUM(DRAPE_OK),
    ENUM(DRAPE_ERROR_NULL_POINTER),
    ENUM(DRAPE_ERROR_INVALID_HANDLE),
    ENUM(DRAPE_ERROR_STRUCT_SIZE),
    ENUM(DRAPE_ERROR_INVALID_ENUM),
    ENUM(DRAPE_ERROR_INVALID_ARGUMENT),
    ENUM(DRAPE_ERROR_NOT_FINITE),
    ENUM(DRAPE_ERROR_INDEX_OUT_OF_RANGE),
    ENUM(DRAPE_ERROR_DEGENERATE_MESH),
    ENUM(DRAPE_ERROR_BUFFER_TOO_SMALL),
    ENUM(DRAPE_ERROR_BACKEND_UNAVAILABLE),
    ENUM(DRAPE_ERROR_UNSTABLE),
    ENUM(DRAPE_ERROR_OUT_OF_MEMORY),
    ENUM(DRAPE_ERROR_GL),
    ENUM(DRAPE_ERROR_INTERNAL),
    ENUM(DRAPE_BACKEND_CPU),
    ENUM(DRAPE_BACKEND_CPU_THREADED),
    ENUM(DRAPE_BACKEND_GLES),
    ENUM(DRAPE_MODEL_MASS_SPRING),
    ENUM(DRAPE_MODEL_PBD),
    ENUM(DRAPE_MODEL_XPBD),
    ENUM(DRAPE_GROUP_STRUCTURAL),
    ENUM(DRAPE_GROUP_SHEAR),
    ENUM(DRAPE_GROUP_BEND),
    ENUM(DRAPE_GROUP_COUNT),
    ENUM(DRAPE_COLLIDER_SPHERE),
    ENUM(DRAPE_COLLIDER_CAPSULE),
    ENUM(DRAPE_COLLIDER_BOX),
    ENUM(DRAPE_COLLIDER_PLANE),
};

__attribute__((visibility("default"))) int32_t drape_probe_count(void) {
    return (int32_t)(sizeof k_entries / sizeof k_entries[0]);
}
__attribute__((visibility("default"))) const char* drape_probe_name(int32_t i) { return k_entries[i].name; }
__attribute__((visibility("default"))) int64_t drape_probe_value(int32_t i) { return k_entries[i].value; }
