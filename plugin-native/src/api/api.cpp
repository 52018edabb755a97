// The C ABI: handle checks, input validation, exceptions -> status + message.
// Nothing reaches src/core before it has been validated here, so a failed call leaves every
// object unchanged.
#include <cmath>
#include <cstring>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <unordered_map>

#include "core/cloth.h"
#include "core/params.h"
#include "core/topology.h"
#include "drape/drape.h"

using namespace drape;

namespace {

thread_local std::string t_last_error;

drape_status fail(drape_status status, std::string message) {
    t_last_error = std::move(message);
    return status;
}

drape_status ok() {
    t_last_error.clear();
    return DRAPE_OK;
}

// Live handles. A pointer the library did not hand out (or already destroyed) is refused
// before it is dereferenced.
enum class Kind { World, Cloth };
std::mutex g_handles_mutex;
std::unordered_map<const void*, Kind>& handles() {
    static std::unordered_map<const void*, Kind> map;
    return map;
}
bool live(const void* p, Kind kind) {
    std::lock_guard<std::mutex> lock(g_handles_mutex);
    auto it = handles().find(p);
    return it != handles().end() && it->second == kind;
}
void track(const void* p, Kind kind) {
    std::lock_guard<std::mutex> lock(g_handles_mutex);
    handles()[p] = kind;
}
void untrack(const void* p) {
    std::lock_guard<std::mutex> lock(g_handles_mutex);
    handles().erase(p);
}

// Limits on sizes: far above any game cloth, low enough that sizes cannot overflow.
constexpr uint32_t kMaxVertices = 1u << 22;
constexpr float kMaxCoordinate = 1e6f;  // m
constexpr float kMaxMass = 1e6f;        // kg

#define DRAPE_REQUIRE(cond, status, msg) \
    do {                                 \
        if (!(cond)) return fail(status, msg); \
    } while (0)

#define DRAPE_CHECK_STRUCT(ptr, type)                                                          \
    do {                                                                                       \
        DRAPE_REQUIRE((ptr) != nullptr, DRAPE_ERROR_NULL_POINTER, #ptr " is NULL");            \
        DRAPE_REQUIRE((ptr)->struct_size == sizeof(type), DRAPE_ERROR_STRUCT_SIZE,             \
                      #ptr "->struct_size is " + std::to_string((ptr)->struct_size) +          \
                          ", this library expects sizeof(" #type ") = " + std::to_string(sizeof(type))); \
    } while (0)

// Runs body, turning any exception into a status (no exception crosses the C boundary).
template <class Body>
drape_status guarded(Body&& body) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return fail(DRAPE_ERROR_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
        return fail(DRAPE_ERROR_INTERNAL, std::string("internal error: ") + e.what());
    } catch (...) {
        return fail(DRAPE_ERROR_INTERNAL, "internal error");
    }
}

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }
bool bounded3(const float* v) {
    return std::fabs(v[0]) <= kMaxCoordinate && std::fabs(v[1]) <= kMaxCoordinate && std::fabs(v[2]) <= kMaxCoordinate;
}

drape_status check_world(const drape_world* w) {
    DRAPE_REQUIRE(w != nullptr, DRAPE_ERROR_NULL_POINTER, "world is NULL");
    DRAPE_REQUIRE(live(w, Kind::World), DRAPE_ERROR_INVALID_HANDLE, "world is not a live drape_world");
    return DRAPE_OK;
}

drape_status check_cloth(const drape_cloth* c) {
    DRAPE_REQUIRE(c != nullptr, DRAPE_ERROR_NULL_POINTER, "cloth is NULL");
    DRAPE_REQUIRE(live(c, Kind::Cloth), DRAPE_ERROR_INVALID_HANDLE, "cloth is not a live drape_cloth");
    return DRAPE_OK;
}

World* as_world(drape_world* w) { return reinterpret_cast<World*>(w); }
Cloth* as_cloth(drape_cloth* c) { return reinterpret_cast<Cloth*>(c); }
const Cloth* as_cloth(const drape_cloth* c) { return reinterpret_cast<const Cloth*>(c); }

drape_status check_cloth_desc(const drape_cloth_desc* desc) {
    DRAPE_CHECK_STRUCT(desc, drape_cloth_desc);
    DRAPE_REQUIRE(desc->backend <= DRAPE_BACKEND_GLES, DRAPE_ERROR_INVALID_ENUM,
                  "backend " + std::to_string(desc->backend) + " is not a drape_backend");
    DRAPE_REQUIRE(std::isfinite(desc->total_mass), DRAPE_ERROR_NOT_FINITE, "total_mass is NaN or infinite");
    DRAPE_REQUIRE(desc->total_mass > 0 && desc->total_mass <= kMaxMass, DRAPE_ERROR_INVALID_ARGUMENT,
                  "total_mass must be in (0, 1e6] kg");
    uint32_t available = 0;
    drape_backend_available(desc->backend, &available);
    DRAPE_REQUIRE(available, DRAPE_ERROR_BACKEND_UNAVAILABLE,
                  "backend " + std::to_string(desc->backend) + " is not available in this build or on this thread");
    return DRAPE_OK;
}

drape_status finish_create(drape_world* world, const drape_cloth_desc* desc, Topology topo, drape_cloth** out) {
    World& w = *as_world(world);
    auto* cloth = new Cloth(w, drape_backend(desc->backend), std::move(topo));
    w.add(cloth);
    track(cloth, Kind::Cloth);
    *out = reinterpret_cast<drape_cloth*>(cloth);
    return ok();
}

drape_status check_vertex_array(const drape_cloth* cloth, const void* data, uint32_t count, const char* what) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(data != nullptr, DRAPE_ERROR_NULL_POINTER, std::string(what) + " is NULL");
    const uint32_t n = as_cloth(cloth)->topology().vertex_count;
    DRAPE_REQUIRE(count == n, DRAPE_ERROR_INVALID_ARGUMENT,
                  std::string(what) + ": count is " + std::to_string(count) + ", the cloth has " +
                      std::to_string(n) + " vertices");
    return DRAPE_OK;
}

