// Bad input of every class gets a specific status and message and leaves the object unchanged.
#include <cstring>
#include <limits>

#include "drape_test_util.h"

using namespace drape_test;

namespace {
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// The message of the last failure must be non-empty and mention `word`.
void expect_message(const char* word) {
    EXPECT_NE(std::strstr(drape_last_error(), word), nullptr) << "message: " << drape_last_error();
}
}  // namespace

TEST(Api, VersionAndBackends) {
    EXPECT_EQ(drape_abi_version(), uint32_t(DRAPE_ABI_VERSION));
    uint32_t available = 7;
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_CPU, &available));
    EXPECT_EQ(available, 1u);
    ASSERT_DRAPE_OK(drape_backend_available(DRAPE_BACKEND_CPU_THREADED, &available));
    EXPECT_EQ(available, 1u);
    EXPECT_EQ(drape_backend_available(99, &available), DRAPE_ERROR_INVALID_ENUM);
    EXPECT_EQ(drape_backend_available(DRAPE_BACKEND_CPU, nullptr), DRAPE_ERROR_NULL_POINTER);
}

TEST(Api, WorldCreationChecksItsInput) {
    drape_world* w = nullptr;
    EXPECT_EQ(drape_world_create(nullptr, &w), DRAPE_ERROR_NULL_POINTER);
    drape_world_desc d{sizeof d + 4, 1};  // a size never shipped
    EXPECT_EQ(drape_world_create(&d, &w), DRAPE_ERROR_STRUCT_SIZE);
    expect_message("struct_size");
    d.struct_size = sizeof d;
    EXPECT_EQ(drape_world_create(&d, nullptr), DRAPE_ERROR_NULL_POINTER);
    d.thread_count = 100000;
    EXPECT_EQ(drape_world_create(&d, &w), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(w, nullptr);
}

TEST(Api, StaleAndForeignHandlesAreRefused) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    ASSERT_DRAPE_OK(drape_cloth_destroy(c));
    EXPECT_EQ(drape_cloth_step(c, 0.01f), DRAPE_ERROR_INVALID_HANDLE);
    EXPECT_EQ(drape_cloth_destroy(c), DRAPE_ERROR_INVALID_HANDLE);
    int not_a_cloth = 0;
    EXPECT_EQ(drape_cloth_step(reinterpret_cast<drape_cloth*>(&not_a_cloth), 0.01f), DRAPE_ERROR_INVALID_HANDLE);
    // A world handle is not a cloth handle.
    EXPECT_EQ(drape_cloth_step(reinterpret_cast<drape_cloth*>(w.get()), 0.01f), DRAPE_ERROR_INVALID_HANDLE);
    EXPECT_EQ(drape_world_step(nullptr, 0.01f), DRAPE_ERROR_NULL_POINTER);
}

