// Self-collision: a cloth folding onto itself does not pass through itself; off by
// default (bit-identical to never asking); threaded == single-threaded bit for bit; bad input.
// Pass-through and closeness are measured here with the test's own geometry, not the library's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "drape_test_util.h"
#ifdef DRAPE_TEST_GLES
#include "gles_test_util.h"
#endif

using namespace drape_test;

namespace {

// The fold scene. A cloth of `cols` x 33 vertices, 1 m along z (row spacing 1/32 m), hangs from
// its middle row (row 16, pinned along x at y = 1, z = 0). Half A (rows 0-15) starts horizontal
// towards +z, half B (rows 17-32) starts tilted 30 degrees down towards -z. Both swing down under
// gravity: A sweeps through the vertical plane under the pin line where B arrives, so without
// self-collision A swings straight through B; with it the halves meet and hang face to face.
constexpr uint32_t kRows = 33, kPinRow = 16;
constexpr float kRowSpacing = 1.0f / 32;
constexpr float kPinY = 1.0f;
constexpr float kThickness = 0.03f;  // about the particle spacing (3.1 cm along z, 3 cm along x)

drape_cloth* fold_cloth(drape_world* w, uint32_t cols, drape_backend backend, drape_model model = DRAPE_MODEL_XPBD) {
    const float width = 0.03f * float(cols - 1);
    drape_grid_desc g = grid_desc(cols, kRows, width, 1.0f);
    g.origin[1] = kPinY;
    g.origin[2] = 0.5f;  // axis_v = -z: row r at z = 0.5 - r/32
    drape_cloth* c = make_grid(w, g, 0.3f, backend, model);
    std::vector<float> x = positions(c);
    const float tilt = 30.0f * 3.14159265f / 180.0f;
    for (uint32_t r = kPinRow + 1; r < kRows; ++r)
        for (uint32_t col = 0; col < cols; ++col) {
            const float rho = float(r - kPinRow) * kRowSpacing;
            float* p = &x[3 * (r * cols + col)];
            p[1] = kPinY - rho * std::sin(tilt);
            p[2] = -rho * std::cos(tilt);
        }
    EXPECT_DRAPE_OK(drape_cloth_set_positions(c, x.data(), cols * kRows));
    std::vector<drape_pin> pins(cols);
    for (uint32_t col = 0; col < cols; ++col) {
        const uint32_t v = kPinRow * cols + col;
        pins[col] = drape_pin{sizeof(drape_pin), v, {x[3 * v], x[3 * v + 1], x[3 * v + 2]}};
    }
    EXPECT_DRAPE_OK(drape_cloth_set_pins(c, pins.data(), cols));
    return c;
}

drape_self_collision_desc self_desc(uint32_t enabled, float thickness, float friction = 0.0f) {
    drape_self_collision_desc d{};
    d.struct_size = sizeof d;
    d.enabled = enabled;
    d.thickness = thickness;
    d.friction = friction;
    return d;
}

// Angle of a point about the pin line (the x axis through y = kPinY), 0 straight down, +90
// degrees towards +z (where half A starts), -60 degrees where half B starts.
float swing_angle(const float* p) { return std::atan2(p[2], kPinY - p[1]); }

struct FoldMeasure {
    uint32_t wrong_side = 0;   ///< mirror pairs (A row 16-k, B row 16+k, same column, k >= 2) in the wrong order
    uint32_t close_pairs = 0;  ///< non-neighbour pairs closer than thickness/2
    float min_distance = 1e30f;///< over non-neighbour pairs, m
};

// Non-neighbours: not joined by a spring of the 12-neighbour stencil and at least 1.5 thickness
// apart in the rest grid (the pairs the library is asked to keep apart).
bool non_neighbours(uint32_t ca, uint32_t ra, uint32_t cb, uint32_t rb) {
    const int dc = std::abs(int(ca) - int(cb)), dr = std::abs(int(ra) - int(rb));
    if ((dc <= 1 && dr <= 1) || (dc == 2 && dr == 0) || (dc == 0 && dr == 2)) return false;
    const float dx = 0.03f * float(dc), dz = kRowSpacing * float(dr);
    return dx * dx + dz * dz >= (1.5f * kThickness) * (1.5f * kThickness);
}

FoldMeasure measure_fold(const std::vector<float>& x, uint32_t cols) {
    FoldMeasure m;
    for (uint32_t k = 2; k <= kPinRow; ++k)
        for (uint32_t col = 0; col < cols; ++col) {
            const float a = swing_angle(&x[3 * ((kPinRow - k) * cols + col)]);
            const float b = swing_angle(&x[3 * ((kPinRow + k) * cols + col)]);
            if (a < b) ++m.wrong_side;
        }
    const uint32_t n = cols * kRows;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = i + 1; j < n; ++j) {
            if (!non_neighbours(i % cols, i / cols, j % cols, j / cols)) continue;
            const float dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1], dz = x[3 * i + 2] - x[3 * j + 2];
            const float dist = std::sqrt(dx * dx + dy * dy + dz * dz);
            m.min_distance = std::min(m.min_distance, dist);
            if (dist < 0.5f * kThickness) ++m.close_pairs;
        }
    return m;
}