drape_status check_xyz_array(const float* xyz, uint32_t count, const char* what) {
    for (uint32_t v = 0; v < count; ++v) {
        DRAPE_REQUIRE(finite3(xyz + 3 * v), DRAPE_ERROR_NOT_FINITE,
                      std::string(what) + " of vertex " + std::to_string(v) + " is NaN or infinite");
        DRAPE_REQUIRE(bounded3(xyz + 3 * v), DRAPE_ERROR_INVALID_ARGUMENT,
                      std::string(what) + " of vertex " + std::to_string(v) + " is beyond 1e6");
    }
    return DRAPE_OK;
}

}  // namespace

extern "C" {

uint32_t drape_abi_version(void) { return DRAPE_ABI_VERSION; }

const char* drape_last_error(void) { return t_last_error.c_str(); }

drape_status drape_backend_available(uint32_t backend, uint32_t* out_available) {
    DRAPE_REQUIRE(out_available != nullptr, DRAPE_ERROR_NULL_POINTER, "out_available is NULL");
    DRAPE_REQUIRE(backend <= DRAPE_BACKEND_GLES, DRAPE_ERROR_INVALID_ENUM,
                  "backend " + std::to_string(backend) + " is not a drape_backend");
    *out_available = backend == DRAPE_BACKEND_CPU || backend == DRAPE_BACKEND_CPU_THREADED;
    return ok();
}

drape_status drape_params_default(drape_params* out_params) {
    DRAPE_REQUIRE(out_params != nullptr, DRAPE_ERROR_NULL_POINTER, "out_params is NULL");
    *out_params = default_params();
    return ok();
}

drape_status drape_world_create(const drape_world_desc* desc, drape_world** out_world) {
    DRAPE_CHECK_STRUCT(desc, drape_world_desc);
    DRAPE_REQUIRE(out_world != nullptr, DRAPE_ERROR_NULL_POINTER, "out_world is NULL");
    DRAPE_REQUIRE(desc->thread_count <= 256, DRAPE_ERROR_INVALID_ARGUMENT, "thread_count above 256");
    return guarded([&] {
        uint32_t threads = desc->thread_count;
        if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
        auto* world = new World(threads);
        track(world, Kind::World);
        *out_world = reinterpret_cast<drape_world*>(world);
        return ok();
    });
}

drape_status drape_world_destroy(drape_world* world) {
    if (drape_status s = check_world(world)) return s;
    return guarded([&] {
        World* w = as_world(world);
        for (Cloth* c : w->cloths()) untrack(c);
        untrack(w);
        delete w;
        return ok();
    });
}

drape_status drape_world_step(drape_world* world, float dt) {
    if (drape_status s = check_world(world)) return s;
    DRAPE_REQUIRE(std::isfinite(dt), DRAPE_ERROR_NOT_FINITE, "dt is NaN or infinite");
    DRAPE_REQUIRE(dt > 0 && dt <= 1, DRAPE_ERROR_INVALID_ARGUMENT, "dt must be in (0, 1] s");
    return guarded([&] {
        Result r = as_world(world)->step(dt);
        return r.ok() ? ok() : fail(r.status, r.message);
    });
}

drape_status drape_cloth_create_grid(drape_world* world, const drape_cloth_desc* desc, const drape_grid_desc* grid,
                                     drape_cloth** out_cloth) {
    if (drape_status s = check_world(world)) return s;
    if (drape_status s = check_cloth_desc(desc)) return s;
    DRAPE_CHECK_STRUCT(grid, drape_grid_desc);
    DRAPE_REQUIRE(out_cloth != nullptr, DRAPE_ERROR_NULL_POINTER, "out_cloth is NULL");
    DRAPE_REQUIRE(grid->columns >= 1 && grid->rows >= 1 && uint64_t(grid->columns) * grid->rows >= 2,
                  DRAPE_ERROR_INVALID_ARGUMENT, "grid needs columns >= 1, rows >= 1 and at least 2 vertices");
    DRAPE_REQUIRE(uint64_t(grid->columns) * grid->rows <= kMaxVertices, DRAPE_ERROR_INVALID_ARGUMENT,
                  "grid has more than 4194304 vertices");
    DRAPE_REQUIRE(std::isfinite(grid->width) && std::isfinite(grid->height) && finite3(grid->origin) &&
                      finite3(grid->axis_u) && finite3(grid->axis_v),
                  DRAPE_ERROR_NOT_FINITE, "grid width, height, origin and axes must be finite");
    DRAPE_REQUIRE(grid->width > 0 && grid->height > 0 && grid->width <= kMaxCoordinate &&
                      grid->height <= kMaxCoordinate && bounded3(grid->origin),
                  DRAPE_ERROR_INVALID_ARGUMENT, "grid width and height must be in (0, 1e6] m, origin within 1e6 m");
    const float* u = grid->axis_u;
    const float* v = grid->axis_v;
    const float cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const bool default_axes = (u[0] == 0 && u[1] == 0 && u[2] == 0) || (v[0] == 0 && v[1] == 0 && v[2] == 0);
    DRAPE_REQUIRE(default_axes || cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] > 1e-12f *
                      (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]),
                  DRAPE_ERROR_INVALID_ARGUMENT, "grid axis_u and axis_v are parallel");
    return guarded([&] { return finish_create(world, desc, cook_grid(*grid, desc->total_mass), out_cloth); });
}

