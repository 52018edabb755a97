// Long-run soak: many cloths created, stepped for many frames with random parameter, pin, mass
// and collider changes, destroyed; no NaN, no crash, no memory growth, no allocation in a step.
// Its own binary: it replaces operator new/delete to count allocations (and ASan's allocator
// or glibc's mallinfo2 gives the live heap bytes).
//
// The work is fixed (DRAPE_SOAK_ROUNDS rounds from a fixed seed, default 40; at least 4), never a
// time budget: a slow machine (qemu, sanitizers) takes longer but reaches the same verdict. The
// memory checks compare the heap between rounds (nothing alive), after two warm-up rounds.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <vector>

#include "drape_test_util.h"
#ifdef DRAPE_TEST_GLES
#include "gles_test_util.h"
#endif

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRAPE_SOAK_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define DRAPE_SOAK_ASAN 1
#endif
#ifdef DRAPE_SOAK_ASAN
#include <sanitizer/allocator_interface.h>
#else
#include <malloc.h>
#endif

// ---- allocation counting --------------------------------------------------------------------
namespace {
std::atomic<uint64_t> g_news{0};
}
void* operator new(std::size_t n) {
    g_news.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    g_news.fetch_add(1, std::memory_order_relaxed);
    return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void* operator new(std::size_t n, std::align_val_t a) {
    g_news.fetch_add(1, std::memory_order_relaxed);
    const std::size_t al = std::max<std::size_t>(std::size_t(a), sizeof(void*));
    if (void* p = std::aligned_alloc(al, (n + al - 1) / al * al)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace drape_test;

namespace {

size_t live_heap_bytes() {
#ifdef DRAPE_SOAK_ASAN
    return __sanitizer_get_current_allocated_bytes();
#else
    struct mallinfo2 mi = mallinfo2();
    return mi.uordblks + mi.hblkhd;
#endif
}

int soak_rounds(int fallback) {
    const char* s = std::getenv("DRAPE_SOAK_ROUNDS");
    const int n = s ? std::atoi(s) : fallback;
    return n < 4 ? 4 : n;  // two warm-up rounds, then at least two compared
}

bool all_finite(const std::vector<float>& v) {
    for (float f : v)
        if (!std::isfinite(f)) return false;
    return true;
}

struct Soak {
    std::mt19937 rng{12345};
    uint64_t frames = 0, cloths_made = 0, unstable = 0, step_news = 0, checked_steps = 0;

    float uni(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); }
    uint32_t pick(uint32_t a, uint32_t b) { return std::uniform_int_distribution<uint32_t>(a, b)(rng); }

    uint32_t gles_per_round = 0;  ///< GLES cloths added to every round (needs a current context)

    drape_cloth* make_cloth(drape_world* w, bool gles = false) {
        const uint32_t cpu = pick(0, 1) ? uint32_t(DRAPE_BACKEND_CPU_THREADED) : uint32_t(DRAPE_BACKEND_CPU);
        drape_cloth_desc d{sizeof d, gles ? uint32_t(DRAPE_BACKEND_GLES) : cpu, uni(0.1f, 2.0f)};
        drape_cloth* c = nullptr;
        if (pick(0, 3) == 0) {  // a mesh: a split-seam strip of quads
            const uint32_t n = pick(3, 12);
            std::vector<float> pos;
            std::vector<uint32_t> idx;
            for (uint32_t i = 0; i <= n; ++i)
                for (uint32_t j = 0; j < 2; ++j) pos.insert(pos.end(), {0.1f * float(i), 0.0f, 0.2f * float(j)});
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t a = 2 * i, b = a + 1, c2 = a + 2, e = a + 3;
                idx.insert(idx.end(), {a, b, c2, b, e, c2});
            }
            drape_mesh_desc m{sizeof m, uint32_t(pos.size() / 3), pos.data(), uint32_t(idx.size()), idx.data(), 0.0f};
            EXPECT_EQ(drape_cloth_create_mesh(w, &d, &m, &c), DRAPE_OK) << drape_last_error();
        } else {
            drape_grid_desc g = grid_desc(pick(2, 24), pick(2, 24), uni(0.2f, 2.0f), uni(0.2f, 2.0f));
            g.origin[1] = uni(0.0f, 2.0f);
            EXPECT_EQ(drape_cloth_create_grid(w, &d, &g, &c), DRAPE_OK) << drape_last_error();
        }
        ++cloths_made;
        if (c) {
            drape_pin pin{sizeof pin, 0, {0, 2, 0}};
            EXPECT_EQ(drape_cloth_set_pins(c, &pin, 1), DRAPE_OK) << drape_last_error();
        }
        return c;
    }

    void change_something(drape_cloth* c) {
        drape_cloth_info info{sizeof info};
        ASSERT_EQ(drape_cloth_get_info(c, &info), DRAPE_OK);
        switch (pick(0, 5)) {
            case 0: {
                drape_params p{};
                drape_params_default(&p);
                p.model = pick(0, 3);
                for (float& k : p.stiffness) k = p.model == DRAPE_MODEL_PBD ? uni(0, 1) : uni(0, 3000);
                if (p.model == DRAPE_MODEL_MASS_SPRING) {
                    for (float& k : p.stiffness) k *= 0.05f;  // keeps the automatic substeps low
                    p.substeps = pick(0, 1) ? 0 : pick(1, 8);
                }
                p.damping = uni(0, 2);
                p.wind[0] = uni(-5, 5);
                p.air_drag = uni(0, 1);
                p.iterations = pick(1, 8);
                EXPECT_EQ(drape_cloth_set_params(c, &p), DRAPE_OK) << drape_last_error();
                break;
            }
            case 1: {
                drape_pin pin{sizeof pin, pick(0, info.vertex_count - 1), {uni(-1, 1), uni(0, 2), uni(-1, 1)}};
                EXPECT_EQ(drape_cloth_set_pins(c, &pin, 1), DRAPE_OK) << drape_last_error();
                break;
            }
            case 2: {
                uint32_t v = pick(0, info.vertex_count - 1);
                EXPECT_EQ(drape_cloth_release_pins(c, &v, 1), DRAPE_OK) << drape_last_error();
                break;
            }
            case 3: {
                std::vector<float> vel(size_t(info.vertex_count) * 3);
                for (float& f : vel) f = uni(-1, 1);
                EXPECT_EQ(drape_cloth_set_velocities(c, vel.data(), info.vertex_count), DRAPE_OK) << drape_last_error();
                break;
            }
            case 4: {
                std::vector<float> inv(info.vertex_count);
                for (float& f : inv) f = pick(0, 20) == 0 ? 0.0f : uni(0.5f, 50);
                EXPECT_EQ(drape_cloth_set_inverse_masses(c, inv.data(), info.vertex_count), DRAPE_OK)
                    << drape_last_error();
                break;
            }
            default: set_colliders(c); break;
        }
    }

    void set_colliders(drape_cloth* c) {
#ifdef DRAPE_MAX_COLLIDERS
        drape_collider col[3] = {};
        const uint32_t n = pick(0, 3);
        for (uint32_t i = 0; i < n; ++i) {
            col[i].struct_size = sizeof col[i];
            col[i].shape = pick(0, 3);
            col[i].id = i;
            col[i].position[0] = uni(-1, 1);
            col[i].position[1] = uni(-1, 1.5f);
            col[i].position[2] = uni(-1, 1);
            col[i].rotation[3] = 1;
            col[i].size[0] = uni(0.1f, 0.5f);
            col[i].size[1] = uni(0.1f, 0.5f);
            col[i].size[2] = uni(0.1f, 0.5f);
            col[i].margin = 0.01f;
            col[i].friction = uni(0, 1);
        }
        EXPECT_EQ(drape_cloth_set_colliders(c, col, n), DRAPE_OK) << drape_last_error();
#else
        (void)c;
#endif
    }

    // One round: a world, 3-8 cloths, 40-80 frames, everything destroyed.
    void round() {
        WorldPtr w = make_world(pick(1, 3));
        std::vector<drape_cloth*> cloths;
        std::vector<bool> stepped;
        const uint32_t count = pick(3, 8);
        for (uint32_t k = 0; k < count; ++k) cloths.push_back(make_cloth(w.get()));
        for (uint32_t k = 0; k < gles_per_round; ++k) cloths.push_back(make_cloth(w.get(), true));
        const size_t first_gles = count;
        stepped.assign(cloths.size(), false);
        const uint32_t nframes = pick(40, 80);
        // A world's first drape_world_step sizes its per-step lists, and a change (parameters,
        // pins, a new cloth) may resize state: only steps of the same kind as one already made
        // since the last change are checked for allocations.
        bool params_changed = true, world_stepped = false, clothes_stepped = false;
        for (uint32_t f = 0; f < nframes; ++f) {
            if (pick(0, 4) == 0) {
                change_something(cloths[pick(0, uint32_t(cloths.size()) - 1)]);
                params_changed = true;
            }
            // Steps after the first frame must not allocate (architecture: C ABI rules).
            const uint64_t before = g_news.load();
            drape_status s;
            const bool by_world = pick(0, 1) == 1;
            const bool steady = !params_changed && (by_world ? world_stepped : clothes_stepped);
            if (by_world) {
                s = drape_world_step(w.get(), 1 / 60.f);
            } else {
                s = DRAPE_OK;
                for (drape_cloth* c : cloths)
                    if (drape_status r = drape_cloth_step(c, 1 / 60.f); r != DRAPE_OK && s == DRAPE_OK) s = r;
            }
            const uint64_t news = g_news.load() - before;
            if (s == DRAPE_ERROR_UNSTABLE) ++unstable;
            else EXPECT_EQ(s, DRAPE_OK) << drape_last_error();
            if (steady && s == DRAPE_OK) {
                step_news += news;
                ++checked_steps;
            }
            if (params_changed) world_stepped = clothes_stepped = false;
            (by_world ? world_stepped : clothes_stepped) = true;
            params_changed = false;
            for (drape_cloth* c : cloths) EXPECT_TRUE(all_finite(positions(c))) << "frame " << f;
            ++frames;
            // Sometimes replace a cloth mid-round.
            if (pick(0, 30) == 0) {
                const uint32_t k = pick(0, uint32_t(cloths.size()) - 1);
                EXPECT_EQ(drape_cloth_destroy(cloths[k]), DRAPE_OK);
                cloths[k] = make_cloth(w.get(), k >= first_gles);
                params_changed = true;
            }
        }
        // Half the rounds destroy cloths one by one, the others leave them to the world.
        if (pick(0, 1))
            for (drape_cloth* c : cloths) EXPECT_EQ(drape_cloth_destroy(c), DRAPE_OK);
    }
};

// Runs `total` rounds and checks: every round ran, the heap between rounds comes back to where it
// was after two warm-up rounds, enough steady steps were checked and none of them allocated.
// `peak_too`: bound the largest heap seen between rounds and the last one. Without it (GLES),
// the smallest heap over the second half of the rounds: Mesa's pools grow with the largest program
// compiled so far and shrink again (measured under ASan: one round 735 KB above the baseline, the
// last at +23 KB), while a leak raises every later round.
void run_soak(Soak& soak, int total, const char* name, size_t slack_bytes, bool peak_too) {
    size_t baseline = 0, peak_between_rounds = 0, last = 0, late_floor = SIZE_MAX;
    int rounds = 0;
    for (; rounds < total; ++rounds) {
        soak.round();
        if (::testing::Test::HasFailure()) break;
        last = live_heap_bytes();
        if (rounds == 1) baseline = last;  // after two warm-up rounds
        if (rounds >= 1) peak_between_rounds = std::max(peak_between_rounds, last);
        if (rounds >= total / 2) late_floor = std::min(late_floor, last);
    }
    std::printf("%s: %d rounds, %llu cloths, %llu frames, %llu rolled-back steps; heap between rounds: "
                "baseline %zu B, last %zu B, peak %zu B; %llu allocations in %llu checked steps\n",
                name, rounds, (unsigned long long)soak.cloths_made, (unsigned long long)soak.frames,
                (unsigned long long)soak.unstable, baseline, last, peak_between_rounds,
                (unsigned long long)soak.step_news, (unsigned long long)soak.checked_steps);
    EXPECT_EQ(rounds, total);
    // Nothing is alive between rounds: the heap must come back to where it was (a little slack
    // for allocator bookkeeping and hash-table buckets sized by the largest round).
    EXPECT_LE(peak_too ? last : late_floor, baseline + slack_bytes) << "heap grew over " << rounds << " rounds";
    if (peak_too) EXPECT_LE(peak_between_rounds, baseline + slack_bytes);
    EXPECT_GT(soak.checked_steps, uint64_t(total));
    EXPECT_EQ(soak.step_news, 0u) << "steps allocated after their first frame";
}

}  // namespace

TEST(Soak, ManyClothsRandomChangesNoNanNoGrowthNoAllocationInStep) {
    Soak soak;
    run_soak(soak, soak_rounds(40), "soak", 64 * 1024, true);
}

#ifdef DRAPE_TEST_GLES
// The same rounds with two GLES cloths in every world (immediate use: a headless Mesa context
// current on this thread). GLES steps record GL work and must not allocate either; the GL objects
// of destroyed cloths are all released (same live GL names between rounds).
TEST(Soak, GlesClothsJoinTheSoakNoGrowthNoAllocationInStep) {
    HeadlessGles gl;
    const std::string why = gl.create();
    if (!why.empty() || !gl.make_current()) {
        gl.destroy();
        DRAPE_GLES_UNAVAILABLE(why.empty() ? "eglMakeCurrent failed" : why);
    }
    const GlNameCounts names_before = GlNameCounts::take();
    {
        Soak soak;
        soak.gles_per_round = 2;
        // Mesa keeps compiled programs and its own pools: more slack than the CPU-only soak.
        run_soak(soak, std::max(4, soak_rounds(40) / 4), "soak with GLES", 256 * 1024, false);
        EXPECT_EQ(GlNameCounts::take(), names_before) << "GL objects left behind by destroyed cloths";
    }
    gl.destroy();
}
#endif

// The counting hook itself works (a test that cannot fail is worse than none).
TEST(Soak, AllocationCounterSeesTheLibrary) {
    const uint64_t before = g_news.load();
    WorldPtr w = make_world(1);
    drape_cloth* c = make_grid(w.get(), grid_desc(4, 4, 1, 1), 1);
    EXPECT_NE(c, nullptr);
    EXPECT_GT(g_news.load() - before, 3u);
    const size_t with_cloth = live_heap_bytes();
    EXPECT_EQ(drape_cloth_destroy(c), DRAPE_OK);
    EXPECT_LT(live_heap_bytes(), with_cloth);
}
