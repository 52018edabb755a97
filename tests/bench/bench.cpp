// drape_bench: run time against error, stability stress and the paper's measurements
// (docs/accuracy.md). Uses the library through the C ABI only and writes CSV
// files into --out; tests/bench/plot.py turns them into PNGs and REPORT.md.
//
//   drape_bench [--quick] [--out DIR] [--only a,b,...] [--threads N] [--rest-largest N] [--rest-models a,b]
//   parts: throughput, threads, precision, rest, stiff, fall, stress, vibration, stages
//
// Timings are wall-clock medians over repeated steps of one run on a shared machine; they are
// numbers to compare within one run, never assertions.
#include <dirent.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "backend/cpu/thread_pool.h"  // the threads part's calibration only: the same pool as the library's
#include "drape/drape.h"
#include "reference.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kG = 9.81;

// ---------------------------------------------------------------------------------------------
// Options, output, progress

struct Options {
    std::string out = "bench-out";
    bool quick = false;
    std::set<std::string> only;
    uint32_t threads = 2;  ///< CPU_THREADED workers (including the caller); this machine has 2 cores
    uint32_t rest_largest = 257;  ///< the rest part's largest size (257^2's references take the longest)
    /// The rest part's models besides the library default (model_name; empty: all). Re-timing the
    /// IMPLICIT rows on a quiet machine alone takes minutes; XPBD and MASS_SPRING to rest take most of an hour.
    std::set<std::string> rest_models;
    bool wants(const char* part) const { return only.empty() || only.count(part); }
};

class Csv {
  public:
    Csv(const std::string& path, const char* header) : f_(std::fopen(path.c_str(), "w")) {
        if (!f_) {
            std::fprintf(stderr, "drape_bench: cannot write %s\n", path.c_str());
            std::exit(1);
        }
        std::fprintf(f_, "%s\n", header);
    }
    ~Csv() { std::fclose(f_); }
    template <class... A>
    void row(const char* fmt, A... a) {
        std::fprintf(f_, fmt, a...);
        std::fputc('\n', f_);
        std::fflush(f_);
    }

  private:
    FILE* f_;
};

/// One line rewritten in place on a terminal; in a log, a line every 10% or 20 s.
class Progress {
  public:
    void start(const std::string& phase, int total) {
        phase_ = phase;
        total_ = std::max(total, 1);
        done_ = 0;
        last_decile_ = -1;
        show("");
    }
    void tick(const std::string& label) {
        ++done_;
        show(label);
    }
    void finish() {
        if (tty_) std::fputc('\n', stderr);
    }

  private:
    void show(const std::string& label) {
        const double t = std::chrono::duration<double>(Clock::now() - t0_).count();
        const int decile = 10 * done_ / total_;
        if (!tty_ && decile == last_decile_ && t < last_line_ + 20) return;
        last_decile_ = decile;
        last_line_ = t;
        std::fprintf(stderr, "%s[drape_bench %6.1fs] %-10s %3d/%-3d %-44.44s%s", tty_ ? "\r" : "", t,
                     phase_.c_str(), done_, total_, label.c_str(), tty_ ? "" : "\n");
        std::fflush(stderr);
    }
    std::string phase_;
    int total_ = 1, done_ = 0, last_decile_ = -1;
    double last_line_ = 0;
    bool tty_ = isatty(2) != 0;
    Clock::time_point t0_ = Clock::now();
};

Progress g_progress;
std::string g_load_start = "?";

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

const char* model_name(uint32_t m) {
    return m == DRAPE_MODEL_MASS_SPRING ? "mass_spring"
           : m == DRAPE_MODEL_PBD       ? "pbd"
           : m == DRAPE_MODEL_XPBD      ? "xpbd"
                                        : "implicit";
}
const char* backend_name(uint32_t b) {
    return b == DRAPE_BACKEND_CPU ? "cpu" : b == DRAPE_BACKEND_CPU_THREADED ? "cpu_threaded" : "gles";
}
const uint32_t kModels[] = {DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD, DRAPE_MODEL_IMPLICIT};
constexpr int kModelCount = int(sizeof kModels / sizeof kModels[0]);

void die_on(drape_status s, const char* what) {
    if (s == DRAPE_OK) return;
    std::fprintf(stderr, "\ndrape_bench: %s failed (status %d): %s\n", what, int(s), drape_last_error());
    std::exit(1);
}

// ---------------------------------------------------------------------------------------------
// Scenes

enum class Pins { None, TwoTopCorners, TopVertex };

/// One world holding one cloth; destroyed together.
struct Sim {
    drape_world* world = nullptr;
    drape_cloth* cloth = nullptr;
    uint32_t cols = 0, rows = 0, vertices = 0;
    double size = 1.0;  ///< m, cloth (or chain) extent
    double mass = 0.0;  ///< kg, total simulated mass
    std::vector<float> inv_mass;
    ~Sim() {
        if (world) drape_world_destroy(world);
    }
    std::vector<float> positions() const {
        std::vector<float> out(size_t(vertices) * 3);
        drape_vertex_layout l{};
        l.struct_size = sizeof l;
        l.stride = 12;
        l.position_offset = 0;
        l.normal_offset = -1;
        die_on(drape_cloth_read(cloth, &l, out.data(), out.size() * sizeof(float)), "drape_cloth_read");
        return out;
    }
    drape_stats stats() const {
        drape_stats s{};
        s.struct_size = sizeof s;
        die_on(drape_cloth_get_stats(cloth, &s), "drape_cloth_get_stats");
        return s;
    }
    void set_params(const drape_params& p) {
        die_on(drape_cloth_set_params(cloth, &p), "drape_cloth_set_params");
    }
    void set_positions(const std::vector<float>& x) {
        die_on(drape_cloth_set_positions(cloth, x.data(), vertices), "drape_cloth_set_positions");
    }
    void set_inverse_masses(const std::vector<float>& w) {
        inv_mass = w;
        die_on(drape_cloth_set_inverse_masses(cloth, w.data(), vertices), "drape_cloth_set_inverse_masses");
    }
};

struct GridSpec {
    uint32_t cols = 32, rows = 32;
    double width = 1.0, height = 1.0;
    double mass = 0.2;     ///< kg: a 1 m^2 cloth of 200 g/m^2
    bool vertical = true;  ///< in the x-y plane hanging down (-y); false: horizontal (x-z plane)
    Pins pins = Pins::TwoTopCorners;
    uint32_t backend = DRAPE_BACKEND_CPU;
    uint32_t threads = 2;
    bool profile_stages = false;  ///< drape_world_desc.profile_stages: drape_stats.stage_ms filled
};

/// The library's description of the grid `s`.
void describe(const GridSpec& s, drape_cloth_desc* cd, drape_grid_desc* g) {
    *cd = drape_cloth_desc{};
    cd->struct_size = sizeof *cd;
    cd->backend = s.backend;
    cd->total_mass = float(s.mass);
    *g = drape_grid_desc{};
    g->struct_size = sizeof *g;
    g->columns = s.cols;
    g->rows = s.rows;
    g->width = float(s.width);
    g->height = float(s.height);
    g->axis_u[0] = 1.0f;
    if (s.vertical)
        g->axis_v[1] = -1.0f;
    else
        g->axis_v[2] = -1.0f;
}

/// Uniform particle masses (set explicitly, so the double-precision reference is the same
/// system); pinned vertices get inverse mass 0 where they are.
std::unique_ptr<Sim> make_grid(const GridSpec& s) {
    auto sim = std::make_unique<Sim>();
    drape_world_desc wd{};
    wd.struct_size = sizeof wd;
    wd.thread_count = s.threads;
    wd.profile_stages = s.profile_stages ? 1 : 0;
    die_on(drape_world_create(&wd, &sim->world), "drape_world_create");
    drape_cloth_desc cd;
    drape_grid_desc g;
    describe(s, &cd, &g);
    die_on(drape_cloth_create_grid(sim->world, &cd, &g, &sim->cloth), "drape_cloth_create_grid");
    sim->cols = s.cols;
    sim->rows = s.rows;
    sim->vertices = s.cols * s.rows;
    sim->size = std::max(s.width, s.height);
    sim->mass = s.mass;
    std::vector<float> w(sim->vertices, float(sim->vertices / s.mass));
    if (s.pins == Pins::TwoTopCorners) w[0] = w[s.cols - 1] = 0.0f;
    if (s.pins == Pins::TopVertex) w[0] = 0.0f;
    sim->set_inverse_masses(w);
    return sim;
}

/// Material per model: the library defaults (2000, 1000, 200 N/m) scaled by `scale` for the
/// physical models; PBD takes fractions per iteration (1, 0.5, 0.1) times `scale` (<= 1).
drape_params params_for(uint32_t model, double scale = 1.0) {
    drape_params p{};
    die_on(drape_params_default(&p), "drape_params_default");
    p.model = model;
    const float ratio[3] = {1.0f, 0.5f, 0.1f};
    for (int gi = 0; gi < 3; ++gi)
        p.stiffness[gi] = model == DRAPE_MODEL_PBD ? float(std::min(1.0, scale * ratio[gi]))
                                                   : float(2000.0 * scale * ratio[gi]);
    return p;
}

/// The parameters a new CPU cloth gets from the library (model, budget, tethers: what "the
/// default" is on every plot and in REPORT.md), so a change of the library's default moves the
/// marks by itself.
drape_params library_default() {
    GridSpec gs;
    gs.cols = gs.rows = 4;
    auto sim = make_grid(gs);
    drape_params p{};
    p.struct_size = sizeof p;
    die_on(drape_cloth_get_params(sim->cloth, &p), "drape_cloth_get_params");
    return p;
}

struct Config {
    uint32_t model, substeps, iterations;  ///< 0 = automatic (the library's budget)
};

/// Times one step (wall clock around the C call).
double timed_step(Sim& s, float dt, drape_status* st) {
    auto t0 = Clock::now();
    *st = drape_cloth_step(s.cloth, dt);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Energy the model stores, J: kinetic + gravity + what its springs hold.
///
/// MASS_SPRING and IMPLICIT apply F = k (l - L0) along the simulated springs, so drape_stats'
/// elastic energy (1/2 k (l - L0)^2 over the library's own 12-spring table, at the model's k) is
/// what they store. XPBD stores its compliance energy 1/2 alpha |lambda / h^2|^2 (alpha = 1/k), the
/// energy of the forces it applied; that equals 1/2 k C^2 only when its solve converges. With a
/// few Jacobi passes per substep its springs act softer than k and drape_stats' 1/2 k C^2 counts
/// the unresolved stretch at the full k (a 16^2 cloth at 1e9 N/m hanging still "stored" 1e2-6e4 x
/// M g H by it). drape_stats does not report lambda, and PBD (stiffness as a fraction per
/// iteration) defines no energy at all, so for both the springs count as 0: what a spring stores
/// is >= 0, so kinetic + gravity alone never exceeds the energy at the start plus the work put
/// in, whatever the springs hold. Their check then sees growth that shows as motion or height,
/// which every blow-up does.
double stored_energy(const drape_stats& s, uint32_t model) {
    const bool springs = model == DRAPE_MODEL_MASS_SPRING || model == DRAPE_MODEL_IMPLICIT;
    return double(s.kinetic_energy) + s.potential_energy + (springs ? s.elastic_energy : 0.0);
}

/// Failure criteria of accuracy.md ("Exploded"), checked after every step.
struct Monitor {
    /// Energy growth beyond the work put in, as a fraction of M g H + the energy stored at the start,
    /// that counts as exploded. In a full stress run the surviving cloths stayed below 0.2 (highest:
    /// MASS_SPRING at 1e7 N/m, 642 substeps, 0.19; XPBD with jittered frame times, 0.13); Verlet
    /// stepped above its stability bound passes 0.5 within a few frames.
    static constexpr double kEnergyGrowthLimit = 0.5;
    double v_limit = 0, bbox0 = 0, e0 = 0, e_scale = 0, energy_growth = 0;
    bool energy_check = false;
    uint32_t model = 0;
    std::vector<float> prev;
    std::string criterion;
    double t_fail = -1;
    float max_strain = 0;

    static double bbox_diag(const std::vector<float>& x) {
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < x.size(); ++i) {
            lo[i % 3] = std::min(lo[i % 3], double(x[i]));
            hi[i % 3] = std::max(hi[i % 3], double(x[i]));
        }
        return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]));
    }
    static double energy(const drape_stats& s) {
        return double(s.kinetic_energy) + s.potential_energy + s.elastic_energy;
    }

    /// Call after the scene is set up, before the first step. The speed limit is
    /// 10 x (sqrt(2 g H) + the speed the initial elastic/kinetic energy could give the mass).
    /// `check_energy`: false where the run puts in work the check cannot count (a moving kinematic
    /// collider), or where the start stores energy the model cannot state (PBD stretched).
    /// At the start XPBD's springs count 1/2 k C^2 (drape_stats): its softer springs release
    /// less than that, so the bound stays one the model must keep.
    void begin(const Sim& s, uint32_t m, bool check_energy = true) {
        model = m;
        prev = s.positions();
        bbox0 = std::max(bbox_diag(prev), 1e-3);
        const drape_stats st = s.stats();
        const double stored = double(st.elastic_energy) + st.kinetic_energy;
        e0 = energy(st);  // PBD reports elastic energy 0
        double mass = 0;  // simulated mass, pinned particles excluded
        for (float w : s.inv_mass)
            if (w > 0) mass += 1.0 / w;
        v_limit = 10.0 * (std::sqrt(2.0 * kG * s.size) + std::sqrt(2.0 * stored / mass));
        e_scale = mass * kG * s.size + stored;
        energy_check = check_energy;
    }
    /// false once failed (criterion and t_fail set).
    bool after_step(const Sim& s, drape_status st, float dt, double t) {
        if (!criterion.empty()) return false;
        if (st == DRAPE_ERROR_UNSTABLE) return fail("library rollback (non-finite or strain>10)", t);
        if (st != DRAPE_OK) return fail(std::string("status ") + std::to_string(int(st)), t);
        std::vector<float> x = s.positions();
        double vmax = 0;
        for (size_t i = 0; i < x.size(); ++i)
            if (!std::isfinite(x[i])) return fail("non-finite output", t);
        for (size_t i = 0; i < x.size(); i += 3) {
            double dx = x[i] - prev[i], dy = x[i + 1] - prev[i + 1], dz = x[i + 2] - prev[i + 2];
            vmax = std::max(vmax, std::sqrt(dx * dx + dy * dy + dz * dz) / dt);
        }
        prev.swap(x);
        const drape_stats ss = s.stats();
        max_strain = std::max(max_strain, ss.max_strain);
        if (energy_check) {
            energy_growth = std::max(energy_growth, (stored_energy(ss, model) - e0) / e_scale);
            if (energy_growth > kEnergyGrowthLimit)
                return fail(fmt("energy growth > %g x (M g H + stored)", kEnergyGrowthLimit), t);
        }
        if (vmax > v_limit) return fail("speed > limit", t);
        if (bbox_diag(prev) > 10.0 * bbox0) return fail("bounding box > 10x", t);
        return true;
    }
    bool fail(const std::string& c, double t) {
        criterion = c;
        t_fail = t;
        return false;
    }
};

