// Sleeping: a cloth at rest stops stepping (same bits, ~no time); every kind of change
// wakes it; unchanged re-sends of colliders, pins or parameters do not.
#include <chrono>
#include <cstring>
#include <functional>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// A 24x24 cloth hanging from its two top corners, sleeping enabled (0.02 m/s for 0.5 s).
drape_cloth* hanging(drape_world* w, uint32_t n = 24) {
    drape_grid_desc g = grid_desc(n, n, 1, 1);
    g.axis_v[1] = -1;
    g.axis_v[2] = 0;
    drape_cloth* c = make_grid(w, g, 0.2f);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), n - 1, {1, 0, 0}}};
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    drape_params p{};
    drape_params_default(&p);
    p.model = DRAPE_MODEL_XPBD;
    p.air_drag = 3;  // settle within a few seconds
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    drape_sleep_desc s{sizeof s, 0.02f, 0.5f};
    EXPECT_DRAPE_OK(drape_cloth_set_sleep(c, &s));
    return c;
}

// Steps until asleep (at most 20 s); returns the seconds it took, or -1.
float step_until_asleep(drape_cloth* c) {
    for (int f = 0; f < 1200; ++f) {
        EXPECT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        if (stats_of(c).sleeping) return float(f + 1) / 60;
    }
    return -1;
}

double seconds_per_step(drape_cloth* c, int steps) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) drape_cloth_step(c, 1.0f / 60);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
}

}  // namespace

TEST(Sleep, AsleepClothDoesNoWorkAndKeepsItsBits) {
    WorldPtr w = make_world();
    drape_cloth* c = hanging(w.get(), 32);
    EXPECT_EQ(stats_of(c).sleeping, 0u);
    const double awake = seconds_per_step(c, 30);
    const float t = step_until_asleep(c);
    ASSERT_GT(t, 0) << "a damped hanging cloth should come to rest within 20 s";
    const std::vector<float> before = positions(c);
    const double asleep = seconds_per_step(c, 300);
    const std::vector<float> after = positions(c);
    EXPECT_EQ(0, std::memcmp(before.data(), after.data(), before.size() * 4));
    const drape_stats s = stats_of(c);
    EXPECT_EQ(s.sleeping, 1u);
    // "No work" is judged by the work done (no substep ran), not by the clock: a timing verdict
    // flakes on a loaded machine. The times are printed for information only.
    EXPECT_EQ(s.substeps, 0u);
    EXPECT_EQ(s.step_ms, 0.0f);  // set, not measured: the asleep path returns before the timer
    std::printf("[ measured ] 32x32 cloth fell asleep after %.2f s; step %.1f us awake, %.3f us asleep (%.0fx)\n", t,
                awake * 1e6, asleep * 1e6, awake / asleep);
    // drape_world_step skips it as well.
    ASSERT_DRAPE_OK(drape_world_step(w.get(), 1.0f / 60));
    const std::vector<float> world_after = positions(c);
    EXPECT_EQ(0, std::memcmp(before.data(), world_after.data(), before.size() * 4));
}

TEST(Sleep, SleepIsOffByDefaultAndStatsKeepTheOldStructSize) {
    WorldPtr w = make_world();
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    for (int f = 0; f < 200; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));  // lies still (free fall though)
    EXPECT_EQ(stats_of(c).sleeping, 0u);
    // A caller built against drape_stats without `sleeping` gets the prefix; the rest untouched.
    struct {
        drape_stats s;
        uint32_t guard;
    } old{};
    std::memset(&old, 0xab, sizeof old);
    old.s.struct_size = offsetof(drape_stats, sleeping);
    ASSERT_DRAPE_OK(drape_cloth_get_stats(c, &old.s));
    EXPECT_EQ(old.s.struct_size, offsetof(drape_stats, sleeping));
    EXPECT_EQ(old.s.sleeping, 0xababababu);
    EXPECT_GT(old.s.substeps, 0u);
    drape_stats bad{};
    bad.struct_size = 12;
    EXPECT_EQ(drape_cloth_get_stats(c, &bad), DRAPE_ERROR_STRUCT_SIZE);
    drape_sleep_desc s{sizeof s, -1, 1};
    EXPECT_EQ(drape_cloth_set_sleep(c, &s), DRAPE_ERROR_INVALID_ARGUMENT);
    s = {sizeof s, NAN, 1};
    EXPECT_EQ(drape_cloth_set_sleep(c, &s), DRAPE_ERROR_NOT_FINITE);
    s = {4, 0.1f, 1};
    EXPECT_EQ(drape_cloth_set_sleep(c, &s), DRAPE_ERROR_STRUCT_SIZE);
}