struct FoldRun {
    FoldMeasure worst;  ///< max counts / min distance over all frames
    FoldMeasure last;
    float max_strain = 0;
    double ms_per_step = 0;
};

FoldRun run_fold(bool self_collision, uint32_t cols, int frames, drape_backend backend = DRAPE_BACKEND_CPU,
                 float friction = 0.0f, drape_model model = DRAPE_MODEL_XPBD) {
    WorldPtr w = make_world();
    drape_cloth* c = fold_cloth(w.get(), cols, backend, model);
    if (self_collision) {
        const drape_self_collision_desc d = self_desc(1, kThickness, friction);
        EXPECT_DRAPE_OK(drape_cloth_set_self_collision(c, &d));
    }
    FoldRun run;
    for (int f = 0; f < frames; ++f) {
        EXPECT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        const drape_stats s = stats_of(c);
        run.ms_per_step += s.step_ms;
        run.max_strain = std::max(run.max_strain, s.max_strain);
        const FoldMeasure m = measure_fold(positions(c), cols);
        run.worst.wrong_side = std::max(run.worst.wrong_side, m.wrong_side);
        run.worst.close_pairs = std::max(run.worst.close_pairs, m.close_pairs);
        run.worst.min_distance = std::min(run.worst.min_distance, m.min_distance);
        run.last = m;
    }
    run.ms_per_step /= frames;
    return run;
}

