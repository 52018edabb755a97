// The C ABI: handle checks, input validation, exceptions -> status + message.
// Nothing reaches src/core before it has been validated here, so a failed call leaves every
// object unchanged.
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <new>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "api/last_error.h"
#include "backend/backends.h"
#include "core/cloth.h"
#include "core/drag.h"
#include "core/abi_tables.h"
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

drape_status status_of(const Result& r) { return r.ok() ? ok() : fail(r.status, r.message); }

// Handles are ids, not addresses (Box2D v3's b2BodyId): a slot index, the object kind and the
// slot's generation packed into a pointer-sized value. Destroying an object bumps its slot's
// generation, so its old handle stays refused when the slot (or the object's memory) is reused.
// A slot whose generation would wrap is retired instead of reused, so two handles never alias.
enum class Kind : uintptr_t { World = 1, Cloth = 2 };

class HandleTable {
public:
    static constexpr unsigned kHalf = sizeof(uintptr_t) * 4;  // 32 bits on 64-bit platforms
    static constexpr unsigned kIndexBits = kHalf - 2;         // the other 2: the kind
    static constexpr uintptr_t kIndexMask = (uintptr_t(1) << kIndexBits) - 1;
    static constexpr uintptr_t kGenerationMask = (uintptr_t(1) << kHalf) - 1;

    /// A handle for a new object. Throws std::bad_alloc (or length_error when out of slots).
    uintptr_t add(void* object, Kind kind) {
        std::lock_guard<std::mutex> lock(mutex_);
        uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
        } else {
            if (slots_.size() > kIndexMask) throw std::length_error("no free handle slot");
            index = uint32_t(slots_.size());
            slots_.emplace_back();
            free_.reserve(slots_.capacity());  // remove() then never allocates
            free_.push_back(index);
        }
        Slot& s = slots_[index];
        const uintptr_t handle = encode(index, kind, s.generation);
        by_object_.emplace(object, handle);  // may throw: nothing changed yet
        free_.pop_back();
        s.object = object;
        s.kind = kind;
        return handle;
    }
    /// The live object of that kind the handle names, or nullptr.
    void* find(const void* handle, Kind kind) {
        const uintptr_t h = reinterpret_cast<uintptr_t>(handle);
        if (Kind((h >> kIndexBits) & 3) != kind) return nullptr;
        const uintptr_t index = h & kIndexMask;
        const uintptr_t generation = (h >> kHalf) & kGenerationMask;
        std::lock_guard<std::mutex> lock(mutex_);
        if (index >= slots_.size()) return nullptr;
        const Slot& s = slots_[index];
        return s.object && s.kind == kind && s.generation == generation ? s.object : nullptr;
    }
    /// Frees the slot of a live object: its handle is refused from now on.
    void remove(const void* object) {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = by_object_.find(object);
        if (it == by_object_.end()) return;
        const uintptr_t index = it->second & kIndexMask;
        by_object_.erase(it);
        Slot& s = slots_[index];
        s.object = nullptr;
        s.generation = (s.generation + 1) & kGenerationMask;
        if (s.generation != 0) free_.push_back(uint32_t(index));  // 0: wrapped, slot retired
    }

private:
    struct Slot {
        void* object = nullptr;
        Kind kind = Kind::World;
        uintptr_t generation = 1;
    };
    static uintptr_t encode(uint32_t index, Kind kind, uintptr_t generation) {
        return (generation << kHalf) | (uintptr_t(kind) << kIndexBits) | index;
    }
    std::mutex mutex_;
    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
    std::unordered_map<const void*, uintptr_t> by_object_;  // live object -> its handle
};

HandleTable& handles() {
    static HandleTable table;  // constructed on first use, never destroyed before the last call
    return table;
}

// Limits on sizes: far above any game cloth, low enough that sizes cannot overflow.
constexpr uint32_t kMaxVertices = 1u << 22;
constexpr float kMaxCoordinate = 1e6f;  // m

#define DRAPE_REQUIRE(cond, status, msg) \
    do {                                 \
        if (!(cond)) return fail(status, msg); \
    } while (0)

// ---- struct_size: every size a struct has shipped (core/abi_tables.h, from tools/abi/abi.py) ----

template <class T>
bool shipped_size(uint32_t size) {
    for (uint32_t s : abi::Layout<T>::sizes)
        if (s == size) return true;
    return false;
}

template <class T>
std::string struct_size_problem(const char* what, uint32_t size) {
    std::string sizes;
    for (uint32_t s : abi::Layout<T>::sizes) sizes += (sizes.empty() ? "" : " or ") + std::to_string(s);
    return std::string(what) + "->struct_size is " + std::to_string(size) + ", " + abi::Layout<T>::name +
           " has shipped with size " + sizes + " (set it to sizeof(" + abi::Layout<T>::name + "))";
}

// A caller's struct of any shipped revision, as the current one: its fields over the defaults.
template <class T>
drape_status read_struct(const T* in, const char* what, T* out) {
    DRAPE_REQUIRE(in != nullptr, DRAPE_ERROR_NULL_POINTER, std::string(what) + " is NULL");
    DRAPE_REQUIRE(shipped_size<T>(in->struct_size), DRAPE_ERROR_STRUCT_SIZE, struct_size_problem<T>(what, in->struct_size));
    *out = abi::Layout<T>::defaults();
    std::memcpy(static_cast<void*>(out), in, in->struct_size);
    out->struct_size = sizeof(T);
    return DRAPE_OK;
}

