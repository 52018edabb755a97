// Callgrind probe: steps one scene through the C ABI and turns callgrind's instrumentation on for the
// measured steps only (README: "IMPLICIT's cost at rest"). Prints a hash of the positions (CPU and
// CPU_THREADED must agree), the most and total IMPLICIT iterations per step, and with `ref` the worst
// vertex's distance from the Newton equilibrium over the largest displacement (run that one natively).
//   drape_callgrind_probe curtain N WARM MEASURED [threaded] [ref]  the rest part's curtain: 1 kg, top
//                                                                   row pinned, air drag 3, no tethers
//   drape_callgrind_probe corners N MEASURED [threaded]              part fall's sheet: 0.2 kg, two
//                                                                   corners of one edge, from flat
// Library defaults otherwise, IMPLICIT; PROBE_BUDGET=SxI sets substeps x iterations. For example:
//   valgrind --tool=callgrind --instr-atstart=no build/release/tests/bench/drape_callgrind_probe curtain 65 180 60
//   callgrind_annotate --inclusive=yes callgrind.out.PID | grep drape_cloth_step
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "drape/drape.h"
#include "reference.h"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#endif
#endif
#ifndef CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

namespace {

void check(drape_status s, const char* what) {
    if (s == DRAPE_OK) return;
    std::fprintf(stderr, "%s: %s\n", what, drape_last_error());
    std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s curtain N WARM MEASURED [threaded] [ref] | corners N MEASURED [threaded]\n", argv[0]);
        return 2;
    }
    const bool curtain = std::strcmp(argv[1], "curtain") == 0;
    const uint32_t n = uint32_t(std::atoi(argv[2]));
    const int warm = curtain ? std::atoi(argv[3]) : 0, measured = std::atoi(argv[curtain ? 4 : 3]);
    bool threaded = false, ref = false;
    for (int a = 1; a < argc; ++a) {
        threaded |= std::strcmp(argv[a], "threaded") == 0;
        ref |= std::strcmp(argv[a], "ref") == 0;
    }
    drape_world_desc wd{};
    wd.struct_size = sizeof wd;
    wd.thread_count = threaded ? 2 : 1;
    drape_world* world = nullptr;
    check(drape_world_create(&wd, &world), "drape_world_create");
    const double mass = curtain ? 1.0 : 0.2;
    drape_cloth_desc cd{};
    cd.struct_size = sizeof cd;
    cd.backend = threaded ? DRAPE_BACKEND_CPU_THREADED : DRAPE_BACKEND_CPU;
    cd.total_mass = float(mass);
    drape_grid_desc g{};
    g.struct_size = sizeof g;
    g.columns = g.rows = n;
    g.width = g.height = 1;
    if (curtain) {
        g.axis_v[1] = -1;
        g.axis_v[2] = 0;
    }
    drape_cloth* cloth = nullptr;
    check(drape_cloth_create_grid(world, &cd, &g, &cloth), "drape_cloth_create_grid");
    const uint32_t count = n * n;
    std::vector<float> w(count, float(count / mass));
    std::vector<double> m(count, mass / count), rest(3 * size_t(count), 0.0);
    for (uint32_t r = 0; r < n; ++r)
        for (uint32_t c = 0; c < n; ++c) {
            const uint32_t v = r * n + c;
            if (curtain ? r == 0 : r == 0 && (c == 0 || c == n - 1)) w[v] = 0, m[v] = 0;
            rest[3 * v] = c / double(n - 1);
            rest[3 * v + (curtain ? 1 : 2)] = -double(r) / (n - 1);
        }
    check(drape_cloth_set_inverse_masses(cloth, w.data(), count), "drape_cloth_set_inverse_masses");
    drape_params p{};
    check(drape_params_default(&p), "drape_params_default");
    p.model = DRAPE_MODEL_IMPLICIT;
    if (curtain) {
        p.air_drag = 3;
        p.max_stretch = 0;
    }
    if (const char* budget = std::getenv("PROBE_BUDGET")) std::sscanf(budget, "%ux%u", &p.substeps, &p.iterations);
    check(drape_cloth_set_params(cloth, &p), "drape_cloth_set_params");
    for (int s = 0; s < warm; ++s) check(drape_cloth_step(cloth, 1.0f / 60), "drape_cloth_step");
    uint32_t most = 0, total = 0;
    CALLGRIND_START_INSTRUMENTATION;
    for (int s = 0; s < measured; ++s) {
        check(drape_cloth_step(cloth, 1.0f / 60), "drape_cloth_step");
        drape_stats st{};
        st.struct_size = sizeof st;
        check(drape_cloth_get_stats(cloth, &st), "drape_cloth_get_stats");  // costs ~8 %: count the step alone
        most = st.iterations > most ? st.iterations : most;
        total += st.iterations;
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    std::vector<float> x(size_t(count) * 3);
    drape_vertex_layout layout{};
    layout.struct_size = sizeof layout;
    layout.stride = 12;
    layout.normal_offset = -1;
    check(drape_cloth_read(cloth, &layout, x.data(), x.size() * sizeof(float)), "drape_cloth_read");
    uint64_t hash = 1469598103934665603ull;  // FNV-1a over the coordinates' bits
    for (float f : x) {
        uint32_t u;
        std::memcpy(&u, &f, sizeof u);
        hash = (hash ^ u) * 1099511628211ull;
    }
    std::printf("%s %u^2, %d + %d steps%s: positions hash %016llx, iterations per step at most %u, %u in all\n",
                argv[1], n, warm, measured, threaded ? ", threaded" : "", (unsigned long long)hash, most, total);
    if (ref) {
        const double k[3] = {p.stiffness[0], p.stiffness[1], p.stiffness[2]};
        const auto springs = bench::grid_springs(n, n, 1.0 / (n - 1), 1.0 / (n - 1), k);
        std::vector<double> eq = rest;
        const double gravity[3] = {0, -9.81, 0};
        bench::solve_static(eq, m, springs, gravity);
        double worst = 0, largest = 0;
        for (uint32_t v = 0; v < count; ++v) {
            double d = 0, disp = 0;
            for (int a = 0; a < 3; ++a) {
                d += (x[3 * v + a] - eq[3 * v + a]) * (x[3 * v + a] - eq[3 * v + a]);
                disp += (eq[3 * v + a] - rest[3 * v + a]) * (eq[3 * v + a] - rest[3 * v + a]);
            }
            worst = std::fmax(worst, std::sqrt(d));
            largest = std::fmax(largest, std::sqrt(disp));
        }
        std::printf("worst vertex %.3g of the largest displacement from the Newton equilibrium\n", worst / largest);
    }
    drape_world_destroy(world);
    return 0;
}