// ---------------------------------------------------------------------------------------------
// 1. Throughput (seed, paper Fig. 6) and thread sweep

struct Timing {
    double ms_median = NAN, ms_min = NAN, vit_per_s = NAN;
    uint32_t steps = 0, substeps = 0, iterations = 0;
    float max_strain = 0, rms_strain = 0;
    bool ok = true;
};

/// Hanging cloth stepped at 60 Hz: `warmup` frames, then frames until min_frames are done and
/// min_seconds (or max_seconds) have passed. A frame is `frame_steps` library steps of
/// 1/60 s / frame_steps (see frame_steps_for). A rolled-back step, or one whose automatic substeps
/// hit DRAPE_MAX_SUBSTEPS (below the stability bound: it would blow up), makes the row not ok.
/// Vertex-iterations = particles x substeps per frame x iterations per substep (1 for MASS_SPRING).
Timing time_cloth(Sim& s, double min_seconds, double max_seconds, uint32_t min_frames, int warmup,
                  uint32_t frame_steps = 1) {
    Timing r;
    const float dt = 1.0f / 60.0f / float(frame_steps);
    auto frame = [&] {
        double ms = 0;
        for (uint32_t k = 0; k < frame_steps; ++k) {
            drape_status st;
            ms += timed_step(s, dt, &st);
            if (st != DRAPE_OK || s.stats().substeps >= DRAPE_MAX_SUBSTEPS) r.ok = false;
        }
        return ms;
    };
    for (int i = 0; i < warmup; ++i) frame();
    std::vector<double> ms;
    double total = 0;
    while (ms.size() < min_frames || (total < min_seconds * 1e3 && total < max_seconds * 1e3)) {
        ms.push_back(frame());
        total += ms.back();
    }
    drape_stats ss = s.stats();
    r.steps = uint32_t(ms.size());
    r.ms_median = median(ms);
    r.ms_min = *std::min_element(ms.begin(), ms.end());
    r.substeps = ss.substeps * frame_steps;
    r.iterations = ss.iterations;
    r.vit_per_s = double(s.vertices) * r.substeps * ss.iterations / (r.ms_median * 1e-3);
    r.max_strain = ss.max_strain;
    r.rms_strain = ss.rms_strain;
    return r;
}

/// Library steps per 60 Hz frame: 1, or more where MASS_SPRING's stability bound needs more
/// substeps than one step may take (DRAPE_MAX_SUBSTEPS; drape_estimate_stability tells). The
/// hanging cloth needs ~1170 substeps per frame at 128^2 and ~4200 at 256^2 (the dashpot term of
/// the bound dominates there): one step capped at 1000 is unstable and rolled back, so those frames
/// are 3 and 11 library steps.
uint32_t frame_steps_for(const GridSpec& gs, const drape_params& p) {
    drape_cloth_desc cd;
    drape_grid_desc g;
    describe(gs, &cd, &g);
    drape_stability e{};
    e.struct_size = sizeof e;
    die_on(drape_estimate_stability(&cd, &g, nullptr, &p, 1.0f / 60.0f, &e), "drape_estimate_stability");
    return std::max(1u, (e.stable_substeps + DRAPE_MAX_SUBSTEPS - 1) / DRAPE_MAX_SUBSTEPS);
}

std::vector<uint32_t> available_backends() {
    std::vector<uint32_t> out;
    for (uint32_t b : {DRAPE_BACKEND_CPU, DRAPE_BACKEND_CPU_THREADED, DRAPE_BACKEND_GLES}) {
        uint32_t a = 0;
        if (drape_backend_available(b, &a) == DRAPE_OK && a) out.push_back(b);
    }
    return out;
}

void run_throughput(const Options& o) {
    const std::vector<uint32_t> sizes =
        o.quick ? std::vector<uint32_t>{16, 32} : std::vector<uint32_t>{32, 64, 128, 256};
    const auto backends = available_backends();
    Csv csv(
        o.out + "/throughput.csv",
        "size,vertices,model,setting,backend,threads,substeps,iterations,frame_steps,steps,ms_median,ms_min,"
        "vertex_iter_per_s,max_strain,rms_strain,ok");
    // Every model at its automatic budget, and IMPLICIT at 1 x 1 (its cheapest).
    std::vector<Config> configs;
    for (uint32_t m : kModels) configs.push_back({m, 0, 0});
    configs.push_back({DRAPE_MODEL_IMPLICIT, 1, 1});
    g_progress.start("throughput", int(sizes.size() * configs.size() * backends.size()));
    for (uint32_t n : sizes)
        for (const Config& c : configs)
            for (uint32_t b : backends) {
                const uint32_t m = c.model;
                GridSpec gs;
                gs.cols = gs.rows = n;
                gs.backend = b;
                gs.threads = o.threads;
                auto sim = make_grid(gs);
                drape_params p = params_for(m);
                p.substeps = c.substeps;
                p.iterations = c.iterations;
                if (drape_cloth_set_params(sim->cloth, &p) != DRAPE_OK) {  // a model this backend lacks
                    g_progress.tick(std::to_string(n) + "^2 " + model_name(m) + " " + backend_name(b) + ": " +
                                    drape_last_error());
                    continue;
                }
                const uint32_t frame_steps = frame_steps_for(gs, p);
                // MASS_SPRING runs hundreds to thousands of substeps per frame here: fewer frames
                // (a median of 3 in a full run; one at 256^2, where a frame takes a minute or
                // more of a loaded core). From 128^2 no warm-up frame (the first step allocates
                // nothing the later ones would not).
                const bool slow = m == DRAPE_MODEL_MASS_SPRING;
                Timing t = o.quick ? time_cloth(*sim, 0.1, 1.0, slow ? 1 : 5, slow ? 0 : 2, frame_steps)
                                   : time_cloth(*sim, 0.6, 4.0, slow ? (n >= 256 ? 1 : 3) : 9,
                                                slow ? (n >= 128 ? 0 : 1) : 3, frame_steps);
                const std::string setting =
                    c.substeps == 0 ? "auto" : fmt("%g", c.substeps) + "x" + fmt("%g", c.iterations);
                csv.row("%u,%u,%s,%s,%s,%u,%u,%u,%u,%u,%.4f,%.4f,%.4g,%.5g,%.5g,%d", n, sim->vertices,
                        model_name(m), setting.c_str(), backend_name(b),
                        b == DRAPE_BACKEND_CPU ? 1u : o.threads, t.substeps, t.iterations, frame_steps,
                        t.steps, t.ms_median, t.ms_min, t.vit_per_s, t.max_strain, t.rms_strain, int(t.ok));
                g_progress.tick(std::to_string(n) + "^2 " + model_name(m) + " " + backend_name(b) + " " +
                                fmt("%.3g Mvit/s", t.vit_per_s * 1e-6));
            }
    g_progress.finish();
}

// Two threads against one on a shared VM: interleaved rounds (one thread, then two, then the other
// way round), the ratio taken per round, so that a burst of load or a slower hour falls on both
// sides of it; beside each round, what each thread did meanwhile (Linux /proc), so a round in which
// a thread was descheduled shows as such.