// Validates *ptr's struct_size and points ptr at a current-revision copy (older revisions get
// the defaults for the fields they lack). Use once per struct parameter, before reading it.
#define DRAPE_CHECK_STRUCT(ptr, type)                                                   \
    type ptr##_current_;                                                                \
    if (drape_status ptr##_status_ = read_struct<type>(ptr, #ptr, &ptr##_current_)) \
        return ptr##_status_;                                                           \
    ptr = &ptr##_current_

// An array of structs of one shipped revision (stride = the first element's struct_size), as
// current-revision copies.
template <class T>
drape_status read_array(const T* in, uint32_t count, const char* what, std::vector<T>* out) {
    out->clear();
    if (count == 0) return DRAPE_OK;
    const uint32_t size = in->struct_size;
    DRAPE_REQUIRE(shipped_size<T>(size), DRAPE_ERROR_STRUCT_SIZE,
                  struct_size_problem<T>((std::string(what) + "[0]").c_str(), size));
    out->resize(count);
    const char* bytes = reinterpret_cast<const char*>(in);
    for (uint32_t k = 0; k < count; ++k) {
        const T* e = reinterpret_cast<const T*>(bytes + size_t(k) * size);
        DRAPE_REQUIRE(e->struct_size == size, DRAPE_ERROR_STRUCT_SIZE,
                      std::string(what) + "[" + std::to_string(k) + "]->struct_size is " + std::to_string(e->struct_size) +
                          ", element 0's is " + std::to_string(size) + " (one array, one struct size)");
        (*out)[k] = abi::Layout<T>::defaults();
        std::memcpy(static_cast<void*>(&(*out)[k]), e, size);
        (*out)[k].struct_size = sizeof(T);
    }
    return DRAPE_OK;
}

// Out-structs that ABI 1 callers were not asked to prepare (get_info, get_params,
// params_default): a size never shipped (0, garbage) reads as the first revision's.
template <class T>
uint32_t lenient_out_size(const T* out) {
    return shipped_size<T>(out->struct_size) ? out->struct_size : abi::Layout<T>::sizes[0];
}

// Writes the first `size` bytes of `full` (a shipped size) to out, struct_size = size.
template <class T>
void write_out(T full, T* out, uint32_t size) {
    full.struct_size = size;
    std::memcpy(static_cast<void*>(out), &full, size);
}

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

World* as_world(const drape_world* w) { return static_cast<World*>(handles().find(w, Kind::World)); }
Cloth* as_cloth(const drape_cloth* c) { return static_cast<Cloth*>(handles().find(c, Kind::Cloth)); }

drape_status check_world(const drape_world* w) {
    DRAPE_REQUIRE(w != nullptr, DRAPE_ERROR_NULL_POINTER, "world is NULL");
    DRAPE_REQUIRE(as_world(w) != nullptr, DRAPE_ERROR_INVALID_HANDLE,
                  "world is not a live drape_world (destroyed, or not a world handle)");
    return DRAPE_OK;
}

drape_status check_cloth(const drape_cloth* c) {
    DRAPE_REQUIRE(c != nullptr, DRAPE_ERROR_NULL_POINTER, "cloth is NULL");
    DRAPE_REQUIRE(as_cloth(c) != nullptr, DRAPE_ERROR_INVALID_HANDLE,
                  "cloth is not a live drape_cloth (destroyed, its world destroyed, or not a cloth handle)");
    return DRAPE_OK;
}

// desc: already through DRAPE_CHECK_STRUCT. need_available: creation needs the backend here.
drape_status check_cloth_desc(const drape_cloth_desc* desc, bool need_available = true) {
    std::string problem;  // backend enum, total_mass finite and in (0, 1e6] kg (tools/abi/abi.py)
    if (drape_status s = abi::Layout<drape_cloth_desc>::check(*desc, &problem)) return fail(s, problem);
    if (!need_available) return DRAPE_OK;
    return status_of(backend_available(drape_backend(desc->backend)));
}

// Setters go through Cloth::edit: a backend whose state lives elsewhere (GLES: on the GPU) reads
// it back first where the setter needs it, or queues the setter (Unity's main thread).
using Access = Cloth::Access;
drape_status apply_edit(Cloth* c, Access access, std::function<void(Cloth&)> fn) {
    return status_of(c->edit(access, std::move(fn)));
}

// OK, or the backend's refusal of a feature it lacks.
drape_status check_supports(const Cloth* c, Feature feature) { return status_of(c->supports(feature)); }

// layout: already through DRAPE_CHECK_STRUCT.
drape_status check_layout(const drape_vertex_layout* layout) {
    DRAPE_REQUIRE(layout->stride >= 12 && layout->stride % 4 == 0 && layout->stride <= 1024,
                  DRAPE_ERROR_INVALID_ARGUMENT, "stride must be a multiple of 4 in [12, 1024]");
    DRAPE_REQUIRE(finite3(layout->origin), DRAPE_ERROR_NOT_FINITE, "layout->origin is NaN or infinite");
    DRAPE_REQUIRE(bounded3(layout->origin), DRAPE_ERROR_INVALID_ARGUMENT, "layout->origin is beyond 1e6 m");
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
    return DRAPE_OK;
}

// Keys of cooked descriptions (World::describe): the exact bytes a cloth is cooked from.
template <class T>
void append_bytes(std::string& key, const T* data, size_t count) {
    key.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

std::string grid_key(const drape_grid_desc& grid, float total_mass) {
    static_assert(sizeof(drape_grid_desc) == 14 * 4, "drape_grid_desc: 4-byte fields, no padding bytes");
    std::string key = "grid";
    append_bytes(key, &grid, 1);
    append_bytes(key, &total_mass, 1);
    return key;
}

std::string mesh_key(const drape_mesh_desc& mesh, float total_mass) {
    std::string key = "mesh";
    append_bytes(key, &mesh.vertex_count, 1);
    append_bytes(key, &mesh.index_count, 1);
    append_bytes(key, &mesh.weld_distance, 1);
    append_bytes(key, &total_mass, 1);
    append_bytes(key, mesh.positions, size_t(mesh.vertex_count) * 3);
    append_bytes(key, mesh.indices, mesh.index_count);
    return key;
}

// key and cook: the cloth's description (World::describe). origin: where its coordinates start
// in the caller's space (Cloth::origin).
drape_status finish_create(drape_world* world, const drape_cloth_desc* desc, const std::string& key,
                           const std::function<CookResult(Topology&)>& cook, drape_cloth** out,
                           const glm::dvec3& origin) {
    World& w = *as_world(world);
    CookResult cooked;
    std::shared_ptr<const Description> description = w.describe(key, cook, &cooked);
    if (!description) return fail(cooked.status, cooked.message);
    std::unique_ptr<Cloth> owned;
    if (Result r = create_cloth(w, drape_backend(desc->backend), std::move(description), &owned); !r.ok())
        return fail(r.status, r.message);
    Cloth* cloth = owned.get();
    cloth->set_origin(origin);
    w.add(cloth);
    uintptr_t handle = 0;
    try {
        handle = handles().add(cloth, Kind::Cloth);
    } catch (...) {
        w.remove(cloth);
        throw;
    }
    owned.release();
    *out = reinterpret_cast<drape_cloth*>(handle);
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

// grid, mesh: already through DRAPE_CHECK_STRUCT.
drape_status check_grid(const drape_grid_desc* grid) {
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
    return DRAPE_OK;
}

drape_status check_mesh(const drape_mesh_desc* mesh) {
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
    return DRAPE_OK;
}

// ---- caller space <-> a cloth's local coordinates (Cloth::origin), in double -----------------

void to_local(const Cloth& c, const float* in, float* out) {
    const glm::dvec3& o = c.origin();
    for (int k = 0; k < 3; ++k) out[k] = float(double(in[k]) - o[k]);
}

// Origin of a new cloth whose first vertex is at p: 0 near the caller's origin, else p in whole
// metres.
glm::dvec3 initial_origin(const float* p) {
    if (std::fabs(p[0]) <= kRecentreDistance && std::fabs(p[1]) <= kRecentreDistance &&
        std::fabs(p[2]) <= kRecentreDistance)
        return glm::dvec3(0.0);
    return glm::round(glm::dvec3(p[0], p[1], p[2]));
}

void xyz_to_local(const Cloth& c, std::vector<float>& xyz) {
    for (size_t v = 0; v + 2 < xyz.size(); v += 3) to_local(c, &xyz[v], &xyz[v]);
}

}  // namespace

drape_status drape::set_last_error(drape_status status, const char* message) {
    t_last_error = status == DRAPE_OK ? std::string() : std::string(message ? message : "");
    return status;
}

extern "C" {

uint32_t drape_abi_version(void) { return DRAPE_ABI_VERSION; }

const char* drape_last_error(void) { return t_last_error.c_str(); }

drape_status drape_backend_available(uint32_t backend, uint32_t* out_available) {
    DRAPE_REQUIRE(out_available != nullptr, DRAPE_ERROR_NULL_POINTER, "out_available is NULL");
    DRAPE_REQUIRE(backend <= DRAPE_BACKEND_GLES, DRAPE_ERROR_INVALID_ENUM,
                  "backend " + std::to_string(backend) + " is not a drape_backend");
    *out_available = backend_available(drape_backend(backend)).ok() ? 1 : 0;
    return ok();
}

drape_status drape_params_default(drape_params* out_params) {
    DRAPE_REQUIRE(out_params != nullptr, DRAPE_ERROR_NULL_POINTER, "out_params is NULL");
    write_out(default_params(), out_params, lenient_out_size(out_params));
    return ok();
}

drape_status drape_world_create(const drape_world_desc* desc, drape_world** out_world) {
    DRAPE_CHECK_STRUCT(desc, drape_world_desc);
    DRAPE_REQUIRE(out_world != nullptr, DRAPE_ERROR_NULL_POINTER, "out_world is NULL");
    std::string problem;  // thread_count in [0, 256] (tools/abi/abi.py)
    if (drape_status s = abi::Layout<drape_world_desc>::check(*desc, &problem)) return fail(s, problem);
    return guarded([&] {
        uint32_t threads = desc->thread_count;
        if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
        auto world = std::make_unique<World>(threads, desc->profile_stages != 0);
        *out_world = reinterpret_cast<drape_world*>(handles().add(world.get(), Kind::World));
        world.release();
        return ok();
    });
}

drape_status drape_world_destroy(drape_world* world) {
    if (drape_status s = check_world(world)) return s;
    return guarded([&] {
        World* w = as_world(world);
        for (Cloth* c : w->cloths()) handles().remove(c);
        handles().remove(w);
        delete w;
        return ok();
    });
}

drape_status drape_world_step(drape_world* world, float dt) {
    if (drape_status s = check_world(world)) return s;
    DRAPE_REQUIRE(std::isfinite(dt), DRAPE_ERROR_NOT_FINITE, "dt is NaN or infinite");
    DRAPE_REQUIRE(dt > 0 && dt <= DRAPE_MAX_DT, DRAPE_ERROR_INVALID_ARGUMENT, "dt must be in (0, 1] s");
    if (dt < DRAPE_MIN_DT) return ok();  // too short to represent: a no-op (drape.h)
    return guarded([&] { return status_of(as_world(world)->step(dt)); });
}

drape_status drape_cloth_create_grid(drape_world* world, const drape_cloth_desc* desc, const drape_grid_desc* grid,
                                     drape_cloth** out_cloth) {
    if (drape_status s = check_world(world)) return s;
    DRAPE_CHECK_STRUCT(desc, drape_cloth_desc);
    if (drape_status s = check_cloth_desc(desc)) return s;
    DRAPE_CHECK_STRUCT(grid, drape_grid_desc);
    DRAPE_REQUIRE(out_cloth != nullptr, DRAPE_ERROR_NULL_POINTER, "out_cloth is NULL");
    if (drape_status s = check_grid(grid)) return s;
    return guarded([&] {
        // Cooked and simulated around the cloth's own origin (float-safe anywhere).
        const glm::dvec3 origin = initial_origin(grid->origin);
        drape_grid_desc local = *grid;
        for (int k = 0; k < 3; ++k) local.origin[k] = float(double(grid->origin[k]) - origin[k]);
        const float mass = desc->total_mass;
        auto cook = [&](Topology& t) {
            t = cook_grid(local, mass);
            return CookResult{};
        };
        return finish_create(world, desc, grid_key(local, mass), cook, out_cloth, origin);
    });
}

drape_status drape_cloth_create_mesh(drape_world* world, const drape_cloth_desc* desc, const drape_mesh_desc* mesh,
                                     drape_cloth** out_cloth) {
    if (drape_status s = check_world(world)) return s;
    DRAPE_CHECK_STRUCT(desc, drape_cloth_desc);
    if (drape_status s = check_cloth_desc(desc)) return s;
    DRAPE_CHECK_STRUCT(mesh, drape_mesh_desc);
    DRAPE_REQUIRE(out_cloth != nullptr, DRAPE_ERROR_NULL_POINTER, "out_cloth is NULL");
    if (drape_status s = check_mesh(mesh)) return s;
    return guarded([&] {
        const glm::dvec3 origin = initial_origin(mesh->positions);  // see create_grid
        drape_mesh_desc local = *mesh;
        std::vector<float> shifted;
        if (origin != glm::dvec3(0.0)) {
            shifted.resize(size_t(mesh->vertex_count) * 3);
            for (size_t k = 0; k < shifted.size(); ++k) shifted[k] = float(double(mesh->positions[k]) - origin[k % 3]);
            local.positions = shifted.data();
        }
        const float mass = desc->total_mass;
        auto cook = [&](Topology& t) { return cook_mesh(local, mass, t); };
        return finish_create(world, desc, mesh_key(local, mass), cook, out_cloth, origin);
    });
}

drape_status drape_cloth_destroy(drape_cloth* cloth) {
    if (drape_status s = check_cloth(cloth)) return s;
    return guarded([&] {
        Cloth* c = as_cloth(cloth);
        c->world().remove(c);
        handles().remove(c);
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
    if (params->model == DRAPE_MODEL_IMPLICIT)
        if (drape_status s = check_supports(as_cloth(cloth), Feature::ImplicitModel)) return s;
    if (params->model == DRAPE_MODEL_XPBD)
        if (drape_status s = check_supports(as_cloth(cloth), Feature::XpbdModel)) return s;
    const drape_params p = *params;
    return guarded([&] { return apply_edit(as_cloth(cloth), Access::NoState, [p](Cloth& c) { c.set_params(p); }); });
}

drape_status drape_cloth_get_params(const drape_cloth* cloth, drape_params* out_params) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_params != nullptr, DRAPE_ERROR_NULL_POINTER, "out_params is NULL");
    write_out(as_cloth(cloth)->params(), out_params, lenient_out_size(out_params));
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
        std::vector<float> w(inverse_masses, inverse_masses + count);
        return apply_edit(as_cloth(cloth), Access::ReadsState, [w](Cloth& c) { c.set_inverse_masses(w.data()); });
    });
}

drape_status drape_cloth_set_pins(drape_cloth* cloth, const drape_pin* pins, uint32_t count) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(pins != nullptr || count == 0, DRAPE_ERROR_NULL_POINTER, "pins is NULL");
    const uint32_t n = as_cloth(cloth)->topology().vertex_count;
    std::vector<drape_pin> current;
    if (drape_status s = guarded([&] { return read_array(pins, count, "pins", &current); })) return s;
    pins = current.data();
    for (uint32_t k = 0; k < count; ++k) {
        DRAPE_REQUIRE(pins[k].vertex < n, DRAPE_ERROR_INDEX_OUT_OF_RANGE,
                      "pin " + std::to_string(k) + " vertex " + std::to_string(pins[k].vertex) + " >= vertex count " +
                          std::to_string(n));
        DRAPE_REQUIRE(finite3(pins[k].position), DRAPE_ERROR_NOT_FINITE,
                      "pin " + std::to_string(k) + " position is NaN or infinite");
        DRAPE_REQUIRE(bounded3(pins[k].position), DRAPE_ERROR_INVALID_ARGUMENT,
                      "pin " + std::to_string(k) + " position is beyond 1e6 m");
    }
    return guarded([&] {
        // Moving pins that are already pinned only changes targets (no GPU readback on GLES).
        const Cloth* c = as_cloth(cloth);
        bool all_pinned = true;
        for (uint32_t k = 0; k < count && all_pinned; ++k) {
            const drape_pin& pin = pins[k];
            all_pinned = c->is_pinned(pin.vertex);
        }
        // Positions become local when the edit is applied: a GLES cloth may re-centre before then.
        return apply_edit(as_cloth(cloth), all_pinned ? Access::NoState : Access::ReadsState,
                          [copy = std::move(current)](Cloth& c) mutable {
                              for (drape_pin& pin : copy) to_local(c, pin.position, pin.position);
                              c.set_pins(copy.data(), uint32_t(copy.size()));
                          });
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
        std::vector<uint32_t> copy(vertices, vertices + count);
        return apply_edit(as_cloth(cloth), Access::ReadsState,
                          [copy](Cloth& c) { c.release_pins(copy.data(), uint32_t(copy.size())); });
    });
}

