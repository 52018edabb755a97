// GLES backend features beyond stepping, each against the CPU backend on the same scene: owner
// transform (inertia, teleport). Headless Mesa (llvmpipe; softpipe by the softpipe preset).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "drape_test_util.h"
#include "gles_test_util.h"

using namespace drape_test;

namespace {

class GlesFeatures : public WithHeadlessGles<::testing::TestWithParam<drape_model>> {};

constexpr uint32_t kCols = 16, kRows = 16;
const float kExtent = std::sqrt(2.0f);  // the sheet's diagonal, m

// A 1 m sheet at y = 1 (axes +x, -z) pinned at its two near corners, on `backend`.
drape_cloth* sheet(drape_world* w, drape_backend backend, drape_model model) {
    drape_grid_desc g = grid_desc(kCols, kRows, 1.0f, 1.0f);
    g.origin[1] = 1.0f;
    drape_cloth* c = make_grid(w, g, 0.5f, backend);
    if (!c) return nullptr;
    drape_params p{};
    EXPECT_DRAPE_OK(drape_params_default(&p));
    p.model = model;
    if (model == DRAPE_MODEL_PBD) {  // PBD stiffness is a fraction per iteration
        p.stiffness[0] = p.stiffness[1] = 1.0f;
        p.stiffness[2] = 0.2f;
    }
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0.0f, 1.0f, 0.0f}}, {sizeof(drape_pin), kCols - 1, {1.0f, 1.0f, 0.0f}}};
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    return c;
}

float max_abs_diff(const std::vector<float>& a, const std::vector<float>& b) {
    float m = 0;
    for (size_t k = 0; k < a.size(); ++k) m = std::max(m, std::fabs(a[k] - b[k]));
    return m;
}

// The parity bound of test_gles.cpp: 1e-5 of the cloth size per step over the first 4 steps
// (a few float ulps per step, two orders of margin), 1e-3 of it over the run.
void expect_parity(float err, int step) {
    if (step <= 4) EXPECT_LE(err, 1e-5f * kExtent * float(step)) << "step " << step;
    EXPECT_LE(err, 1e-3f * kExtent) << "step " << step;
}

}  // namespace

// The owner walks and turns (half its motion carried, half left to inertia), then jumps 50 m
// (teleport: the cloth moves rigidly, at rest) and walks on. GLES moves its GPU state in a pass;
// it must follow the CPU cloth step by step.
TEST_P(GlesFeatures, OwnerTransformMatchesCpu) {
    WorldPtr w = make_world(1);
    drape_cloth* cpu = sheet(w.get(), DRAPE_BACKEND_CPU, GetParam());
    drape_cloth* gpu = sheet(w.get(), DRAPE_BACKEND_GLES, GetParam());
    ASSERT_NE(gpu, nullptr);
    float worst = 0, teleported = 0;
    for (int s = 0; s <= 20; ++s) {
        const std::vector<float> before = positions(cpu);
        drape_owner o{};
        ASSERT_DRAPE_OK(drape_owner_default(&o));
        const float angle = 0.03f * float(s);  // about y
        o.position[0] = 0.02f * float(s) + (s >= 10 ? 50.0f : 0.0f);
        o.rotation[1] = std::sin(0.5f * angle);
        o.rotation[3] = std::cos(0.5f * angle);
        o.linear_inertia = 0.5f;
        o.angular_inertia = 0.5f;
        o.teleport_distance = 1.0f;
        for (drape_cloth* c : {cpu, gpu}) ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));
        if (s == 0) continue;  // the first call only records the owner
        for (drape_cloth* c : {cpu, gpu}) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        const std::vector<float> xc = positions(cpu);
        if (s == 10) teleported = xc[0] - before[0];
        const float err = max_abs_diff(xc, positions(gpu));
        worst = std::max(worst, err);
        expect_parity(err, s);
    }
    EXPECT_NEAR(teleported, 50.0f, 0.1f) << "the teleport did not move the cloth";
    std::printf("[ parity   ] owner transform, model %d: max |gles - cpu| = %.3g m over 20 steps\n", GetParam(), worst);
}

INSTANTIATE_TEST_SUITE_P(Models, GlesFeatures,
                         ::testing::Values(DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD),
                         [](const ::testing::TestParamInfo<drape_model>& info) {
                             return info.param == DRAPE_MODEL_MASS_SPRING ? std::string("MassSpring")
                                    : info.param == DRAPE_MODEL_PBD       ? std::string("Pbd")
                                                                          : std::string("Xpbd");
                         });