/// CPU time of the calling thread, ms: on the CPU backend (a one-thread world) the work of one
/// core, whatever else loads the machine.
double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/// Linux thread ids of this process.
std::vector<long> task_ids() {
    std::vector<long> out;
    if (DIR* d = opendir("/proc/self/task")) {
        while (dirent* e = readdir(d))
            if (e->d_name[0] != '.') out.push_back(std::atol(e->d_name));
        closedir(d);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Thread ids of this process that are not in `before` (task_ids() taken earlier): the workers of a
/// pool created since.
std::vector<long> new_task_ids(const std::vector<long>& before) {
    std::vector<long> out;
    for (long id : task_ids())
        if (!std::binary_search(before.begin(), before.end(), id)) out.push_back(id);
    return out;
}

/// A thread's time on a CPU and its time runnable but waiting for one, ms (/proc/<tid>/schedstat;
/// 0 where the kernel does not keep them), and how often it slept (its voluntary context switches,
/// /proc/<tid>/status: a pool worker sleeps when a gap between passes outlasts its spinning).
struct SchedMs {
    double run = 0, wait = 0, sleeps = 0;
};
SchedMs sched_ms(long tid) {
    SchedMs s;
    const std::string dir = "/proc/self/task/" + std::to_string(tid);
    std::ifstream f(dir + "/schedstat");
    double run_ns = 0, wait_ns = 0;
    if (f >> run_ns >> wait_ns) s.run = run_ns * 1e-6, s.wait = wait_ns * 1e-6;
    std::ifstream status(dir + "/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("voluntary_ctxt_switches:", 0) == 0) s.sleeps = std::atof(line.c_str() + 24);
    return s;
}

/// The whole machine's steal time, ms: what the hypervisor gave other guests while this one's
/// vCPUs wanted to run (/proc/stat, all CPUs summed; 10 ms ticks).
double steal_ms() {
    std::ifstream f("/proc/stat");
    std::string cpu;
    double v[8] = {};
    f >> cpu;
    for (double& x : v) f >> x;
    return v[7] * 1e3 / double(sysconf(_SC_CLK_TCK));
}

/// One round of a timing: its wall time and, over it, the calling thread's CPU time
/// (CLOCK_THREAD_CPUTIME_ID) and wait for a CPU, the timed pool's workers' CPU time and wait
/// (summed over them; a worker spins between passes, so its CPU time counts its waiting for the
/// caller too) and sleeps, and the machine's steal. All ms but the sleeps.
struct Round {
    double wall = 0, caller_cpu = 0, caller_wait = 0, worker_cpu = 0, worker_wait = 0, worker_sleeps = 0, steal = 0;
};
template <class Fn>
Round timed_round(const std::vector<long>& workers, Fn&& fn) {
    const long self = long(syscall(SYS_gettid));
    auto workers_ms = [&] {
        SchedMs sum;
        for (long t : workers) {
            const SchedMs s = sched_ms(t);
            sum.run += s.run, sum.wait += s.wait, sum.sleeps += s.sleeps;
        }
        return sum;
    };
    const SchedMs w0 = workers_ms(), s0 = sched_ms(self);
    const double c0 = thread_cpu_ms(), st0 = steal_ms();
    const auto t0 = Clock::now();
    fn();
    Round r;
    r.wall = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    r.caller_cpu = thread_cpu_ms() - c0;
    r.steal = steal_ms() - st0;
    const SchedMs w1 = workers_ms(), s1 = sched_ms(self);
    r.caller_wait = s1.wait - s0.wait;
    r.worker_cpu = w1.run - w0.run;
    r.worker_wait = w1.wait - w0.wait;
    r.worker_sleeps = w1.sleeps - w0.sleeps;
    return r;
}

/// Quantile q of v (linear between order statistics).
double quantile(std::vector<double> v, double q) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const double at = q * double(v.size() - 1);
    const size_t i = size_t(at);
    return i + 1 < v.size() ? v[i] + (at - double(i)) * (v[i + 1] - v[i]) : v[i];
}

/// The per-round ratios of one thread's wall time to several threads', as the threads CSVs give them:
/// median, quartiles, min, max.
std::string ratio_summary(const std::vector<double>& one, const std::vector<double>& many) {
    std::vector<double> r;
    for (size_t k = 0; k < one.size() && k < many.size(); ++k) r.push_back(one[k] / many[k]);
    return fmt("%.3f", median(r)) + "," + fmt("%.3f", quantile(r, 0.25)) + "," + fmt("%.3f", quantile(r, 0.75)) +
           "," + fmt("%.3f", quantile(r, 0)) + "," + fmt("%.3f", quantile(r, 1));
}

/// One side of an interleaved timing: what it runs per round, the pool's worker threads, its rounds.
struct Side {
    std::string scene, backend;
    uint32_t threads = 1;
    std::function<void()> round;
    std::vector<long> workers;
    std::vector<Round> rounds;
};

/// Runs the sides' rounds interleaved: the sides in groups of `group` consecutive ones (0: one
/// group), each group in turn forwards and backwards, so neither side of a group always follows the
/// other and a burst of load falls on all of them. With one group, its first and last side run twice
/// in a row where the order turns (a warmer cache).
void run_rounds(std::vector<Side>& sides, int rounds, size_t group = 0) {
    const size_t g = group ? group : sides.size();
    for (int k = 0; k < rounds; ++k)
        for (size_t first = 0; first < sides.size(); first += g)
            for (size_t i = 0; i < g && first + i < sides.size(); ++i) {
                const size_t n = std::min(g, sides.size() - first);
                Side& s = sides[first + (k % 2 ? n - 1 - i : i)];
                s.rounds.push_back(timed_round(s.workers, s.round));
            }
}

/// Per-round ratios of a's wall time to b's.
std::vector<double> round_ratios(const Side& a, const Side& b) {
    std::vector<double> r;
    for (size_t k = 0; k < a.rounds.size() && k < b.rounds.size(); ++k) r.push_back(a.rounds[k].wall / b.rounds[k].wall);
    return r;
}

/// run_rounds, then the sides' rounds to rounds_csv and their summaries to csv, with the per-round
/// speed-up against the first reported side (one thread). With `ceiling`, the first and the last
/// side are the short calibration on one thread and on several, in the same rounds and not reported:
/// the machine's two-thread ceiling at the time of each round (idle, one thread's calibration time
/// moved by a fifth from round to round in one run, the two threads' did not), and each reported side
/// with several threads gets its per-round speed-up over that round's ceiling. (At the ends, they are
/// the sides that run twice in a row where run_rounds turns, so each reported side always follows
/// another.)
void interleave(std::vector<Side>& sides, bool ceiling, int rounds, Csv& csv, Csv& rounds_csv,
                const std::string& prefix) {
    run_rounds(sides, rounds);
    const size_t first = ceiling ? 1 : 0, last = ceiling ? sides.size() - 1 : sides.size();
    std::vector<double> one;
    for (const Round& r : sides[first].rounds) one.push_back(r.wall);
    const std::vector<double> ceilings = ceiling ? round_ratios(sides.front(), sides.back()) : std::vector<double>{};
    for (size_t i = first; i < last; ++i) {
        const Side& s = sides[i];
        const std::vector<double> speedup = round_ratios(sides[first], s);
        std::vector<double> over;
        for (size_t k = 0; k < ceilings.size() && k < speedup.size(); ++k) over.push_back(speedup[k] / ceilings[k]);
        std::vector<double> wall;
        double caller_cpu = 0, worker_cpu = 0, wait = 0, sleeps = 0, steal = 0, total = 0;
        for (size_t k = 0; k < s.rounds.size(); ++k) {
            const Round& r = s.rounds[k];
            wall.push_back(r.wall);
            total += r.wall, caller_cpu += r.caller_cpu, worker_cpu += r.worker_cpu;
            wait += r.caller_wait + r.worker_wait, sleeps += r.worker_sleeps, steal += r.steal;
            rounds_csv.row("%s,%s,%s,%u,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.0f,%.4f,%s", prefix.c_str(), s.scene.c_str(),
                           s.backend.c_str(), s.threads, k, r.wall, one[k] / r.wall, r.caller_cpu, r.caller_wait,
                           r.worker_cpu, r.worker_wait, r.worker_sleeps, r.steal,
                           k < ceilings.size() ? fmt("%.4f", ceilings[k]).c_str() : "");
        }
        const double rounds = double(s.rounds.size());
        const std::string vs_ceiling =
            ceilings.empty() || s.threads == 1 ? "," : fmt("%.3f", median(ceilings)) + "," + fmt("%.3f", median(over));
        csv.row("%s,%s,%s,%u,%zu,%.4f,%s,%s,%.3f,%.3f,%.4f,%.1f,%.4f", prefix.c_str(), s.scene.c_str(), s.backend.c_str(),
                s.threads, s.rounds.size(), median(wall), ratio_summary(one, wall).c_str(), vs_ceiling.c_str(),
                caller_cpu / total, worker_cpu / total, wait / rounds, sleeps / rounds, steal / rounds);
    }
}

/// Calibration: the same pool (thread_pool.h) on work with no shared writes (each chunk iterates
/// its own items and writes one sum to its own cache line), in passes about as long as the cloth's
/// (short) and 40x longer (long). Its speed-up is what this machine gives two threads at best, with
/// the pool's barriers (short) and without them (long), in the same run as the cloth's. Passes with
/// no work (empty, 1000 a round), each chunk waiting until every chunk has started so that every
/// thread takes part (with no work the caller would take them all): the pool's own cost per pass
/// (the several threads' ms per round is us per pass; their "speed-up" means nothing). Wide: long
/// passes of 32 independent chains per item, bound by the core's issue width rather than by one
/// chain's latency: two threads on two cores gain as much as in the long passes, two hardware threads
/// of one core (the VM's vCPUs may be such siblings on the host) far less, since they share the issue
/// width that the cloth's SIMD passes need.
struct Calibration {
    explicit Calibration(uint32_t threads) : pool(threads), sums(threads * 16) {}
    /// `passes` passes over `items` items (0: empty passes); wide: 32 chains an item.
    void run(uint32_t items, int passes, bool wide = false) {
        const uint32_t n = pool.size();
        for (int p = 0; p < passes; ++p) {
            std::atomic<uint32_t> started{0};
            pool.run_on_all([&](uint32_t t) {
                if (items == 0) {  // yields after a while: a thread spinning on the other's core would hold it off
                    started.fetch_add(1);
                    for (int spins = 0; started.load() < n; ++spins)
                        if (spins > 1000) std::this_thread::yield();
                    return;
                }
                float acc = 0;
                for (uint32_t i = items * t / n; i < items * (t + 1) / n; ++i) {
                    if (wide) {
                        float x[32];
                        for (int j = 0; j < 32; ++j) x[j] = float(i + j);
                        for (int k = 0; k < 64; ++k)
                            for (int j = 0; j < 32; ++j) x[j] = x[j] * 0.999f + 0.5f;  // independent chains
                        for (int j = 0; j < 32; ++j) acc += x[j];
                        continue;
                    }
                    float x = float(i);
                    for (int k = 0; k < 64; ++k) x = x * 0.999f + 0.5f;  // a dependent chain: compute only
                    acc += x;
                }
                sums[t * 16] = acc;  // 16 floats apart: its own cache line
            });
        }
    }
    drape::ThreadPool pool;
    std::vector<float> sums;
};

void run_threads(const Options& o) {
    const std::vector<uint32_t> sizes =
        o.quick ? std::vector<uint32_t>{32} : std::vector<uint32_t>{64, 128, 256};
    // The default model (IMPLICIT: the issue's "two threads >= 1.8x one") and XPBD.
    const uint32_t models[] = {DRAPE_MODEL_IMPLICIT, DRAPE_MODEL_XPBD};
    const int rounds = o.quick ? 3 : 15;
    Csv csv(o.out + "/threads.csv",
            "part,scene,backend,threads,rounds,wall_ms_median,speedup_median,speedup_q1,speedup_q3,speedup_min,"
            "speedup_max,ceiling_speedup_median,speedup_over_ceiling_median,caller_cpu_share,worker_cpu_share,"
            "wait_ms_per_round,worker_sleeps_per_round,steal_ms_per_round");
    Csv rounds_csv(o.out + "/threads_rounds.csv",
                   "part,scene,backend,threads,round,wall_ms,speedup,caller_cpu_ms,caller_wait_ms,worker_cpu_ms,"
                   "worker_wait_ms,worker_sleeps,steal_ms,ceiling_speedup");
    g_progress.start("threads", int(4 + sizes.size() * std::size(models)));
    // The pool alone: one thread (a pool of 1 runs every chunk on the caller) and o.threads, as
    // sides of a timing (`passes` passes over `items` items a round).
    std::vector<std::unique_ptr<Calibration>> pools;
    auto calibration_sides = [&](const std::string& scene, uint32_t items, int passes, bool wide = false) {
        std::vector<Side> sides;
        for (uint32_t t : {1u, o.threads}) {
            const std::vector<long> before = task_ids();
            pools.push_back(std::make_unique<Calibration>(t));
            Side s;
            s.scene = scene;
            s.backend = "pool";
            s.threads = t;
            s.workers = new_task_ids(before);
            Calibration* c = pools.back().get();
            s.round = [c, items, passes, wide] { c->run(items, passes, wide); };
            sides.push_back(std::move(s));
        }
        return sides;
    };
    // Items per pass: about 50 us of one thread (short: a cloth pass at 64^2-128^2), or 2 ms.
    const double t0 = thread_cpu_ms();
    Calibration(1).run(1 << 16, 4);
    const double ms_per_item = std::max(1e-9, (thread_cpu_ms() - t0) / (4.0 * (1 << 16)));
    const uint32_t short_items = uint32_t(std::max(64.0, 0.05 / ms_per_item));
    const double t1 = thread_cpu_ms();
    Calibration(1).run(1 << 12, 4, true);
    const double ms_per_wide_item = std::max(1e-9, (thread_cpu_ms() - t1) / (4.0 * (1 << 12)));
    for (const char* length : {"empty", "short", "long", "wide"}) {
        const bool empty = length[0] == 'e', short_passes = length[0] == 's', wide = length[0] == 'w';
        const uint32_t items = empty           ? 0
                               : short_passes ? short_items
                                              : uint32_t(std::max(64.0, 2.0 / (wide ? ms_per_wide_item : ms_per_item)));
        const int passes = empty ? 1000 : short_passes ? (o.quick ? 100 : 1000) : (o.quick ? 3 : 25);  // ~50 ms a round
        std::vector<Side> sides = calibration_sides(std::string("calibration_") + length, items, passes, wide);
        interleave(sides, false, rounds, csv, rounds_csv, "calibration");
        g_progress.tick(std::string("calibration ") + length);
    }
    // The falling cloth (two top corners) on the CPU backend (one thread), CPU_THREADED with one
    // thread (the same code path as with several) and with o.threads; all take the same steps (the
    // same bits), so a round is the same work on each. The short calibration in the same rounds
    // (200 passes, ~10 ms of one thread), first and last in the order, is each round's ceiling.
    const std::vector<Side> ceiling = calibration_sides("ceiling", short_items, o.quick ? 20 : 200);
    for (uint32_t n : sizes)
        for (uint32_t model : models) {
            std::vector<std::unique_ptr<Sim>> sims;
            std::vector<Side> sides;
            const std::pair<uint32_t, uint32_t> runs[] = {{DRAPE_BACKEND_CPU, 1u},
                                                          {DRAPE_BACKEND_CPU_THREADED, 1u},
                                                          {DRAPE_BACKEND_CPU_THREADED, o.threads}};
            for (auto [backend, threads] : runs) {
                GridSpec gs;
                gs.cols = gs.rows = n;
                gs.backend = backend;
                gs.threads = threads;
                const std::vector<long> before = task_ids();
                sims.push_back(make_grid(gs));
                sims.back()->set_params(params_for(model));
                Side s;
                s.scene = std::to_string(n) + "^2 " + model_name(model);
                s.backend = backend_name(backend);
                s.threads = threads;
                s.workers = new_task_ids(before);
                sides.push_back(std::move(s));
            }
            // Three steps of warm-up each, then steps per round: about 50 ms of one thread.
            const double t0 = thread_cpu_ms();
            for (auto& s : sims)
                for (int k = 0; k < 3; ++k) drape_cloth_step(s->cloth, 1.0f / 60);
            const int reps = std::max(1, std::min(50, int(50.0 / ((thread_cpu_ms() - t0) / 9.0))));
            for (size_t i = 0; i < sides.size(); ++i) {
                Sim* sim = sims[i].get();
                sides[i].round = [sim, reps] {
                    for (int k = 0; k < reps; ++k) drape_cloth_step(sim->cloth, 1.0f / 60);
                };
            }
            sides.insert(sides.begin(), ceiling[0]);
            sides.push_back(ceiling[1]);
            interleave(sides, true, rounds, csv, rounds_csv, "cloth");
            if (sims[0]->positions() != sims[2]->positions())
                std::fprintf(stderr, "threads: %u^2 %s: CPU_THREADED differs from CPU\n", n, model_name(model));
            g_progress.tick(std::to_string(n) + "^2 " + model_name(model));
        }
    g_progress.finish();
}

// ---------------------------------------------------------------------------------------------
// 2. Work-precision

std::vector<Config> precision_configs(const Options& o, bool chain) {
    std::vector<Config> out;
    // Every substeps x iterations (powers of 2) up to 64 passes per substep-frame; beyond that
    // (the costly corner) XPBD only with 1-2 iterations, up to 256 substeps, where its Pareto front
    // lies (full runs at 925240f and since: more iterations at equal cost were always worse).
    const uint32_t max_cost = o.quick ? 16 : 64;
    const bool quick_diag = o.quick;  // quick: only the equal-cost diagonals 4 and 16
    for (uint32_t m : {DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD}) {
        for (uint32_t s = 1; s <= max_cost; s *= 2)
            for (uint32_t i = 1; s * i <= max_cost; i *= 2)
                if (!quick_diag || s * i == 4 || s * i == 16) out.push_back({m, s, i});
        if (!o.quick && m == DRAPE_MODEL_XPBD)
            for (Config c : {Config{m, 128, 1}, Config{m, 64, 2}, Config{m, 256, 1}, Config{m, 128, 2}})
                out.push_back(c);
    }
    // MASS_SPRING: automatic (the stability bound: 143 at 32^2) and two finer steps. Settings
    // below the bound only blow up, and 1000 substeps cost more than the whole XPBD sweep.
    std::vector<uint32_t> ms = o.quick ? std::vector<uint32_t>{0, 64} : std::vector<uint32_t>{0, 400};
    if (chain) ms = o.quick ? std::vector<uint32_t>{0} : std::vector<uint32_t>{0, 64, 256, 1000};
    for (uint32_t s : ms) out.push_back({DRAPE_MODEL_MASS_SPRING, s, 1});
    // IMPLICIT: the automatic budget (4 x 4) and cheaper / dearer ones.
    for (Config c : {Config{DRAPE_MODEL_IMPLICIT, 0, 0}, Config{DRAPE_MODEL_IMPLICIT, 1, 1},
                     Config{DRAPE_MODEL_IMPLICIT, 1, 4}, Config{DRAPE_MODEL_IMPLICIT, 2, 2}})
        if (!o.quick || c.substeps == 0) out.push_back(c);
    return out;
}

// 2b. Stretch-dominated rest states (accuracy.md R13): curtain pinned along its top row and a
// horizontal sheet pinned along two opposite edges, run to rest (air drag 3 /s, which exerts no
// force at rest), against the double-precision Newton equilibrium of the same springs. Error:
// max vertex distance over the largest displacement from the rest pose, the same for the lowest
// point, and the lowest point's error over the hanging length (the metric of the Jolt 5.5 figures
// that plot.py sets beside the curtain's).
double max_distance(const std::vector<float>& x, const std::vector<double>& xr);

/// The settings of the rest scenes: the library's defaults as they are (model, budget, tethers),
/// then without tethers XPBD at its automatic budget and finer, MASS_SPRING at its stability
/// bound, IMPLICIT at its automatic budget and at 1 x 1 (substeps/iterations 0 = automatic: the
/// budget comes from the library). Up to `rest_size` a setting runs to rest; larger sizes up to
/// `max_size` only take part in the timing rounds (MASS_SPRING at 129^2: 320 substeps, 0.5 s of
/// CPU and 1.2 s on the loaded 2-core machine per frame, so 600 frames to rest would be 12 minutes
/// of the run). At 257^2 only the default and IMPLICIT auto run to rest (no XPBD setting here
/// rests within 0.5 % from 65^2 on, and IMPLICIT 1x1 rests where IMPLICIT auto does);
/// MASS_SPRING is left out there: its stability bound needs ~1300 substeps per frame, more than
/// one step may take (DRAPE_MAX_SUBSTEPS), so a frame would be rolled back.
struct RestConfig {
    Config c;
    float max_stretch;
    uint32_t max_size;
    uint32_t rest_size = 129;
};
std::vector<RestConfig> rest_configs(const Options& o) {
    const drape_params def = library_default();
    std::vector<RestConfig> out = {{{def.model, def.substeps, def.iterations}, def.max_stretch, 257, 257},
                                   {{DRAPE_MODEL_XPBD, 0, 0}, 0, 257},
                                   {{DRAPE_MODEL_IMPLICIT, 0, 0}, 0, 257, 257},
                                   {{DRAPE_MODEL_IMPLICIT, 1, 1}, 0, 257},
                                   {{DRAPE_MODEL_MASS_SPRING, 0, 0}, 0, 129, 65},
                                   {{DRAPE_MODEL_XPBD, 64, 1}, 0, 257}};
    if (!o.quick) out.push_back({{DRAPE_MODEL_XPBD, 32, 1}, 0, 65});
    if (!o.rest_models.empty())  // the default (first) always runs
        out.erase(std::remove_if(out.begin() + 1, out.end(),
                                 [&](const RestConfig& rc) { return !o.rest_models.count(model_name(rc.c.model)); }),
                  out.end());
    return out;
}
/// Each size's Newton solve starts from the one below (bench::add_coarse_displacement), so it
/// takes a few iterations, and its LDL^T serves several of them (reference.h): one factorisation
/// of the 257^2 grid (198k unknowns) takes minutes.
std::vector<uint32_t> rest_sizes(const Options& o, bool curtain) {
    if (o.quick) return curtain ? std::vector<uint32_t>{17, 33} : std::vector<uint32_t>{17};
    std::vector<uint32_t> sizes;
    for (uint32_t n : {17u, 33u, 65u, 129u, 257u})
        if (n <= o.rest_largest) sizes.push_back(n);
    return sizes;
}
int rest_runs(const Options& o) {
    int n = 0;
    for (bool curtain : {true, false})
        for (uint32_t size : rest_sizes(o, curtain))
            for (const RestConfig& rc : rest_configs(o)) n += size <= rc.max_size;
    return n;
}

/// A rest scene and its Newton equilibrium: a curtain pinned along its top row (1 kg) or a
/// horizontal sheet pinned along two opposite edges (0.5 kg), the default springs.
struct RestScene {
    GridSpec grid;
    std::vector<float> w;         ///< inverse masses, 0 where pinned
    std::vector<double> x, rest;  ///< equilibrium and rest positions
    double largest = 0;           ///< largest displacement of the equilibrium from rest
    size_t low_v = 0;             ///< lowest vertex of the equilibrium
    double low_ref = 0, low_rest = 0, ref_strain = 0;
};

/// The scene at n^2; its Newton solve starts from `coarser`'s solution where it has one (cols > 0).
RestScene rest_scene(const Options& o, bool curtain, uint32_t n, const RestScene& coarser) {
    RestScene r;
    GridSpec& gs = r.grid;
    gs.cols = gs.rows = n;
    gs.mass = curtain ? 1.0 : 0.5;
    gs.vertical = curtain;
    gs.pins = Pins::None;
    gs.threads = 1;
    // Reference: same springs, masses, pins.
    const drape_params base = params_for(DRAPE_MODEL_IMPLICIT);
    const double k[3] = {base.stiffness[0], base.stiffness[1], base.stiffness[2]};
    const double spacing = 1.0 / (n - 1);
    const auto springs = bench::grid_springs(n, n, spacing, spacing, k);
    std::vector<double>& x = r.x;
    x.assign(size_t(n) * n * 3, 0.0);
    std::vector<double> mass(size_t(n) * n, gs.mass / (n * n));
    r.w.assign(size_t(n) * n, float(n * n / gs.mass));
    for (uint32_t row = 0; row < n; ++row)
        for (uint32_t c = 0; c < n; ++c) {
            const size_t v = size_t(row) * n + c;
            x[3 * v] = c * spacing;
            x[3 * v + (curtain ? 1 : 2)] = -double(row) * spacing;
            if (curtain ? row == 0 : (c == 0 || c == n - 1)) mass[v] = 0, r.w[v] = 0;
        }
    r.rest = x;
    if (coarser.grid.cols > 0 && !coarser.x.empty())
        bench::add_coarse_displacement(x, n, coarser.x, coarser.rest, coarser.grid.cols);
    const double g[3] = {0, -kG, 0};
    bench::SolveStats st;
    const auto t0 = Clock::now();
    const double residual = bench::solve_static(x, mass, springs, g, &st);
    std::fprintf(stderr, "rest: %s %u^2 Newton reference: gradient %.2g N after %d iterations (%d LDL^T, %d CG) in %.1f s\n",
                 curtain ? "curtain" : "sheet", n, residual, st.newton, st.factorisations, st.cg,
                 std::chrono::duration<double>(Clock::now() - t0).count());
    r.ref_strain = bench::max_strain(x, springs, k[2]);
    for (size_t v = 0; v < mass.size(); ++v) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a)
            d2 += (x[3 * v + a] - r.rest[3 * v + a]) * (x[3 * v + a] - r.rest[3 * v + a]);
        r.largest = std::max(r.largest, std::sqrt(d2));
        if (x[3 * v + 1] < r.low_ref) r.low_ref = x[3 * v + 1], r.low_v = v, r.low_rest = r.rest[3 * v + 1];
    }
    std::ofstream f(o.out + "/reference.csv", std::ios::app);
    f << (curtain ? "curtain" : "sheet") << "_rest," << n << "," << residual << "," << r.ref_strain
      << ",newton_static\n";
    return r;
}

