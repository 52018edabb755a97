// struct_size versioning: every size a struct has shipped is accepted. "ABI 1" is the layout
// released first; its sizes are frozen here as numbers (64-bit targets: x86_64, arm64, Windows
// x64), so a change that breaks callers built against it fails this file.
#include <cstddef>
#include <cstring>
#include <vector>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// ABI 1 sizes (bytes), as the header of commit 3a1d742 compiles on x86_64. drape_stats shipped
// twice in ABI 1: without and with `sleeping`.
constexpr uint32_t kAbi1WorldDesc = 8, kAbi1ClothDesc = 12, kAbi1GridDesc = 56, kAbi1MeshDesc = 40,
                   kAbi1Params = 64, kAbi1VertexLayout = 16, kAbi1Pin = 20, kAbi1ClothInfo = 32,
                   kAbi1StatsOld = 44, kAbi1Stats = 48, kAbi1Collider = 60, kAbi1SleepDesc = 12, kAbi1View = 204,
                   kAbi1Touch = 28, kAbi1Owner = 44, kAbi1SelfCollision = 16;

// A struct as a caller built against ABI 1 lays it out: the current struct's first `size` bytes
// (the fields of ABI 1 keep their offsets), followed by bytes that are not the struct's.
template <class T>
struct Abi1Buffer {
    alignas(T) unsigned char bytes[sizeof(T) + 32];
    Abi1Buffer(const T& value, uint32_t size) {
        std::memset(bytes, 0xAB, sizeof bytes);
        std::memcpy(bytes, &value, size);
        reinterpret_cast<T*>(bytes)->struct_size = size;
    }
    T* get() { return reinterpret_cast<T*>(bytes); }
    bool tail_untouched(uint32_t size) const {
        for (size_t k = size; k < sizeof bytes; ++k)
            if (bytes[k] != 0xAB) return false;
        return true;
    }
};

}  // namespace

TEST(AbiVersions, CurrentStructsStillHaveTheAbi1Layout) {
    if (sizeof(void*) != 8) GTEST_SKIP() << "ABI 1 sizes are recorded for 64-bit targets";
    EXPECT_EQ(offsetof(drape_world_desc, profile_stages), kAbi1WorldDesc);  // revision 1 added `profile_stages`
    EXPECT_EQ(sizeof(drape_cloth_desc), kAbi1ClothDesc);
    EXPECT_EQ(sizeof(drape_grid_desc), kAbi1GridDesc);
    EXPECT_EQ(sizeof(drape_mesh_desc), kAbi1MeshDesc);
    EXPECT_EQ(sizeof(drape_params), kAbi1Params);
    EXPECT_EQ(offsetof(drape_vertex_layout, origin), kAbi1VertexLayout);  // revision 1 added `origin`
    EXPECT_EQ(sizeof(drape_pin), kAbi1Pin);
    EXPECT_EQ(offsetof(drape_cloth_info, description_id), kAbi1ClothInfo);  // revision 1 added `description_*`
    EXPECT_EQ(offsetof(drape_stats, sleeping), kAbi1StatsOld);
    EXPECT_EQ(offsetof(drape_stats, stage_ms), kAbi1Stats);  // revision 2 added `stage_ms`
    EXPECT_EQ(sizeof(drape_collider), kAbi1Collider);
    EXPECT_EQ(sizeof(drape_sleep_desc), kAbi1SleepDesc);
    EXPECT_EQ(sizeof(drape_view), kAbi1View);
    EXPECT_EQ(sizeof(drape_touch), kAbi1Touch);
    EXPECT_EQ(sizeof(drape_owner), kAbi1Owner);
    EXPECT_EQ(sizeof(drape_self_collision_desc), kAbi1SelfCollision);
}