drape_status drape_cloth_create_mesh(drape_world* world, const drape_cloth_desc* desc, const drape_mesh_desc* mesh,
                                     drape_cloth** out_cloth) {
    if (drape_status s = check_world(world)) return s;
    if (drape_status s = check_cloth_desc(desc)) return s;
    DRAPE_CHECK_STRUCT(mesh, drape_mesh_desc);
    DRAPE_REQUIRE(out_cloth != nullptr, DRAPE_ERROR_NULL_POINTER, "out_cloth is NULL");
    DRAPE_REQUIRE(mesh->positions != nullptr, DRAPE_ERROR_NULL_POINTER, "mesh->positions is NULL");
    DRAPE_REQUIRE(mesh->indices != nullptr, DRAPE_ERROR_NULL_POINTER, "mesh->indices is NULL");
    DRAPE_REQUIRE(mesh->vertex_count >= 3 && mesh->vertex_count <= kMaxVertices, DRAPE_ERROR_INVALID_ARGUMENT,
                  "mesh vertex_count must be in [3, 4194304]");
    DRAPE_REQUIRE(mesh->index_count >= 3 && mesh->index_count % 3 == 0 && mesh->index_count <= 3 * 2 * kMaxVertices,
                  DRAPE_ERROR_INVALID_ARGUMENT, "mesh index_count must be a positive multiple of 3 (triangle list)");
    DRAPE_REQUIRE(std::isfinite(mesh->weld_distance), DRAPE_ERROR_NOT_FINITE, "weld_distance is NaN or infinite");
    DRAPE_REQUIRE(mesh->weld_distance >= 0 && mesh->weld_distance <= 1, DRAPE_ERROR_INVALID_ARGUMENT,
                  "weld_distance must be in [0, 1] m");
    if (drape_status s = check_xyz_array(mesh->positions, mesh->vertex_count, "mesh position")) return s;
    return guarded([&] {
        Topology topo;
        CookResult r = cook_mesh(*mesh, desc->total_mass, topo);
        if (r.status != DRAPE_OK) return fail(r.status, r.message);
        return finish_create(world, desc, std::move(topo), out_cloth);
    });
}

