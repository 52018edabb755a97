// Headless native demo (npm run demo): the paper's scenes, a cloth hanging from two corners and a
// curtain hanging from its top edge in wind, simulated with every model x CPU backend at several
// resolutions. Prints the paper's "time for one step" as a table with vertex counts and strain.
// Pictures come from drape_render (GLES), which npm run demo runs next.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "drape/drape.h"

namespace {

#define CHECK(call)                                                                    \
    do {                                                                               \
        drape_status s_ = (call);                                                      \
        if (s_ != DRAPE_OK) {                                                          \
            std::fprintf(stderr, "%s failed (%d): %s\n", #call, int(s_), drape_last_error()); \
            std::exit(1);                                                              \
        }                                                                              \
    } while (0)

enum class Scene { TwoCorners, Curtain };

struct Row {
    double median_ms;
    uint32_t vertices, substeps, iterations;
    float max_strain, rms_strain;
    int unstable;
};

Row run(Scene scene, drape_model model, drape_backend backend, uint32_t n, int frames) {
    drape_world_desc wd{sizeof wd, 0};
    drape_world* world = nullptr;
    CHECK(drape_world_create(&wd, &world));
    drape_grid_desc g{};
    g.struct_size = sizeof g;
    g.columns = g.rows = n;
    g.width = g.height = 1.0f;
    g.origin[1] = 1.5f;
    if (scene == Scene::Curtain) g.axis_v[1] = -1.0f;  // hangs straight down; otherwise horizontal
    drape_cloth_desc cd{sizeof cd, uint32_t(backend), 0.25f};
    drape_cloth* cloth = nullptr;
    CHECK(drape_cloth_create_grid(world, &cd, &g, &cloth));
    std::vector<drape_pin> pins;
    if (scene == Scene::TwoCorners) {
        pins.push_back({sizeof(drape_pin), 0, {0, 1.5f, 0}});
        pins.push_back({sizeof(drape_pin), n - 1, {1, 1.5f, 0}});
    } else {
        for (uint32_t c = 0; c < n; c += std::max(1u, n / 16))
            pins.push_back({sizeof(drape_pin), c, {float(c) / float(n - 1), 1.5f, 0}});
    }
    CHECK(drape_cloth_set_pins(cloth, pins.data(), uint32_t(pins.size())));
    drape_params p{};
    CHECK(drape_params_default(&p));
    p.model = model;
    if (model == DRAPE_MODEL_PBD) p.stiffness[0] = p.stiffness[1] = p.stiffness[2] = 0.9f;
    if (model == DRAPE_MODEL_MASS_SPRING) {
        // Explicit: the automatic substep count follows stiffness (and damping) per vertex mass,
        // which falls as 1/n^2; scaling both with it keeps about 20 substeps at every size.
        const float scale = 1024.0f / float(n * n);
        p.stiffness[0] = 90 * scale, p.stiffness[1] = 45 * scale, p.stiffness[2] = 9 * scale;
        p.damping = 0.005f * scale;
    }
    if (scene == Scene::Curtain) p.wind[2] = 2.0f, p.air_drag = 0.5f;
    CHECK(drape_cloth_set_params(cloth, &p));
    std::vector<double> ms;
    int unstable = 0;
    for (int f = 0; f < frames; ++f) {
        drape_status s = drape_cloth_step(cloth, 1.0f / 60.0f);
        if (s == DRAPE_ERROR_UNSTABLE)
            ++unstable;
        else
            CHECK(s);
        drape_stats st{sizeof st};
        CHECK(drape_cloth_get_stats(cloth, &st));
        ms.push_back(st.step_ms);
    }
    drape_stats st{sizeof st};
    CHECK(drape_cloth_get_stats(cloth, &st));
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    Row r{ms[ms.size() / 2], n * n, st.substeps, st.iterations, st.max_strain, st.rms_strain, unstable};
    CHECK(drape_world_destroy(world));
    return r;
}

const char* model_name(drape_model m) {
    return m == DRAPE_MODEL_MASS_SPRING ? "mass-spring" : m == DRAPE_MODEL_PBD ? "PBD" : m == DRAPE_MODEL_XPBD ? "XPBD" : "IMPLICIT";
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
    const int frames = quick ? 30 : 120;
    const bool progress = isatty(STDERR_FILENO);
    const std::vector<uint32_t> sizes = quick ? std::vector<uint32_t>{16, 32} : std::vector<uint32_t>{16, 32, 64, 128};
    std::printf("Drape %u demo: %d frames of 1/60 s per row (2 s of cloth), median time for one step.\n",
                drape_abi_version(), frames);
    std::printf("Max/RMS strain over structural+shear springs at the end; tethers (max_stretch 0.1) on.\n\n");
    for (Scene scene : {Scene::TwoCorners, Scene::Curtain}) {
        std::printf("%s\n", scene == Scene::TwoCorners ? "Cloth hanging from two corners (the paper's rest test)"
                                                       : "Curtain pinned along its top edge, wind 2 m/s");
        std::printf("  %-12s %-12s %8s %10s %9s %10s %10s %8s\n", "model", "backend", "vertices", "ms/step",
                    "substeps", "max strain", "rms strain", "rollback");
        for (drape_model model : {DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD, DRAPE_MODEL_IMPLICIT})
            for (drape_backend backend : {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED})
                for (uint32_t n : sizes) {
                    if (model == DRAPE_MODEL_IMPLICIT && n > 64) continue;  // 4x4 solves: ~0.3 s per step at 128^2
                    if (progress)
                        std::fprintf(stderr, "  running %s %s %ux%u...\r", model_name(model),
                                     backend == DRAPE_BACKEND_CPU ? "CPU" : "threaded", n, n);
                    const Row r = run(scene, model, backend, n, frames);
                    if (progress) std::fprintf(stderr, "%60s\r", "");
                    std::printf("  %-12s %-12s %8u %10.3f %5ux%-3u %10.4f %10.4f %8d\n", model_name(model),
                                backend == DRAPE_BACKEND_CPU ? "CPU" : "CPU_THREADED", r.vertices, r.median_ms,
                                r.substeps, r.iterations, r.max_strain, r.rms_strain, r.unstable);
                    std::fflush(stdout);
                }
        std::printf("\n");
    }
    std::printf("GLES step times and pictures: drape_render (demo-out/).\n");
    return 0;
}