// Every call taking a struct accepts it at its ABI 1 size, and a size never shipped is refused
// with STRUCT_SIZE and a message naming the sizes that are accepted.
TEST(AbiVersions, InputStructsAtAbi1SizesAreAccepted) {
    if (sizeof(void*) != 8) GTEST_SKIP() << "ABI 1 sizes are recorded for 64-bit targets";
    drape_world_desc wd{kAbi1WorldDesc, 1};
    drape_world* w = nullptr;
    ASSERT_DRAPE_OK(drape_world_create(&wd, &w));
    WorldPtr world(w);
    drape_cloth_desc cd{kAbi1ClothDesc, DRAPE_BACKEND_CPU, 1.0f};
    drape_grid_desc g = grid_desc(4, 4, 1, 1);
    g.struct_size = kAbi1GridDesc;
    drape_cloth* c = nullptr;
    ASSERT_DRAPE_OK(drape_cloth_create_grid(w, &cd, &g, &c));
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    const uint32_t idx[3] = {0, 1, 2};
    drape_mesh_desc md{kAbi1MeshDesc, 3, pos, 3, idx, 0.0f};
    drape_cloth* m = nullptr;
    ASSERT_DRAPE_OK(drape_cloth_create_mesh(w, &cd, &md, &m));

    drape_params p{};
    drape_params_default(&p);
    p.struct_size = kAbi1Params;
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    drape_pin pin{kAbi1Pin, 0, {0, 0, 0}};
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
    drape_collider col{};
    col.struct_size = kAbi1Collider;
    col.shape = DRAPE_COLLIDER_SPHERE;
    col.rotation[3] = 1;
    col.size[0] = 0.1f;
    col.position[1] = -5;
    EXPECT_DRAPE_OK(drape_cloth_set_colliders(c, &col, 1));
    drape_sleep_desc sl{kAbi1SleepDesc, 0.0f, 1.0f};
    EXPECT_DRAPE_OK(drape_cloth_set_sleep(c, &sl));
    drape_self_collision_desc sc{kAbi1SelfCollision, 0, 0, 0};
    EXPECT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
    drape_owner o{};
    drape_owner_default(&o);
    o.struct_size = kAbi1Owner;
    EXPECT_DRAPE_OK(drape_cloth_set_owner(c, &o));
    drape_view v{};
    v.struct_size = kAbi1View;
    for (int k = 0; k < 4; ++k) v.world[k * 5] = v.view[k * 5] = v.projection[k * 5] = 1;
    v.viewport[0] = v.viewport[1] = 100;
    drape_touch t{};
    drape_touch_default(&t);
    t.struct_size = kAbi1Touch;
    EXPECT_DRAPE_OK(drape_cloth_drag(c, &v, &t, 1));
    EXPECT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    // drape_vertex_layout grew `origin` after ABI 1: a caller built against the 16-byte struct has
    // other bytes where `origin` is now; they are not read, the default (0) is used instead.
    drape_vertex_layout current{sizeof current, 12, 0, -1, {0, 0, 0}};
    std::vector<float> expected(16 * 3), got(16 * 3);
    EXPECT_DRAPE_OK(drape_cloth_read(c, &current, expected.data(), expected.size() * 4));
    Abi1Buffer<drape_vertex_layout> old(current, kAbi1VertexLayout);  // 0xAB bytes after the ABI 1 fields
    EXPECT_DRAPE_OK(drape_cloth_read(c, old.get(), got.data(), got.size() * 4));
    EXPECT_EQ(got, expected);
    current.origin[1] = 1.0f;  // the new field works when given
    EXPECT_DRAPE_OK(drape_cloth_read(c, &current, got.data(), got.size() * 4));
    EXPECT_FLOAT_EQ(got[1], expected[1] - 1.0f);

    // Sizes never shipped.
    for (uint32_t bad : {0u, kAbi1Params - 4, kAbi1Params + 4, 1000u}) {
        p.struct_size = bad;
        EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_ERROR_STRUCT_SIZE) << bad;
        EXPECT_NE(std::strstr(drape_last_error(), "has shipped with size 64"), nullptr) << drape_last_error();
    }
    // An array is one struct size: a mixed array is refused.
    drape_pin pins[2] = {{kAbi1Pin, 0, {0, 0, 0}}, {kAbi1Pin + 4, 1, {0, 0, 0}}};
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_ERROR_STRUCT_SIZE);
}