void run_rest(const Options& o) {
    Csv csv(o.out + "/rest.csv",
            "scene,size,model,setting,substeps,iterations,max_stretch,is_default,cpu_ms_median,wall_ms_"
            "median,rounds,"
            "vertex_error,lowest_error,length_error,max_strain,ref_max_strain,ok,threads,threaded_wall_ms_"
            "median,threaded_same,speedup_median,speedup_q1,speedup_q3,speedup_min,speedup_max");
    const int steps = o.quick ? 180 : 600, rounds = o.quick ? 3 : 5;
    g_progress.start("rest", rest_runs(o));
    for (const char* scene_name : {"curtain", "sheet"}) {
        const bool curtain = scene_name[0] == 'c';
        RestScene coarser;
        for (uint32_t n : rest_sizes(o, curtain)) {
            const RestScene scene = rest_scene(o, curtain, n, coarser);
            // Every setting of this scene and size runs to rest, then they are timed in
            // interleaved rounds, so a burst of load from other processes falls on all of them.
            struct Run {
                RestConfig rc;
                bool is_default, at_rest;
                std::unique_ptr<Sim> sim;
                /// CPU_THREADED twin (o.threads), run to rest by the same steps as sim (the same
                /// bits, so the same state and iterations); timed by the wall clock (its work is on
                /// several threads). A twin started from sim's positions alone lost its velocity and
                /// fresh-start state, and took more iterations than sim in the rounds.
                std::unique_ptr<Sim> threaded;
                std::vector<long> workers;  ///< the twin's pool's worker threads
                bool threaded_same = false;  ///< the twin's positions equal sim's, bit for bit, at rest
                bool ok = true;
                int reps = 1;  ///< steps per round: about 50 ms of work, at least one
                std::vector<double> cpu_ms, wall_ms, threaded_wall_ms;
            };
            std::vector<Run> runs;
            const std::vector<RestConfig> configs = rest_configs(o);
            for (const RestConfig& rc : configs) {
                if (n > rc.max_size) continue;
                Run r;
                r.rc = rc;
                r.is_default = &rc == &configs[0];
                drape_params p = params_for(rc.c.model);
                p.substeps = rc.c.substeps;
                p.iterations = rc.c.iterations;
                p.air_drag = 3;
                p.max_stretch = rc.max_stretch;
                r.sim = make_grid(scene.grid);
                r.sim->set_inverse_masses(scene.w);
                r.sim->set_params(p);
                r.at_rest = n <= rc.rest_size;
                const int to_rest = r.at_rest ? steps : 1;
                const double t0 = thread_cpu_ms();
                for (int step = 0; step < to_rest; ++step)
                    if (drape_cloth_step(r.sim->cloth, 1.0f / 60) != DRAPE_OK) r.ok = false;
                r.reps = std::max(1, std::min(50, int(50.0 / ((thread_cpu_ms() - t0) / to_rest))));
                if (o.threads > 1) {
                    GridSpec tg = scene.grid;
                    tg.backend = DRAPE_BACKEND_CPU_THREADED;
                    tg.threads = o.threads;
                    const std::vector<long> before = task_ids();
                    r.threaded = make_grid(tg);
                    r.workers = new_task_ids(before);
                    r.threaded->set_inverse_masses(scene.w);
                    r.threaded->set_params(p);
                    for (int step = 0; step < to_rest; ++step)
                        if (drape_cloth_step(r.threaded->cloth, 1.0f / 60) != DRAPE_OK) r.ok = false;
                    r.threaded_same = r.threaded->positions() == r.sim->positions();
                    if (!r.threaded_same)
                        std::fprintf(stderr, "rest: %s %u^2 %s: CPU_THREADED differs from CPU\n", scene_name, n,
                                     model_name(rc.c.model));
                }
                g_progress.tick(std::string(scene_name) + " " + std::to_string(n) + "^2 " +
                                model_name(rc.c.model) + (r.at_rest ? " to rest" : " (timing only)"));
                runs.push_back(std::move(r));
            }
            // One thread and the twin of each setting, interleaved (run_rounds, a group per setting: in
            // odd rounds the twin first); the speed-up is taken per round (threads.csv's way).
            std::vector<Side> sides;
            for (Run& r : runs)
                for (Sim* sim : {r.sim.get(), r.threaded.get()}) {
                    if (!sim) continue;
                    Side side;
                    side.workers = sim == r.threaded.get() ? r.workers : std::vector<long>{};
                    side.round = [&r, sim] {
                        for (int k = 0; k < r.reps; ++k)
                            if (drape_cloth_step(sim->cloth, 1.0f / 60) != DRAPE_OK) r.ok = false;
                    };
                    sides.push_back(std::move(side));
                }
            run_rounds(sides, rounds, o.threads > 1 ? 2 : 1);
            for (size_t k = 0, side = 0; k < runs.size(); ++k) {
                Run& r = runs[k];
                for (const Round& round : sides[side].rounds) {
                    r.cpu_ms.push_back(round.caller_cpu / r.reps);
                    r.wall_ms.push_back(round.wall / r.reps);
                }
                if (r.threaded)
                    for (const Round& round : sides[side + 1].rounds) r.threaded_wall_ms.push_back(round.wall / r.reps);
                side += r.threaded ? 2 : 1;
            }
            for (const Run& r : runs) {
                const std::vector<float> xs = r.sim->positions();
                const double low = xs[3 * scene.low_v + 1];
                const double e_vertex = r.at_rest ? max_distance(xs, scene.x) / scene.largest : NAN;
                const double e_low =
                    r.at_rest ? std::fabs(low - scene.low_ref) / std::fabs(scene.low_ref - scene.low_rest)
                              : NAN;
                const double e_length =
                    r.at_rest ? std::fabs(low - scene.low_ref) / std::fabs(scene.low_ref) : NAN;
                const drape_stats ss = r.sim->stats();
                const Config& c = r.rc.c;
                const std::string setting =
                    c.substeps == 0 && c.iterations == 0 ? "auto"
                    : c.model == DRAPE_MODEL_MASS_SPRING
                        ? std::to_string(c.substeps)
                        : std::to_string(c.substeps) + "x" + std::to_string(c.iterations);
                csv.row("%s,%u,%s,%s,%u,%u,%g,%d,%.4f,%.4f,%d,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%u,%.4f,%s,%s",
                        scene_name, n, model_name(c.model), setting.c_str(), ss.substeps, ss.iterations,
                        double(r.rc.max_stretch), int(r.is_default), median(r.cpu_ms), median(r.wall_ms),
                        rounds, e_vertex, e_low, e_length, ss.max_strain, scene.ref_strain, int(r.ok),
                        r.threaded ? o.threads : 1u, r.threaded ? median(r.threaded_wall_ms) : NAN,
                        r.threaded ? (r.threaded_same ? "1" : "0") : "",
                        r.threaded ? ratio_summary(r.wall_ms, r.threaded_wall_ms).c_str() : ",,,,");
            }
            coarser = scene;
        }
    }
    g_progress.finish();
}

/// Static equilibrium of the cloth hanging from its two top corners (n x n, 1 m, 0.2 kg, the
/// default springs) by Newton in double precision (reference.h). Appends it to reference.csv.
struct TwoCornerRef {
    uint32_t n = 0;
    std::vector<double> x, rest;  ///< equilibrium and rest positions
    double residual = NAN, max_strain = NAN;
};
/// `coarser`: a solution at a smaller size whose displacement starts the Newton solve (none if empty).
TwoCornerRef two_corner_reference(const Options& o, uint32_t n, const TwoCornerRef& coarser = {}) {
    TwoCornerRef r;
    const GridSpec gs;
    const drape_params base = params_for(DRAPE_MODEL_XPBD);
    const double k[3] = {base.stiffness[0], base.stiffness[1], base.stiffness[2]};
    const double spacing = 1.0 / (n - 1);
    auto springs = bench::grid_springs(n, n, spacing, spacing, k);
    r.x.assign(size_t(n) * n * 3, 0.0);
    std::vector<double> mass(size_t(n) * n, gs.mass / (n * n));
    for (uint32_t row = 0; row < n; ++row)
        for (uint32_t c = 0; c < n; ++c) {
            r.x[3 * (row * n + c)] = c * spacing;
            r.x[3 * (row * n + c) + 1] = -double(row) * spacing;
        }
    mass[0] = mass[n - 1] = 0;
    r.rest = r.x;
    if (!coarser.x.empty()) bench::add_coarse_displacement(r.x, n, coarser.x, coarser.rest, coarser.n);
    r.n = n;
    const double g[3] = {0, -kG, 0};
    r.residual = bench::solve_static(r.x, mass, springs, g);
    r.max_strain = bench::max_strain(r.x, springs, k[2]);
    std::ofstream f(o.out + "/reference.csv", std::ios::app);
    f << "two_corners," << n << "," << r.residual << "," << r.max_strain << ",newton_static\n";
    return r;
}