void print_fold(const char* name, const FoldRun& r, uint32_t cols) {
    std::printf("[ measured ] %-22s %ux%u: wrong-side mirror pairs max %u / end %u (of %u); pairs < t/2 max %u / "
                "end %u; min non-neighbour distance %.4f m (t = %.3f); max strain %.3f; %.3f ms/step\n",
                name, cols, kRows, r.worst.wrong_side, r.last.wrong_side, (kPinRow - 1) * cols, r.worst.close_pairs,
                r.last.close_pairs, r.worst.min_distance, kThickness, r.max_strain, r.ms_per_step);
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

// The fold: without self-collision half A swings through half B (the control shows the measure
// sees it); with it no mirror pair ever ends up on the wrong side and no two non-neighbour
// particles come closer than half the thickness, at any frame of 3 s. XPBD and the default
// (IMPLICIT, 2 substeps unless self-collision asks for more: the automatic budget keeps each
// particle's move per substep under a quarter of the thickness).
TEST(SelfCollision, FoldingClothDoesNotPassThroughItself) {
    for (drape_model model : {DRAPE_MODEL_XPBD, DRAPE_MODEL_AUTO}) {
    SCOPED_TRACE(model == DRAPE_MODEL_XPBD ? "XPBD" : "default");
    const uint32_t cols = 16;
    const FoldRun off = run_fold(false, cols, 180, DRAPE_BACKEND_CPU, 0.0f, model);
    const FoldRun on = run_fold(true, cols, 180, DRAPE_BACKEND_CPU, 0.0f, model);
    const FoldRun on_friction = run_fold(true, cols, 180, DRAPE_BACKEND_CPU, 0.3f, model);
    print_fold("without self-collision", off, cols);
    print_fold("with self-collision", on, cols);
    print_fold("with, friction 0.3", on_friction, cols);
    // The control: the halves pass through each other.
    EXPECT_GT(off.worst.wrong_side, (kPinRow - 1) * cols / 2);
    EXPECT_GT(off.worst.close_pairs, 0u);
    for (const FoldRun* r : {&on, &on_friction}) {
        EXPECT_EQ(r->worst.wrong_side, 0u);
        EXPECT_EQ(r->worst.close_pairs, 0u);
        EXPECT_GE(r->worst.min_distance, 0.5f * kThickness);
        EXPECT_LT(r->max_strain, 0.2f);  // sanity: the contact does not tear the cloth apart
    }
    }
}

// Off by default: a cloth that never heard of self-collision, one told "off" (with a thickness
// and friction), and one switched on and off again before stepping give the same bits, with
// colliders and pins in the scene. A new cloth reports enabled 0, thickness 0, friction 0.
TEST(SelfCollision, OffByDefaultIsBitIdentical) {
    const uint32_t cols = 16;
    std::vector<float> result[3];
    for (int variant = 0; variant < 3; ++variant) {
        WorldPtr w = make_world();
        drape_cloth* c = fold_cloth(w.get(), cols, DRAPE_BACKEND_CPU);
        drape_self_collision_desc got{};
        got.struct_size = sizeof got;
        ASSERT_DRAPE_OK(drape_cloth_get_self_collision(c, &got));
        EXPECT_EQ(got.enabled, 0u);
        EXPECT_EQ(got.thickness, 0.0f);
        EXPECT_EQ(got.friction, 0.0f);
        if (variant == 1) {
            const drape_self_collision_desc off = self_desc(0, kThickness, 0.4f);
            ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &off));
        } else if (variant == 2) {
            const drape_self_collision_desc on = self_desc(1, kThickness), off = self_desc(0, kThickness);
            ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &on));
            ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &off));
        }
        drape_collider plane{};
        plane.struct_size = sizeof plane;
        plane.shape = DRAPE_COLLIDER_PLANE;
        plane.position[1] = 0.5f;
        plane.rotation[3] = 1;
        plane.margin = 0.01f;
        plane.friction = 0.5f;
        ASSERT_DRAPE_OK(drape_cloth_set_colliders(c, &plane, 1));
        for (int f = 0; f < 90; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        result[variant] = positions(c);
    }
    EXPECT_TRUE(same_bits(result[0], result[1])) << "set off (with a thickness) changed the result";
    EXPECT_TRUE(same_bits(result[0], result[2])) << "on then off changed the result";
}

// CPU_THREADED splits the gather over the pool; each particle's correction is a sum in the hash's
// fixed order, so the bits match the single-threaded backend. 64 x 33 = 2112 particles (above
// ThreadPool::kMinParallelCount, so the passes really split over 4 threads); 1.5 s covers the
// impact. The run must differ from one without self-collision (contacts happened).
TEST(SelfCollision, ThreadedMatchesSingleThreadedBitForBit) {
    const uint32_t cols = 64;
    std::vector<float> result[3];
    const drape_backend backends[3] = {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED, DRAPE_BACKEND_CPU};
    for (int k = 0; k < 3; ++k) {
        WorldPtr w = make_world(4);
        drape_cloth* c = fold_cloth(w.get(), cols, backends[k]);
        const drape_self_collision_desc d = self_desc(k < 2 ? 1 : 0, kThickness, 0.2f);
        ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &d));
        for (int f = 0; f < 90; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        result[k] = positions(c);
    }
    EXPECT_TRUE(same_bits(result[0], result[1])) << "CPU_THREADED differs from CPU with self-collision on";
    EXPECT_FALSE(same_bits(result[0], result[2])) << "self-collision made no difference: no contacts?";
}