drape_status drape_cloth_set_positions(drape_cloth* cloth, const float* positions, uint32_t count) {
    if (drape_status s = check_vertex_array(cloth, positions, count, "positions")) return s;
    if (drape_status s = check_xyz_array(positions, count, "position")) return s;
    return guarded([&] {
        std::vector<float> copy(positions, positions + size_t(count) * 3);
        return apply_edit(as_cloth(cloth), Access::WritesState, [copy](Cloth& c) mutable {
            xyz_to_local(c, copy);  // when applied (see set_pins)
            c.set_positions(copy.data());
        });
    });
}

drape_status drape_cloth_set_velocities(drape_cloth* cloth, const float* velocities, uint32_t count) {
    if (drape_status s = check_vertex_array(cloth, velocities, count, "velocities")) return s;
    if (drape_status s = check_xyz_array(velocities, count, "velocity")) return s;
    return guarded([&] {
        std::vector<float> copy(velocities, velocities + size_t(count) * 3);
        return apply_edit(as_cloth(cloth), Access::ReadsState, [copy](Cloth& c) { c.set_velocities(copy.data()); });
    });
}

drape_status drape_cloth_step(drape_cloth* cloth, float dt) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(std::isfinite(dt), DRAPE_ERROR_NOT_FINITE, "dt is NaN or infinite");
    DRAPE_REQUIRE(dt > 0 && dt <= DRAPE_MAX_DT, DRAPE_ERROR_INVALID_ARGUMENT, "dt must be in (0, 1] s");
    if (dt < DRAPE_MIN_DT) return ok();  // too short to represent: a no-op (drape.h)
    return guarded([&] { return status_of(as_cloth(cloth)->step(dt)); });
}