drape_status drape_cloth_destroy(drape_cloth* cloth) {
    if (drape_status s = check_cloth(cloth)) return s;
    return guarded([&] {
        Cloth* c = as_cloth(cloth);
        c->world().remove(c);
        untrack(c);
        delete c;
        return ok();
    });
}

drape_status drape_cloth_set_params(drape_cloth* cloth, const drape_params* params) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_CHECK_STRUCT(params, drape_params);
    drape_status status;
    std::string problem = validate_params(*params, &status);
    if (status != DRAPE_OK) return fail(status, problem);
    return guarded([&] {
        as_cloth(cloth)->set_params(*params);
        return ok();
    });
}

drape_status drape_cloth_get_params(const drape_cloth* cloth, drape_params* out_params) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_params != nullptr, DRAPE_ERROR_NULL_POINTER, "out_params is NULL");
    *out_params = as_cloth(cloth)->params();
    return ok();
}

drape_status drape_cloth_set_inverse_masses(drape_cloth* cloth, const float* inverse_masses, uint32_t count) {
    if (drape_status s = check_vertex_array(cloth, inverse_masses, count, "inverse_masses")) return s;
    for (uint32_t v = 0; v < count; ++v) {
        DRAPE_REQUIRE(std::isfinite(inverse_masses[v]), DRAPE_ERROR_NOT_FINITE,
                      "inverse mass of vertex " + std::to_string(v) + " is NaN or infinite");
        DRAPE_REQUIRE(inverse_masses[v] >= 0 && inverse_masses[v] <= 1e9f, DRAPE_ERROR_INVALID_ARGUMENT,
                      "inverse mass of vertex " + std::to_string(v) + " must be in [0, 1e9] 1/kg");
    }
    return guarded([&] {
        as_cloth(cloth)->set_inverse_masses(inverse_masses);
        return ok();
    });
}

drape_status drape_cloth_set_pins(drape_cloth* cloth, const drape_pin* pins, uint32_t count) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(pins != nullptr || count == 0, DRAPE_ERROR_NULL_POINTER, "pins is NULL");
    const uint32_t n = as_cloth(cloth)->topology().vertex_count;
    for (uint32_t k = 0; k < count; ++k) {
        DRAPE_CHECK_STRUCT(&pins[k], drape_pin);
        DRAPE_REQUIRE(pins[k].vertex < n, DRAPE_ERROR_INDEX_OUT_OF_RANGE,
                      "pin " + std::to_string(k) + " vertex " + std::to_string(pins[k].vertex) + " >= vertex count " +
                          std::to_string(n));
        DRAPE_REQUIRE(finite3(pins[k].position), DRAPE_ERROR_NOT_FINITE,
                      "pin " + std::to_string(k) + " position is NaN or infinite");
        DRAPE_REQUIRE(bounded3(pins[k].position), DRAPE_ERROR_INVALID_ARGUMENT,
                      "pin " + std::to_string(k) + " position is beyond 1e6 m");
    }
    return guarded([&] {
        as_cloth(cloth)->set_pins(pins, count);
        return ok();
    });
}

drape_status drape_cloth_release_pins(drape_cloth* cloth, const uint32_t* vertices, uint32_t count) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(vertices != nullptr || count == 0, DRAPE_ERROR_NULL_POINTER, "vertices is NULL");
    const uint32_t n = as_cloth(cloth)->topology().vertex_count;
    for (uint32_t k = 0; k < count; ++k)
        DRAPE_REQUIRE(vertices[k] < n, DRAPE_ERROR_INDEX_OUT_OF_RANGE,
                      "vertex " + std::to_string(vertices[k]) + " >= vertex count " + std::to_string(n));
    return guarded([&] {
        as_cloth(cloth)->release_pins(vertices, count);
        return ok();
    });
}

