// Handles cannot alias: a destroyed world's or cloth's handle is refused by every call that takes
// it, even when a new object took its slot (and, for the allocator, its memory), from any thread.
#include <atomic>
#include <cstring>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

drape_view identity_view() {
    drape_view v{};
    v.struct_size = sizeof v;
    for (int k = 0; k < 4; ++k) v.world[k * 5] = v.view[k * 5] = v.projection[k * 5] = 1.0f;
    v.viewport[0] = v.viewport[1] = 100.0f;
    return v;
}

struct ClothCall {
    const char* name;
    std::function<drape_status(drape_cloth*)> call;
};

// Every entry point that takes a cloth, with arguments that are valid for a live 4x4 CPU cloth,
// so a refusal can only come from the handle.
std::vector<ClothCall> every_cloth_call() {
    static float xyz[16 * 3] = {};
    static float inv[16];
    for (float& w : inv) w = 1.0f;
    static const float where[2] = {50, 50};
    std::vector<ClothCall> calls = {
        {"set_params", [](drape_cloth* c) { drape_params p{}; drape_params_default(&p); return drape_cloth_set_params(c, &p); }},
        {"get_params", [](drape_cloth* c) { drape_params p{sizeof p}; return drape_cloth_get_params(c, &p); }},
        {"set_inverse_masses", [](drape_cloth* c) { return drape_cloth_set_inverse_masses(c, inv, 16); }},
        {"set_pins", [](drape_cloth* c) { drape_pin pin{sizeof pin, 0, {0, 1, 0}}; return drape_cloth_set_pins(c, &pin, 1); }},
        {"release_pins", [](drape_cloth* c) { uint32_t v = 0; return drape_cloth_release_pins(c, &v, 1); }},
        {"set_positions", [](drape_cloth* c) { return drape_cloth_set_positions(c, xyz, 16); }},
        {"set_velocities", [](drape_cloth* c) { return drape_cloth_set_velocities(c, xyz, 16); }},
        {"step", [](drape_cloth* c) { return drape_cloth_step(c, 0.01f); }},
        {"read", [](drape_cloth* c) { float out[16 * 3]; drape_vertex_layout l{sizeof l, 12, 0, -1}; return drape_cloth_read(c, &l, out, sizeof out); }},
        {"get_info", [](drape_cloth* c) { drape_cloth_info i{sizeof i}; return drape_cloth_get_info(c, &i); }},
        {"get_stats", [](drape_cloth* c) { drape_stats s{sizeof s}; return drape_cloth_get_stats(c, &s); }},
        {"set_output_buffer", [](drape_cloth* c) { return drape_cloth_set_output_buffer(c, 0, nullptr); }},
        {"readback", [](drape_cloth* c) { return drape_cloth_readback(c); }},
        {"set_colliders", [](drape_cloth* c) { return drape_cloth_set_colliders(c, nullptr, 0); }},
        {"set_sleep", [](drape_cloth* c) { drape_sleep_desc s{sizeof s, 0.01f, 1.0f}; return drape_cloth_set_sleep(c, &s); }},
        {"wake", [](drape_cloth* c) { return drape_cloth_wake(c); }},
        {"drag", [](drape_cloth* c) { drape_view v = identity_view(); drape_touch t{}; drape_touch_default(&t); return drape_cloth_drag(c, &v, &t, 1); }},
        {"grab", [](drape_cloth* c) { drape_view v = identity_view(); uint32_t got = 0; return drape_cloth_grab(c, &v, 1, where, 10.0f, &got); }},
        {"grab_move", [](drape_cloth* c) { drape_view v = identity_view(); return drape_cloth_grab_move(c, &v, 1, where); }},
        {"grab_release", [](drape_cloth* c) { return drape_cloth_grab_release(c, 1); }},
        {"set_owner", [](drape_cloth* c) { drape_owner o{}; drape_owner_default(&o); return drape_cloth_set_owner(c, &o); }},
        {"set_self_collision", [](drape_cloth* c) { drape_self_collision_desc d{sizeof d, 0, 0, 0}; return drape_cloth_set_self_collision(c, &d); }},
        {"get_self_collision", [](drape_cloth* c) { drape_self_collision_desc d{sizeof d}; return drape_cloth_get_self_collision(c, &d); }},
        {"destroy", [](drape_cloth* c) { return drape_cloth_destroy(c); }},  // last: on a live cloth it succeeds
    };
    return calls;
}

struct WorldCall {
    const char* name;
    std::function<drape_status(drape_world*)> call;
};

std::vector<WorldCall> every_world_call() {
    return {
        {"world_step", [](drape_world* w) { return drape_world_step(w, 0.01f); }},
        {"cloth_create_grid", [](drape_world* w) {
             drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 1.0f};
             drape_grid_desc g = grid_desc(4, 4, 1, 1);
             drape_cloth* c = nullptr;
             return drape_cloth_create_grid(w, &d, &g, &c);
         }},
        {"cloth_create_mesh", [](drape_world* w) {
             const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
             const uint32_t idx[3] = {0, 1, 2};
             drape_cloth_desc d{sizeof d, DRAPE_BACKEND_CPU, 1.0f};
             drape_mesh_desc m{sizeof m, 3, pos, 3, idx, 0.0f};
             drape_cloth* c = nullptr;
             return drape_cloth_create_mesh(w, &d, &m, &c);
         }},
        {"world_destroy", [](drape_world* w) { return drape_world_destroy(w); }},  // last
    };
}