drape_status drape_cloth_read(const drape_cloth* cloth, const drape_vertex_layout* layout, void* dst,
                              size_t dst_size) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_CHECK_STRUCT(layout, drape_vertex_layout);
    if (drape_status s = check_layout(layout)) return s;
    DRAPE_REQUIRE(dst != nullptr, DRAPE_ERROR_NULL_POINTER, "dst is NULL");
    const uint64_t needed = uint64_t(as_cloth(cloth)->topology().vertex_count) * layout->stride;
    DRAPE_REQUIRE(dst_size >= needed, DRAPE_ERROR_BUFFER_TOO_SMALL,
                  "dst_size is " + std::to_string(dst_size) + " bytes, the layout needs " + std::to_string(needed));
    return guarded([&] {
        return status_of(as_cloth(cloth)->read(*layout, dst));
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
    info.description_id = c->description().id;
    info.description_users = c->description_users();
    write_out(info, out_info, lenient_out_size(out_info));
    return ok();
}

drape_status drape_cloth_get_stats(const drape_cloth* cloth, drape_stats* out_stats) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_stats != nullptr, DRAPE_ERROR_NULL_POINTER, "out_stats is NULL");
    const uint32_t size = out_stats->struct_size;  // any shipped revision: that prefix is written
    DRAPE_REQUIRE(shipped_size<drape_stats>(size), DRAPE_ERROR_STRUCT_SIZE, struct_size_problem<drape_stats>("out_stats", size));
    return guarded([&] {
        drape_stats full{};
        full.struct_size = sizeof full;
        Result r = as_cloth(cloth)->stats(&full);
        if (r.ok()) write_out(full, out_stats, size);
        return status_of(r);
    });
}