drape_status drape_cloth_set_positions(drape_cloth* cloth, const float* positions, uint32_t count) {
    if (drape_status s = check_vertex_array(cloth, positions, count, "positions")) return s;
    if (drape_status s = check_xyz_array(positions, count, "position")) return s;
    return guarded([&] {
        as_cloth(cloth)->set_positions(positions);
        return ok();
    });
}

drape_status drape_cloth_set_velocities(drape_cloth* cloth, const float* velocities, uint32_t count) {
    if (drape_status s = check_vertex_array(cloth, velocities, count, "velocities")) return s;
    if (drape_status s = check_xyz_array(velocities, count, "velocity")) return s;
    return guarded([&] {
        as_cloth(cloth)->set_velocities(velocities);
        return ok();
    });
}

drape_status drape_cloth_step(drape_cloth* cloth, float dt) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(std::isfinite(dt), DRAPE_ERROR_NOT_FINITE, "dt is NaN or infinite");
    DRAPE_REQUIRE(dt > 0 && dt <= 1, DRAPE_ERROR_INVALID_ARGUMENT, "dt must be in (0, 1] s");
    return guarded([&] {
        Result r = as_cloth(cloth)->step(dt);
        return r.ok() ? ok() : fail(r.status, r.message);
    });
}

drape_status drape_cloth_read(const drape_cloth* cloth, const drape_vertex_layout* layout, void* dst,
                              size_t dst_size) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_CHECK_STRUCT(layout, drape_vertex_layout);
    DRAPE_REQUIRE(dst != nullptr, DRAPE_ERROR_NULL_POINTER, "dst is NULL");
    DRAPE_REQUIRE(layout->stride >= 12 && layout->stride % 4 == 0 && layout->stride <= 1024,
                  DRAPE_ERROR_INVALID_ARGUMENT, "stride must be a multiple of 4 in [12, 1024]");
    DRAPE_REQUIRE(layout->position_offset >= 0 || layout->normal_offset >= 0, DRAPE_ERROR_INVALID_ARGUMENT,
                  "layout writes neither positions nor normals");
    for (int32_t off : {layout->position_offset, layout->normal_offset}) {
        if (off < 0) continue;
        DRAPE_REQUIRE(off % 4 == 0 && uint32_t(off) + 12 <= layout->stride, DRAPE_ERROR_INVALID_ARGUMENT,
                      "offset " + std::to_string(off) + " is not a multiple of 4 or does not fit in stride " +
                          std::to_string(layout->stride));
    }
    DRAPE_REQUIRE(layout->position_offset < 0 || layout->normal_offset < 0 ||
                      std::abs(layout->position_offset - layout->normal_offset) >= 12,
                  DRAPE_ERROR_INVALID_ARGUMENT, "position and normal overlap");
    const uint64_t needed = uint64_t(as_cloth(cloth)->topology().vertex_count) * layout->stride;
    DRAPE_REQUIRE(dst_size >= needed, DRAPE_ERROR_BUFFER_TOO_SMALL,
                  "dst_size is " + std::to_string(dst_size) + " bytes, the layout needs " + std::to_string(needed));
    return guarded([&] {
        as_cloth(cloth)->read(*layout, dst);
        return ok();
    });
}

drape_status drape_cloth_get_info(const drape_cloth* cloth, drape_cloth_info* out_info) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_info != nullptr, DRAPE_ERROR_NULL_POINTER, "out_info is NULL");
    const Cloth* c = as_cloth(cloth);
    const Topology& t = c->topology();
    drape_cloth_info info{};
    info.struct_size = sizeof info;
    info.vertex_count = t.vertex_count;
    info.particle_count = t.particle_count;
    for (int g = 0; g < DRAPE_GROUP_COUNT; ++g) info.spring_count[g] = t.spring_count[g];
    info.triangle_count = uint32_t(t.triangles.size() / 3);
    info.backend = c->backend();
    *out_info = info;
    return ok();
}

drape_status drape_cloth_get_stats(const drape_cloth* cloth, drape_stats* out_stats) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_stats != nullptr, DRAPE_ERROR_NULL_POINTER, "out_stats is NULL");
    return guarded([&] {
        as_cloth(cloth)->stats(out_stats);
        return ok();
    });
}

}  // extern "C"
