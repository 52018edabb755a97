// Tethers (long-range attachments): no particle gets further from its nearest pin than
// (1 + max_stretch) times its rest distance along the cloth, whatever the resolution.
#include <algorithm>
#include <cmath>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// Rest distance along an n x n grid of spacing a from vertex (0,0) to (c,r) over structural and
// shear springs: diagonal steps first, then straight ones.
double grid_geodesic(int dc, int dr, double a) {
    const int lo = std::min(std::abs(dc), std::abs(dr)), hi = std::max(std::abs(dc), std::abs(dr));
    return a * (lo * std::sqrt(2.0) + (hi - lo));
}

// Largest ratio (distance to the nearer top corner) / (rest distance along the cloth to it) of a
// fine cloth hanging from its two top corners after `seconds`.
double worst_stretch(drape_model model, float max_stretch, uint32_t n, float seconds) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(n, n, 1, 1), 0.3f);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), n - 1, {1, 0, 0}}};
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_OK);
    drape_params p = params_of(c);
    p.model = model;
    if (model == DRAPE_MODEL_PBD) p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 1.0f;
    p.max_stretch = max_stretch;
    EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_OK) << drape_last_error();
    for (int f = 0; f < int(seconds * 60); ++f) EXPECT_EQ(drape_cloth_step(c, 1 / 60.f), DRAPE_OK) << drape_last_error();
    const std::vector<float> x = positions(c);
    const double a = 1.0 / (n - 1);
    double worst = 0;
    for (uint32_t r = 0; r < n; ++r)
        for (uint32_t col = 0; col < n; ++col) {
            if (r == 0 && (col == 0 || col == n - 1)) continue;
            const float* xi = &x[3 * (r * n + col)];
            const double to_left = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
            const double to_right = std::sqrt((xi[0] - 1) * (xi[0] - 1) + xi[1] * xi[1] + xi[2] * xi[2]);
            const double g_left = grid_geodesic(int(col), int(r), a);
            const double g_right = grid_geodesic(int(n - 1 - col), int(r), a);
            // The tether goes to the nearer pin along the cloth.
            worst = std::max(worst, g_left <= g_right ? to_left / g_left : to_right / g_right);
        }
    return worst;
}

}  // namespace

TEST(Tethers, BoundStretchOfAFineHangingCloth) {
    for (drape_model model : {DRAPE_MODEL_XPBD, DRAPE_MODEL_PBD}) {
        const double with = worst_stretch(model, 0.1f, 48, 2.0f);
        const double without = worst_stretch(model, 0.0f, 48, 2.0f);
        std::printf("[ measured ] model %d 48x48, worst distance/rest-geodesic to the nearer pin: %.3f with "
                    "tethers (0.1), %.3f without\n", int(model), with, without);
        EXPECT_LE(with, 1.1 + 1e-4) << "model " << model;
        EXPECT_GT(without, 1.1) << "model " << model << ": the scene does not need tethers, the test shows nothing";
    }
}

TEST(Tethers, FreeClothIsUntouched) {
    // No pins, no tethers: max_stretch changes nothing (bit for bit).
    auto run = [](float max_stretch) {
        WorldPtr w = make_world();
        drape_cloth* c = make_grid(w.get(), grid_desc(10, 10, 1, 1), 0.3f);
        drape_params p = params_of(c);
        p.max_stretch = max_stretch;
        EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_OK);
        std::vector<float> v(300, 0.0f);
        for (size_t i = 0; i < v.size(); i += 3) v[i] = float(i % 7) - 3.0f;
        EXPECT_EQ(drape_cloth_set_velocities(c, v.data(), 100), DRAPE_OK);
        for (int f = 0; f < 30; ++f) EXPECT_EQ(drape_cloth_step(c, 1 / 60.f), DRAPE_OK);
        return positions(c);
    };
    EXPECT_EQ(run(0.0f), run(0.1f));
}

TEST(Tethers, FollowMovingPins) {
    // Pins moved every frame keep their tethers (anchors are rebuilt only when the pinned set
    // changes) and the cloth follows within the bound.
    const uint32_t n = 16;
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(n, n, 1, 1), 0.3f);
    for (int f = 0; f < 120; ++f) {
        const float shift = 0.02f * float(f);
        drape_pin pins[2] = {{sizeof(drape_pin), 0, {shift, 0, 0}}, {sizeof(drape_pin), n - 1, {1 + shift, 0, 0}}};
        ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    }
    const std::vector<float> x = positions(c);
    const float* bottom = &x[3 * (n * (n - 1))];  // bottom-left vertex, tethered to the left pin
    const float shift = 0.02f * 119;
    const double dist = std::sqrt((bottom[0] - shift) * (bottom[0] - shift) + bottom[1] * bottom[1] + bottom[2] * bottom[2]);
    EXPECT_LE(dist, 1.1 * 1.0 + 1e-4);
    EXPECT_GT(bottom[0], 1.0f) << "cloth did not follow the pins";
}

TEST(Tethers, MaxStretchIsValidated) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 0.3f);
    drape_params p = params_of(c);
    p.max_stretch = -0.5f;
    EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_ERROR_INVALID_ARGUMENT);
    p.max_stretch = NAN;
    EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_ERROR_NOT_FINITE);
}