drape_status drape_estimate_stability(const drape_cloth_desc* desc, const drape_grid_desc* grid,
                                      const drape_mesh_desc* mesh, const drape_params* params, float dt,
                                      drape_stability* out_estimate) {
    DRAPE_CHECK_STRUCT(desc, drape_cloth_desc);
    if (drape_status s = check_cloth_desc(desc, /*need_available=*/false)) return s;
    DRAPE_REQUIRE((grid != nullptr) != (mesh != nullptr), grid ? DRAPE_ERROR_INVALID_ARGUMENT : DRAPE_ERROR_NULL_POINTER,
                  "give exactly one of grid and mesh (the other NULL)");
    // The current-revision copies live for the whole call (grid/mesh point at them below).
    drape_grid_desc grid_copy;
    drape_mesh_desc mesh_copy;
    if (grid) {
        if (drape_status s = read_struct<drape_grid_desc>(grid, "grid", &grid_copy)) return s;
        grid = &grid_copy;
        if (drape_status s = check_grid(grid)) return s;
    } else {
        if (drape_status s = read_struct<drape_mesh_desc>(mesh, "mesh", &mesh_copy)) return s;
        mesh = &mesh_copy;
        if (drape_status s = check_mesh(mesh)) return s;
    }
    DRAPE_CHECK_STRUCT(params, drape_params);
    drape_status status;
    std::string problem = validate_params(*params, &status);
    if (status != DRAPE_OK) return fail(status, problem);
    DRAPE_REQUIRE(std::isfinite(dt), DRAPE_ERROR_NOT_FINITE, "dt is NaN or infinite");
    DRAPE_REQUIRE(dt > 0 && dt <= DRAPE_MAX_DT, DRAPE_ERROR_INVALID_ARGUMENT, "dt must be in (0, 1] s");
    DRAPE_REQUIRE(out_estimate != nullptr, DRAPE_ERROR_NULL_POINTER, "out_estimate is NULL");
    const uint32_t size = out_estimate->struct_size;
    DRAPE_REQUIRE(shipped_size<drape_stability>(size), DRAPE_ERROR_STRUCT_SIZE,
                  struct_size_problem<drape_stability>("out_estimate", size));
    return guarded([&] {
        Topology topo;
        if (grid) {
            topo = cook_grid(*grid, desc->total_mass);
        } else {
            CookResult r = cook_mesh(*mesh, desc->total_mass, topo);
            if (r.status != DRAPE_OK) return fail(r.status, r.message);
        }
        const StabilityEstimate e = estimate_stability(topo, resolve_model(*params), drape_backend(desc->backend), dt);
        drape_stability out = abi::Layout<drape_stability>::defaults();
        out.substeps = e.substeps;
        out.stable_substeps = e.stable_substeps;
        out.max_stable_substep = e.max_stable_substep;
        out.stable = e.substeps >= e.stable_substeps ? 1 : 0;
        write_out(out, out_estimate, size);
        return ok();
    });
}

