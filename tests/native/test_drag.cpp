// Touch drag (paper section IV, eq. 9 with the exponent's sign restored) and pick-and-hold grabs.
#include <cmath>
#include <cstring>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

// Identity world/view/projection: sim (x, y) in [-1, 1] maps to pixel ((x+1)*100, (y+1)*100) in a
// 200 x 200 viewport; NDC depth = z. Easy to compute by hand.
drape_view ortho_view() {
    drape_view v{};
    v.struct_size = sizeof v;
    for (int k = 0; k < 16; k += 5) v.world[k] = v.view[k] = v.projection[k] = 1;
    v.viewport[0] = v.viewport[1] = 200;
    return v;
}

// A perspective camera at (0, 0, 3) looking down -z (OpenGL), 60 degree fov, 400 x 300 px, and a
// world matrix that moves the cloth by (0.2, 0, 0) and scales it by 1 (sim -> world).
drape_view perspective_view() {
    drape_view v{};
    v.struct_size = sizeof v;
    for (int k = 0; k < 16; k += 5) v.world[k] = v.view[k] = 1;
    v.world[12] = 0.2f;
    v.view[14] = -3;  // world -> camera: translate by -3 in z
    const float aspect = 400.0f / 300.0f, f = 1.0f / std::tan(0.5f * 1.0471976f), zn = 0.1f, zf = 100;
    v.projection[0] = f / aspect;
    v.projection[5] = f;
    v.projection[10] = (zf + zn) / (zn - zf);
    v.projection[11] = -1;
    v.projection[14] = 2 * zf * zn / (zn - zf);
    v.viewport[0] = 400;
    v.viewport[1] = 300;
    return v;
}

// Column-major 4x4 times (x, y, z, 1).
void mul(const float* m, const float* p, double out[4]) {
    for (int r = 0; r < 4; ++r) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

// Pixel position of a sim-space point (test's own projection).
void project(const drape_view& v, const float* p, double px[2]) {
    double a[4], b[4], c[4];
    mul(v.world, p, a);
    const float fa[3] = {float(a[0]), float(a[1]), float(a[2])};
    mul(v.view, fa, b);
    const float fb[3] = {float(b[0]), float(b[1]), float(b[2])};
    mul(v.projection, fb, c);
    px[0] = (c[0] / c[3] * 0.5 + 0.5) * v.viewport[0];
    px[1] = (c[1] / c[3] * 0.5 + 0.5) * v.viewport[1];
}

// A 41 x 41 cloth in the z = 0 plane, x and y in [-1, 1] (pixels 0..200 in steps of 5), with no
// springs, gravity or drag: each vertex moves exactly by what the touch gives it.
drape_cloth* free_plane(drape_world* w) {
    drape_grid_desc g = grid_desc(41, 41, 2, 2);
    g.origin[0] = -1;
    g.origin[1] = -1;
    g.axis_u[0] = 1;
    g.axis_v[1] = 1;
    drape_cloth* c = make_grid(w, g, 1);
    drape_params p{};
    drape_params_default(&p);
    p.model = DRAPE_MODEL_XPBD;
    p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 0;
    p.gravity[1] = 0;
    p.air_drag = 0;
    p.damping = 0;
    EXPECT_DRAPE_OK(drape_cloth_set_params(c, &p));
    return c;
}

}  // namespace

