// Measurement driver (not built by default): steps one scene through the C ABI and logs each
// measured step's TSC start / end and iterations to $DRAPE_POOL_TRACE.steps.<pid>; a library built
// with -DDRAPE_POOL_TRACE logs its pool passes beside it (thread_pool.h).
//   pool_trace curtain|sheet N WARM MEASURED THREADS [cpu]
// curtain: the rest part's (1 kg, top row, air drag 3, library defaults); sheet: the threads part's
// falling cloth (0.2 kg, two top corners, defaults).
#include <x86intrin.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "drape/drape.h"

static void check(drape_status s, const char* what) {
    if (s == DRAPE_OK) return;
    std::fprintf(stderr, "%s: %s\n", what, drape_last_error());
    std::exit(1);
}

int main(int argc, char** argv) {
    if (argc < 6) return 2;
    const bool curtain = std::strcmp(argv[1], "curtain") == 0;
    const uint32_t n = uint32_t(std::atoi(argv[2]));
    const int warm = std::atoi(argv[3]), measured = std::atoi(argv[4]);
    const uint32_t threads = uint32_t(std::atoi(argv[5]));
    const bool cpu = argc > 6 && std::strcmp(argv[6], "cpu") == 0;
    drape_world_desc wd{};
    wd.struct_size = sizeof wd;
    wd.thread_count = threads;
    drape_world* world = nullptr;
    check(drape_world_create(&wd, &world), "world");
    const float mass = curtain ? 1.0f : 0.2f;
    drape_cloth_desc cd{};
    cd.struct_size = sizeof cd;
    cd.backend = cpu ? DRAPE_BACKEND_CPU : DRAPE_BACKEND_CPU_THREADED;
    cd.total_mass = mass;
    drape_grid_desc g{};
    g.struct_size = sizeof g;
    g.columns = g.rows = n;
    g.width = g.height = 1;
    g.axis_u[0] = 1;
    g.axis_v[1] = -1;
    drape_cloth* cloth = nullptr;
    check(drape_cloth_create_grid(world, &cd, &g, &cloth), "cloth");
    const uint32_t count = n * n;
    std::vector<float> w(count, float(count / mass));
    for (uint32_t c = 0; c < n; ++c)
        if (curtain || c == 0 || c == n - 1) w[c] = 0;
    check(drape_cloth_set_inverse_masses(cloth, w.data(), count), "masses");
    drape_params p{};
    check(drape_params_default(&p), "params");
    p.model = DRAPE_MODEL_IMPLICIT;
    p.stiffness[0] = 2000, p.stiffness[1] = 1000, p.stiffness[2] = 200;
    if (curtain) p.air_drag = 3;
    check(drape_cloth_set_params(cloth, &p), "set_params");
    for (int s = 0; s < warm; ++s) check(drape_cloth_step(cloth, 1.0f / 60), "step");
    struct Step {
        uint64_t start, end;
        uint32_t iterations, pad;
    };
    std::vector<Step> steps(measured);
    for (int s = 0; s < measured; ++s) {
        steps[s].start = __rdtsc();
        check(drape_cloth_step(cloth, 1.0f / 60), "step");
        steps[s].end = __rdtsc();
        drape_stats st{};
        st.struct_size = sizeof st;
        check(drape_cloth_get_stats(cloth, &st), "stats");
        steps[s].iterations = st.iterations;
    }
    // TSC ticks per us
    const auto c0 = std::chrono::steady_clock::now();
    const uint64_t t0 = __rdtsc();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const uint64_t t1 = __rdtsc();
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - c0).count();
    drape_world_destroy(world);
    if (const char* path = std::getenv("DRAPE_POOL_TRACE")) {
        char name[512];
        std::snprintf(name, sizeof name, "%s.steps.%d", path, int(getpid()));
        FILE* f = std::fopen(name, "wb");
        const double per_us = double(t1 - t0) / us;
        std::fwrite(&per_us, sizeof per_us, 1, f);
        std::fwrite(steps.data(), sizeof(Step), steps.size(), f);
        std::fclose(f);
    }
    return 0;
}