drape_cloth* make_small(drape_world* w) {
    drape_grid_desc g = grid_desc(4, 4, 1, 1);
    g.origin[1] = 1.0f;
    return make_grid(w, g, 1.0f);
}

}  // namespace

// The calls list really succeeds on a live cloth: a refusal of the stale handle then says
// something about the handle, not about the other arguments.
TEST(Handles, EveryClothCallAcceptsALiveCloth) {
    WorldPtr w = make_world(1);
    drape_cloth* c = make_small(w.get());
    for (const ClothCall& k : every_cloth_call()) {
        const drape_status s = k.call(c);
        // Moving an unheld grab and a GL output on a CPU cloth are refused by argument, never by
        // handle.
        if (std::strcmp(k.name, "grab_move") == 0 || std::strcmp(k.name, "set_output_buffer") == 0) EXPECT_NE(s, DRAPE_ERROR_INVALID_HANDLE) << k.name;
        else EXPECT_EQ(s, DRAPE_OK) << k.name << ": " << drape_last_error();
    }
}

TEST(Handles, DestroyedClothStaysRefusedAfterItsSlotIsReused) {
    WorldPtr w = make_world(1);
    for (int round = 0; round < 50; ++round) {
        drape_cloth* old = make_small(w.get());
        ASSERT_DRAPE_OK(drape_cloth_destroy(old));
        drape_cloth* fresh = make_small(w.get());  // takes the freed slot (and, often, the memory)
        ASSERT_NE(fresh, nullptr);
        EXPECT_NE(fresh, old) << "a new cloth got the handle of a destroyed one";
        ASSERT_DRAPE_OK(drape_cloth_step(fresh, 0.01f));
        const std::vector<float> before = positions(fresh);
        for (const ClothCall& k : every_cloth_call()) {
            EXPECT_EQ(k.call(old), DRAPE_ERROR_INVALID_HANDLE) << k.name << " accepted a destroyed cloth";
            EXPECT_NE(std::strstr(drape_last_error(), "not a live drape_cloth"), nullptr) << drape_last_error();
        }
        // None of those calls reached the new cloth.
        EXPECT_EQ(positions(fresh), before);
        drape_stats s = stats_of(fresh);
        EXPECT_EQ(s.sleeping, 0u);
        ASSERT_DRAPE_OK(drape_cloth_destroy(fresh));
    }
}

TEST(Handles, ClothsOfADestroyedWorldStayRefused) {
    WorldPtr keep = make_world(1);
    drape_world_desc d{sizeof d, 1};
    drape_world* w = nullptr;
    ASSERT_DRAPE_OK(drape_world_create(&d, &w));
    drape_cloth* a = make_small(w);
    drape_cloth* b = make_small(w);
    ASSERT_DRAPE_OK(drape_world_destroy(w));
    drape_cloth* c1 = make_small(keep.get());
    drape_cloth* c2 = make_small(keep.get());
    for (drape_cloth* stale : {a, b})
        for (const ClothCall& k : every_cloth_call())
            EXPECT_EQ(k.call(stale), DRAPE_ERROR_INVALID_HANDLE) << k.name;
    EXPECT_DRAPE_OK(drape_cloth_destroy(c1));
    EXPECT_DRAPE_OK(drape_cloth_destroy(c2));
}

TEST(Handles, DestroyedWorldStaysRefusedAfterItsSlotIsReused) {
    for (int round = 0; round < 20; ++round) {
        drape_world_desc d{sizeof d, 1};
        drape_world* old = nullptr;
        ASSERT_DRAPE_OK(drape_world_create(&d, &old));
        ASSERT_DRAPE_OK(drape_world_destroy(old));
        drape_world* fresh = nullptr;
        ASSERT_DRAPE_OK(drape_world_create(&d, &fresh));
        EXPECT_NE(fresh, old);
        drape_cloth* in_fresh = make_small(fresh);
        for (const WorldCall& k : every_world_call())
            EXPECT_EQ(k.call(old), DRAPE_ERROR_INVALID_HANDLE) << k.name << " accepted a destroyed world";
        // The new world and its cloth are intact: one cloth, still stepping.
        drape_cloth_info info{sizeof info};
        EXPECT_DRAPE_OK(drape_cloth_get_info(in_fresh, &info));
        EXPECT_DRAPE_OK(drape_world_step(fresh, 0.01f));
        ASSERT_DRAPE_OK(drape_world_destroy(fresh));
        EXPECT_EQ(drape_cloth_get_info(in_fresh, &info), DRAPE_ERROR_INVALID_HANDLE);
    }
}