drape_status drape_cloth_set_output_buffer(drape_cloth* cloth, uint32_t gl_buffer, const drape_vertex_layout* layout) {
    if (drape_status s = check_cloth(cloth)) return s;
    drape_vertex_layout layout_current_{};
    if (gl_buffer != 0) {
        if (drape_status s = read_struct(layout, "layout", &layout_current_)) return s;
        layout = &layout_current_;
        if (drape_status s = check_layout(layout)) return s;
        DRAPE_REQUIRE(layout->origin[0] == 0 && layout->origin[1] == 0 && layout->origin[2] == 0,
                      DRAPE_ERROR_INVALID_ARGUMENT,
                      "layout->origin must be 0 for a GL output buffer (the GPU writes the caller's space)");
    }
    const drape_vertex_layout l = layout ? *layout : drape_vertex_layout{sizeof(drape_vertex_layout), 12, 0, -1, {0, 0, 0}};
    return guarded([&] { return status_of(as_cloth(cloth)->set_output(gl_buffer, l)); });
}

drape_status drape_cloth_readback(drape_cloth* cloth) {
    if (drape_status s = check_cloth(cloth)) return s;
    return guarded([&] { return status_of(as_cloth(cloth)->readback()); });
}

drape_status drape_gles_context_lost(void) {
    return guarded([&] {
        gl_context_lost();
        return ok();
    });
}

}  // extern "C"

// ---- colliders, sleeping, touch drag, grabs, owner transform ---------------------------------
// Validation here; the state lives in core/interaction.{h,cpp}.
namespace {

constexpr float kQuatTolerance = 1e-3f;  // | |q| - 1 | allowed before renormalising
constexpr float kMaxMargin = 10.0f;       // m
constexpr float kMaxFriction = 10.0f;
constexpr float kMaxPickRadius = 1e4f;    // px

bool finite_n(const float* v, int n) {
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(v[k])) return false;
    return true;
}

drape_status check_unit_quat(const float* q, const std::string& what) {
    DRAPE_REQUIRE(finite_n(q, 4), DRAPE_ERROR_NOT_FINITE, what + " rotation is NaN or infinite");
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    DRAPE_REQUIRE(std::fabs(len - 1.0f) <= kQuatTolerance, DRAPE_ERROR_INVALID_ARGUMENT,
                  what + " rotation is not a unit quaternion (|q| = " + std::to_string(len) + ")");
    return DRAPE_OK;
}

drape_status check_cloth_supports(const drape_cloth* cloth, Feature feature) {
    if (drape_status s = check_cloth(cloth)) return s;
    return check_supports(as_cloth(cloth), feature);
}

drape_status check_collider(const drape_collider& c, uint32_t k) {
    const std::string what = "collider " + std::to_string(k);
    DRAPE_REQUIRE(c.shape <= DRAPE_COLLIDER_PLANE, DRAPE_ERROR_INVALID_ENUM,
                  what + " shape " + std::to_string(c.shape) + " is not a drape_collider_shape");
    DRAPE_REQUIRE(finite3(c.position), DRAPE_ERROR_NOT_FINITE, what + " position is NaN or infinite");
    DRAPE_REQUIRE(bounded3(c.position), DRAPE_ERROR_INVALID_ARGUMENT, what + " position is beyond 1e6 m");
    if (drape_status s = check_unit_quat(c.rotation, what)) return s;
    DRAPE_REQUIRE(finite3(c.size) && std::isfinite(c.margin) && std::isfinite(c.friction), DRAPE_ERROR_NOT_FINITE,
                  what + " size, margin or friction is NaN or infinite");
    const int used = c.shape == DRAPE_COLLIDER_SPHERE ? 1 : c.shape == DRAPE_COLLIDER_CAPSULE ? 2
                   : c.shape == DRAPE_COLLIDER_BOX    ? 3 : 0;
    for (int a = 0; a < used; ++a) {
        const bool may_be_zero = c.shape == DRAPE_COLLIDER_CAPSULE && a == 1;  // capsule half length
        DRAPE_REQUIRE((may_be_zero ? c.size[a] >= 0 : c.size[a] > 0) && c.size[a] <= kMaxCoordinate,
                      DRAPE_ERROR_INVALID_ARGUMENT,
                      what + " size[" + std::to_string(a) + "] = " + std::to_string(c.size[a]) +
                          (may_be_zero ? " must be in [0, 1e6] m" : " must be in (0, 1e6] m"));
    }
    DRAPE_REQUIRE(c.margin >= 0 && c.margin <= kMaxMargin, DRAPE_ERROR_INVALID_ARGUMENT,
                  what + " margin must be in [0, 10] m");
    DRAPE_REQUIRE(c.friction >= 0 && c.friction <= kMaxFriction, DRAPE_ERROR_INVALID_ARGUMENT,
                  what + " friction must be in [0, 10]");
    return DRAPE_OK;
}

// v: already through DRAPE_CHECK_STRUCT.
drape_status check_view(const drape_view* v) {
    DRAPE_REQUIRE(finite_n(v->world, 16) && finite_n(v->view, 16) && finite_n(v->projection, 16) &&
                      finite_n(v->viewport, 2),
                  DRAPE_ERROR_NOT_FINITE, "view matrices or viewport contain NaN or infinity");
    DRAPE_REQUIRE(v->viewport[0] >= 1 && v->viewport[1] >= 1 && v->viewport[0] <= 1e5f && v->viewport[1] <= 1e5f,
                  DRAPE_ERROR_INVALID_ARGUMENT, "viewport must be in [1, 1e5] px");
    const ScreenMapping m = make_screen_mapping(*v);
    const double det = glm::determinant(m.mvp);
    DRAPE_REQUIRE(std::isfinite(det) && std::fabs(det) > 1e-30, DRAPE_ERROR_INVALID_ARGUMENT,
                  "projection * view * world is singular (cannot unproject)");
    return DRAPE_OK;
}