// Each wake source, on a fresh asleep cloth: after the change and one step it is awake and (for
// the changes that move something) its positions changed.
TEST(Sleep, EveryChangeWakesTheCloth) {
    const uint32_t n = 24;
    drape_view view{};
    view.struct_size = sizeof view;
    for (int k = 0; k < 16; k += 5) view.world[k] = view.view[k] = view.projection[k] = 1;  // identity
    view.viewport[0] = view.viewport[1] = 200;  // sim x, y in [-1, 1] -> pixels (x+1)*100

    struct Source {
        const char* name;
        std::function<void(drape_cloth*)> change;
        bool moves;
    };
    std::vector<Source> sources = {
        {"params", [](drape_cloth* c) {
             drape_params p = params_of(c);
             p.wind[2] = 5;
             EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
         }, true},
        {"pin move", [](drape_cloth* c) {
             drape_pin pin{sizeof pin, 0, {0.1f, 0, 0}};
             EXPECT_DRAPE_OK(drape_cloth_set_pins(c, &pin, 1));
         }, true},
        {"pin release", [n](drape_cloth* c) {
             uint32_t v = n - 1;
             EXPECT_DRAPE_OK(drape_cloth_release_pins(c, &v, 1));
         }, true},
        {"collider", [](drape_cloth* c) {
             drape_collider s{};
             s.struct_size = sizeof s;
             s.position[0] = 0.5f;
             s.position[1] = -0.5f;
             s.position[2] = 0.05f;
             s.rotation[3] = 1;
             s.size[0] = 0.1f;
             EXPECT_DRAPE_OK(drape_cloth_set_colliders(c, &s, 1));
         }, true},
        {"drag", [&view](drape_cloth* c) {
             drape_touch t{};
             drape_touch_default(&t);
             t.position[0] = 150;  // x = 0.5
             t.position[1] = 50;   // y = -0.5
             t.motion[0] = 5;
             EXPECT_DRAPE_OK(drape_cloth_drag(c, &view, &t, 1));
         }, true},
        {"grab", [&view](drape_cloth* c) {
             const float at[2] = {150, 50};
             uint32_t v = 0;
             EXPECT_DRAPE_OK(drape_cloth_grab(c, &view, 7, at, 20, &v));
             EXPECT_NE(v, UINT32_MAX);
             const float to[2] = {160, 50};
             EXPECT_DRAPE_OK(drape_cloth_grab_move(c, &view, 7, to));
         }, true},
        {"owner", [](drape_cloth* c) {
             drape_owner o{};
             drape_owner_default(&o);
             o.position[0] = 0.2f;
             EXPECT_DRAPE_OK(drape_cloth_set_owner(c, &o));
         }, true},
        {"positions", [](drape_cloth* c) {
             std::vector<float> x = positions(c);
             x[3 * 300 + 2] += 0.05f;
             EXPECT_DRAPE_OK(drape_cloth_set_positions(c, x.data(), uint32_t(x.size() / 3)));
         }, true},
        {"velocities", [n](drape_cloth* c) {
             std::vector<float> v(size_t(n) * n * 3, 0.0f);
             v[3 * 300 + 2] = 1;
             EXPECT_DRAPE_OK(drape_cloth_set_velocities(c, v.data(), uint32_t(v.size() / 3)));
         }, true},
        {"inverse masses", [n](drape_cloth* c) {
             std::vector<float> inv(size_t(n) * n, 1.0f / (0.2f / float(n * n)));
             inv[0] = inv[n - 1] = 0;
             EXPECT_DRAPE_OK(drape_cloth_set_inverse_masses(c, inv.data(), uint32_t(inv.size())));
         }, false},
        {"wake", [](drape_cloth* c) { EXPECT_DRAPE_OK(drape_cloth_wake(c)); }, false},
    };
    for (const Source& src : sources) {
        WorldPtr w = make_world();
        drape_cloth* c = hanging(w.get(), n);
        drape_owner o{};
        drape_owner_default(&o);
        ASSERT_DRAPE_OK(drape_cloth_set_owner(c, &o));  // first call only records
        ASSERT_GT(step_until_asleep(c), 0) << src.name;
        const std::vector<float> before = positions(c);
        src.change(c);
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60)) << src.name;
        const drape_stats s = stats_of(c);
        EXPECT_EQ(s.sleeping, 0u) << src.name;
        EXPECT_GT(s.substeps, 0u) << src.name;
        if (src.moves) EXPECT_NE(0, std::memcmp(before.data(), positions(c).data(), before.size() * 4)) << src.name;
    }
}

TEST(Sleep, UnchangedResendsDoNotWake) {
    WorldPtr w = make_world();
    drape_cloth* c = hanging(w.get());
    drape_collider s{};
    s.struct_size = sizeof s;
    s.position[1] = -5;
    s.rotation[3] = 1;
    s.size[0] = 0.1f;
    ASSERT_DRAPE_OK(drape_cloth_set_colliders(c, &s, 1));
    ASSERT_GT(step_until_asleep(c), 0);
    for (int f = 0; f < 10; ++f) {
        // What a host does every frame for a static scene.
        ASSERT_DRAPE_OK(drape_cloth_set_colliders(c, &s, 1));
        drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), 23, {1, 0, 0}}};
        ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
        drape_params p = params_of(c);
        ASSERT_DRAPE_OK(drape_cloth_set_params(c, &p));
        drape_cloth_drag(c, nullptr, nullptr, 0);  // refused (NULL view): no effect
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        EXPECT_EQ(stats_of(c).sleeping, 1u);
    }
}