double max_distance(const std::vector<float>& x, const std::vector<double>& xr) {
    double e = 0;
    for (size_t i = 0; i + 2 < x.size(); i += 3) {
        double dx = x[i] - xr[i], dy = x[i + 1] - xr[i + 1], dz = x[i + 2] - xr[i + 2];
        double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        e = std::max(e, std::isfinite(d) ? d : INFINITY);
    }
    return e;
}

/// Cloth hanging from its two top corners in the x-y plane. Reference: the static equilibrium
/// of the same springs, masses and pins, by Newton in double precision (reference.h). The
/// simulation starts flat and unstretched and runs `seconds` at 60 Hz with the default damping;
/// E2 is measured at the end. Energy drift comes from a second, undamped run (damping 0,
/// air drag 0) over `energy_seconds`: max |E(t) - E(0)| / (M g H).
void run_precision_cloth(const Options& o, Csv& csv) {
    const uint32_t n = o.quick ? 12 : 32;
    const double seconds = o.quick ? 1.0 : 3.0, energy_seconds = o.quick ? 0.25 : 1.0;
    const float dt = 1.0f / 60.0f;
    GridSpec gs;
    gs.cols = gs.rows = n;
    const TwoCornerRef ref = two_corner_reference(o, n);
    const std::vector<double>& xr = ref.x;
    const double ref_strain = ref.max_strain;
    for (const Config& c : precision_configs(o, false)) {
        drape_params p = params_for(c.model);
        p.substeps = c.substeps;
        p.iterations = c.iterations;
        auto sim = make_grid(gs);
        sim->set_params(p);
        std::vector<double> ms;
        bool ok = true;
        drape_status st;
        for (int step = 0; step < int(seconds * 60 + 0.5); ++step) {
            ms.push_back(timed_step(*sim, dt, &st));
            if (st != DRAPE_OK) ok = false;
        }
        const drape_stats ss = sim->stats();
        const double e2 = max_distance(sim->positions(), xr);
        // Undamped run for the energy drift.
        drape_params pu = p;
        pu.damping = 0;
        pu.air_drag = 0;
        auto su = make_grid(gs);
        su->set_params(pu);
        const double e0 = Monitor::energy(su->stats());
        double drift = 0, drift_end = 0;
        for (int step = 0; step < int(energy_seconds * 60 + 0.5); ++step) {
            if (drape_cloth_step(su->cloth, dt) != DRAPE_OK) ok = false;
            drift_end = (Monitor::energy(su->stats()) - e0) / (gs.mass * kG * gs.height);
            drift = std::max(drift, std::fabs(drift_end));
        }
        csv.row("two_corners,%u,%s,cpu,%u,%u,%u,%.4f,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%.3g,%.5g", n,
                model_name(c.model), ss.substeps, ss.iterations, c.substeps == 0 ? 1 : 0, median(ms),
                ss.max_strain, ss.rms_strain, ref_strain, std::fabs(ss.max_strain - ref_strain) / ref_strain,
                e2 / gs.height, drift, drift_end, int(ok), double(p.max_stretch), NAN);
        g_progress.tick(std::string("cloth ") + model_name(c.model) + " s" + std::to_string(ss.substeps) +
                        " i" + std::to_string(ss.iterations));
    }
}

/// R4 hanging chain: N particles of mass m below a pinned top, tip mass M (mass ratio M/(N m)),
/// spring stiffness chosen so the top spring's exact strain is 1%. Starts at the exact
/// equilibrium at rest; E2 = max over 2 s of max_j |x_j - exact_j| / (N L0).
void run_precision_chain(const Options& o, Csv& csv) {
    const uint32_t N = 20;
    const double L0 = 0.05, m = 0.005;
    const float dt = 1.0f / 60.0f;
    const double seconds = o.quick ? 1.0 : 2.0;
    const std::vector<double> ratios =
        o.quick ? std::vector<double>{1e3} : std::vector<double>{1, 1e2, 1e4, 1e5};
    for (double ratio : ratios) {
        const double M = ratio * N * m;
        const double k = (N * m + M) * kG / (0.01 * L0);
        std::vector<float> exact(size_t(N + 1) * 3, 0.0f);
        for (uint32_t j = 0; j <= N; ++j)
            exact[3 * j + 1] =
                -float(j * L0 + (m * kG / k) * (double(j) * N - 0.5 * j * (j - 1.0)) + M * kG * j / k);
        const double ext_exact = -exact[3 * N + 1] - N * L0;
        for (const Config& c : precision_configs(o, true)) {
            GridSpec gs;
            gs.cols = 1;
            gs.rows = N + 1;
            gs.width = 1.0;
            gs.height = N * L0;
            gs.mass = N * m + M;
            gs.pins = Pins::TopVertex;
            auto sim = make_grid(gs);
            std::vector<float> w(N + 1, float(1.0 / m));
            w[0] = 0;
            w[N] = float(1.0 / (m + M));
            sim->set_inverse_masses(w);
            drape_params p = params_for(c.model);
            if (c.model == DRAPE_MODEL_PBD)
                p.stiffness[0] = 1.0f;
            else
                p.stiffness[0] = float(k);
            p.stiffness[1] = p.stiffness[2] = 0;
            p.substeps = c.substeps;
            p.iterations = c.iterations;
            sim->set_params(p);
            sim->set_positions(exact);
            std::vector<double> ms;
            double e2 = 0;
            bool ok = true;
            drape_status st;
            for (int step = 0; step < int(seconds * 60 + 0.5); ++step) {
                ms.push_back(timed_step(*sim, dt, &st));
                if (st != DRAPE_OK) ok = false;
                const std::vector<float> x = sim->positions();
                for (uint32_t j = 0; j <= N; ++j) {
                    double dx = x[3 * j] - exact[3 * j], dy = x[3 * j + 1] - exact[3 * j + 1],
                           dz = x[3 * j + 2] - exact[3 * j + 2];
                    double e = std::sqrt(dx * dx + dy * dy + dz * dz);
                    e2 = std::max(e2, std::isfinite(e) ? e : INFINITY);
                }
            }
            const drape_stats ss = sim->stats();
            const std::vector<float> x = sim->positions();
            const double ext = -x[3 * N + 1] - N * L0;
            csv.row("chain_1e%g,%u,%s,cpu,%u,%u,%u,%.4f,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%.3g,%.5g",
                    std::log10(ratio), N + 1, model_name(c.model), ss.substeps, ss.iterations,
                    c.substeps == 0 ? 1 : 0, median(ms), ss.max_strain, ss.rms_strain, 0.01,
                    std::fabs(ss.max_strain - 0.01) / 0.01, e2 / (N * L0),
                    std::fabs(ext - ext_exact) / ext_exact, NAN, int(ok), double(p.max_stretch), NAN);
            g_progress.tick(std::string("chain 1e") + fmt("%g ", std::log10(ratio)) + model_name(c.model) +
                            " s" + std::to_string(ss.substeps) + " i" + std::to_string(ss.iterations));
        }
    }
}

/// Tethers (drape_params.max_stretch) on the two-corner cloth at 64^2 and 128^2 (quick: 16^2):
/// the same scene and Newton reference as run_precision_cloth, each PBD/XPBD setting run with
/// max_stretch 0 (off) and the default. MASS_SPRING is left out (hundreds of substeps per frame
/// at these sizes: minutes). Reported: max strain at the end and its peak over the run, E2 at
/// the end.
int tether_rows(const Options& o) { return int((o.quick ? 1 : 2) * 3 * 2); }
void run_precision_tethers(const Options& o, Csv& csv) {
    const std::vector<uint32_t> sizes = o.quick ? std::vector<uint32_t>{16} : std::vector<uint32_t>{64, 128};
    const double seconds = o.quick ? 1.0 : 3.0;
    const float dt = 1.0f / 60.0f;
    const drape_params def = library_default();
    const Config cfgs[] = {{DRAPE_MODEL_XPBD, 0, def.iterations},
                           {DRAPE_MODEL_PBD, 0, def.iterations},
                           {DRAPE_MODEL_XPBD, 4, 4}};
    for (uint32_t n : sizes) {
        const TwoCornerRef ref = two_corner_reference(o, n);
        GridSpec gs;
        gs.cols = gs.rows = n;
        for (const Config& c : cfgs)
            for (float stretch : {0.0f, def.max_stretch}) {
                drape_params p = params_for(c.model);
                p.substeps = c.substeps;
                p.iterations = c.iterations;
                p.max_stretch = stretch;
                auto sim = make_grid(gs);
                sim->set_params(p);
                std::vector<double> ms;
                bool ok = true;
                drape_status st;
                float peak = 0;
                for (int step = 0; step < int(seconds * 60 + 0.5); ++step) {
                    ms.push_back(timed_step(*sim, dt, &st));
                    if (st != DRAPE_OK) ok = false;
                    peak = std::max(peak, sim->stats().max_strain);
                }
                const drape_stats ss = sim->stats();
                const double e2 = max_distance(sim->positions(), ref.x);
                csv.row(
                    "two_corners_%u,%u,%s,cpu,%u,%u,%u,%.4f,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%.3g,%.5g",
                    n, n, model_name(c.model), ss.substeps, ss.iterations, c.substeps == 0 ? 1 : 0,
                    median(ms), ss.max_strain, ss.rms_strain, ref.max_strain,
                    std::fabs(ss.max_strain - ref.max_strain) / ref.max_strain, e2 / gs.height, NAN, NAN,
                    int(ok), double(stretch), double(peak));
                g_progress.tick(fmt("tethers %g ", stretch) + std::to_string(n) + "^2 " +
                                model_name(c.model) + " s" + std::to_string(ss.substeps) + " i" +
                                std::to_string(ss.iterations));
            }
    }
}

/// Cloth draped onto a sphere: a horizontal 1 m cloth (no pins) starts at rest 5 cm above a
/// sphere of radius 0.25 m (centre slightly off the cloth's centre), friction 0.5, margin 5 mm,
/// falls onto it (contact at ~0.1 s) and wraps over it. No exact answer: the reference is the
/// same scene converged, XPBD with 1 iteration and the most substeps the library takes (1000 per
/// 1/60 s frame, h = 1.7e-5 s), in float. Its own error is estimated by the distance to the same
/// run at 500 substeps (reference.csv). E2 = max vertex distance to the reference at 0.2 s / cloth
/// size. Measured later, the scene has no converged answer to compare with: once the overhang
/// buckles into folds (from ~0.25 s), the 1000- and 500-substep runs differ by 3-10 cm in
/// max norm at 0.3-1.5 s, and 1000 vs 250 no closer (16^2, measured while building this).
std::vector<Config> sphere_configs(const Options& o) {
    std::vector<Config> out;
    for (uint32_t m : {DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD})
        for (uint32_t s : {1u, 4u, 16u, 64u, 256u})
            for (uint32_t i : {1u, 4u, 16u})
                if (s * i <= (o.quick ? 16u : 256u) && (!o.quick || s * i >= 4)) out.push_back({m, s, i});
    for (uint32_t s : o.quick ? std::vector<uint32_t>{0} : std::vector<uint32_t>{0, 500})
        out.push_back({DRAPE_MODEL_MASS_SPRING, s, 1});
    out.push_back({DRAPE_MODEL_IMPLICIT, 0, 0});  // its automatic budget
    return out;
}
// The benchmarks' sphere collider (id 1, 5 mm margin) at (x, y, z) with radius r.
drape_collider bench_sphere(float x, float y, float z, float r, float friction = 0.3f) {
    drape_collider c{};
    c.struct_size = sizeof c;
    c.shape = DRAPE_COLLIDER_SPHERE;
    c.id = 1;
    c.position[0] = x;
    c.position[1] = y;
    c.position[2] = z;
    c.rotation[3] = 1.0f;
    c.size[0] = r;
    c.margin = 0.005f;
    c.friction = friction;
    return c;
}

void run_precision_sphere(const Options& o, Csv& csv) {
    const uint32_t n = o.quick ? 12 : 32;
    const double seconds = 0.2;
    const float dt = 1.0f / 60.0f;
    GridSpec gs;
    gs.cols = gs.rows = n;
    gs.vertical = false;  // x-z plane at y = 0: x in [0, 1], z in [-1, 0]
    gs.pins = Pins::None;
    const drape_collider sphere = bench_sphere(0.52f, -0.30f, -0.47f, 0.25f, 0.5f);
    struct Run {
        std::vector<float> x;
        std::vector<double> ms;
        drape_stats stats{};
        bool ok = true;
    };
    auto run = [&](const Config& c) {
        Run r;
        drape_params p = params_for(c.model);
        p.substeps = c.substeps;
        p.iterations = c.iterations;
        auto sim = make_grid(gs);
        sim->set_params(p);
        die_on(drape_cloth_set_colliders(sim->cloth, &sphere, 1), "drape_cloth_set_colliders");
        drape_status st;
        for (int step = 0; step < int(seconds * 60 + 0.5); ++step) {
            r.ms.push_back(timed_step(*sim, dt, &st));
            if (st != DRAPE_OK) r.ok = false;
        }
        r.x = sim->positions();
        r.stats = sim->stats();
        return r;
    };
    const Run ref = run({DRAPE_MODEL_XPBD, 1000, 1});
    g_progress.tick("sphere reference xpbd s1000 i1");
    const Run half = run({DRAPE_MODEL_XPBD, 500, 1});
    g_progress.tick("sphere reference check s500");
    std::vector<double> xr(ref.x.begin(), ref.x.end());
    const double self_error = max_distance(half.x, xr);
    {
        std::ofstream f(o.out + "/reference.csv", std::ios::app);
        f << "sphere_drape," << n << "," << self_error << "," << ref.stats.max_strain
          << ",xpbd_1000x1_vs_500x1\n";
    }
    for (const Config& c : sphere_configs(o)) {
        const Run r = run(c);
        const double e2 = max_distance(r.x, xr);
        csv.row("sphere_drape,%u,%s,cpu,%u,%u,%u,%.4f,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%.3g,%.5g", n,
                model_name(c.model), r.stats.substeps, r.stats.iterations, c.substeps == 0 ? 1 : 0,
                median(r.ms), r.stats.max_strain, r.stats.rms_strain, ref.stats.max_strain,
                std::fabs(r.stats.max_strain - ref.stats.max_strain) / std::max(ref.stats.max_strain, 1e-6f),
                e2 / gs.width, NAN, NAN, int(r.ok), double(params_for(c.model).max_stretch), NAN);
        g_progress.tick(std::string("sphere ") + model_name(c.model) + " s" +
                        std::to_string(r.stats.substeps) + " i" + std::to_string(r.stats.iterations));
    }
}