drape_status check_screen_point(const float* p, const char* what) {
    DRAPE_REQUIRE(p != nullptr, DRAPE_ERROR_NULL_POINTER, std::string(what) + " is NULL");
    DRAPE_REQUIRE(finite_n(p, 2), DRAPE_ERROR_NOT_FINITE, std::string(what) + " is NaN or infinite");
    DRAPE_REQUIRE(std::fabs(p[0]) <= 1e6f && std::fabs(p[1]) <= 1e6f, DRAPE_ERROR_INVALID_ARGUMENT,
                  std::string(what) + " is beyond 1e6 px");
    return DRAPE_OK;
}

}  // namespace

extern "C" {

drape_status drape_cloth_set_colliders(drape_cloth* cloth, const drape_collider* colliders, uint32_t count) {
    if (drape_status s = check_cloth(cloth)) return s;  // GLES too (collision pass on the GPU)
    DRAPE_REQUIRE(colliders != nullptr || count == 0, DRAPE_ERROR_NULL_POINTER, "colliders is NULL");
    DRAPE_REQUIRE(count <= DRAPE_MAX_COLLIDERS, DRAPE_ERROR_INVALID_ARGUMENT,
                  std::to_string(count) + " colliders, at most " + std::to_string(DRAPE_MAX_COLLIDERS) + " per cloth");
    std::vector<drape_collider> current;
    if (drape_status s = guarded([&] { return read_array(colliders, count, "colliders", &current); })) return s;
    colliders = current.data();
    for (uint32_t k = 0; k < count; ++k) {
        if (drape_status s = check_collider(colliders[k], k)) return s;
        for (uint32_t j = 0; j < k; ++j)
            DRAPE_REQUIRE(colliders[j].id != colliders[k].id, DRAPE_ERROR_INVALID_ARGUMENT,
                          "colliders " + std::to_string(j) + " and " + std::to_string(k) + " share id " +
                              std::to_string(colliders[k].id));
    }
    return guarded([&] {
        // Copied: a GLES cloth on Unity's main thread applies it on the render thread.
        return apply_edit(as_cloth(cloth), Access::NoState, [copy = std::move(current)](Cloth& c) mutable {
            for (drape_collider& col : copy) to_local(c, col.position, col.position);  // when applied (see set_pins)
            c.set_colliders(copy.data(), uint32_t(copy.size()));
        });
    });
}

drape_status drape_cloth_set_sleep(drape_cloth* cloth, const drape_sleep_desc* desc) {
    if (drape_status s = check_cloth_supports(cloth, Feature::Sleep)) return s;
    DRAPE_CHECK_STRUCT(desc, drape_sleep_desc);
    std::string problem;
    if (drape_status s = abi::Layout<drape_sleep_desc>::check(*desc, &problem)) return fail(s, "sleep " + problem);
    return guarded([&] {
        as_cloth(cloth)->set_sleep(desc->threshold, desc->time);
        return ok();
    });
}

drape_status drape_cloth_wake(drape_cloth* cloth) {
    if (drape_status s = check_cloth(cloth)) return s;
    as_cloth(cloth)->wake();
    return ok();
}

drape_status drape_touch_default(drape_touch* out_touch) {
    DRAPE_REQUIRE(out_touch != nullptr, DRAPE_ERROR_NULL_POINTER, "out_touch is NULL");
    static_assert(kTouchAmplitude == 200.0f && kTouchSigma == 300.0f, "tools/abi/abi.py: drape_touch defaults");
    *out_touch = abi::Layout<drape_touch>::defaults();
    return ok();
}

drape_status drape_cloth_drag(drape_cloth* cloth, const drape_view* view, const drape_touch* touches, uint32_t count) {
    if (drape_status s = check_cloth(cloth)) return s;  // GLES too (evaluated on the GPU)
    DRAPE_CHECK_STRUCT(view, drape_view);
    if (drape_status s = check_view(view)) return s;
    DRAPE_REQUIRE(touches != nullptr || count == 0, DRAPE_ERROR_NULL_POINTER, "touches is NULL");
    DRAPE_REQUIRE(count <= kMaxTouches, DRAPE_ERROR_INVALID_ARGUMENT,
                  std::to_string(count) + " touches, at most " + std::to_string(kMaxTouches));
    std::vector<drape_touch> current;
    if (drape_status s = guarded([&] { return read_array(touches, count, "touches", &current); })) return s;
    for (uint32_t k = 0; k < count; ++k) {
        std::string problem;
        if (drape_status s = abi::Layout<drape_touch>::check(current[k], &problem))
            return fail(s, "touch " + std::to_string(k) + " " + problem);
    }
    return guarded([&] { return status_of(as_cloth(cloth)->drag(*view, std::move(current))); });
}

drape_status drape_cloth_grab(drape_cloth* cloth, const drape_view* view, uint32_t touch_id, const float position[2],
                              float pick_radius, uint32_t* out_vertex) {
    if (drape_status s = check_cloth_supports(cloth, Feature::Grab)) return s;
    DRAPE_CHECK_STRUCT(view, drape_view);
    if (drape_status s = check_view(view)) return s;
    if (drape_status s = check_screen_point(position, "position")) return s;
    DRAPE_REQUIRE(out_vertex != nullptr, DRAPE_ERROR_NULL_POINTER, "out_vertex is NULL");
    DRAPE_REQUIRE(std::isfinite(pick_radius), DRAPE_ERROR_NOT_FINITE, "pick_radius is NaN or infinite");
    DRAPE_REQUIRE(pick_radius > 0 && pick_radius <= kMaxPickRadius, DRAPE_ERROR_INVALID_ARGUMENT,
                  "pick_radius must be in (0, 1e4] px");
    Cloth* c = as_cloth(cloth);
    return guarded([&] {
        // At most kMaxGrabs at once (a grab with a live id replaces it, so does not count).
        if (c->grab_count() >= kMaxGrabs && !c->grabbing(touch_id))
            return fail(DRAPE_ERROR_INVALID_ARGUMENT, "already " + std::to_string(kMaxGrabs) + " grabs held");
        *out_vertex = c->grab(*view, touch_id, position, pick_radius);
        return ok();
    });
}

drape_status drape_cloth_grab_move(drape_cloth* cloth, const drape_view* view, uint32_t touch_id,
                                   const float position[2]) {
    if (drape_status s = check_cloth_supports(cloth, Feature::Grab)) return s;
    DRAPE_CHECK_STRUCT(view, drape_view);
    if (drape_status s = check_view(view)) return s;
    if (drape_status s = check_screen_point(position, "position")) return s;
    DRAPE_REQUIRE(as_cloth(cloth)->grabbing(touch_id), DRAPE_ERROR_INVALID_ARGUMENT,
                  "touch_id " + std::to_string(touch_id) + " holds no grabbed vertex");
    return guarded([&] {
        if (!as_cloth(cloth)->grab_move(*view, touch_id, position))
            return fail(DRAPE_ERROR_INVALID_ARGUMENT, "position does not unproject to a finite point");
        return ok();
    });
}

drape_status drape_cloth_grab_release(drape_cloth* cloth, uint32_t touch_id) {
    if (drape_status s = check_cloth_supports(cloth, Feature::Grab)) return s;
    return guarded([&] {
        as_cloth(cloth)->grab_release(touch_id);
        return ok();
    });
}

drape_status drape_owner_default(drape_owner* out_owner) {
    DRAPE_REQUIRE(out_owner != nullptr, DRAPE_ERROR_NULL_POINTER, "out_owner is NULL");
    *out_owner = abi::Layout<drape_owner>::defaults();
    return ok();
}

drape_status drape_cloth_set_owner(drape_cloth* cloth, const drape_owner* owner) {
    if (drape_status s = check_cloth_supports(cloth, Feature::Owner)) return s;
    DRAPE_CHECK_STRUCT(owner, drape_owner);
    std::string problem;
    if (drape_status s = abi::Layout<drape_owner>::check(*owner, &problem)) return fail(s, "owner " + problem);
    if (drape_status s = check_unit_quat(owner->rotation, "owner")) return s;
    return guarded([&] {
        // Converted to the cloth's frame when applied (see set_pins); a GLES cloth moves its GPU
        // state in a pass.
        return apply_edit(as_cloth(cloth), Access::NoState, [o = *owner](Cloth& c) mutable {
            to_local(c, o.position, o.position);
            c.set_owner(o);
        });
    });
}

}  // extern "C"