// Falloff shape and direction against hand-computed values. Touch at pixel (100, 100) (sim
// origin), motion (10, 0) px = 0.1 m along +x. c = min(1, 200 exp(-r^2/600)):
//   r = 0, 50, 55 px: 1 (clamped: 200 e^-4.17 = 3.1, 200 e^-5.04 = 1.29);
//   r = 60: 200 e^-6 = 0.4958;  r = 65: 200 e^-7.042 = 0.1750;  r = 70: 200 e^-8.167 = 0.0568;
//   r = 80: 200 e^-10.67 = 0.00466;  r = 100: 200 e^-16.67 = 1.2e-5.
TEST(Drag, FalloffAndDirectionMatchEquation9) {
    WorldPtr w = make_world();
    drape_cloth* c = free_plane(w.get());
    const std::vector<float> x0 = positions(c);
    drape_view view = ortho_view();
    drape_touch t{};
    ASSERT_DRAPE_OK(drape_touch_default(&t));
    EXPECT_EQ(t.amplitude, 200.0f);
    EXPECT_EQ(t.sigma, 300.0f);
    t.position[0] = t.position[1] = 100;
    t.motion[0] = 10;
    ASSERT_DRAPE_OK(drape_cloth_drag(c, &view, &t, 1));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    const std::vector<float> x = positions(c);
    // Vertices along the +y axis from the touch: column 20, row 20 + k (5 px per row).
    struct Expect {
        int pixels;
        float c;
    } table[] = {{0, 1}, {50, 1}, {55, 1}, {60, 0.4958f}, {65, 0.1750f}, {70, 0.0568f}, {80, 0.00466f}, {100, 1.2e-5f}};
    for (const Expect& e : table) {
        const uint32_t v = uint32_t(20 + e.pixels / 5) * 41 + 20;
        const float dx = x[3 * v] - x0[3 * v];
        EXPECT_NEAR(dx, 0.1f * e.c, 2e-4f * e.c + 1e-6f) << "r = " << e.pixels << " px";
        EXPECT_NEAR(x[3 * v + 1], x0[3 * v + 1], 1e-6f) << "moves along the finger only";
        EXPECT_EQ(x[3 * v + 2], x0[3 * v + 2]) << "depth kept";
    }
    // Monotone decrease with distance in every direction; nothing beyond 120 px moves.
    for (uint32_t v = 0; v < 41 * 41; ++v) {
        const float r = 100.0f * std::hypot(x0[3 * v], x0[3 * v + 1]);
        const float dx = x[3 * v] - x0[3 * v];
        EXPECT_GE(dx, 0.0f);
        if (r > 120) EXPECT_EQ(dx, 0.0f) << v;
    }
    // Sign: motion the other way moves the other way.
    t.motion[0] = 0;
    t.motion[1] = -10;
    const std::vector<float> x1 = positions(c);
    ASSERT_DRAPE_OK(drape_cloth_set_velocities(c, std::vector<float>(x1.size(), 0.0f).data(), uint32_t(x1.size() / 3)));
    ASSERT_DRAPE_OK(drape_cloth_drag(c, &view, &t, 1));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    const std::vector<float> x2 = positions(c);
    const uint32_t centre = 20 * 41 + 20;
    EXPECT_NEAR(x2[3 * centre + 1] - x1[3 * centre + 1], -0.1f, 1e-5f);
}

// Two touches at once move two regions, each by its own finger.
TEST(Drag, SeveralTouches) {
    WorldPtr w = make_world();
    drape_cloth* c = free_plane(w.get());
    const std::vector<float> x0 = positions(c);
    drape_view view = ortho_view();
    drape_touch t[2];
    drape_touch_default(&t[0]);
    drape_touch_default(&t[1]);
    t[0].position[0] = 40, t[0].position[1] = 40, t[0].motion[1] = 5;      // sim (-0.6, -0.6): +y
    t[1].position[0] = 160, t[1].position[1] = 160, t[1].motion[0] = -8;   // sim (0.6, 0.6): -x
    ASSERT_DRAPE_OK(drape_cloth_drag(c, &view, t, 2));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    const std::vector<float> x = positions(c);
    const uint32_t a = 8 * 41 + 8, b = 32 * 41 + 32, mid = 20 * 41 + 20;
    EXPECT_NEAR(x[3 * a + 1] - x0[3 * a + 1], 0.05f, 1e-5f);
    EXPECT_NEAR(x[3 * a] - x0[3 * a], 0.0f, 1e-6f);
    EXPECT_NEAR(x[3 * b] - x0[3 * b], -0.08f, 1e-5f);
    EXPECT_NEAR(x[3 * b + 1] - x0[3 * b + 1], 0.0f, 1e-6f);
    // The centre (100, 100) px is r^2 = 7200 px^2 from both touches: c = 200 e^-12 = 1.229e-3, so it
    // moves by 5 c px = 6.14e-5 m in +y and 8 c px = 9.83e-5 m in -x.
    EXPECT_NEAR(x[3 * mid + 1] - x0[3 * mid + 1], 6.144e-5f, 1e-7f);
    EXPECT_NEAR(x[3 * mid] - x0[3 * mid], -9.831e-5f, 1e-7f);
}

// Perspective: the vertex under the finger moves so that its projection follows the finger,
// at its own depth (the motion is unprojected at the vertex's depth, through the world matrix).
TEST(Drag, PerspectiveUnprojectsAtTheVertexDepth) {
    WorldPtr w = make_world();
    drape_cloth* c = free_plane(w.get());
    const drape_view view = perspective_view();
    const std::vector<float> x0 = positions(c);
    const uint32_t v = 25 * 41 + 15;  // sim (-0.25, 0.25, 0)
    double p0[2];
    project(view, &x0[3 * v], p0);
    drape_touch t{};
    drape_touch_default(&t);
    t.position[0] = float(p0[0]);
    t.position[1] = float(p0[1]);
    t.motion[0] = 12;
    t.motion[1] = -7;
    ASSERT_DRAPE_OK(drape_cloth_drag(c, &view, &t, 1));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    const std::vector<float> x = positions(c);
    double p1[2];
    project(view, &x[3 * v], p1);
    EXPECT_NEAR(p1[0] - p0[0], 12, 0.01);
    EXPECT_NEAR(p1[1] - p0[1], -7, 0.01);
}