TEST(Handles, KindsDoNotMix) {
    WorldPtr w = make_world(1);
    drape_cloth* c = make_small(w.get());
    for (const ClothCall& k : every_cloth_call())
        EXPECT_EQ(k.call(reinterpret_cast<drape_cloth*>(w.get())), DRAPE_ERROR_INVALID_HANDLE) << k.name;
    for (const WorldCall& k : every_world_call())
        EXPECT_EQ(k.call(reinterpret_cast<drape_world*>(c)), DRAPE_ERROR_INVALID_HANDLE) << k.name;
    int junk[4] = {};
    EXPECT_EQ(drape_cloth_step(reinterpret_cast<drape_cloth*>(junk), 0.01f), DRAPE_ERROR_INVALID_HANDLE);
    EXPECT_EQ(drape_world_step(reinterpret_cast<drape_world*>(junk), 0.01f), DRAPE_ERROR_INVALID_HANDLE);
    EXPECT_DRAPE_OK(drape_cloth_step(c, 0.01f));
}

// Several threads each churn their own worlds and cloths (create, destroy, create again) and try
// every stale handle any thread has published: all are refused, no live handle is ever handed
// out twice, and every thread's live objects keep working.
TEST(Handles, StaleHandlesAreRefusedFromManyThreads) {
    constexpr int kThreads = 4, kRounds = 60;
    std::mutex m;
    std::vector<drape_cloth*> stale_cloths;
    std::vector<drape_world*> stale_worlds;
    std::set<const void*> live;
    std::atomic<int> accepted{0}, duplicates{0}, failures{0};
    auto claim = [&](const void* h) {
        std::lock_guard<std::mutex> lock(m);
        if (!live.insert(h).second) ++duplicates;
    };
    auto retire = [&](const void* h) {
        std::lock_guard<std::mutex> lock(m);
        live.erase(h);
    };
    const std::vector<ClothCall> cloth_calls = every_cloth_call();
    const std::vector<WorldCall> world_calls = every_world_call();
    auto worker = [&](int t) {
        for (int r = 0; r < kRounds; ++r) {
            drape_world_desc d{sizeof d, 1};
            drape_world* w = nullptr;
            if (drape_world_create(&d, &w) != DRAPE_OK) { ++failures; return; }
            claim(w);
            drape_cloth* c = make_small(w);
            claim(c);
            retire(c);
            if (drape_cloth_destroy(c) != DRAPE_OK) ++failures;
            drape_cloth* c2 = make_small(w);
            claim(c2);
            if (drape_cloth_step(c2, 0.01f) != DRAPE_OK) ++failures;
            {
                std::lock_guard<std::mutex> lock(m);
                stale_cloths.push_back(c);
            }
            // Try a few published stale handles (other threads' included) with varied calls.
            std::vector<drape_cloth*> sample;
            std::vector<drape_world*> wsample;
            {
                std::lock_guard<std::mutex> lock(m);
                for (size_t k = 0; k < 4 && k < stale_cloths.size(); ++k)
                    sample.push_back(stale_cloths[(size_t(r) * 7 + k * 13 + size_t(t)) % stale_cloths.size()]);
                for (size_t k = 0; k < 2 && k < stale_worlds.size(); ++k)
                    wsample.push_back(stale_worlds[(size_t(r) * 5 + k * 11 + size_t(t)) % stale_worlds.size()]);
            }
            for (size_t k = 0; k < sample.size(); ++k)
                if (cloth_calls[(size_t(r) + k + size_t(t)) % cloth_calls.size()].call(sample[k]) !=
                    DRAPE_ERROR_INVALID_HANDLE)
                    ++accepted;
            for (size_t k = 0; k < wsample.size(); ++k)
                if (world_calls[(size_t(r) + k) % world_calls.size()].call(wsample[k]) != DRAPE_ERROR_INVALID_HANDLE)
                    ++accepted;
            retire(c2);
            retire(w);
            if (drape_world_destroy(w) != DRAPE_OK) ++failures;  // takes c2 with it
            std::lock_guard<std::mutex> lock(m);
            stale_worlds.push_back(w);
            stale_cloths.push_back(c2);
        }
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) threads.emplace_back(worker, t);
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(failures.load(), 0);
    EXPECT_EQ(duplicates.load(), 0) << "a live handle was handed out twice";
    EXPECT_EQ(accepted.load(), 0) << "a stale handle was accepted";
    // Afterwards, every stale handle is refused by every call.
    ASSERT_EQ(stale_cloths.size(), size_t(2 * kThreads * kRounds));
    for (drape_cloth* c : stale_cloths)
        for (const ClothCall& k : cloth_calls) ASSERT_EQ(k.call(c), DRAPE_ERROR_INVALID_HANDLE) << k.name;
    for (drape_world* w : stale_worlds)
        for (const WorldCall& k : world_calls) ASSERT_EQ(k.call(w), DRAPE_ERROR_INVALID_HANDLE) << k.name;
}
