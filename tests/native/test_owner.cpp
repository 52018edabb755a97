// Owner transform: pins follow the owner; inertia 0 carries the cloth rigidly (local
// space), 1 leaves it to swing (world space); a teleport moves the cloth instead of stretching it.
#include <algorithm>
#include <cmath>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// 16 x 16 cloth hanging from its top corners at (0,0,0) and (1,0,0), settled for 3 s.
drape_cloth* hanging(drape_world* w) {
    drape_grid_desc g = grid_desc(16, 16, 1, 1);
    g.axis_v[1] = -1;
    g.axis_v[2] = 0;
    drape_cloth* c = make_grid(w, g, 0.2f);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), 15, {1, 0, 0}}};
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    drape_params p{};
    drape_params_default(&p);
    p.model = DRAPE_MODEL_XPBD;
    p.air_drag = 3;
    // The scene as first measured (4 substeps x 4 iterations, no tethers): a softer cloth whose lag
    // behind a moving owner is large; tethers and the converged 16-substep default both cap it.
    p.substeps = 4;
    p.iterations = 4;
    p.max_stretch = 0;
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    for (int f = 0; f < 180; ++f) EXPECT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    return c;
}

drape_owner owner_at(float x, float linear_inertia = 1, float teleport = 1) {
    drape_owner o{};
    drape_owner_default(&o);
    o.position[0] = x;
    o.linear_inertia = linear_inertia;
    o.teleport_distance = teleport;
    return o;
}

// Max over vertices of |(x - x_ref) - shift| along x, and max |y - y_ref|, |z - z_ref|.
float shape_change(const std::vector<float>& x, const std::vector<float>& ref, float shift) {
    float worst = 0;
    for (size_t v = 0; v < x.size() / 3; ++v) {
        worst = std::max(worst, std::fabs(x[3 * v] - ref[3 * v] - shift));
        worst = std::max(worst, std::fabs(x[3 * v + 1] - ref[3 * v + 1]));
        worst = std::max(worst, std::fabs(x[3 * v + 2] - ref[3 * v + 2]));
    }
    return worst;
}

}  // namespace

// The owner jumps 100 m: with teleport detection the cloth arrives in the same shape; without
// (threshold above the jump) the pins drag it across the world in one step and it stretches
// until the step is refused or the strain explodes.
TEST(Owner, TeleportMovesTheClothInsteadOfStretchingIt) {
    for (bool detect : {true, false}) {
        WorldPtr w = make_world();
        drape_cloth* c = hanging(w.get());
        drape_owner o = owner_at(0, 1, detect ? 1.0f : 1000.0f);
        ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));
        const std::vector<float> before = positions(c);
        const float strain_before = stats_of(c).max_strain;
        o.position[0] = 100;
        ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));
        const drape_status st = drape_cloth_step(c, 1.0f / 60);
        const float change = shape_change(positions(c), before, 100);
        std::printf("[ measured ] teleport 100 m, detection %s: step status %d, shape change %.4f m, strain %.3f\n",
                    detect ? "on" : "off", st, change, stats_of(c).max_strain);
        if (detect) {
            ASSERT_EQ(st, DRAPE_OK) << drape_last_error();
            EXPECT_LT(change, 0.01f);
            EXPECT_LT(stats_of(c).max_strain, strain_before + 0.01f) << "not stretched by the jump";
        } else {
            EXPECT_TRUE(st == DRAPE_ERROR_UNSTABLE || stats_of(c).max_strain > 1.0f);
        }
    }
}

// Owner walking at 6 m/s along x: with linear inertia 0 the cloth is carried rigidly (it hangs
// as if the owner stood still); with inertia 1 it lags behind the pins and swings.
TEST(Owner, InertiaScaleBlendsLocalAndWorldSpace) {
    float lag[2];
    const float inertia[2] = {0, 1};
    for (int k = 0; k < 2; ++k) {
        WorldPtr w = make_world();
        drape_cloth* c = hanging(w.get());
        const std::vector<float> rest = positions(c);
        drape_owner o = owner_at(0, inertia[k]);
        ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));
        for (int f = 1; f <= 30; ++f) {
            o.position[0] = 0.1f * float(f);
            ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));
            ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        }
        const std::vector<float> x = positions(c);
        EXPECT_NEAR(x[0], 3.0f, 1e-4f) << "pins follow the owner";
        EXPECT_NEAR(x[3 * 15], 4.0f, 1e-4f);
        lag[k] = shape_change(x, rest, 3.0f);
        std::printf("[ measured ] owner moving 6 m/s, linear inertia %.0f: shape change vs rest %.4f m\n", inertia[k],
                    lag[k]);
    }
    EXPECT_LT(lag[0], 2e-3f) << "local space: carried rigidly";
    EXPECT_GT(lag[1], 0.05f) << "world space: lags and swings";
}

TEST(Owner, BadInputIsRefused) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    drape_owner o = owner_at(0);
    o.rotation[3] = 2;
    EXPECT_EQ(drape_cloth_set_owner(c, &o), DRAPE_ERROR_INVALID_ARGUMENT);
    o = owner_at(NAN);
    EXPECT_EQ(drape_cloth_set_owner(c, &o), DRAPE_ERROR_NOT_FINITE);
    o = owner_at(0, 1.5f);
    EXPECT_EQ(drape_cloth_set_owner(c, &o), DRAPE_ERROR_INVALID_ARGUMENT);
    o = owner_at(0, 1, 0);
    EXPECT_EQ(drape_cloth_set_owner(c, &o), DRAPE_ERROR_INVALID_ARGUMENT);
    o = owner_at(0);
    o.struct_size = 0;
    EXPECT_EQ(drape_cloth_set_owner(c, &o), DRAPE_ERROR_STRUCT_SIZE);
    EXPECT_EQ(drape_cloth_set_owner(c, nullptr), DRAPE_ERROR_NULL_POINTER);
}