// Out-structs: the library writes exactly the revision the caller asked for. drape_stats at its
// older ABI 1 size gets the prefix and not a byte more; get_info / get_params / params_default
// read an unset struct_size (0, garbage: ABI 1 callers were not asked to set it) as the first
// revision, write that and report it.
TEST(AbiVersions, OutStructsWriteTheRevisionAskedFor) {
    WorldPtr w = make_world(1);
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    const uint32_t old_stats = uint32_t(offsetof(drape_stats, sleeping));
    Abi1Buffer<drape_stats> stats(drape_stats{}, old_stats);
    ASSERT_DRAPE_OK(drape_cloth_get_stats(c, stats.get()));
    EXPECT_EQ(stats.get()->struct_size, old_stats);
    EXPECT_GT(stats.get()->substeps, 0u);
    EXPECT_TRUE(stats.tail_untouched(old_stats)) << "wrote past the caller's drape_stats";
    Abi1Buffer<drape_stats> bad_stats(drape_stats{}, old_stats + 2);
    EXPECT_EQ(drape_cloth_get_stats(c, bad_stats.get()), DRAPE_ERROR_STRUCT_SIZE);

    for (uint32_t unset : {0u, 3u, 0xABABABABu}) {
        Abi1Buffer<drape_cloth_info> info(drape_cloth_info{}, kAbi1ClothInfo);
        info.get()->struct_size = unset;
        ASSERT_DRAPE_OK(drape_cloth_get_info(c, info.get()));
        EXPECT_EQ(info.get()->struct_size, kAbi1ClothInfo);
        EXPECT_EQ(info.get()->vertex_count, 16u);
        EXPECT_TRUE(info.tail_untouched(kAbi1ClothInfo));
        Abi1Buffer<drape_params> params(drape_params{}, sizeof(drape_params));
        params.get()->struct_size = unset;
        ASSERT_DRAPE_OK(drape_cloth_get_params(c, params.get()));
        EXPECT_EQ(params.get()->struct_size, sizeof(drape_params));
        EXPECT_EQ(params.get()->model, uint32_t(DRAPE_MODEL_XPBD));
        EXPECT_TRUE(params.tail_untouched(sizeof(drape_params)));
        params.get()->struct_size = unset;
        ASSERT_DRAPE_OK(drape_params_default(params.get()));
        EXPECT_EQ(params.get()->iterations, 0u);  // automatic
        EXPECT_TRUE(params.tail_untouched(sizeof(drape_params)));
    }
}

TEST(AbiVersions, StabilityEstimateChecksItsInput) {
    drape_cloth_desc d{sizeof d, DRAPE_BACKEND_GLES, 0.011f};  // availability is not needed
    drape_grid_desc g = grid_desc(1, 11, 1, 1);
    drape_params p{};
    drape_params_default(&p);
    p.model = DRAPE_MODEL_MASS_SPRING;
    p.stiffness[1] = p.stiffness[2] = 0;
    p.stiffness[0] = 1000;
    p.damping = 0;
    drape_stability e{sizeof e};
    ASSERT_DRAPE_OK(drape_estimate_stability(&d, &g, nullptr, &p, 1 / 60.f, &e));
    EXPECT_EQ(e.stable_substeps, 19u);  // worked by hand in unity-package/Tests/Core/ParamsTests.cs
    EXPECT_EQ(drape_estimate_stability(&d, nullptr, nullptr, &p, 1 / 60.f, &e), DRAPE_ERROR_NULL_POINTER);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    const uint32_t idx[3] = {0, 1, 2};
    drape_mesh_desc m{sizeof m, 3, pos, 3, idx, 0};
    EXPECT_EQ(drape_estimate_stability(&d, &g, &m, &p, 1 / 60.f, &e), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_DRAPE_OK(drape_estimate_stability(&d, nullptr, &m, &p, 1 / 60.f, &e));
    EXPECT_EQ(drape_estimate_stability(&d, &g, nullptr, &p, 0.0f, &e), DRAPE_ERROR_INVALID_ARGUMENT);
    p.stiffness[0] = -1;
    EXPECT_EQ(drape_estimate_stability(&d, &g, nullptr, &p, 1 / 60.f, &e), DRAPE_ERROR_INVALID_ARGUMENT);
    p.stiffness[0] = 1000;
    e.struct_size = 3;
    EXPECT_EQ(drape_estimate_stability(&d, &g, nullptr, &p, 1 / 60.f, &e), DRAPE_ERROR_STRUCT_SIZE);
    // Far beyond DRAPE_MAX_SUBSTEPS: reported, not capped; the automatic choice is capped.
    p.stiffness[0] = 1e9f;
    e.struct_size = sizeof e;
    ASSERT_DRAPE_OK(drape_estimate_stability(&d, &g, nullptr, &p, 1.0f, &e));
    EXPECT_GT(e.stable_substeps, uint32_t(DRAPE_MAX_SUBSTEPS));
    EXPECT_EQ(e.substeps, uint32_t(DRAPE_MAX_SUBSTEPS));
    EXPECT_EQ(e.stable, 0u);
}