TEST(Api, GridCreationChecksItsInput) {
    WorldPtr w = make_world();
    drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 1.0f};
    drape_cloth* c = nullptr;
    auto try_grid = [&](drape_grid_desc g) { return drape_cloth_create_grid(w.get(), &d, &g, &c); };
    EXPECT_EQ(try_grid(grid_desc(0, 4, 1, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(try_grid(grid_desc(1, 1, 1, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(try_grid(grid_desc(100000, 100000, 1, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(try_grid(grid_desc(4, 4, -1, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(try_grid(grid_desc(4, 4, 0, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(try_grid(grid_desc(4, 4, kNaN, 1)), DRAPE_ERROR_NOT_FINITE);
    EXPECT_EQ(try_grid(grid_desc(4, 4, 1, kInf)), DRAPE_ERROR_NOT_FINITE);
    EXPECT_EQ(try_grid(grid_desc(4, 4, 1e30f, 1)), DRAPE_ERROR_INVALID_ARGUMENT);
    drape_grid_desc parallel = grid_desc(4, 4, 1, 1);
    parallel.axis_u[0] = 1;
    parallel.axis_v[0] = 2;
    EXPECT_EQ(try_grid(parallel), DRAPE_ERROR_INVALID_ARGUMENT);
    expect_message("parallel");
    drape_grid_desc bad_size = grid_desc(4, 4, 1, 1);
    bad_size.struct_size = 3;
    EXPECT_EQ(try_grid(bad_size), DRAPE_ERROR_STRUCT_SIZE);
    EXPECT_EQ(drape_cloth_create_grid(w.get(), &d, nullptr, &c), DRAPE_ERROR_NULL_POINTER);
    drape_grid_desc g = grid_desc(4, 4, 1, 1);
    EXPECT_EQ(drape_cloth_create_grid(w.get(), &d, &g, nullptr), DRAPE_ERROR_NULL_POINTER);
    d.backend = 17;
    EXPECT_EQ(try_grid(g), DRAPE_ERROR_INVALID_ENUM);
    d.backend = DRAPE_BACKEND_CPU;
    d.total_mass = 0;
    EXPECT_EQ(try_grid(g), DRAPE_ERROR_INVALID_ARGUMENT);
    d.total_mass = kNaN;
    EXPECT_EQ(try_grid(g), DRAPE_ERROR_NOT_FINITE);
    EXPECT_EQ(c, nullptr);
}

TEST(Api, MeshCreationChecksItsInput) {
    WorldPtr w = make_world();
    drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 1.0f};
    float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    uint32_t idx[] = {0, 1, 2, 1, 3, 2};
    drape_mesh_desc m{sizeof m, 4, pos, 6, idx, 0.0f};
    drape_cloth* c = nullptr;
    ASSERT_DRAPE_OK(drape_cloth_create_mesh(w.get(), &d, &m, &c));
    ASSERT_DRAPE_OK(drape_cloth_destroy(c));
    c = nullptr;

    uint32_t out_of_range[] = {0, 1, 4, 1, 3, 2};
    m.indices = out_of_range;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_INDEX_OUT_OF_RANGE);
    expect_message("index");
    uint32_t repeated[] = {0, 1, 1, 1, 3, 2};
    m.indices = repeated;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_DEGENERATE_MESH);
    expect_message("triangle 0");
    float collinear[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0};
    m.indices = idx;
    m.positions = collinear;
    uint32_t line[] = {0, 1, 2, 1, 3, 2};
    m.indices = line;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_DEGENERATE_MESH);
    m.indices = idx;
    float nan_pos[] = {0, 0, 0, 1, kNaN, 0, 0, 1, 0, 1, 1, 0};
    m.positions = nan_pos;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_NOT_FINITE);
    expect_message("vertex 1");
    m.positions = pos;
    m.index_count = 5;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_INVALID_ARGUMENT);
    m.index_count = 6;
    m.positions = nullptr;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_NULL_POINTER);
    m.positions = pos;
    m.weld_distance = -1;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_INVALID_ARGUMENT);
    m.weld_distance = 0;
    m.vertex_count = 2;
    EXPECT_EQ(drape_cloth_create_mesh(w.get(), &d, &m, &c), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(c, nullptr);
}

// The default model is AUTO; a cloth stores and reports the model it resolved to, at creation and
// when given AUTO again, and the stability estimate counts the resolved model's substeps.
TEST(Api, DefaultModelResolvesPerBackend) {
    drape_params p{};
    ASSERT_DRAPE_OK(drape_params_default(&p));
    EXPECT_EQ(p.model, uint32_t(DRAPE_MODEL_AUTO));
    WorldPtr w = make_world();
    for (drape_backend b : {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED}) {
        drape_cloth_desc d{sizeof d, uint32_t(b), 1.0f};
        drape_grid_desc g = grid_desc(4, 4, 1, 1);
        drape_cloth* c = nullptr;
        ASSERT_DRAPE_OK(drape_cloth_create_grid(w.get(), &d, &g, &c));
        EXPECT_EQ(params_of(c).model, uint32_t(DRAPE_MODEL_IMPLICIT));
        drape_params xpbd = p;
        xpbd.model = DRAPE_MODEL_XPBD;
        ASSERT_DRAPE_OK(drape_cloth_set_params(c, &xpbd));
        EXPECT_EQ(params_of(c).model, uint32_t(DRAPE_MODEL_XPBD));
        ASSERT_DRAPE_OK(drape_cloth_set_params(c, &p));
        EXPECT_EQ(params_of(c).model, uint32_t(DRAPE_MODEL_IMPLICIT));
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        EXPECT_EQ(stats_of(c).substeps, 2u);  // IMPLICIT's automatic substeps, not XPBD's 16
        drape_stability e{};
        e.struct_size = sizeof e;
        ASSERT_DRAPE_OK(drape_estimate_stability(&d, &g, nullptr, &p, 1.0f / 60, &e));
        EXPECT_EQ(e.substeps, 2u);
        ASSERT_DRAPE_OK(drape_cloth_destroy(c));
    }
}

TEST(Api, BadParamsLeaveTheClothUnchanged) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    const drape_params before = params_of(c);
    drape_params p = before;
    auto expect_refused = [&](drape_status expected) {
        EXPECT_EQ(drape_cloth_set_params(c, &p), expected) << drape_last_error();
        drape_params now = params_of(c);
        EXPECT_EQ(std::memcmp(&now, &before, sizeof now), 0) << "params changed by a refused call";
        p = before;
    };
    p.model = 5;
    expect_refused(DRAPE_ERROR_INVALID_ENUM);
    p.stiffness[1] = kNaN;
    expect_refused(DRAPE_ERROR_NOT_FINITE);
    p.stiffness[0] = -5;
    expect_refused(DRAPE_ERROR_INVALID_ARGUMENT);
    p.model = DRAPE_MODEL_PBD;  // PBD stiffness is a fraction; the default 2000 is not
    expect_refused(DRAPE_ERROR_INVALID_ARGUMENT);
    p.damping = kInf;
    expect_refused(DRAPE_ERROR_NOT_FINITE);
    p.gravity[2] = kNaN;
    expect_refused(DRAPE_ERROR_NOT_FINITE);
    p.wind[0] = 1e9f;
    expect_refused(DRAPE_ERROR_INVALID_ARGUMENT);
    p.iterations = DRAPE_MAX_ITERATIONS + 1;  // 0 is automatic
    expect_refused(DRAPE_ERROR_INVALID_ARGUMENT);
    p.substeps = 1000000;
    expect_refused(DRAPE_ERROR_INVALID_ARGUMENT);
    p.struct_size = 8;
    expect_refused(DRAPE_ERROR_STRUCT_SIZE);
    EXPECT_EQ(drape_cloth_set_params(c, nullptr), DRAPE_ERROR_NULL_POINTER);
}

TEST(Api, BadStateInputLeavesTheClothUnchanged) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(3, 3, 1, 1), 1);
    const std::vector<float> before = positions(c);
    std::vector<float> xyz(27, 0.5f);
    xyz[13] = kNaN;
    EXPECT_EQ(drape_cloth_set_positions(c, xyz.data(), 9), DRAPE_ERROR_NOT_FINITE);
    expect_message("vertex 4");
    xyz[13] = 0;
    EXPECT_EQ(drape_cloth_set_positions(c, xyz.data(), 8), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_set_positions(c, nullptr, 9), DRAPE_ERROR_NULL_POINTER);
    EXPECT_EQ(drape_cloth_set_velocities(c, xyz.data(), 10), DRAPE_ERROR_INVALID_ARGUMENT);
    std::vector<float> inv(9, 1.0f);
    inv[3] = -1;
    EXPECT_EQ(drape_cloth_set_inverse_masses(c, inv.data(), 9), DRAPE_ERROR_INVALID_ARGUMENT);
    inv[3] = kNaN;
    EXPECT_EQ(drape_cloth_set_inverse_masses(c, inv.data(), 9), DRAPE_ERROR_NOT_FINITE);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), 9, {0, 0, 0}}};
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_ERROR_INDEX_OUT_OF_RANGE);
    pins[1].vertex = 8;
    pins[1].position[1] = kInf;
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_ERROR_NOT_FINITE);
    pins[1].position[1] = 0;
    pins[1].struct_size = 4;
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_ERROR_STRUCT_SIZE);
    uint32_t release[] = {42};
    EXPECT_EQ(drape_cloth_release_pins(c, release, 1), DRAPE_ERROR_INDEX_OUT_OF_RANGE);
    EXPECT_EQ(drape_cloth_step(c, kNaN), DRAPE_ERROR_NOT_FINITE);
    EXPECT_EQ(drape_cloth_step(c, 0), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_step(c, -0.01f), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_step(c, 5.0f), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(positions(c), before);
}