// Every bad input gets its status and leaves the setting as it was.
TEST(SelfCollision, BadInputIsRefusedAndChangesNothing) {
    WorldPtr w = make_world();
    drape_cloth* c = fold_cloth(w.get(), 16, DRAPE_BACKEND_CPU);  // rest diagonal 1.09 m: max thickness 0.27 m
    const drape_self_collision_desc good = self_desc(1, kThickness, 0.25f);
    ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &good));

    EXPECT_EQ(drape_cloth_set_self_collision(nullptr, &good), DRAPE_ERROR_NULL_POINTER);
    EXPECT_EQ(drape_cloth_set_self_collision(reinterpret_cast<drape_cloth*>(w.get()), &good),
              DRAPE_ERROR_INVALID_HANDLE);
    EXPECT_EQ(drape_cloth_set_self_collision(c, nullptr), DRAPE_ERROR_NULL_POINTER);
    struct Case {
        drape_self_collision_desc d;
        drape_status expected;
        const char* what;
    };
    drape_self_collision_desc wrong_size = self_desc(1, 0.05f);
    wrong_size.struct_size = sizeof wrong_size - 4;
    const Case cases[] = {
        {wrong_size, DRAPE_ERROR_STRUCT_SIZE, "struct_size"},
        {self_desc(2, 0.05f), DRAPE_ERROR_INVALID_ARGUMENT, "enabled = 2"},
        {self_desc(1, NAN), DRAPE_ERROR_NOT_FINITE, "NaN thickness"},
        {self_desc(1, INFINITY), DRAPE_ERROR_NOT_FINITE, "infinite thickness"},
        {self_desc(0, NAN), DRAPE_ERROR_NOT_FINITE, "NaN thickness, disabled"},
        {self_desc(1, 0.05f, NAN), DRAPE_ERROR_NOT_FINITE, "NaN friction"},
        {self_desc(1, -0.01f), DRAPE_ERROR_INVALID_ARGUMENT, "negative thickness"},
        {self_desc(0, -0.01f), DRAPE_ERROR_INVALID_ARGUMENT, "negative thickness, disabled"},
        {self_desc(1, 0.0f), DRAPE_ERROR_INVALID_ARGUMENT, "zero thickness, enabled"},
        {self_desc(1, 0.3f), DRAPE_ERROR_INVALID_ARGUMENT, "thickness above a quarter of the cloth"},
        {self_desc(1, 1e30f), DRAPE_ERROR_INVALID_ARGUMENT, "absurd thickness"},
        {self_desc(1, 0.05f, -0.1f), DRAPE_ERROR_INVALID_ARGUMENT, "negative friction"},
        {self_desc(1, 0.05f, 11.0f), DRAPE_ERROR_INVALID_ARGUMENT, "friction above 10"},
    };
    for (const Case& k : cases) {
        EXPECT_EQ(drape_cloth_set_self_collision(c, &k.d), k.expected) << k.what;
        EXPECT_STRNE(drape_last_error(), "") << k.what;
        drape_self_collision_desc got{};
        got.struct_size = sizeof got;
        ASSERT_DRAPE_OK(drape_cloth_get_self_collision(c, &got));
        EXPECT_EQ(got.enabled, 1u) << k.what;
        EXPECT_EQ(got.thickness, kThickness) << k.what;
        EXPECT_EQ(got.friction, 0.25f) << k.what;
    }
    drape_self_collision_desc out{};
    EXPECT_EQ(drape_cloth_get_self_collision(c, &out), DRAPE_ERROR_STRUCT_SIZE);  // struct_size 0
    EXPECT_EQ(drape_cloth_get_self_collision(c, nullptr), DRAPE_ERROR_NULL_POINTER);
    EXPECT_EQ(drape_cloth_get_self_collision(nullptr, &out), DRAPE_ERROR_NULL_POINTER);
    // Edge values are accepted: disabled with thickness 0, the largest thickness, friction 10.
    const drape_self_collision_desc zero_off = self_desc(0, 0.0f), edge = self_desc(1, 0.27f, 10.0f);
    EXPECT_DRAPE_OK(drape_cloth_set_self_collision(c, &zero_off));
    EXPECT_DRAPE_OK(drape_cloth_set_self_collision(c, &edge));
    ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
}