// Pick-and-hold: the grabbed vertex goes where the finger is (on screen, at its grab depth),
// pulls the cloth along, and falls freely once released.
TEST(Drag, GrabMovesAVertexUnderTheFinger) {
    WorldPtr w = make_world();
    drape_grid_desc g = grid_desc(21, 21, 1, 1);
    g.origin[0] = -0.5f;
    g.origin[1] = 0.5f;
    g.axis_u[0] = 1;
    g.axis_v[1] = -1;  // vertical cloth in z = 0
    drape_cloth* c = make_grid(w.get(), g, 0.2f);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {-0.5f, 0.5f, 0}}, {sizeof(drape_pin), 20, {0.5f, 0.5f, 0}}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    const drape_view view = perspective_view();
    const std::vector<float> x0 = positions(c);
    const uint32_t target = 20 * 21 + 10;  // bottom middle, sim (0, -0.5, 0)
    double p0[2];
    project(view, &x0[3 * target], p0);
    const float at[2] = {float(p0[0]) + 1, float(p0[1]) - 1};  // a pixel off (vertices ~4 px apart)
    uint32_t grabbed = 0;
    ASSERT_DRAPE_OK(drape_cloth_grab(c, &view, 1, at, 30, &grabbed));
    EXPECT_EQ(grabbed, target);
    const float far_away[2] = {5, 5};
    uint32_t none = 0;
    ASSERT_DRAPE_OK(drape_cloth_grab(c, &view, 2, far_away, 10, &none));
    EXPECT_EQ(none, UINT32_MAX);
    const float finger[2] = {float(p0[0]) + 60, float(p0[1]) + 40};
    ASSERT_DRAPE_OK(drape_cloth_grab_move(c, &view, 1, finger));
    for (int f = 0; f < 30; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    const std::vector<float> x = positions(c);
    double p1[2];
    project(view, &x[3 * target], p1);
    EXPECT_NEAR(p1[0], finger[0], 0.01);
    EXPECT_NEAR(p1[1], finger[1], 0.01);
    EXPECT_NEAR(x[3 * target + 2], 0.0f, 1e-4f) << "held at the depth it was grabbed at";
    // Its neighbour followed (the cloth is pulled along).
    EXPECT_GT(x[3 * (target - 21) + 1], x0[3 * (target - 21) + 1] + 0.05f);
    EXPECT_EQ(drape_cloth_grab_move(c, &view, 9, finger), DRAPE_ERROR_INVALID_ARGUMENT);
    ASSERT_DRAPE_OK(drape_cloth_grab_release(c, 1));
    for (int f = 0; f < 30; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    EXPECT_LT(positions(c)[3 * target + 1], x[3 * target + 1] - 0.05f) << "released: falls back";
}

TEST(Drag, BadInputIsRefused) {
    WorldPtr w = make_world();
    drape_cloth* c = free_plane(w.get());
    drape_view view = ortho_view();
    drape_touch t{};
    drape_touch_default(&t);
    EXPECT_EQ(drape_cloth_drag(c, nullptr, &t, 1), DRAPE_ERROR_NULL_POINTER);
    EXPECT_EQ(drape_cloth_drag(c, &view, nullptr, 1), DRAPE_ERROR_NULL_POINTER);
    drape_view bad = view;
    bad.projection[3] = NAN;
    EXPECT_EQ(drape_cloth_drag(c, &bad, &t, 1), DRAPE_ERROR_NOT_FINITE);
    bad = view;
    bad.projection[0] = 0;  // singular
    EXPECT_EQ(drape_cloth_drag(c, &bad, &t, 1), DRAPE_ERROR_INVALID_ARGUMENT);
    bad = view;
    bad.viewport[0] = 0;
    EXPECT_EQ(drape_cloth_drag(c, &bad, &t, 1), DRAPE_ERROR_INVALID_ARGUMENT);
    bad = view;
    bad.struct_size = 3;
    EXPECT_EQ(drape_cloth_drag(c, &bad, &t, 1), DRAPE_ERROR_STRUCT_SIZE);
    drape_touch bt = t;
    bt.sigma = 0;
    EXPECT_EQ(drape_cloth_drag(c, &view, &bt, 1), DRAPE_ERROR_INVALID_ARGUMENT);
    bt = t;
    bt.motion[0] = INFINITY;
    EXPECT_EQ(drape_cloth_drag(c, &view, &bt, 1), DRAPE_ERROR_NOT_FINITE);
    std::vector<drape_touch> many(17, t);
    EXPECT_EQ(drape_cloth_drag(c, &view, many.data(), 17), DRAPE_ERROR_INVALID_ARGUMENT);
    const float at[2] = {100, 100};
    uint32_t v;
    EXPECT_EQ(drape_cloth_grab(c, &view, 0, at, -1, &v), DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(drape_cloth_grab(c, &view, 0, nullptr, 5, &v), DRAPE_ERROR_NULL_POINTER);
    EXPECT_EQ(drape_cloth_grab(c, &view, 0, at, 5, nullptr), DRAPE_ERROR_NULL_POINTER);
    // Refused calls moved nothing.
    const std::vector<float> x0 = positions(c);
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    EXPECT_EQ(0, std::memcmp(x0.data(), positions(c).data(), x0.size() * 4));
}