// ---- self-collision ----------------------------------------------------------------------------
// Validation here; the state lives in core/self_collision.{h,cpp}.
extern "C" {

drape_status drape_cloth_set_self_collision(drape_cloth* cloth, const drape_self_collision_desc* desc) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_CHECK_STRUCT(desc, drape_self_collision_desc);
    DRAPE_REQUIRE(desc->enabled <= 1, DRAPE_ERROR_INVALID_ARGUMENT,
                  "self-collision enabled is " + std::to_string(desc->enabled) + ", must be 0 or 1");
    DRAPE_REQUIRE(std::isfinite(desc->thickness), DRAPE_ERROR_NOT_FINITE, "self-collision thickness is NaN or infinite");
    DRAPE_REQUIRE(std::isfinite(desc->friction), DRAPE_ERROR_NOT_FINITE, "self-collision friction is NaN or infinite");
    Cloth* c = as_cloth(cloth);
    const float max_thickness = kSelfMaxThicknessFraction * c->topology().extent;
    DRAPE_REQUIRE(desc->thickness >= 0 && desc->thickness <= max_thickness, DRAPE_ERROR_INVALID_ARGUMENT,
                  "self-collision thickness " + std::to_string(desc->thickness) + " m must be in [0, " +
                      std::to_string(max_thickness) + "] m (a quarter of the cloth's rest diagonal)");
    DRAPE_REQUIRE(!desc->enabled || desc->thickness > 0, DRAPE_ERROR_INVALID_ARGUMENT,
                  "self-collision thickness must be > 0 m when enabled");
    DRAPE_REQUIRE(desc->friction >= 0 && desc->friction <= kMaxFriction, DRAPE_ERROR_INVALID_ARGUMENT,
                  "self-collision friction must be in [0, 10]");
    if (desc->enabled)
        if (drape_status s = check_supports(c, Feature::SelfCollision)) return s;
    return guarded([&] {
        c->set_self_collision(desc->enabled != 0, desc->thickness, desc->friction);
        return ok();
    });
}

drape_status drape_cloth_get_self_collision(const drape_cloth* cloth, drape_self_collision_desc* out_desc) {
    if (drape_status s = check_cloth(cloth)) return s;
    DRAPE_REQUIRE(out_desc != nullptr, DRAPE_ERROR_NULL_POINTER, "out_desc is NULL");
    const uint32_t size = out_desc->struct_size;
    DRAPE_REQUIRE(shipped_size<drape_self_collision_desc>(size), DRAPE_ERROR_STRUCT_SIZE,
                  struct_size_problem<drape_self_collision_desc>("out_desc", size));
    const SelfCollision& sc = as_cloth(cloth)->self_collision();
    drape_self_collision_desc d = abi::Layout<drape_self_collision_desc>::defaults();
    d.enabled = sc.enabled ? 1 : 0;
    d.thickness = sc.thickness;
    d.friction = sc.friction;
    write_out(d, out_desc, size);
    return ok();
}

}  // extern "C"
