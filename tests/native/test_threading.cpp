// Thread-safety rules of drape.h (hardening), exercised so that ThreadSanitizer (preset
// tsan, label "tsan") sees every pattern the header allows:
//  - one world stepping several CPU_THREADED and CPU cloths in one call (the worker pool, and
//    single-threaded cloths spread over it);
//  - different worlds used from different threads at the same time (shared: the handle registry);
//  - a world handed from one thread to another (used by one thread at a time);
//  - drape_last_error() is per thread;
//  - stale handles checked while other threads create and destroy objects.
#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "drape_test_util.h"

using namespace drape_test;

namespace {

drape_cloth* pinned_grid(drape_world* w, uint32_t n, drape_backend backend) {
    drape_cloth* c = make_grid(w, grid_desc(n, n, 1, 1), 0.4f, backend);
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 0, 0}}, {sizeof(drape_pin), n - 1, {1, 0, 0}}};
    EXPECT_EQ(drape_cloth_set_pins(c, pins, 2), DRAPE_OK) << drape_last_error();
    return c;
}

void add_sphere(drape_cloth* c) {
#ifdef DRAPE_MAX_COLLIDERS
    drape_collider s{};
    s.struct_size = sizeof s;
    s.shape = DRAPE_COLLIDER_SPHERE;
    s.position[0] = 0.5f;
    s.position[1] = -0.6f;
    s.position[2] = -0.5f;
    s.rotation[3] = 1;
    s.size[0] = 0.3f;
    s.margin = 0.01f;
    s.friction = 0.3f;
    EXPECT_EQ(drape_cloth_set_colliders(c, &s, 1), DRAPE_OK) << drape_last_error();
#else
    (void)c;
#endif
}

bool finite(const std::vector<float>& v) {
    for (float f : v)
        if (!std::isfinite(f)) return false;
    return true;
}

}  // namespace

// The CPU_THREADED pool and the spreading of CPU cloths over it, in one drape_world_step; the
// result must equal stepping each cloth alone in a single-threaded world (same bits).
TEST(Threading, WorldStepsThreadedAndSingleThreadedClothsTogether) {
    const drape_backend kinds[] = {DRAPE_BACKEND_CPU_THREADED, DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU,
                                   DRAPE_BACKEND_CPU_THREADED, DRAPE_BACKEND_CPU};
    WorldPtr w = make_world(3);
    WorldPtr ref = make_world(1);
    std::vector<drape_cloth*> a, b;
    // Cloth 0 (48^2 = 2304 particles) is large enough for its passes to be split over the pool
    // (ThreadPool::kMinParallelCount); the small ones are spread over it whole. Cloths 1 and 2 are
    // identical, so they share one cooked description, read by two pool threads at once.
    const uint32_t sizes[] = {48, 12, 12, 14, 16};
    for (int k = 0; k < 5; ++k) {
        a.push_back(pinned_grid(w.get(), sizes[k], kinds[k]));
        b.push_back(pinned_grid(ref.get(), sizes[k], DRAPE_BACKEND_CPU));
        if (k % 2) {
            add_sphere(a.back());
            add_sphere(b.back());
        }
    }
    for (int f = 0; f < 12; ++f) {
        ASSERT_DRAPE_OK(drape_world_step(w.get(), 1 / 60.f));
        for (drape_cloth* c : b) ASSERT_DRAPE_OK(drape_cloth_step(c, 1 / 60.f));
    }
    for (int k = 0; k < 5; ++k) {
        const std::vector<float> pa = positions(a[k]), pb = positions(b[k]);
        EXPECT_TRUE(finite(pa));
        EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0) << "cloth " << k;
    }
}

