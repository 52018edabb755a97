// CPU and CPU_THREADED give the same bits (per-particle Jacobi gathers do not depend on how the
// particle range is split); a run is deterministic; a diverging step is rolled back.
#include <cmath>
#include <cstring>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// Two-corner hanging cloth (the paper's scene), stepped `frames` times with wind.
std::vector<float> run_scene(drape_model model, drape_backend backend, uint32_t threads, uint32_t n, int frames) {
    WorldPtr w = make_world(threads);
    drape_cloth* c = make_grid(w.get(), grid_desc(n, n, 1, 1), 0.5f, backend);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), n - 1, {1, 0, 0}}};
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_OK);
    drape_params p{};
    drape_params_default(&p);
    p.model = model;
    if (model == DRAPE_MODEL_PBD) p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 0.8f;
    if (model == DRAPE_MODEL_MASS_SPRING) {  // explicit: keep the automatic substep count small
        p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 20.0f;
        p.damping = 0.01f;
    }
    p.wind[2] = 3.0f;
    EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_OK) << drape_last_error();
    for (int f = 0; f < frames; ++f) EXPECT_EQ(drape_cloth_step(c, 1 / 60.f), DRAPE_OK) << drape_last_error();
    return positions(c);
}

class Backends : public ::testing::TestWithParam<drape_model> {};

}  // namespace

TEST_P(Backends, ThreadedEqualsSingleThreadedBitForBit) {
    // 7^2 runs on the caller alone (below ThreadPool::kMinParallelCount); 50^2 = 2500 particles
    // is split over the workers.
    for (uint32_t n : {7u, 50u}) {
        const std::vector<float> single = run_scene(GetParam(), DRAPE_BACKEND_CPU, 1, n, 20);
        for (uint32_t threads : {2u, 3u}) {
            const std::vector<float> threaded = run_scene(GetParam(), DRAPE_BACKEND_CPU_THREADED, threads, n, 20);
            ASSERT_EQ(single.size(), threaded.size());
            EXPECT_EQ(std::memcmp(single.data(), threaded.data(), single.size() * sizeof(float)), 0)
                << "n " << n << " threads " << threads;
        }
    }
}

TEST_P(Backends, SameInputSameBits) {
    const std::vector<float> a = run_scene(GetParam(), DRAPE_BACKEND_CPU, 1, 20, 40);
    const std::vector<float> b = run_scene(GetParam(), DRAPE_BACKEND_CPU, 1, 20, 40);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
    // And the cloth did move (the comparison is not between two untouched grids).
    const std::vector<float> start = run_scene(GetParam(), DRAPE_BACKEND_CPU, 1, 20, 0);
    EXPECT_GT(std::fabs(a[3 * 210 + 1] - start[3 * 210 + 1]), 0.05f);
}

INSTANTIATE_TEST_SUITE_P(Models, Backends,
                         ::testing::Values(DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD));

TEST(Backends, WorldStepEqualsSteppingEachCloth) {
    // Two single-threaded cloths stepped by the world (spread over the pool) and one threaded
    // cloth, against the same cloths stepped one by one.
    auto build = [](drape_world* w, std::vector<drape_cloth*>& out) {
        const drape_backend backends[] = {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED};
        for (int k = 0; k < 3; ++k) {
            drape_cloth* c = make_grid(w, grid_desc(10 + k, 10, 1, 1), 0.3f, backends[k]);
            drape_pin pin{sizeof(drape_pin), 0, {0, 0, 0}};
            EXPECT_EQ(drape_cloth_set_pins(c, &pin, 1), DRAPE_OK);
            out.push_back(c);
        }
    };
    WorldPtr w1 = make_world(2), w2 = make_world(2);
    std::vector<drape_cloth*> a, b;
    build(w1.get(), a);
    build(w2.get(), b);
    for (int f = 0; f < 20; ++f) {
        ASSERT_DRAPE_OK(drape_world_step(w1.get(), 1 / 60.f));
        for (drape_cloth* c : b) ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    }
    for (int k = 0; k < 3; ++k) EXPECT_EQ(positions(a[k]), positions(b[k])) << "cloth " << k;
}

// A mass-spring cloth forced past the explicit stability limit (1 substep, huge stiffness)
// diverges: the step returns UNSTABLE, restores the last good state, and what the caller reads
// stays finite. The automatic substep count keeps the same cloth stable.
TEST(Backends, ForcedInstabilityRollsBack) {
    for (drape_backend backend : {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED}) {
        WorldPtr w = make_world();
        drape_cloth* c = make_grid(w.get(), grid_desc(16, 16, 1, 1), 0.1f, backend);
        drape_pin pin{sizeof(drape_pin), 0, {0, 0, 0}};
        ASSERT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
        drape_params p{};
        drape_params_default(&p);
        p.model = DRAPE_MODEL_MASS_SPRING;
        p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 1e4f;
        ASSERT_DRAPE_OK(drape_cloth_set_params(c, &p));
        for (int f = 0; f < 30; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));  // automatic: stable
        EXPECT_GT(stats_of(c).substeps, 50u);

        p.substeps = 1;
        ASSERT_DRAPE_OK(drape_cloth_set_params(c, &p));
        std::vector<float> before = positions(c);
        drape_status status = DRAPE_OK;
        int f = 0;
        for (; f < 200 && status == DRAPE_OK; ++f) {
            before = positions(c);
            status = drape_cloth_step(c, 1 / 60.f);
        }
        ASSERT_EQ(status, DRAPE_ERROR_UNSTABLE) << "did not diverge in 200 frames";
        EXPECT_NE(std::string(drape_last_error()).find("restored"), std::string::npos) << drape_last_error();
        const std::vector<float> after = positions(c);
        EXPECT_EQ(after, before) << "state not restored";
        for (float x : after) ASSERT_TRUE(std::isfinite(x));
        const drape_stats s = stats_of(c);
        EXPECT_EQ(s.unstable_steps, 1u);
        // Read with normals too: nothing non-finite reaches caller memory.
        std::vector<float> vn(256 * 6);
        drape_vertex_layout l{sizeof l, 24, 0, 12};
        ASSERT_DRAPE_OK(drape_cloth_read(c, &l, vn.data(), vn.size() * 4));
        for (float x : vn) ASSERT_TRUE(std::isfinite(x));
    }
}

TEST(Backends, StepDoesNotChangeStatsOfOtherCloths) {
    WorldPtr w = make_world();
    drape_cloth* a = make_grid(w.get(), grid_desc(5, 5, 1, 1), 0.1f);
    drape_cloth* b = make_grid(w.get(), grid_desc(5, 5, 1, 1), 0.1f);
    ASSERT_DRAPE_OK(drape_cloth_step(a, 1 / 60.f));
    EXPECT_GT(stats_of(a).substeps, 0u);
    EXPECT_EQ(stats_of(b).substeps, 0u);
}
