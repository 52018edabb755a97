// Arbitrary triangle meshes: welding of split seam vertices, springs from edges, output to every
// copy of a welded vertex.
#include <cmath>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

struct Mesh {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
};

// An n x n vertex grid in the xz plane as a triangle mesh. With `seam`, the vertices of column
// `seam` are duplicated (as Unity does at a UV seam): triangles left of the seam use the originals,
// triangles right of it the copies, which come after all other vertices.
Mesh grid_mesh(uint32_t n, uint32_t seam = 0) {
    Mesh m;
    for (uint32_t r = 0; r < n; ++r)
        for (uint32_t c = 0; c < n; ++c) m.positions.insert(m.positions.end(), {float(c) / (n - 1), 0, -float(r) / (n - 1)});
    auto copy_of = [&](uint32_t r) { return n * n + r; };
    if (seam)
        for (uint32_t r = 0; r < n; ++r) m.positions.insert(m.positions.end(), {float(seam) / (n - 1), 0, -float(r) / (n - 1)});
    for (uint32_t r = 0; r + 1 < n; ++r)
        for (uint32_t c = 0; c + 1 < n; ++c) {
            uint32_t v00 = r * n + c, v10 = v00 + 1, v01 = v00 + n, v11 = v01 + 1;
            if (seam && c == seam) v00 = copy_of(r), v01 = copy_of(r + 1);  // right of the seam
            m.indices.insert(m.indices.end(), {v00, v01, v10, v10, v01, v11});
        }
    return m;
}

drape_cloth* make_mesh(drape_world* w, const Mesh& m, float weld = 0) {
    drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 0.5f};
    drape_mesh_desc md{sizeof md, uint32_t(m.positions.size() / 3), m.positions.data(), uint32_t(m.indices.size()),
                       m.indices.data(), weld};
    drape_cloth* c = nullptr;
    EXPECT_EQ(drape_cloth_create_mesh(w, &d, &md, &c), DRAPE_OK) << drape_last_error();
    return c;
}

void hang_and_step(drape_cloth* c, uint32_t n, int frames) {
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), n - 1, {1, 0, 0}}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    for (int f = 0; f < frames; ++f) ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
}

}  // namespace

TEST(Mesh, EdgesBecomeStructuralAndOppositeCornersBend) {
    WorldPtr w = make_world();
    drape_cloth* c = make_mesh(w.get(), grid_mesh(3));
    drape_cloth_info info{sizeof info};
    ASSERT_DRAPE_OK(drape_cloth_get_info(c, &info));
    EXPECT_EQ(info.particle_count, 9u);
    EXPECT_EQ(info.triangle_count, 8u);
    // Edges of a 3x3 vertex grid with one diagonal per cell: 6 horizontal + 6 vertical + 4 diagonal.
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_STRUCTURAL], 16u);
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_SHEAR], 0u);
    // One bend spring per interior edge (8 of them): opposite corners of the two triangles.
    EXPECT_EQ(info.spring_count[DRAPE_GROUP_BEND], 8u);
}

TEST(Mesh, SeamVerticesAreWeldedAndBehaveLikeTheUnsplitMesh) {
    const uint32_t n = 9;
    WorldPtr w = make_world();
    drape_cloth* whole = make_mesh(w.get(), grid_mesh(n));
    drape_cloth* split = make_mesh(w.get(), grid_mesh(n, 4));
    drape_cloth_info info{sizeof info};
    ASSERT_DRAPE_OK(drape_cloth_get_info(split, &info));
    EXPECT_EQ(info.vertex_count, n * n + n);
    EXPECT_EQ(info.particle_count, n * n) << "seam copies were not welded";
    hang_and_step(whole, n, 90);
    hang_and_step(split, n, 90);
    const std::vector<float> a = positions(whole), b = positions(split);
    float moved = 0;
    for (uint32_t v = 0; v < n * n; ++v)
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a[3 * v + k], b[3 * v + k], 1e-5f) << "vertex " << v;
            moved = std::max(moved, std::fabs(a[3 * v + k] - grid_mesh(n).positions[3 * v + k]));
        }
    EXPECT_GT(moved, 0.1f);
    // Each copy is written with its original's position (un-welded on output).
    for (uint32_t r = 0; r < n; ++r)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(b[3 * (n * n + r) + k], b[3 * (r * n + 4) + k]);
}

TEST(Mesh, WeldDistanceJoinsNearbyVertices) {
    Mesh m = grid_mesh(4, 2);
    for (uint32_t r = 0; r < 4; ++r) m.positions[3 * (16 + r)] += 1e-4f;  // copies slightly off
    WorldPtr w = make_world();
    drape_cloth_info info{sizeof info};
    drape_cloth* exact = make_mesh(w.get(), m, 0);
    ASSERT_DRAPE_OK(drape_cloth_get_info(exact, &info));
    EXPECT_EQ(info.particle_count, 20u);
    drape_cloth* welded = make_mesh(w.get(), m, 1e-3f);
    ASSERT_DRAPE_OK(drape_cloth_get_info(welded, &info));
    EXPECT_EQ(info.particle_count, 16u);
}

TEST(Mesh, NormalsAreSharedAcrossTheSeam) {
    const uint32_t n = 5;
    WorldPtr w = make_world();
    drape_cloth* c = make_mesh(w.get(), grid_mesh(n, 2));
    hang_and_step(c, n, 30);
    std::vector<float> vn((n * n + n) * 6);
    drape_vertex_layout l{sizeof l, 24, 0, 12};
    ASSERT_DRAPE_OK(drape_cloth_read(c, &l, vn.data(), vn.size() * 4));
    for (uint32_t r = 0; r < n; ++r) {
        const float* copy = &vn[6 * (n * n + r)];
        const float* orig = &vn[6 * (r * n + 2)];
        for (int k = 3; k < 6; ++k) EXPECT_EQ(copy[k], orig[k]);
        EXPECT_NEAR(copy[3] * copy[3] + copy[4] * copy[4] + copy[5] * copy[5], 1.0f, 1e-5f);
    }
}