void run_precision(const Options& o) {
    // energy_drift for chains is the relative error of the tip extension (column reused, see header).
    Csv csv(o.out + "/precision.csv",
            "scene,size,model,backend,substeps,iterations,auto_substeps,ms_median,max_strain,rms_strain,ref_"
            "max_strain,"
            "e1_rel_error,e2,energy_drift_or_ext_error,energy_drift_end,ok,max_stretch,peak_max_strain");
    const int cloth = int(precision_configs(o, false).size());
    const int chain = int(precision_configs(o, true).size()) * (o.quick ? 1 : 4);
    const int sphere = int(sphere_configs(o).size()) + 2;
    g_progress.start("precision", cloth + chain + tether_rows(o) + sphere);
    run_precision_cloth(o, csv);
    run_precision_chain(o, csv);
    run_precision_tethers(o, csv);
    run_precision_sphere(o, csv);
    g_progress.finish();
}

/// Stiff under load: the cloth hanging from its two top corners (precision's two_corners scene)
/// at 128^2 and 256^2 (quick: 16^2, 32^2), 3 s at 60 Hz from flat with the default damping; its
/// max strain (structural and shear springs, drape_stats) at the end against the exact
/// equilibrium's (Newton, each size started from the one below: 32^2, 64^2, 128^2, 256^2). The
/// library's default as it is, its model without tethers, and IMPLICIT and XPBD at their
/// automatic budgets without tethers.
void run_stiff(const Options& o) {
    Csv csv(o.out + "/stiff_under_load.csv",
            "size,model,setting,max_stretch,is_default,seconds,max_strain,ref_max_strain,strain_over_ref,ms_median,ok");
    const std::vector<uint32_t> sizes = o.quick ? std::vector<uint32_t>{16, 32} : std::vector<uint32_t>{128, 256};
    const drape_params def = library_default();
    struct Setting {
        Config c;
        float max_stretch;
    };
    std::vector<Setting> settings = {{{def.model, def.substeps, def.iterations}, def.max_stretch}};
    for (Setting st : {Setting{{def.model, def.substeps, def.iterations}, 0}, Setting{{DRAPE_MODEL_IMPLICIT, 0, 0}, 0},
                       Setting{{DRAPE_MODEL_XPBD, 0, 0}, 0}}) {
        const bool seen = std::any_of(settings.begin(), settings.end(), [&](const Setting& t) {
            return t.c.model == st.c.model && t.c.substeps == st.c.substeps && t.c.iterations == st.c.iterations &&
                   t.max_stretch == st.max_stretch;
        });
        if (!seen) settings.push_back(st);
    }
    const double seconds = 3.0;
    g_progress.start("stiff", int(sizes.size() * settings.size()));
    TwoCornerRef ref;
    for (uint32_t n = sizes.front() / 4; n <= sizes.back(); n *= 2) {
        ref = two_corner_reference(o, n, ref);
        if (n < sizes.front()) continue;
        GridSpec gs;
        gs.cols = gs.rows = n;
        gs.threads = 1;
        for (const Setting& st : settings) {
            drape_params p = params_for(st.c.model);
            p.substeps = st.c.substeps;
            p.iterations = st.c.iterations;
            p.max_stretch = st.max_stretch;
            auto sim = make_grid(gs);
            sim->set_params(p);
            std::vector<double> ms;
            bool ok = true;
            drape_status status;
            for (int step = 0; step < int(seconds * 60 + 0.5); ++step) {
                ms.push_back(timed_step(*sim, 1.0f / 60, &status));
                if (status != DRAPE_OK) ok = false;
            }
            const drape_stats ss = sim->stats();
            const bool is_default = &st == &settings[0];
            const std::string setting = st.c.substeps == 0 ? "auto" : fmt("%g", st.c.substeps) + "x" + fmt("%g", st.c.iterations);
            csv.row("%u,%s,%s,%g,%d,%g,%.5g,%.5g,%.4g,%.4f,%d", n, model_name(st.c.model), setting.c_str(),
                    double(st.max_stretch), int(is_default), seconds, ss.max_strain, ref.max_strain,
                    ss.max_strain / ref.max_strain, median(ms), int(ok));
            g_progress.tick(std::to_string(n) + "^2 " + model_name(st.c.model) + " " + setting +
                            fmt(" strain x%.3g", ss.max_strain / ref.max_strain));
        }
    }
    g_progress.finish();
}

/// Motion: the sheet of the stress part (horizontal, pinned at two corners of one edge, 0.2 kg)
/// falling from flat for 0.5 s at 60 Hz with the default damping, at the library's stiffness
/// times 1, 10 and 50 (structural 2e3, 2e4, 1e5 N/m), 17^2 (quick: 9^2). Rest-state scenes cannot
/// see how fast a cloth moves; this one can. Reference: MASS_SPRING (the same springs, dashpots and
/// tethers, integrated explicitly within its stability bound) stepped in `calls` library steps per
/// frame, `calls` doubled until no step is refused; its own error is the distance to the same run
/// at half the substep. Each setting's error: the largest distance of any vertex from the
/// reference's at any frame, over the cloth size, and how far its centre of mass fell against
/// the reference's (1 = as far).
void run_fall(const Options& o) {
    Csv csv(o.out + "/fall.csv",
            "size,stiffness_scale,structural_stiffness,model,setting,is_default,ms_median,max_vertex_error,fall_ratio,"
            "ref_error,ok");
    const uint32_t n = o.quick ? 9 : 17;
    const int frames = 30;
    const float dt = 1.0f / 60;
    const drape_params def = library_default();
    const std::vector<Config> settings = {{def.model, def.substeps, def.iterations},
                                          {DRAPE_MODEL_IMPLICIT, 1, 1},
                                          {DRAPE_MODEL_IMPLICIT, 2, 16},
                                          {DRAPE_MODEL_XPBD, 0, 0},
                                          {DRAPE_MODEL_XPBD, 64, 4}};
    const double scales[] = {1, 10, 50};
    GridSpec gs;
    gs.cols = gs.rows = n;
    gs.vertical = false;
    gs.threads = 1;
    struct Run {
        std::vector<std::vector<float>> x;  ///< positions at the start and after each frame
        std::vector<double> ms;
        bool ok = true;
        uint32_t substeps = 0;  ///< per library step, the last one's
    };
    auto run = [&](const drape_params& p, int calls) {
        auto sim = make_grid(gs);
        sim->set_params(p);
        Run r;
        r.x.push_back(sim->positions());
        for (int f = 0; f < frames; ++f) {
            double ms = 0;
            for (int c = 0; c < calls; ++c) {
                drape_status st;
                ms += timed_step(*sim, dt / float(calls), &st);
                if (st != DRAPE_OK) r.ok = false;
            }
            r.ms.push_back(ms);
            r.x.push_back(sim->positions());
        }
        r.substeps = sim->stats().substeps;
        return r;
    };
    auto max_distance = [](const Run& a, const Run& b) {
        double d = 0;
        for (size_t f = 0; f < a.x.size(); ++f)
            for (size_t i = 0; i < a.x[f].size(); i += 3) {
                const double dx = a.x[f][i] - b.x[f][i], dy = a.x[f][i + 1] - b.x[f][i + 1],
                             dz = a.x[f][i + 2] - b.x[f][i + 2];
                d = std::max(d, std::sqrt(dx * dx + dy * dy + dz * dz));
            }
        return d;
    };
    auto mean_y = [](const std::vector<float>& x) {
        double y = 0;
        for (size_t i = 1; i < x.size(); i += 3) y += x[i];
        return y / double(x.size() / 3);
    };
    g_progress.start("fall", int(std::size(scales) * (settings.size() + 1)));
    for (double scale : scales) {
        const drape_params ref_p = params_for(DRAPE_MODEL_MASS_SPRING, scale);
        int calls = 4;
        Run ref = run(ref_p, calls);
        while (!ref.ok && calls < 1024) ref = run(ref_p, calls *= 2);
        drape_params fine = ref_p;  // the reference at half its substep
        fine.substeps = 2 * ref.substeps;
        const bool more_calls = fine.substeps > DRAPE_MAX_SUBSTEPS;
        if (more_calls) fine.substeps = ref.substeps;
        const double ref_error = max_distance(ref, run(fine, more_calls ? 2 * calls : calls)) / gs.width;
        const double y0 = mean_y(ref.x.front()), ref_fall = y0 - mean_y(ref.x.back());
        g_progress.tick(fmt("x%g reference", scale) + fmt(" (%g calls per frame,", calls) +
                        fmt(" %g substeps each)", ref.substeps));
        for (const Config& c : settings) {
            drape_params p = params_for(c.model, scale);
            p.substeps = c.substeps;
            p.iterations = c.iterations;
            const Run r = run(p, 1);
            const bool is_default = &c == &settings[0];
            const std::string setting = c.substeps == 0 ? "auto" : fmt("%g", c.substeps) + "x" + fmt("%g", c.iterations);
            const double err = max_distance(r, ref) / gs.width, fall = (y0 - mean_y(r.x.back())) / ref_fall;
            csv.row("%u,%g,%g,%s,%s,%d,%.4f,%.4g,%.4g,%.3g,%d", n, scale, double(p.stiffness[0]), model_name(c.model),
                    setting.c_str(), int(is_default), median(r.ms), err, fall, ref_error, int(r.ok));
            g_progress.tick(fmt("x%g ", scale) + model_name(c.model) + " " + setting + fmt(" error %.3g", err) +
                            fmt(" fall x%.2f", fall));
        }
    }
    g_progress.finish();
}

// ---------------------------------------------------------------------------------------------
// 3. Stress (accuracy.md S1 S2 S3 S5 S7 S10)

struct StressCase {
    std::string test, label;
    uint32_t model;
    double stiffness = 0, dt = 1.0 / 60.0;
    uint32_t substeps_used = 0;
};

/// Runs `seconds` of frames (dt from dt_of(k)) with the monitor; returns survived.
bool run_monitored(Sim& s, uint32_t model, double seconds, const std::function<float(int)>& dt_of,
                   Monitor& mon, uint32_t* substeps = nullptr, bool check_energy = true) {
    mon.begin(s, model, check_energy);
    double t = 0;
    for (int k = 0; t < seconds - 1e-9; ++k) {
        const float dt = dt_of(k);
        drape_status st = drape_cloth_step(s.cloth, dt);
        t += dt;
        if (substeps) *substeps = s.stats().substeps;
        if (!mon.after_step(s, st, dt, t)) return false;
    }
    return true;
}

/// The energy criterion sees a cloth that gains energy and leaves a still one alone, or the
/// stress table would mean nothing: a Verlet step above its stability bound (MASS_SPRING, one
/// substep of 1/60 s at 10 N/m: 3 x h_crit = 0.64 sqrt(m/k), accuracy.md) grows exponentially and
/// must fail on energy growth; XPBD at 1e9 N/m with its default budget hangs still and must not
/// (1/2 k C^2 of its unresolved stretch failed it before).
void self_check_energy_criterion() {
    GridSpec gs;
    gs.cols = gs.rows = 16;
    gs.vertical = false;
    auto run = [&](uint32_t model, double k, uint32_t substeps) {
        auto sim = make_grid(gs);
        drape_params p = params_for(model);
        for (float& s : p.stiffness) s = float(k);
        p.damping = 0;
        p.substeps = substeps;
        sim->set_params(p);
        Monitor mon;
        run_monitored(
            *sim, model, 0.5, [](int) { return 1.0f / 60; }, mon);
        return mon;
    };
    const Monitor growing = run(DRAPE_MODEL_MASS_SPRING, 10, 1);
    const Monitor still = run(DRAPE_MODEL_XPBD, 1e9, 0);
    if (growing.criterion.rfind("energy growth", 0) != 0 || !still.criterion.empty()) {
        std::fprintf(
            stderr,
            "\ndrape_bench: energy criterion self-check failed: unstable Verlet cloth -> '%s' (growth %.3g), "
            "still stiff XPBD cloth -> '%s' (growth %.3g)\n",
            growing.criterion.c_str(), growing.energy_growth, still.criterion.c_str(), still.energy_growth);
        std::exit(1);
    }
}