TEST(Api, ReadChecksLayoutAndSize) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(3, 2, 1, 1), 1);
    std::vector<uint8_t> buf(6 * 32, 0xAB);
    drape_vertex_layout l{sizeof l, 32, 0, 16};
    ASSERT_DRAPE_OK(drape_cloth_read(c, &l, buf.data(), buf.size()));
    EXPECT_EQ(drape_cloth_read(c, &l, buf.data(), buf.size() - 1), DRAPE_ERROR_BUFFER_TOO_SMALL);
    expect_message("needs 192");
    drape_vertex_layout bad = l;
    bad.stride = 10;
    EXPECT_EQ(drape_cloth_read(c, &bad, buf.data(), buf.size()), DRAPE_ERROR_INVALID_ARGUMENT);
    bad = l;
    bad.normal_offset = 24;  // 24 + 12 > 32
    EXPECT_EQ(drape_cloth_read(c, &bad, buf.data(), buf.size()), DRAPE_ERROR_INVALID_ARGUMENT);
    bad = l;
    bad.normal_offset = 4;  // overlaps the position
    EXPECT_EQ(drape_cloth_read(c, &bad, buf.data(), buf.size()), DRAPE_ERROR_INVALID_ARGUMENT);
    bad = l;
    bad.position_offset = bad.normal_offset = -1;
    EXPECT_EQ(drape_cloth_read(c, &bad, buf.data(), buf.size()), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_read(c, &l, nullptr, buf.size()), DRAPE_ERROR_NULL_POINTER);
}

