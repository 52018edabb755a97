// Small RAII helpers so tests read like the scene they build.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "drape/drape.h"

#define ASSERT_DRAPE_OK(call) ASSERT_EQ((call), DRAPE_OK) << drape_last_error()
#define EXPECT_DRAPE_OK(call) EXPECT_EQ((call), DRAPE_OK) << drape_last_error()

namespace drape_test {

struct WorldDeleter {
    void operator()(drape_world* w) const { drape_world_destroy(w); }
};
using WorldPtr = std::unique_ptr<drape_world, WorldDeleter>;

inline WorldPtr make_world(uint32_t threads = 2) {
    drape_world_desc d{sizeof d, threads};
    drape_world* w = nullptr;
    EXPECT_EQ(drape_world_create(&d, &w), DRAPE_OK) << drape_last_error();
    return WorldPtr(w);
}

inline drape_grid_desc grid_desc(uint32_t cols, uint32_t rows, float width, float height) {
    drape_grid_desc g{};
    g.struct_size = sizeof g;
    g.columns = cols;
    g.rows = rows;
    g.width = width;
    g.height = height;
    return g;
}

/// A grid cloth running `model`. Tests name their model rather than take the library's default,
/// so a change of default changes only the tests about the default; XPBD is the one most tests
/// about other things (collision, drag, backends, the Unity plug-in) were written and tuned for.
inline drape_cloth* make_grid(drape_world* w, const drape_grid_desc& g, float mass,
                              drape_backend backend = DRAPE_BACKEND_CPU, drape_model model = DRAPE_MODEL_XPBD) {
    drape_cloth_desc d{sizeof d, uint32_t(backend), mass};
    drape_cloth* c = nullptr;
    EXPECT_EQ(drape_cloth_create_grid(w, &d, &g, &c), DRAPE_OK) << drape_last_error();
    if (!c) return c;
    drape_params p{};
    p.struct_size = sizeof p;
    EXPECT_EQ(drape_cloth_get_params(c, &p), DRAPE_OK) << drape_last_error();
    p.model = model;
    EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_OK) << drape_last_error();
    return c;
}

/// A vertical chain: `links` springs of rest length `rest` hanging down -y from the origin,
/// vertex 0 pinned at the top (accuracy.md R4). Grid with one column: structural springs
/// between neighbours, bend springs two apart (switched off by the caller's stiffness).
inline drape_cloth* make_chain(drape_world* w, uint32_t links, float rest, float particle_mass,
                               drape_backend backend = DRAPE_BACKEND_CPU) {
    drape_grid_desc g = grid_desc(1, links + 1, 1.0f, rest * float(links));
    g.axis_v[1] = -1.0f;
    g.axis_u[0] = 1.0f;
    drape_cloth* c = make_grid(w, g, particle_mass * float(links + 1), backend);
    std::vector<float> inv(links + 1, 1.0f / particle_mass);
    inv[0] = 0.0f;
    EXPECT_EQ(drape_cloth_set_inverse_masses(c, inv.data(), uint32_t(inv.size())), DRAPE_OK) << drape_last_error();
    return c;
}

/// A collider at (x, y, z), unrotated, size (s0, s1, s2) as drape_collider_shape says; 1 cm margin,
/// friction 0.5.
inline drape_collider collider(drape_collider_shape shape, float x, float y, float z, float s0 = 0, float s1 = 0,
                               float s2 = 0) {
    drape_collider c{};
    c.struct_size = sizeof c;
    c.shape = shape;
    c.position[0] = x;
    c.position[1] = y;
    c.position[2] = z;
    c.rotation[3] = 1;
    c.size[0] = s0;
    c.size[1] = s1;
    c.size[2] = s2;
    c.margin = 0.01f;
    c.friction = 0.5f;
    return c;
}

inline std::vector<float> positions(const drape_cloth* c) {
    drape_cloth_info info{sizeof info};
    drape_cloth_get_info(c, &info);
    std::vector<float> out(size_t(info.vertex_count) * 3);
    drape_vertex_layout l{sizeof l, 12, 0, -1};
    EXPECT_EQ(drape_cloth_read(c, &l, out.data(), out.size() * sizeof(float)), DRAPE_OK) << drape_last_error();
    return out;
}

inline drape_params params_of(const drape_cloth* c) {
    drape_params p{};
    drape_cloth_get_params(c, &p);
    return p;
}

inline drape_stats stats_of(const drape_cloth* c) {
    drape_stats s{sizeof s};
    drape_cloth_get_stats(c, &s);
    return s;
}

}  // namespace drape_test