void run_stress(const Options& o) {
    self_check_energy_criterion();
    Csv csv(o.out + "/stress.csv",
            "test,case,model,stiffness,dt,substeps,h,survived,time_to_failure_s,criterion,max_strain,energy_"
            "growth,seconds");
    const uint32_t n = o.quick ? 8 : 16;
    const double secs = o.quick ? 0.25 : 2.0;
    std::vector<double> ks, dts;
    if (o.quick) {
        ks = {10, 1e3, 1e5, 1e7, 1e9};
        dts = {1.0 / 240, 1.0 / 60, 1.0 / 10};
    } else {
        ks = {10, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
        dts = {1.0 / 240, 1.0 / 120, 1.0 / 60, 1.0 / 30, 1.0 / 10};
    }
    const std::vector<double> pbd_fractions = {0.001, 0.01, 0.1, 0.5, 1.0};
    // S1 configurations: MASS_SPRING with one substep (the explicit limit), MASS_SPRING with
    // automatic substeps, PBD, XPBD, IMPLICIT at their automatic budgets, IMPLICIT at 1 x 1.
    // Equal stiffness in all three groups and no damping, so the analytic Verlet limit applies.
    struct S1Cfg {
        const char* label;
        uint32_t model, substeps, iterations;
    };
    const S1Cfg s1cfg[] = {{"mass_spring_1substep", DRAPE_MODEL_MASS_SPRING, 1, 0},
                           {"mass_spring", DRAPE_MODEL_MASS_SPRING, 0, 0},
                           {"pbd", DRAPE_MODEL_PBD, 0, 0},
                           {"xpbd", DRAPE_MODEL_XPBD, 0, 0},
                           {"implicit", DRAPE_MODEL_IMPLICIT, 0, 0},
                           {"implicit_1x1", DRAPE_MODEL_IMPLICIT, 1, 1}};
    const std::vector<uint32_t> res =
        o.quick ? std::vector<uint32_t>{8, 16} : std::vector<uint32_t>{16, 32, 64, 128, 256};
    int total = 0;
    for (const auto& c : s1cfg)
        total += int((c.model == DRAPE_MODEL_PBD ? pbd_fractions.size() : ks.size()) * dts.size());
    total += kModelCount * 12 + kModelCount * 10 + kModelCount + kModelCount * 3 + kModelCount * 2 +
             kModelCount * int(res.size()) + 2 * int(res.size()) + kModelCount * 3;
    g_progress.start("stress", total);
    auto record = [&](const std::string& test, const std::string& label, uint32_t model, double k, double dt,
                      uint32_t substeps, bool ok, const Monitor& mon, double seconds) {
        csv.row("%s,%s,%s,%.6g,%.6g,%u,%.6g,%d,%.4g,%s,%.4g,%.3g,%.3g", test.c_str(), label.c_str(),
                model_name(model), k, dt, substeps, substeps ? dt / substeps : NAN, int(ok),
                ok ? NAN : mon.t_fail, ok ? "" : mon.criterion.c_str(), mon.max_strain,
                mon.energy_check ? mon.energy_growth : NAN, seconds);
        g_progress.tick(test + " " + label + " " + model_name(model) + (ok ? " ok" : " FAIL"));
    };
    std::ofstream s8(o.out + "/s8_colliders.csv");
    s8 << "test,speed_m_per_s,model,max_fraction_inside_or_behind,survived\n";
    auto base_grid = [&](bool vertical) {
        GridSpec gs;
        gs.cols = gs.rows = n;
        gs.vertical = vertical;
        return gs;
    };

    // S1 stiffness x dt map.
    for (const auto& c : s1cfg) {
        const auto& kk = c.model == DRAPE_MODEL_PBD ? pbd_fractions : ks;
        for (double k : kk)
            for (double dt : dts) {
                auto sim = make_grid(base_grid(false));
                drape_params p = params_for(c.model);
                for (float& s : p.stiffness) s = float(k);
                p.damping = 0;
                p.substeps = c.substeps;
                p.iterations = c.iterations;
                sim->set_params(p);
                Monitor mon;
                uint32_t sub = 0;
                // 0.5 s per cell: failures in the full runs came within 0.2 s, and stiff
                // MASS_SPRING cells run 1000 substeps per frame.
                const double s1 = std::min(secs, 0.5);
                bool ok = run_monitored(
                    *sim, c.model, s1, [&](int) { return float(dt); }, mon, &sub);
                record("S1", c.label, c.model, k, dt, sub, ok, mon, s1);
            }
    }
    // S2 frame dt sweep, fixed and jittered (dt x U[0.5, 1.5], fixed seed).
    const double s2dts[] = {1.0 / 240, 1.0 / 120, 1.0 / 60, 1.0 / 30, 1.0 / 20, 1.0 / 10};
    for (uint32_t m : kModels)
        for (double dt : s2dts)
            for (int jitter = 0; jitter < 2; ++jitter) {
                auto sim = make_grid(base_grid(false));
                sim->set_params(params_for(m));
                std::mt19937 rng(1);
                std::uniform_real_distribution<float> u(0.5f, 1.5f);
                Monitor mon;
                uint32_t sub = 0;
                bool ok = run_monitored(
                    *sim, m, secs, [&](int) { return float(dt) * (jitter ? u(rng) : 1.0f); }, mon, &sub);
                record("S2", jitter ? "jitter" : "fixed", m, 0, dt, sub, ok, mon, secs);
            }
    // S3 mass ratio: heavy chain tip (stiffness scaled so the exact top strain is 1%, starts
    // unstretched and drops), and a heavy free corner on the default cloth.
    const double ratios[] = {10, 1e2, 1e3, 1e4, 1e5};
    for (uint32_t m : kModels)
        for (double ratio : ratios) {
            const uint32_t N = 20;
            const double L0 = 0.05, pm = 0.005, M = ratio * N * pm, k = (N * pm + M) * kG / (0.01 * L0);
            GridSpec gs;
            gs.cols = 1;
            gs.rows = N + 1;
            gs.height = N * L0;
            gs.mass = N * pm + M;
            gs.pins = Pins::TopVertex;
            auto sim = make_grid(gs);
            std::vector<float> w(N + 1, float(1 / pm));
            w[0] = 0;
            w[N] = float(1 / (pm + M));
            sim->set_inverse_masses(w);
            drape_params p = params_for(m);
            p.stiffness[0] = m == DRAPE_MODEL_PBD ? 1.0f : float(k);
            p.stiffness[1] = p.stiffness[2] = 0;
            sim->set_params(p);
            Monitor mon;
            uint32_t sub = 0;
            bool ok = run_monitored(
                *sim, m, secs, [](int) { return 1.0f / 60; }, mon, &sub);
            record("S3", "chain_tip_1:" + fmt("%g", ratio), m, p.stiffness[0], 1.0 / 60, sub, ok, mon, secs);
        }
    for (uint32_t m : kModels)
        for (double ratio : ratios) {
            auto sim = make_grid(base_grid(true));
            std::vector<float> w = sim->inv_mass;
            w[n * n - 1] = float(1.0 / (ratio * sim->mass / (n * n)));
            sim->set_inverse_masses(w);
            sim->set_params(params_for(m));
            Monitor mon;
            uint32_t sub = 0;
            bool ok = run_monitored(
                *sim, m, secs, [](int) { return 1.0f / 60; }, mon, &sub);
            record("S3", "heavy_corner_1:" + fmt("%g", ratio), m, 0, 1.0 / 60, sub, ok, mon, secs);
        }
    // S3 heavy sphere on light cloth. Colliders are kinematic in the C API (two-way coupling does
    // not exist), so a heavy sphere is one that does not yield: a sphere (r = 0.15 m) lowered at
    // 0.6 m/s for 1 s into the middle of the horizontal cloth pinned at its four corners, then
    // held 0.4 m below the corners (stretch ~15% along the diagonals, beyond the default tether
    // limit of 10%: tethers and the collider disagree). Fraction of vertices inside the sphere
    // goes to s8_colliders.csv.
    for (uint32_t m : kModels) {
        GridSpec gs = base_grid(false);
        gs.pins = Pins::None;
        auto sim = make_grid(gs);
        std::vector<float> w = sim->inv_mass;
        w[0] = w[n - 1] = w[n * (n - 1)] = w[n * n - 1] = 0.0f;
        sim->set_inverse_masses(w);
        sim->set_params(params_for(m));
        const float r = 0.15f;
        auto sphere_at = [&](double t) {
            return bench_sphere(0.5f, float(r + 0.2 - 0.6 * std::min(t, 1.0)), -0.5f, r);
        };
        drape_collider c0 = sphere_at(0);
        die_on(drape_cloth_set_colliders(sim->cloth, &c0, 1), "drape_cloth_set_colliders");
        Monitor mon;
        mon.begin(*sim, m, false);  // the sphere does work on the cloth
        mon.v_limit += 10.0 * 0.6;  // the collider's speed (accuracy.md)
        double worst = 0, t = 0;
        bool ok = true;
        const float dt = 1.0f / 60;
        uint32_t sub = 0;
        for (int k = 0; ok && t < secs - 1e-9; ++k) {
            t += dt;
            drape_collider c = sphere_at(t);
            die_on(drape_cloth_set_colliders(sim->cloth, &c, 1), "drape_cloth_set_colliders");
            ok = mon.after_step(*sim, drape_cloth_step(sim->cloth, dt), dt, t);
            sub = sim->stats().substeps;
            const std::vector<float>& x = mon.prev;
            int bad = 0;
            for (size_t i = 0; i < x.size(); i += 3) {
                double dx = x[i] - c.position[0], dy = x[i + 1] - c.position[1],
                       dz = x[i + 2] - c.position[2];
                bad += dx * dx + dy * dy + dz * dz < double(r) * r * 0.98;
            }
            worst = std::max(worst, double(bad) / sim->vertices);
        }
        mon.max_strain = sim->stats().max_strain;  // held at the end (the transient peak is not the point)
        record("S3", "heavy_sphere_kinematic_0.4m", m, 0, 1.0 / 60, sub, ok, mon, secs);
        s8 << "S3_heavy_sphere,0.6," << model_name(m) << "," << worst << "," << int(ok) << "\n";
    }
    // S5 stretched start (free cloth, no pins, scaled about its centre) and pull-and-release.
    for (uint32_t m : kModels) {
        for (double factor : {2.0, 10.0}) {
            GridSpec gs = base_grid(false);
            gs.pins = Pins::None;
            auto sim = make_grid(gs);
            sim->set_params(params_for(m));
            std::vector<float> x = sim->positions();
            for (size_t i = 0; i < x.size(); i += 3) {
                x[i] = float(0.5 + (x[i] - 0.5) * factor);
                x[i + 2] = float(-0.5 + (x[i + 2] + 0.5) * factor);
            }
            sim->set_positions(x);
            Monitor mon;
            uint32_t sub = 0;
            // PBD cannot state what its stretched start stores.
            bool ok = run_monitored(
                *sim, m, secs, [](int) { return 1.0f / 60; }, mon, &sub, m != DRAPE_MODEL_PBD);
            record("S5", "stretched_" + fmt("%gx", factor), m, 0, 1.0 / 60, sub, ok, mon, secs);
        }
        auto sim = make_grid(base_grid(true));
        sim->set_params(params_for(m));
        drape_status st;
        for (int i = 0; i < 60; ++i) timed_step(*sim, 1.0f / 60, &st);  // settle
        std::vector<float> x = sim->positions();
        for (uint32_t r = n / 2 - 1; r <= n / 2 + 1; ++r)
            for (uint32_t c = n / 2 - 1; c <= n / 2 + 1; ++c)
                x[3 * (r * n + c) + 2] += 1.0f;  // 1 m = cloth size
        sim->set_positions(x);
        Monitor mon;
        uint32_t sub = 0;
        bool ok = run_monitored(
            *sim, m, secs, [](int) { return 1.0f / 60; }, mon, &sub, m != DRAPE_MODEL_PBD);
        record("S5", "pull_3x3_1m", m, 0, 1.0 / 60, sub, ok, mon, secs);
    }
    // S7 starved budget: 1 substep, 1 iteration, stiff material (1e6 N/m; PBD fraction 1).
    for (uint32_t m : kModels) {
        auto sim = make_grid(base_grid(false));
        drape_params p = params_for(m, m == DRAPE_MODEL_PBD ? 10.0 : 500.0);
        p.substeps = 1;
        p.iterations = 1;
        sim->set_params(p);
        Monitor mon;
        uint32_t sub = 0;
        bool ok = run_monitored(
            *sim, m, secs, [](int) { return 1.0f / 60; }, mon, &sub);
        record("S7", "1substep_1iter_stiff", m, p.stiffness[0], 1.0 / 60, sub, ok, mon, secs);
        // Same stiff material with the default budget, for comparison.
        auto sim2 = make_grid(base_grid(false));
        const drape_params def = library_default();
        p.substeps = def.substeps;
        p.iterations = def.iterations;
        sim2->set_params(p);
        Monitor mon2;
        ok = run_monitored(
            *sim2, m, secs, [](int) { return 1.0f / 60; }, mon2, &sub);
        record("S7", "default_budget_stiff", m, p.stiffness[0], 1.0 / 60, sub, ok, mon2, secs);
    }
    // S8 fast collider: a sphere (r = 0.1 m) crosses the hanging cloth's middle along z at
    // 2, 6 and 18 m/s (0.3 m = 3 radii per frame at 18 m/s), travelling 1 m, then stays. Recorded:
    // the largest fraction of vertices inside the sphere or behind it (inside the swept disc
    // but on the side the sphere came from) over the run.
    for (uint32_t m : kModels)
        for (double speed : {2.0, 6.0, 18.0}) {
            auto sim = make_grid(base_grid(true));
            sim->set_params(params_for(m));
            const float r = 0.1f;
            auto sphere_at = [&](double t) {
                return bench_sphere(0.5f, -0.5f, float(-0.5 + std::min(1.0, speed * t)), r);
            };
            drape_collider c0 = sphere_at(0);
            die_on(drape_cloth_set_colliders(sim->cloth, &c0, 1), "drape_cloth_set_colliders");
            Monitor mon;
            mon.begin(*sim, m, false);  // the sphere does work on the cloth
            double worst = 0, t = 0;
            bool ok = true;
            const float dt = 1.0f / 60;
            for (int k = 0; ok && t < secs - 1e-9; ++k) {
                t += dt;
                drape_collider c = sphere_at(t);
                die_on(drape_cloth_set_colliders(sim->cloth, &c, 1), "drape_cloth_set_colliders");
                ok = mon.after_step(*sim, drape_cloth_step(sim->cloth, dt), dt, t);
                const std::vector<float>& x = mon.prev;
                int bad = 0;
                for (size_t i = 0; i < x.size(); i += 3) {
                    double dx = x[i] - c.position[0], dy = x[i + 1] - c.position[1],
                           dz = x[i + 2] - c.position[2];
                    bool inside = dx * dx + dy * dy + dz * dz < double(r) * r * 0.98;
                    bool behind = dx * dx + dy * dy < double(r) * r * 0.98 && dz < 0;
                    bad += inside || behind;
                }
                worst = std::max(worst, double(bad) / sim->vertices);
            }
            csv.row("S8,sphere_%gm/s,%s,0,%.6g,%u,%.6g,%d,%.4g,%s,%.4g,%.3g,%.3g", speed, model_name(m),
                    double(dt), sim->stats().substeps, NAN, int(ok), ok ? NAN : mon.t_fail,
                    ok ? "" : mon.criterion.c_str(), mon.max_strain,
                    mon.energy_check ? mon.energy_growth : NAN, secs);
            // fraction_inside_or_behind goes to its own file (the stress table keeps its columns)
            s8 << "S8," << speed << "," << model_name(m) << "," << worst << "," << int(ok) << "\n";
            g_progress.tick(fmt("S8 %g m/s ", speed) + model_name(m) + fmt(" %.3f", worst));
        }
    // S10 resolution sweep at the same size and material, default budget: strain after 1 s.
    for (uint32_t m : kModels)
        for (uint32_t r : res) {
            if (m == DRAPE_MODEL_MASS_SPRING && r > 64) {  // ~1000 substeps per frame: minutes
                g_progress.tick("S10 skip");
                continue;
            }
            GridSpec gs = base_grid(true);
            gs.cols = gs.rows = r;
            auto sim = make_grid(gs);
            sim->set_params(params_for(m));
            Monitor mon;
            uint32_t sub = 0;
            const double s10 = o.quick ? 0.5 : 1.0;
            bool ok = run_monitored(
                *sim, m, s10, [](int) { return 1.0f / 60; }, mon, &sub);
            const drape_stats ss = sim->stats();
            mon.max_strain = ss.max_strain;  // strain at the end, not the transient peak
            record("S10", std::to_string(r) + "^2", m, 0, 1.0 / 60, sub, ok, mon, s10);
        }
    // S10 again without tethers (max_stretch 0), PBD and XPBD: what the tethers hold back.
    for (uint32_t m : {DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD})
        for (uint32_t r : res) {
            GridSpec gs = base_grid(true);
            gs.cols = gs.rows = r;
            auto sim = make_grid(gs);
            drape_params p = params_for(m);
            p.max_stretch = 0;
            sim->set_params(p);
            Monitor mon;
            uint32_t sub = 0;
            const double s10 = o.quick ? 0.5 : 1.0;
            bool ok = run_monitored(
                *sim, m, s10, [](int) { return 1.0f / 60; }, mon, &sub);
            mon.max_strain = sim->stats().max_strain;
            record("S10", std::to_string(r) + "^2_no_tethers", m, 0, 1.0 / 60, sub, ok, mon, s10);
        }
    g_progress.finish();

    // S10 second half: solver passes per frame needed for max strain <= 1% after 1 s hanging, in
    // the default form (substeps x 1 iteration, tethers on), doubling from 16 up to 256 (quick 64).
    // Larger cloths never need fewer passes, so each size starts at the previous size's answer.
    Csv it(o.out + "/s10_iterations.csv",
           "model,size,iterations,passes_for_1pct,max_strain_at_that,reached,max_passes");
    const std::vector<uint32_t> res2 = o.quick ? std::vector<uint32_t>{8} : std::vector<uint32_t>{16, 32, 64};
    const uint32_t max_passes = o.quick ? 64 : 256;
    g_progress.start("S10 passes", int(res2.size() * 2));
    for (uint32_t m : {DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD}) {
        uint32_t start = 16;
        for (uint32_t r : res2) {
            uint32_t found = 0;
            float strain = NAN;
            for (uint32_t passes = start; passes <= max_passes; passes *= 2) {
                GridSpec gs = base_grid(true);
                gs.cols = gs.rows = r;
                auto sim = make_grid(gs);
                drape_params p = params_for(m);
                p.substeps = passes;
                p.iterations = 1;
                sim->set_params(p);
                drape_status st;
                for (int i = 0; i < 60; ++i) timed_step(*sim, 1.0f / 60, &st);
                strain = sim->stats().max_strain;
                if (strain <= 0.01f) {
                    found = passes;
                    break;
                }
            }
            it.row("%s,%u,1,%u,%.4g,%d,%u", model_name(m), r, found, strain, int(found > 0), max_passes);
            g_progress.tick(std::string(model_name(m)) + " " + std::to_string(r) + "^2");
            start = found ? found : max_passes * 2;  // not reached: larger sizes are not searched
        }
    }
    g_progress.finish();
}

// ---------------------------------------------------------------------------------------------
// 4. The paper's Fig. 7: vibration at rest against stiffness

void run_vibration(const Options& o) {
    Csv csv(o.out + "/vibration.csv",
            "model,stiffness_scale,structural_stiffness,substeps,vibration_m,survived,criterion");
    // 16^2 (was 20^2): MASS_SPRING's automatic substeps grow with resolution and stiffness, and
    // its stiff points were most of the run time. MASS_SPRING stops at 3e5 N/m (824 substeps at
    // 20^2; 1e6 N/m hits the 1000-substep cap, i.e. it no longer meets its own stability bound).
    const uint32_t n = o.quick ? 8 : 16;
    const double rest_s = o.quick ? 1.0 : 5.0, measure_s = o.quick ? 0.25 : 1.0;
    const std::vector<double> phys = o.quick ? std::vector<double>{0.1, 1, 10, 100}
                                             : std::vector<double>{0.05, 0.15, 0.5, 1.5, 5, 15, 50, 150, 500};
    const std::vector<double> ms =
        o.quick ? std::vector<double>{0.1, 1, 10} : std::vector<double>{0.05, 0.5, 5, 50, 150};
    const std::vector<double> pbd =
        o.quick ? std::vector<double>{0.1, 0.5, 1} : std::vector<double>{0.02, 0.05, 0.1, 0.2, 0.5, 1};
    g_progress.start("vibration", int(phys.size() + ms.size() + pbd.size()));
    for (uint32_t m : kModels)
        for (double scale : m == DRAPE_MODEL_PBD ? pbd : m == DRAPE_MODEL_MASS_SPRING ? ms : phys) {
            GridSpec gs;
            gs.cols = gs.rows = n;
            gs.vertical = false;  // the paper: falls from horizontal, hangs from two corners
            auto sim = make_grid(gs);
            drape_params p = params_for(m, scale);
            p.air_drag = 2.0f;  // so the swing about the pin axis dies out within the rest time
            sim->set_params(p);
            Monitor mon;
            bool ok = run_monitored(
                *sim, m, rest_s, [](int) { return 1.0f / 60; }, mon);
            const uint32_t mid = (n / 2) * n + n / 2;
            std::vector<float> prev = sim->positions();
            double sum = 0;
            int steps = 0;
            for (; ok && steps < int(measure_s * 60); ++steps) {
                if (drape_cloth_step(sim->cloth, 1.0f / 60) != DRAPE_OK) ok = false;
                std::vector<float> x = sim->positions();
                double dx = x[3 * mid] - prev[3 * mid], dy = x[3 * mid + 1] - prev[3 * mid + 1],
                       dz = x[3 * mid + 2] - prev[3 * mid + 2];
                sum += std::sqrt(dx * dx + dy * dy + dz * dz);
                prev.swap(x);
            }
            csv.row("%s,%.4g,%.6g,%u,%.4g,%d,%s", model_name(m), scale, p.stiffness[0], sim->stats().substeps,
                    ok ? sum / steps : NAN, int(ok),
                    ok ? "" : (mon.criterion.empty() ? "step failed" : mon.criterion.c_str()));
            g_progress.tick(std::string(model_name(m)) + fmt(" k=%g", p.stiffness[0]));
        }
    g_progress.finish();
}

// ---------------------------------------------------------------------------------------------
// 5. Where a CPU step's time goes: median wall time per stage (drape_stage), one thread

void run_stages(const Options& o) {
    static const char* const kStageNames[DRAPE_STAGE_COUNT] = {"begin",        "predict", "solve",  "tether",
                                                               "self_collide", "collide", "verify", "finish"};
    std::string header = "size,vertices,model,substeps,iterations,steps,step_ms_median";
    for (const char* s : kStageNames) header += std::string(",") + s + "_ms_median";
    Csv csv(o.out + "/stages.csv", header.c_str());
    const std::vector<uint32_t> sizes = o.quick ? std::vector<uint32_t>{16} : std::vector<uint32_t>{33, 65};
    const uint32_t models[] = {DRAPE_MODEL_MASS_SPRING, DRAPE_MODEL_PBD, DRAPE_MODEL_XPBD,
                               DRAPE_MODEL_IMPLICIT};
    g_progress.start("stages", int(sizes.size() * 4));
    for (uint32_t n : sizes)
        for (uint32_t m : models) {
            // The throughput curtain (two top corners pinned) with every optional stage at work:
            // tethers, a sphere it drapes over, self-collision.
            GridSpec gs;
            gs.cols = gs.rows = n;
            gs.threads = 1;
            gs.profile_stages = true;
            auto sim = make_grid(gs);
            drape_params p = params_for(m);
            p.max_stretch = 0.1f;
            sim->set_params(p);
            drape_collider sphere{};
            sphere.struct_size = sizeof sphere;
            sphere.shape = DRAPE_COLLIDER_SPHERE;
            sphere.position[0] = 0.5f;
            sphere.position[1] = -0.6f;
            sphere.position[2] = 0.15f;
            sphere.rotation[3] = 1.0f;
            sphere.size[0] = 0.2f;
            die_on(drape_cloth_set_colliders(sim->cloth, &sphere, 1), "drape_cloth_set_colliders");
            drape_self_collision_desc sc{};
            sc.struct_size = sizeof sc;
            sc.enabled = 1;
            sc.thickness = 0.5f / float(n - 1);
            die_on(drape_cloth_set_self_collision(sim->cloth, &sc), "drape_cloth_set_self_collision");
            const int warm = o.quick ? 5 : 30, steps = o.quick ? 10 : 60;
            std::vector<double> step_ms, stage_ms[DRAPE_STAGE_COUNT];
            drape_stats s{};
            for (int f = 0; f < warm + steps; ++f) {
                if (drape_cloth_step(sim->cloth, 1.0f / 60) != DRAPE_OK) continue;  // rolled back: not timed
                s = sim->stats();
                if (f < warm) continue;
                step_ms.push_back(s.step_ms);
                for (int k = 0; k < DRAPE_STAGE_COUNT; ++k) stage_ms[k].push_back(s.stage_ms[k]);
            }
            std::string row = fmt("%.0f", n) + "," + std::to_string(sim->vertices) + "," + model_name(m) +
                              "," + std::to_string(s.substeps) + "," + std::to_string(s.iterations) + "," +
                              std::to_string(step_ms.size()) + "," + fmt("%.4f", median(step_ms));
            for (const auto& v : stage_ms) row += "," + fmt("%.4f", median(v));
            csv.row("%s", row.c_str());
            g_progress.tick(std::to_string(n) + "^2 " + model_name(m) + fmt(" %.3g ms", median(step_ms)));
        }
    g_progress.finish();
}

void write_meta(const Options& o, double seconds) {
    std::ofstream f(o.out + "/meta.csv");
    f << "key,value\n";
    f << "mode," << (o.quick ? "quick" : "full") << "\n";
    f << "threads," << o.threads << "\n";
    f << "hardware_threads," << sysconf(_SC_NPROCESSORS_ONLN) << "\n";
    std::ifstream cpu("/proc/cpuinfo");
    for (std::string line; std::getline(cpu, line);)
        if (line.rfind("model name", 0) == 0) {
            std::string v = line.substr(line.find(':') + 2);
            std::replace(v.begin(), v.end(), ',', ' ');
            f << "cpu," << v << "\n";
            break;
        }
    std::ifstream load("/proc/loadavg");
    std::string l1;
    load >> l1;
    f << "loadavg_1min_at_end," << l1 << "\n";
    f << "abi_version," << drape_abi_version() << "\n";
    std::string b;
    for (uint32_t x : available_backends()) b += std::string(b.empty() ? "" : " ") + backend_name(x);
    f << "backends," << b << "\n";
    f << "seconds," << seconds << "\n";
    f << "stress_grid," << (o.quick ? 8 : 16) << "\n";
    f << "vibration_grid," << (o.quick ? 8 : 16) << "\n";
    f << "cloth_mass," << GridSpec{}.mass << "\n";
    // The library's defaults (model, budget) as one step of a small cloth reports them;
    // default_auto_budget: the default asks for the automatic budget (substeps 0).
    const drape_params def = library_default();
    f << "default_auto_budget," << int(def.substeps == 0) << "\n";
    GridSpec gs;
    gs.cols = gs.rows = 4;
    auto sim = make_grid(gs);
    sim->set_params(def);
    die_on(drape_cloth_step(sim->cloth, 1.0f / 60), "drape_cloth_step");
    f << "default_model," << model_name(def.model) << "\n";
    f << "default_substeps," << sim->stats().substeps << "\n";
    f << "default_iterations," << sim->stats().iterations << "\n";
    f << "default_max_stretch," << def.max_stretch << "\n";
    f << "loadavg_1min_at_start," << g_load_start << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    {
        std::ifstream load("/proc/loadavg");
        load >> g_load_start;
    }
    Options o;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--quick")
            o.quick = true;
        else if (a == "--out" && i + 1 < argc)
            o.out = argv[++i];
        else if (a == "--threads" && i + 1 < argc)
            o.threads = uint32_t(std::atoi(argv[++i]));
        else if (a == "--rest-largest" && i + 1 < argc)
            o.rest_largest = uint32_t(std::atoi(argv[++i]));
        else if ((a == "--only" || a == "--rest-models") && i + 1 < argc) {
            std::stringstream ss(argv[++i]);
            for (std::string p; std::getline(ss, p, ',');) (a == "--only" ? o.only : o.rest_models).insert(p);
        } else {
            std::fprintf(stderr,
                         "usage: drape_bench [--quick] [--out DIR] [--threads N] [--rest-largest N] [--rest-models "
                         "implicit,xpbd,mass_spring] [--only "
                         "throughput,threads,precision,rest,stiff,fall,stress,vibration,stages]\n");
            return a == "--help" || a == "-h" ? 0 : 2;
        }
    }
    mkdir(o.out.c_str(), 0755);
    {
        // The precision and rest parts append their references. residual: Newton gradient
        // max-norm (N) for newton_static; for the converged-run reference, the max vertex distance
        // (m) between it and the same run at half the substeps.
        std::ofstream f(o.out + "/reference.csv");
        f << "scene,size,residual,ref_max_strain,kind\n";
    }
    const auto t0 = Clock::now();
    if (o.wants("throughput")) run_throughput(o);
    if (o.wants("threads")) run_threads(o);
    if (o.wants("precision")) run_precision(o);
    if (o.wants("rest")) run_rest(o);
    if (o.wants("stiff")) run_stiff(o);
    if (o.wants("fall")) run_fall(o);
    if (o.wants("stress")) run_stress(o);
    if (o.wants("vibration")) run_vibration(o);
    if (o.wants("stages")) run_stages(o);
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    write_meta(o, secs);
    std::fprintf(stderr, "drape_bench: %s mode done in %.1f s; CSV in %s\n", o.quick ? "quick" : "full", secs,
                 o.out.c_str());
    return 0;
}