#ifdef DRAPE_TEST_GLES
class SelfCollisionGles : public WithHeadlessGles<> {};

// GLES, XPBD and the default (IMPLICIT): the same fold and the same criterion as on the CPU (whose
// test has the control without self-collision and the frictional case; MatchesCpu below has friction).
TEST_F(SelfCollisionGles, FoldingClothDoesNotPassThroughItself) {
    for (drape_model model : {DRAPE_MODEL_XPBD, DRAPE_MODEL_AUTO}) {
        SCOPED_TRACE(model == DRAPE_MODEL_XPBD ? "XPBD" : "default");
        const uint32_t cols = 16;
        const FoldRun on = run_fold(true, cols, 180, DRAPE_BACKEND_GLES, 0.0f, model);
        print_fold(model == DRAPE_MODEL_XPBD ? "GLES XPBD with" : "GLES default with", on, cols);
        EXPECT_EQ(on.worst.wrong_side, 0u);
        EXPECT_EQ(on.worst.close_pairs, 0u);
        EXPECT_GE(on.worst.min_distance, 0.5f * kThickness);
        EXPECT_LT(on.max_strain, 0.2f);
    }
}

static float max_distance(const std::vector<float>& a, const std::vector<float>& b) {
    float worst = 0;
    for (size_t k = 0; k + 2 < a.size(); k += 3) {
        const float dx = a[k] - b[k], dy = a[k + 1] - b[k + 1], dz = a[k + 2] - b[k + 2];
        worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    return worst;
}

// GLES against the CPU (both XPBD, 16 substeps, friction 0.3) on the fold for 1.5 s, through the
// halves' first contact. Not bit parity (the GPU visits a particle's contacts in another order and
// rounds differently), but the same physics: the largest vertex distance GLES-CPU stays within
// 1 mm (a thirtieth of the thickness), while self-collision moves the cloth by decimetres (CPU
// with against without) in the same time.
TEST_F(SelfCollisionGles, MatchesCpu) {
    const uint32_t cols = 16;
    const int frames = 90;
    WorldPtr w = make_world();
    // CPU without, CPU with, GLES with self-collision.
    const drape_backend backend[3] = {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU, DRAPE_BACKEND_GLES};
    drape_cloth* cloths[3];
    for (int k = 0; k < 3; ++k) {
        cloths[k] = fold_cloth(w.get(), cols, backend[k]);
        const drape_self_collision_desc d = self_desc(k > 0 ? 1 : 0, kThickness, 0.3f);
        ASSERT_DRAPE_OK(drape_cloth_set_self_collision(cloths[k], &d));
    }
    float gles_cpu = 0, effect = 0;
    for (int f = 0; f < frames; ++f) {
        std::vector<float> x[3];
        for (int k = 0; k < 3; ++k) {
            ASSERT_DRAPE_OK(drape_cloth_step(cloths[k], 1.0f / 60));
            x[k] = positions(cloths[k]);
        }
        gles_cpu = std::max(gles_cpu, max_distance(x[1], x[2]));
        effect = std::max(effect, max_distance(x[0], x[1]));
    }
    std::printf("[ measured ] fold %ux%u, %d frames: largest GLES-CPU vertex distance %.2e m; self-collision's "
                "effect (CPU with vs without) %.3f m; thickness %.3f m\n",
                cols, kRows, frames, gles_cpu, effect, kThickness);
    EXPECT_GT(effect, 0.1f) << "no contact in the compared time";
    EXPECT_LT(gles_cpu, 1e-3f);
}
#endif