// Different worlds on different threads at once; each thread also checks that the error message
// it reads is its own.
TEST(Threading, IndependentWorldsOnConcurrentThreads) {
    constexpr int kThreads = 3;
    std::atomic<int> failures{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([t, &failures] {
            for (int round = 0; round < 3; ++round) {
                drape_world_desc d{sizeof d, uint32_t(1 + (t + round) % 2)};
                drape_world* w = nullptr;
                if (drape_world_create(&d, &w) != DRAPE_OK) { ++failures; return; }
                drape_cloth_desc cd{sizeof cd, uint32_t(t % 2 ? DRAPE_BACKEND_CPU_THREADED : DRAPE_BACKEND_CPU), 0.5f};
                drape_grid_desc g = grid_desc(6 + t, 6, 1, 1);
                drape_cloth* c = nullptr;
                if (drape_cloth_create_grid(w, &cd, &g, &c) != DRAPE_OK) { ++failures; return; }
                for (int f = 0; f < 8; ++f)
                    if (drape_world_step(w, 1 / 60.f) != DRAPE_OK) ++failures;
                // A failure with a message naming this thread's bad value.
                const float bad_dt = -1.0f - float(t);
                if (drape_cloth_step(c, bad_dt) != DRAPE_ERROR_INVALID_ARGUMENT) ++failures;
                const std::string mine = drape_last_error();
                std::this_thread::yield();
                if (mine.empty() || mine != drape_last_error()) ++failures;
                if (drape_world_destroy(w) != DRAPE_OK) ++failures;
                // The destroyed handles are refused, whatever other threads are doing.
                if (drape_cloth_step(c, 1 / 60.f) == DRAPE_OK) ++failures;
            }
        });
    }
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(failures.load(), 0);
}

// "One thread at a time (any thread)": a world created on one thread, stepped on another, then
// destroyed on a third; the pool's workers survive the hand-over.
TEST(Threading, WorldHandedBetweenThreads) {
    drape_world* w = nullptr;
    drape_cloth* c = nullptr;
    std::thread([&] {
        drape_world_desc d{sizeof d, 2};
        ASSERT_EQ(drape_world_create(&d, &w), DRAPE_OK);
        c = pinned_grid(w, 10, DRAPE_BACKEND_CPU_THREADED);
    }).join();
    ASSERT_NE(c, nullptr);
    std::thread([&] {
        for (int f = 0; f < 10; ++f) EXPECT_EQ(drape_world_step(w, 1 / 60.f), DRAPE_OK) << drape_last_error();
    }).join();
    EXPECT_TRUE(finite(positions(c)));
    std::thread([&] { EXPECT_EQ(drape_world_destroy(w), DRAPE_OK); }).join();
}

// Handle checks (a process-wide registry) while other threads create and destroy cloths.
TEST(Threading, HandleChecksWhileOtherThreadsCreateAndDestroy) {
    std::atomic<bool> stop{false};
    std::atomic<int> failures{0};
    WorldPtr shared_probe = make_world(1);
    drape_cloth* stale = make_grid(shared_probe.get(), grid_desc(3, 3, 1, 1), 1);
    ASSERT_DRAPE_OK(drape_cloth_destroy(stale));
    std::thread churn([&] {
        WorldPtr w = make_world(1);
        for (int i = 0; i < 200; ++i) {
            drape_cloth* c = make_grid(w.get(), grid_desc(3, 3, 1, 1), 1);
            if (drape_cloth_destroy(c) != DRAPE_OK) ++failures;
        }
        stop = true;
    });
    int probes = 0;
    while (!stop.load() || probes < 100) {
        drape_stats s{};
        s.struct_size = sizeof s;
        // `stale` may be handed out again to the churning thread's cloth (same address): then it is
        // that thread's object and must not be touched here, so only calls that do not dereference
        // a live cloth are made: a NULL and a foreign pointer.
        if (drape_cloth_get_stats(nullptr, &s) != DRAPE_ERROR_NULL_POINTER) ++failures;
        if (drape_cloth_get_stats(reinterpret_cast<drape_cloth*>(&s), &s) != DRAPE_ERROR_INVALID_HANDLE) ++failures;
        ++probes;
    }
    churn.join();
    EXPECT_EQ(failures.load(), 0);
}
