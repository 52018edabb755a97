// Cooked descriptions are shared: cloths of one world created from identical input (the same
// grid or mesh bytes and total mass, on any backend) use one immutable description
// (drape_cloth_info.description_id / description_users); different input gets its own; a
// description no cloth uses is forgotten. Sharing it shares nothing else: a cloth whose twin is
// pinned, re-parameterised, moved and stepped differently steps bit for bit like the same cloth
// alone in another world.
#include <cstring>
#include <vector>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

drape_cloth_info info_of(const drape_cloth* c) {
    drape_cloth_info i{sizeof i};
    EXPECT_DRAPE_OK(drape_cloth_get_info(c, &i));
    return i;
}

drape_cloth* make_mesh(drape_world* w, const std::vector<float>& xyz, const std::vector<uint32_t>& idx,
                       float weld = 0.0f) {
    drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 1.0f};
    drape_mesh_desc m{sizeof m, uint32_t(xyz.size() / 3), xyz.data(), uint32_t(idx.size()), idx.data(), weld};
    drape_cloth* c = nullptr;
    EXPECT_DRAPE_OK(drape_cloth_create_mesh(w, &d, &m, &c));
    return c;
}

}  // namespace

TEST(Description, IdenticalGridsShareOneDescription) {
    WorldPtr w = make_world();
    const drape_grid_desc g = grid_desc(8, 8, 1, 1);
    drape_cloth* a = make_grid(w.get(), g, 1.0f);
    drape_cloth* b = make_grid(w.get(), g, 1.0f);
    drape_cloth* threaded = make_grid(w.get(), g, 1.0f, DRAPE_BACKEND_CPU_THREADED);  // backend is not input
    drape_cloth* heavier = make_grid(w.get(), g, 2.0f);
    drape_cloth* wider = make_grid(w.get(), grid_desc(8, 8, 1.5f, 1), 1.0f);

    const uint32_t shared = info_of(a).description_id;
    EXPECT_EQ(info_of(b).description_id, shared);
    EXPECT_EQ(info_of(threaded).description_id, shared);
    EXPECT_EQ(info_of(a).description_users, 3u);
    EXPECT_NE(info_of(heavier).description_id, shared);
    EXPECT_NE(info_of(wider).description_id, shared);
    EXPECT_NE(info_of(wider).description_id, info_of(heavier).description_id);
    EXPECT_EQ(info_of(heavier).description_users, 1u);

    ASSERT_DRAPE_OK(drape_cloth_destroy(b));
    EXPECT_EQ(info_of(a).description_users, 2u);
    // Once no cloth uses it, it is gone: the same input is cooked again, under a new id.
    ASSERT_DRAPE_OK(drape_cloth_destroy(a));
    ASSERT_DRAPE_OK(drape_cloth_destroy(threaded));
    drape_cloth* again = make_grid(w.get(), g, 1.0f);
    EXPECT_NE(info_of(again).description_id, shared);
    EXPECT_EQ(info_of(again).description_users, 1u);

    // Another world cooks its own.
    WorldPtr other = make_world();
    drape_cloth* elsewhere = make_grid(other.get(), g, 1.0f);
    EXPECT_EQ(info_of(elsewhere).description_users, 1u);
}

TEST(Description, IdenticalMeshesShareOneDescription) {
    WorldPtr w = make_world();
    // Two triangles of a unit square.
    const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
    const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
    drape_cloth* a = make_mesh(w.get(), xyz, idx);
    drape_cloth* b = make_mesh(w.get(), xyz, idx);
    EXPECT_EQ(info_of(a).description_id, info_of(b).description_id);
    EXPECT_EQ(info_of(a).description_users, 2u);

    std::vector<float> moved = xyz;
    moved[6] = 1.25f;  // one coordinate of one vertex
    EXPECT_NE(info_of(make_mesh(w.get(), moved, idx)).description_id, info_of(a).description_id);
    const std::vector<uint32_t> other_diagonal = {0, 1, 3, 1, 2, 3};
    EXPECT_NE(info_of(make_mesh(w.get(), xyz, other_diagonal)).description_id, info_of(a).description_id);
    EXPECT_NE(info_of(make_mesh(w.get(), xyz, idx, 0.01f)).description_id, info_of(a).description_id);
}

TEST(Description, ClothsSharingADescriptionStayIndependent) {
    // World `shared`: a and b share a description and step together on the pool; a is pinned
    // differently, stiffer, moved and pushed. World `alone`: b's twin on its own. b must step
    // exactly like its twin.
    const drape_grid_desc g = grid_desc(12, 12, 1, 1);
    WorldPtr shared = make_world(2);
    WorldPtr alone = make_world(2);
    drape_cloth* a = make_grid(shared.get(), g, 0.5f);
    drape_cloth* b = make_grid(shared.get(), g, 0.5f);
    drape_cloth* twin = make_grid(alone.get(), g, 0.5f);
    ASSERT_EQ(info_of(a).description_id, info_of(b).description_id);

    const drape_pin corners[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), 11, {1, 0, 0}}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(b, corners, 2));
    ASSERT_DRAPE_OK(drape_cloth_set_pins(twin, corners, 2));

    const drape_pin edge[3] = {{sizeof(drape_pin), 0, {0, 0.2f, 0}},
                               {sizeof(drape_pin), 6, {0.5f, 0.2f, 0}},
                               {sizeof(drape_pin), 132, {0, 0.2f, -1}}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(a, edge, 3));
    drape_params p = params_of(a);
    p.model = DRAPE_MODEL_MASS_SPRING;
    for (float& k : p.stiffness) k *= 4;
    ASSERT_DRAPE_OK(drape_cloth_set_params(a, &p));
    std::vector<float> x = positions(a);
    for (size_t k = 1; k < x.size(); k += 3) x[k] += 0.1f;
    ASSERT_DRAPE_OK(drape_cloth_set_positions(a, x.data(), uint32_t(x.size() / 3)));
    std::vector<float> v(x.size(), 0.0f);
    for (size_t k = 0; k < v.size(); k += 3) v[k] = 0.5f;
    ASSERT_DRAPE_OK(drape_cloth_set_velocities(a, v.data(), uint32_t(v.size() / 3)));

    for (int f = 0; f < 90; ++f) {
        ASSERT_DRAPE_OK(drape_world_step(shared.get(), 1.0f / 60));
        ASSERT_DRAPE_OK(drape_world_step(alone.get(), 1.0f / 60));
    }
    const std::vector<float> xb = positions(b), xt = positions(twin), xa = positions(a);
    EXPECT_EQ(0, std::memcmp(xb.data(), xt.data(), xb.size() * sizeof(float)));
    EXPECT_NE(0, std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(float)));
    EXPECT_EQ(params_of(b).model, params_of(twin).model);
    EXPECT_EQ(info_of(b).description_users, 2u);
}