TEST(Api, ReadWritesTheInterleavedLayoutOnly) {
    WorldPtr w = make_world();
    drape_grid_desc g = grid_desc(3, 2, 2.0f, 1.0f);
    g.origin[1] = 5;
    drape_cloth* c = make_grid(w.get(), g, 1);
    struct Vertex {
        float pos[3];
        float normal[3];
        float uv[2];
    };
    std::vector<Vertex> v(6);
    for (Vertex& x : v) x.uv[0] = x.uv[1] = 42.0f;
    drape_vertex_layout l{sizeof l, sizeof(Vertex), 0, 12};
    ASSERT_DRAPE_OK(drape_cloth_read(c, &l, v.data(), v.size() * sizeof(Vertex)));
    // Vertex (c, r) = origin + c * 1.0 * x - r * 1.0 * z; the default grid lies in the xz plane,
    // so every normal is +-y; the UVs are untouched.
    for (uint32_t r = 0; r < 2; ++r)
        for (uint32_t col = 0; col < 3; ++col) {
            const Vertex& x = v[r * 3 + col];
            EXPECT_FLOAT_EQ(x.pos[0], float(col));
            EXPECT_FLOAT_EQ(x.pos[1], 5.0f);
            EXPECT_FLOAT_EQ(x.pos[2], -float(r));
            EXPECT_FLOAT_EQ(std::fabs(x.normal[1]), 1.0f);
            EXPECT_EQ(x.uv[0], 42.0f);
        }
}

