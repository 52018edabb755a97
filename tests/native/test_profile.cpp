// Stage profiling (drape_world_desc.profile_stages -> drape_stats.stage_ms): off by default, and
// then every figure is exactly 0; on, a stage whose work does not exist (no tethers, colliders or
// self-collision) stays exactly 0, the stages run before the step's end fit inside step_ms (the
// same clock), and the physics is bit-identical with and without it. Verdicts are on which stages
// ran and how the figures nest, never on how long anything took.
#include <cstring>
#include <vector>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

WorldPtr make_profiling_world(uint32_t threads = 2) {
    drape_world_desc d{sizeof d, threads, 1};
    drape_world* w = nullptr;
    EXPECT_DRAPE_OK(drape_world_create(&d, &w));
    return WorldPtr(w);
}

// A 16 x 16 sheet, 1 m, pinned at its two far corners, in `model`.
drape_cloth* sheet(drape_world* w, drape_model model, drape_backend backend = DRAPE_BACKEND_CPU) {
    drape_cloth* c = make_grid(w, grid_desc(16, 16, 1, 1), 0.5f, backend);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), 15, {1, 0, 0}}};
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    drape_params p = params_of(c);
    p.model = model;
    if (model == DRAPE_MODEL_PBD)
        for (float& k : p.stiffness) k = 0.5f;  // PBD stiffness is a fraction
    p.max_stretch = 0;  // no tethers
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    return c;
}

// Everything the optional stages work on: tethers, a sphere under the sheet, self-collision.
void add_optional_work(drape_cloth* c) {
    drape_params p = params_of(c);
    p.max_stretch = 0.1f;
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    const drape_collider sphere = collider(DRAPE_COLLIDER_SPHERE, 0.5f, -0.4f, -0.5f, 0.2f);
    EXPECT_DRAPE_OK(drape_cloth_set_colliders(c, &sphere, 1));
    drape_self_collision_desc sc{sizeof sc, 1, 0.02f, 0};
    EXPECT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
}

constexpr drape_stage kOptional[] = {DRAPE_STAGE_TETHER, DRAPE_STAGE_SELF_COLLIDE, DRAPE_STAGE_COLLIDE};

bool optional(int stage) {
    for (drape_stage s : kOptional)
        if (s == stage) return true;
    return false;
}

}  // namespace

TEST(Profile, OffByDefaultEveryFigureIsZero) {
    WorldPtr w = make_world();
    drape_cloth* c = sheet(w.get(), DRAPE_MODEL_XPBD);
    add_optional_work(c);
    for (int f = 0; f < 10; ++f) {
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        const drape_stats s = stats_of(c);
        EXPECT_GT(s.substeps, 0u);
        for (int k = 0; k < DRAPE_STAGE_COUNT; ++k) EXPECT_EQ(s.stage_ms[k], 0.0f) << "stage " << k;
    }
}

TEST(Profile, AStageWithoutWorkStaysZeroAndEveryOtherIsTimed) {
    for (drape_model model : {DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD, DRAPE_MODEL_IMPLICIT}) {
        SCOPED_TRACE("model " + std::to_string(model));
        WorldPtr w = make_profiling_world();
        drape_cloth* c = sheet(w.get(), model);
        double total[DRAPE_STAGE_COUNT] = {};
        for (int f = 0; f < 30; ++f) {
            ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
            const drape_stats s = stats_of(c);
            for (drape_stage k : kOptional) EXPECT_EQ(s.stage_ms[k], 0.0f) << "stage " << k << " has no work";
            for (int k = 0; k < DRAPE_STAGE_COUNT; ++k) total[k] += s.stage_ms[k];
        }
        // 30 steps of a 256-particle cloth: every stage that ran took some time on any clock
        // that counts below a millisecond.
        for (int k = 0; k < DRAPE_STAGE_COUNT; ++k)
            if (!optional(k)) EXPECT_GT(total[k], 0.0) << "stage " << k << " ran untimed";

        add_optional_work(c);
        double with_work[DRAPE_STAGE_COUNT] = {};
        for (int f = 0; f < 30; ++f) {
            ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
            const drape_stats s = stats_of(c);
            for (int k = 0; k < DRAPE_STAGE_COUNT; ++k) with_work[k] += s.stage_ms[k];
        }
        for (drape_stage k : kOptional) EXPECT_GT(with_work[k], 0.0) << "stage " << k << " ran untimed";
    }
}

TEST(Profile, StagesUpToVerifyFitInsideTheStepTime) {
    // step_ms runs from before BEGIN to the end of VERIFY on the same clock as the scopes, which
    // do not overlap: their sum cannot exceed it (float rounding aside).
    WorldPtr w = make_profiling_world();
    drape_cloth* c = sheet(w.get(), DRAPE_MODEL_XPBD);
    add_optional_work(c);
    for (int f = 0; f < 30; ++f) {
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        const drape_stats s = stats_of(c);
        float inside = 0;
        for (int k = DRAPE_STAGE_BEGIN; k <= DRAPE_STAGE_VERIFY; ++k) {
            EXPECT_GE(s.stage_ms[k], 0.0f);
            inside += s.stage_ms[k];
        }
        EXPECT_LE(inside, s.step_ms * 1.0001f + 1e-6f) << "step " << f;
    }
}

TEST(Profile, SameBitsWithAndWithoutProfiling) {
    for (drape_backend backend : {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED}) {
        SCOPED_TRACE("backend " + std::to_string(backend));
        WorldPtr plain = make_world();
        WorldPtr profiled = make_profiling_world();
        drape_cloth* a = sheet(plain.get(), DRAPE_MODEL_XPBD, backend);
        drape_cloth* b = sheet(profiled.get(), DRAPE_MODEL_XPBD, backend);
        add_optional_work(a);
        add_optional_work(b);
        for (int f = 0; f < 60; ++f) {
            ASSERT_DRAPE_OK(drape_cloth_step(a, 1.0f / 60));
            ASSERT_DRAPE_OK(drape_cloth_step(b, 1.0f / 60));
        }
        const std::vector<float> pa = positions(a), pb = positions(b);
        EXPECT_EQ(0, std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)));
    }
}
