// R13 (accuracy.md) scenes for the rest-state tests of every backend: a sheet pinned along two
// opposite edges, a curtain pinned along its top row (and a cloth hanging from two corners), with
// their double-precision Newton equilibrium (tests/bench/reference.h: same stencil, rest lengths,
// masses and pins) and the error measures the tests hold them to.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "../bench/reference.h"
#include "drape_test_util.h"

namespace drape_test {

enum class Scene { Sheet, Curtain, TwoCorners };

struct RestScene {
    Scene scene;
    uint32_t n;             ///< n x n vertices, 1 m x 1 m
    float stiffness_scale;  ///< times the default 2000 / 1000 / 200 N/m
    float heavy = 1;        ///< mass of the heaviest vertex over the others' (bottom middle / centre)
    float mass = 0.5f;      ///< kg, the cloth without the heavy vertex's extra
    uint32_t substeps = 0;  ///< 0: the default budget
    uint32_t iterations = 0;
};

inline bool pinned(const RestScene& s, uint32_t c, uint32_t r) {
    if (s.scene == Scene::Sheet) return c == 0 || c == s.n - 1;
    if (s.scene == Scene::Curtain) return r == 0;
    return r == 0 && (c == 0 || c == s.n - 1);
}

struct RestSetup {
    WorldPtr world;
    drape_cloth* cloth = nullptr;
    std::vector<double> rest, mass;  ///< reference input: rest positions, masses (0 = pinned)
    std::vector<bench::RefSpring> springs;
};

/// The cloth (uniform masses set explicitly, pins as inverse mass 0) and the reference's input.
inline RestSetup make_scene(const RestScene& s, drape_model model, drape_backend backend) {
    RestSetup out;
    out.world = make_world(2);
    drape_grid_desc g = grid_desc(s.n, s.n, 1, 1);  // +x columns; rows along -z (sheet) or -y
    if (s.scene != Scene::Sheet) {
        g.axis_v[1] = -1;
        g.axis_v[2] = 0;
    }
    out.cloth = make_grid(out.world.get(), g, s.mass, backend);
    const uint32_t count = s.n * s.n;
    const double m = double(s.mass) / count;
    std::vector<float> w(count);
    out.mass.resize(count);
    out.rest.resize(3 * size_t(count));
    const uint32_t heavy = s.scene == Scene::Curtain ? (s.n - 1) * s.n + s.n / 2 : (s.n / 2) * s.n + s.n / 2;
    const double spacing = 1.0 / (s.n - 1);
    for (uint32_t r = 0; r < s.n; ++r)
        for (uint32_t c = 0; c < s.n; ++c) {
            const uint32_t v = r * s.n + c;
            out.mass[v] = pinned(s, c, r) ? 0.0 : v == heavy ? m * s.heavy : m;
            w[v] = out.mass[v] > 0 ? float(1.0 / out.mass[v]) : 0.0f;
            out.rest[3 * v] = c * spacing;
            out.rest[3 * v + (s.scene == Scene::Sheet ? 2 : 1)] = -double(r) * spacing;
        }
    EXPECT_DRAPE_OK(drape_cloth_set_inverse_masses(out.cloth, w.data(), count));
    drape_params p{};
    EXPECT_DRAPE_OK(drape_params_default(&p));
    p.model = model;
    p.substeps = s.substeps;
    p.iterations = s.iterations;
    for (float& k : p.stiffness) k *= s.stiffness_scale;
    p.air_drag = 3;  // settles within a few seconds; no force at rest, so the rest state is the same
    p.max_stretch = 0;  // the springs alone (tethers would only add a one-sided limit)
    EXPECT_DRAPE_OK(drape_cloth_set_params(out.cloth, &p));
    const double k[3] = {p.stiffness[0], p.stiffness[1], p.stiffness[2]};
    out.springs = bench::grid_springs(s.n, s.n, spacing, spacing, k);
    return out;
}

inline std::vector<double> newton_reference(const RestSetup& s) {
    std::vector<double> x = s.rest;
    const double g[3] = {0, -9.81, 0};
    const double residual = bench::solve_static(x, s.mass, s.springs, g);
    EXPECT_LT(residual, 1e-6) << "reference did not converge";
    return x;
}

/// Steps until no vertex moves more than 1e-7 m in a step (at most `seconds`).
inline void settle(drape_cloth* c, float seconds) {
    std::vector<float> last = positions(c);
    for (int f = 0; f < int(seconds * 60); ++f) {
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
        const std::vector<float> now = positions(c);
        float moved = 0;
        for (size_t i = 0; i < now.size(); ++i) moved = std::max(moved, std::fabs(now[i] - last[i]));
        if (moved < 1e-7f) return;
        last = now;
    }
}

struct RestError {
    double vertex;  ///< max |x - x_ref| over the largest displacement of the reference from rest
    double lowest;  ///< error of the lowest point's displacement, relative
    /// What float positions resolve, relative like vertex: one float step at the largest coordinate.
    /// A stiff cloth stretches by about a hundred steps (33^2 curtain at 1e5 N/m: 1.35e-5 m, a step
    /// 1.19e-7 m, 0.88 %), and a step's change of a spring's length changes its force (k x step,
    /// 0.012 N) by more than a particle's weight (0.0045 N): its rest state lands within about a
    /// step of the reference, on whichever float its rounding gives.
    double floor;
};

inline RestError rest_error(const std::vector<float>& x, const std::vector<double>& ref, const std::vector<double>& rest) {
    double worst = 0, largest = 0, low = 0, low_ref = 0, low_rest = 0;
    float coordinate = 0;
    for (double r : ref) coordinate = std::max(coordinate, std::fabs(float(r)));
    for (size_t v = 0; v < ref.size() / 3; ++v) {
        double d = 0, disp = 0;
        for (int a = 0; a < 3; ++a) {
            d += (x[3 * v + a] - ref[3 * v + a]) * (x[3 * v + a] - ref[3 * v + a]);
            disp += (ref[3 * v + a] - rest[3 * v + a]) * (ref[3 * v + a] - rest[3 * v + a]);
        }
        worst = std::max(worst, std::sqrt(d));
        largest = std::max(largest, std::sqrt(disp));
        if (ref[3 * v + 1] < low_ref) {
            low_ref = ref[3 * v + 1];
            low = x[3 * v + 1];
            low_rest = rest[3 * v + 1];
        }
    }
    const double step = std::nextafter(coordinate, 2 * coordinate) - coordinate;
    return {worst / largest, std::fabs(low - low_ref) / std::fabs(low_ref - low_rest), step / largest};
}

inline const char* scene_name(Scene s) {
    return s == Scene::Sheet ? "sheet, two edges" : s == Scene::Curtain ? "curtain, top row" : "two corners";
}

}  // namespace drape_test