TEST(Api, InfoCountsThe12SpringStencil) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(5, 4, 1, 1), 1);
    drape_cloth_info info{sizeof info};
    ASSERT_DRAPE_OK(drape_cloth_get_info(c, &info));
    EXPECT_EQ(info.vertex_count, 20u);
    EXPECT_EQ(info.particle_count, 20u);
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_STRUCTURAL], 4u * 4 + 5 * 3);  // horizontal + vertical
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_SHEAR], 2u * 4 * 3);
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_BEND], 3u * 4 + 5 * 2);
    EXPECT_EQ(info.triangle_count, 2u * 4 * 3);
}

// A dt shorter than DRAPE_MIN_DT is valid and does nothing: no UNSTABLE, nothing moves, and a pin
// move requested before it is made by the next real step.
TEST(Api, TinyDtIsANoOp) {
    WorldPtr w = make_world(1);
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    drape_pin pin{sizeof pin, 0, {0, 0, 0}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    const std::vector<float> before = positions(c);
    pin.position[0] = 0.05f;
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
    for (float dt : {1e-30f, std::numeric_limits<float>::denorm_min(), 1e-7f, DRAPE_MIN_DT * 0.99f}) {
        EXPECT_DRAPE_OK(drape_cloth_step(c, dt)) << "dt " << dt;
        EXPECT_DRAPE_OK(drape_world_step(w.get(), dt)) << "dt " << dt;
    }
    EXPECT_EQ(positions(c), before);
    EXPECT_EQ(stats_of(c).unstable_steps, 0u);
    ASSERT_DRAPE_OK(drape_cloth_step(c, DRAPE_MIN_DT));  // the shortest real step
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    EXPECT_NEAR(positions(c)[0], 0.05f, 1e-6f);
    EXPECT_EQ(drape_cloth_step(c, 0.0f), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_step(c, -1e-30f), DRAPE_ERROR_INVALID_ARGUMENT);
}

// A step that diverges restores the state, but the pin move asked for before it still happens at
// the next step (it is not silently dropped with the rolled-back state).
TEST(Api, PinMoveBeforeARolledBackStepIsKept) {
    WorldPtr w = make_world(1);
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    drape_pin pin{sizeof pin, 0, {0, 0, 0}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    drape_params good{};
    ASSERT_DRAPE_OK(drape_params_default(&good));
    drape_params wild = good;  // explicit springs far beyond their stability bound: diverges
    wild.model = DRAPE_MODEL_MASS_SPRING;
    for (float& k : wild.stiffness) k = 1e9f;
    wild.substeps = 1;
    wild.max_stretch = 0;  // no tethers to hold it together
    ASSERT_DRAPE_OK(drape_cloth_set_params(c, &wild));
    std::vector<float> stretched = positions(c);  // every spring at twice its rest length
    for (float& x : stretched) x *= 2.0f;
    ASSERT_DRAPE_OK(drape_cloth_set_positions(c, stretched.data(), 16));
    pin.position[0] = 0.05f;
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
    ASSERT_EQ(drape_cloth_step(c, 1 / 60.f), DRAPE_ERROR_UNSTABLE);
    EXPECT_NEAR(positions(c)[0], 0.0f, 1e-7f);  // rolled back
    ASSERT_DRAPE_OK(drape_cloth_set_params(c, &good));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    EXPECT_NEAR(positions(c)[0], 0.05f, 1e-6f) << "the pin move was dropped with the rolled-back step";
}

TEST(Api, UnityRenderEventChecksItsPointers) {
    void* callback = nullptr;
    int32_t id = 0;
    EXPECT_EQ(drape_unity_render_event(nullptr, nullptr), DRAPE_ERROR_NULL_POINTER);
    expect_message("out_callback");
    EXPECT_EQ(drape_unity_render_event(&callback, nullptr), DRAPE_ERROR_NULL_POINTER);
    expect_message("out_event_id");
    EXPECT_DRAPE_OK(drape_unity_render_event(&callback, &id));
    EXPECT_NE(callback, nullptr);
    EXPECT_STREQ(drape_last_error(), "");
}
