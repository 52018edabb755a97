// libFuzzer target over the whole C ABI (hardening).
//
// The input bytes are a program: each step takes an opcode byte and then the bytes its call
// needs (counts, indices, floats drawn from a table of nasty values or raw bits, struct sizes,
// enums, NULL pointers, stale handles). Invariants checked after every call (a violation
// aborts, which libFuzzer reports as a crash):
//   - nothing crashes, leaks or trips ASan/UBSan (the build runs under both);
//   - a failing call returns a status inside drape_status and drape_last_error() is non-empty;
//   - a failing setter leaves the cloth unchanged (positions and parameters bit for bit);
//   - positions read back are always finite, also after DRAPE_ERROR_UNSTABLE (rolled back).
// Sizes are kept small (<= 24x24 grids, <= 32 mesh vertices) so one input runs in milliseconds;
// requests that the library must refuse (huge counts, overflowing products) are still made.
//
// Run: build/asan/tests/fuzz/drape_fuzz_api tests/fuzz/corpus -max_total_time=60
// New API (colliders, sleep, drag, owner) is fuzzed when the header declares it.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "drape/drape.h"

namespace {

[[noreturn]] void die(const char* what, int line) {
    std::fprintf(stderr, "drape_fuzz_api: invariant violated at line %d: %s (last error: \"%s\")\n", line, what,
                 drape_last_error());
    std::abort();
}
#define CHECK(cond)                         \
    do {                                    \
        if (!(cond)) die(#cond, __LINE__);  \
    } while (0)

// Every failure must come with a status from the enum and a message.
bool g_trace = std::getenv("DRAPE_FUZZ_TRACE") != nullptr;  // prints every checked call's status

drape_status checked(drape_status s) {
    if (g_trace) std::fprintf(stderr, "  -> %d %s\n", int(s), s ? drape_last_error() : "");
    CHECK(int(s) >= DRAPE_OK && int(s) <= DRAPE_ERROR_INTERNAL);
    if (s != DRAPE_OK) CHECK(drape_last_error() != nullptr && drape_last_error()[0] != '\0');
    CHECK(s != DRAPE_ERROR_INTERNAL);  // an internal error is a bug, not an input problem
    return s;
}

constexpr uint32_t kMaxWorlds = 2;
constexpr uint32_t kMaxCloths = 6;
constexpr uint32_t kMaxGridSide = 24;
constexpr uint32_t kMaxMeshVertices = 32;

struct Cloth {
    drape_cloth* handle;
    drape_world* world;
    uint32_t vertices;
};

class Harness {
public:
    explicit Harness(FuzzedDataProvider& in) : in_(in) {}
    ~Harness() {
        for (drape_world* w : worlds_) CHECK(drape_world_destroy(w) == DRAPE_OK);
    }

    void run() {
        if (in_.remaining_bytes() > 0) chaos_ = in_.ConsumeBytes<uint8_t>(1)[0] % 4;
        int budget = 64;  // calls per input: keeps each input fast
        while (in_.remaining_bytes() > 0 && budget-- > 0) step_once();
    }

private:
    // ---- input decoding -------------------------------------------------------------------
    float any_float() {
        static const float table[] = {std::numeric_limits<float>::quiet_NaN(),
                                      std::numeric_limits<float>::infinity(),
                                      -std::numeric_limits<float>::infinity(),
                                      0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-3f, 1e-30f,
                                      std::numeric_limits<float>::denorm_min(),
                                      std::numeric_limits<float>::min(), 1e6f, 1.0000001e6f, 1e9f, 1e30f,
                                      std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                                      -9.81f, 1000.0f, 1.0f / 60.0f};
        switch (in_.ConsumeIntegralInRange<int>(0, 3)) {
            case 0: return in_.PickValueInArray(table);
            case 1: {  // raw bits: any float, including signalling NaNs
                uint32_t bits = in_.ConsumeIntegral<uint32_t>();
                float f;
                std::memcpy(&f, &bits, 4);
                return f;
            }
            default: return sane_float(-2.0f, 2.0f);
        }
    }
    float sane_float(float lo, float hi) { return in_.ConsumeFloatingPointInRange<float>(lo, hi); }
    float maybe_bad(float lo, float hi) { return rarely() ? any_float() : sane_float(lo, hi); }
    uint32_t struct_size(uint32_t right) { return rarely() ? in_.ConsumeIntegral<uint32_t>() : right; }
    // How often bad input is made: the input's first byte picks a level, 0 = only valid calls
    // (so that random bytes reach deep states), 3 = a quarter of the choices are bad.
    bool rarely() { return chaos_ > 0 && in_.ConsumeIntegralInRange<int>(0, 32 >> chaos_) == 0; }

    // ---- handles --------------------------------------------------------------------------
    drape_world* pick_world() {
        if (worlds_.empty() || rarely()) return bad_world();
        return worlds_[in_.ConsumeIntegralInRange<size_t>(0, worlds_.size() - 1)];
    }
    drape_world* bad_world() {
        switch (in_.ConsumeIntegralInRange<int>(0, 2)) {
            case 0: return nullptr;
            case 1: return reinterpret_cast<drape_world*>(&stack_junk_);
            default: return cloths_.empty() ? nullptr : reinterpret_cast<drape_world*>(cloths_[0].handle);
        }
    }
    // Index into cloths_, or -1 for a bad handle (NULL, stale, foreign, a world).
    int pick_cloth() {
        if (cloths_.empty() || rarely()) return -1;
        return in_.ConsumeIntegralInRange<int>(0, int(cloths_.size()) - 1);
    }
    drape_cloth* bad_cloth() {
        switch (in_.ConsumeIntegralInRange<int>(0, 3)) {
            case 0: return nullptr;
            case 1: return reinterpret_cast<drape_cloth*>(&stack_junk_);
            case 2: return worlds_.empty() ? nullptr : reinterpret_cast<drape_cloth*>(worlds_[0]);
            default: return stale_.empty() ? nullptr : stale_[in_.ConsumeIntegralInRange<size_t>(0, stale_.size() - 1)];
        }
    }
    bool is_live(const drape_cloth* c) const {
        for (const Cloth& k : cloths_)
            if (k.handle == c) return true;
        return false;
    }
    // A call on a bad handle must be refused (a stale pointer may have been reused by a new
    // cloth: then it is live and anything goes).
    void expect_refused(drape_cloth* c, drape_status s) {
        if (c != nullptr && is_live(c)) return;
        CHECK(s == DRAPE_ERROR_NULL_POINTER || s == DRAPE_ERROR_INVALID_HANDLE);
    }

    // ---- state snapshots (failed calls must leave the cloth unchanged) -------------------
    std::vector<float> read_positions(const Cloth& c) {
        std::vector<float> out(size_t(c.vertices) * 3);
        drape_vertex_layout l{sizeof l, 12, 0, -1};
        CHECK(checked(drape_cloth_read(c.handle, &l, out.data(), out.size() * sizeof(float))) == DRAPE_OK);
        for (float f : out) CHECK(std::isfinite(f));
        return out;
    }
    drape_params read_params(const Cloth& c) {
        drape_params p{};
        CHECK(checked(drape_cloth_get_params(c.handle, &p)) == DRAPE_OK);
        return p;
    }
    struct Snapshot {
        std::vector<float> positions;
        drape_params params;
    };
    Snapshot snapshot(const Cloth& c) { return {read_positions(c), read_params(c)}; }
    void expect_unchanged(const Cloth& c, const Snapshot& before) {
        Snapshot now = snapshot(c);
        CHECK(std::memcmp(now.positions.data(), before.positions.data(), now.positions.size() * sizeof(float)) == 0);
        CHECK(std::memcmp(&now.params, &before.params, sizeof(drape_params)) == 0);
    }

    // ---- operations -----------------------------------------------------------------------
    void step_once() {
        int op = in_.ConsumeIntegralInRange<int>(0, 19);
        // Without a world or a cloth most calls can only fail: make one first (unless chaos says no).
        if (worlds_.empty() && op != 0 && !rarely()) op = 0;
        else if (cloths_.empty() && op >= 5 && !rarely()) op = op % 3 == 0 ? 4 : 2;
        if (g_trace) std::fprintf(stderr, "op %d (worlds %zu, cloths %zu)\n", op, worlds_.size(), cloths_.size());
        switch (op) {
            case 0: create_world(); break;
            case 1: destroy_world(); break;
            case 2: case 3: create_grid(); break;
            case 4: create_mesh(); break;
            case 5: destroy_cloth(); break;
            case 6: case 7: set_params(); break;
            case 8: vertex_floats(0); break;   // inverse masses
            case 9: pins(); break;
            case 10: release_pins(); break;
            case 11: vertex_floats(1); break;  // positions
            case 12: vertex_floats(2); break;  // velocities
            case 13: case 14: step_cloth(); break;
            case 15: step_world(); break;
            case 16: read(); break;
            case 17: queries(); break;
            default: extensions(); break;
        }
    }

    void create_world() {
        drape_world_desc d{struct_size(sizeof d), in_.ConsumeIntegralInRange<uint32_t>(0, 3)};
        if (rarely()) d.thread_count = in_.ConsumeIntegral<uint32_t>();
        drape_world* w = nullptr;
        const bool null_out = rarely();
        drape_status s = checked(drape_world_create(rarely() ? nullptr : &d, null_out ? nullptr : &w));
        if (s == DRAPE_OK) {
            CHECK(w != nullptr);
            if (worlds_.size() >= kMaxWorlds || d.thread_count > 4) {
                CHECK(drape_world_destroy(w) == DRAPE_OK);
            } else {
                worlds_.push_back(w);
            }
        }
    }

    void destroy_world() {
        if (worlds_.empty() || rarely()) {
            drape_world* w = bad_world();
            drape_status s = checked(drape_world_destroy(w));
            if (w == nullptr || std::find(worlds_.begin(), worlds_.end(), w) == worlds_.end())
                CHECK(s == DRAPE_ERROR_NULL_POINTER || s == DRAPE_ERROR_INVALID_HANDLE);
            return;
        }
        const size_t k = in_.ConsumeIntegralInRange<size_t>(0, worlds_.size() - 1);
        drape_world* w = worlds_[k];
        CHECK(checked(drape_world_destroy(w)) == DRAPE_OK);
        worlds_.erase(worlds_.begin() + k);
        for (size_t i = cloths_.size(); i-- > 0;) {
            if (cloths_[i].world != w) continue;
            remember_stale(cloths_[i].handle);
            cloths_.erase(cloths_.begin() + i);
        }
    }

    void remember_stale(drape_cloth* c) {
        if (stale_.size() < 8) stale_.push_back(c);
    }

    drape_cloth_desc cloth_desc() {
        drape_cloth_desc d{};
        d.struct_size = struct_size(sizeof d);
        d.backend = in_.ConsumeIntegralInRange<uint32_t>(0, 3);
        d.total_mass = maybe_bad(0.01f, 5.0f);
        return d;
    }

    void add_cloth(drape_status s, drape_world* w, drape_cloth* c) {
        if (s != DRAPE_OK) return;
        CHECK(c != nullptr);
        drape_cloth_info info{sizeof info};
        CHECK(checked(drape_cloth_get_info(c, &info)) == DRAPE_OK);
        if (cloths_.size() >= kMaxCloths) {
            CHECK(checked(drape_cloth_destroy(c)) == DRAPE_OK);
            remember_stale(c);
            return;
        }
        cloths_.push_back({c, w, info.vertex_count});
        read_positions(cloths_.back());
    }

    void create_grid() {
        drape_world* w = pick_world();
        drape_cloth_desc d = cloth_desc();
        drape_grid_desc g{};
        g.struct_size = struct_size(sizeof g);
        if (rarely()) {  // sizes the library must refuse (too many vertices, overflow, zero)
            static const uint32_t huge[][2] = {{0, 5}, {5, 0}, {1, 1}, {4194305, 1}, {65536, 65536},
                                               {0xffffffffu, 0xffffffffu}, {0x10000u, 0x10001u}, {2049, 2048}};
            const auto& h = huge[in_.ConsumeIntegralInRange<size_t>(0, 7)];
            g.columns = h[0];
            g.rows = h[1];
        } else {
            g.columns = in_.ConsumeIntegralInRange<uint32_t>(1, kMaxGridSide);
            g.rows = in_.ConsumeIntegralInRange<uint32_t>(1, kMaxGridSide);
        }
        g.width = maybe_bad(0.01f, 3.0f);
        g.height = maybe_bad(0.01f, 3.0f);
        for (int i = 0; i < 3; ++i) g.origin[i] = maybe_bad(-5.0f, 5.0f);
        const int axes = in_.ConsumeIntegralInRange<int>(0, 2);  // default / random / parallel
        for (int i = 0; i < 3 && axes > 0; ++i) {
            g.axis_u[i] = maybe_bad(-1.0f, 1.0f);
            g.axis_v[i] = axes == 2 ? 2.0f * g.axis_u[i] : maybe_bad(-1.0f, 1.0f);
        }
        drape_cloth* c = nullptr;
        drape_status s = checked(drape_cloth_create_grid(w, rarely() ? nullptr : &d, rarely() ? nullptr : &g,
                                                         rarely() ? nullptr : &c));
        if (s == DRAPE_OK) CHECK(g.columns <= kMaxGridSide && g.rows <= kMaxGridSide);
        add_cloth(s, w, c);
    }

    void create_mesh() {
        drape_world* w = pick_world();
        drape_cloth_desc d = cloth_desc();
        drape_mesh_desc m{};
        m.struct_size = struct_size(sizeof m);
        const uint32_t nv = in_.ConsumeIntegralInRange<uint32_t>(0, kMaxMeshVertices);
        std::vector<float> pos(size_t(nv) * 3);
        for (uint32_t v = 0; v < nv; ++v) {
            // Often reuse an earlier vertex (seams to weld, degenerate triangles) or a lattice point.
            const int how = in_.ConsumeIntegralInRange<int>(0, 5);
            for (int i = 0; i < 3; ++i) {
                float f;
                if (how == 0 && v > 0) f = pos[3 * in_.ConsumeIntegralInRange<uint32_t>(0, v - 1) + i];
                else if (how <= 2) f = 0.25f * float(in_.ConsumeIntegralInRange<int>(-4, 4));
                else f = maybe_bad(-2.0f, 2.0f);
                pos[3 * v + i] = f;
            }
        }
        uint32_t ni = in_.ConsumeIntegralInRange<uint32_t>(0, 3 * 2 * kMaxMeshVertices);
        if (!rarely()) ni -= ni % 3;
        std::vector<uint32_t> idx(ni);
        for (uint32_t& i : idx) i = rarely() ? in_.ConsumeIntegral<uint32_t>() : in_.ConsumeIntegralInRange<uint32_t>(0, nv);
        m.vertex_count = nv;
        m.index_count = ni;
        m.positions = pos.empty() || rarely() ? nullptr : pos.data();
        m.indices = idx.empty() || rarely() ? nullptr : idx.data();
        m.weld_distance = in_.ConsumeBool() ? 0.0f : maybe_bad(0.0f, 0.3f);
        if (rarely()) m.vertex_count = in_.ConsumeIntegral<uint32_t>() | 0x00400000u;  // lies about its size: refused
        if (m.vertex_count > nv) m.positions = nullptr;  // never let the library read past our arrays
        drape_cloth* c = nullptr;
        drape_status s = checked(drape_cloth_create_mesh(w, rarely() ? nullptr : &d, &m, &c));
        add_cloth(s, w, c);
    }

    void destroy_cloth() {
        const int k = pick_cloth();
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            expect_refused(c, checked(drape_cloth_destroy(c)));
            return;
        }
        CHECK(checked(drape_cloth_destroy(cloths_[k].handle)) == DRAPE_OK);
        remember_stale(cloths_[k].handle);
        cloths_.erase(cloths_.begin() + k);
    }

    void set_params() {
        const int k = pick_cloth();
        drape_params p{};
        CHECK(checked(drape_params_default(&p)) == DRAPE_OK);
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            expect_refused(c, checked(drape_cloth_set_params(c, &p)));
            return;
        }
        const Cloth& c = cloths_[k];
        if (in_.ConsumeBool()) p = read_params(c);
        const int edits = in_.ConsumeIntegralInRange<int>(1, 4);
        for (int e = 0; e < edits; ++e) {
            switch (in_.ConsumeIntegralInRange<int>(0, 9)) {
                case 0: p.model = in_.ConsumeIntegralInRange<uint32_t>(0, 4); break;
                case 1: p.stiffness[in_.ConsumeIntegralInRange<int>(0, 2)] = p.model == DRAPE_MODEL_PBD
                                                                                 ? maybe_bad(0, 1)
                                                                                 : maybe_bad(0, 1e5f);
                        break;
                case 2: p.damping = maybe_bad(0, 50); break;
                case 3: p.gravity[in_.ConsumeIntegralInRange<int>(0, 2)] = maybe_bad(-50, 50); break;
                case 4: p.wind[in_.ConsumeIntegralInRange<int>(0, 2)] = maybe_bad(-50, 50); break;
                case 5: p.air_drag = maybe_bad(0, 10); break;
                case 6: p.substeps = rarely() ? in_.ConsumeIntegral<uint32_t>() : in_.ConsumeIntegralInRange<uint32_t>(0, 8); break;
                case 7: p.iterations = rarely() ? in_.ConsumeIntegral<uint32_t>() : in_.ConsumeIntegralInRange<uint32_t>(0, 8); break;
                case 8: p.struct_size = struct_size(sizeof p); break;
                default: p.stiffness[in_.ConsumeIntegralInRange<int>(0, 2)] = any_float(); break;
            }
        }
        // Keep the work of one step bounded: the library accepts up to 1000 x 1000.
        // MASS_SPRING's automatic substeps go up to 1000 with stiff springs: mostly ask for a few.
        if (p.model == DRAPE_MODEL_MASS_SPRING && p.substeps == 0 && !rarely())
            p.substeps = in_.ConsumeIntegralInRange<uint32_t>(1, 8);
        const bool expensive = uint64_t(std::max(1u, p.substeps)) * std::max(1u, p.iterations) > 64;
        if (expensive) p.iterations = 0;  // still a call, but one the library must refuse
        Snapshot before = snapshot(c);
        drape_status s = checked(drape_cloth_set_params(c.handle, rarely() ? nullptr : &p));
        if (s != DRAPE_OK) expect_unchanged(c, before);
        else {
            // What was set is what is read back, AUTO as the model it resolved to on this backend.
            const drape_params now = read_params(c);
            if (p.model == DRAPE_MODEL_AUTO) {
                drape_cloth_info info{sizeof info};
                CHECK(checked(drape_cloth_get_info(c.handle, &info)) == DRAPE_OK);
                p.model = info.backend == DRAPE_BACKEND_GLES ? DRAPE_MODEL_XPBD : DRAPE_MODEL_IMPLICIT;
            }
            CHECK(std::memcmp(&now, &p, sizeof p) == 0);
        }
    }

    // which: 0 inverse masses (1 float per vertex), 1 positions, 2 velocities (3 floats)
    void vertex_floats(int which) {
        const int k = pick_cloth();
        std::vector<float> data(size_t(kMaxGridSide) * kMaxGridSide * 3 + 3);
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            drape_status s = which == 0 ? drape_cloth_set_inverse_masses(c, data.data(), 1)
                           : which == 1 ? drape_cloth_set_positions(c, data.data(), 1)
                                        : drape_cloth_set_velocities(c, data.data(), 1);
            expect_refused(c, checked(s));
            return;
        }
        const Cloth& c = cloths_[k];
        uint32_t count = c.vertices;
        if (rarely()) count = in_.ConsumeIntegralInRange<uint32_t>(0, c.vertices + 1);
        const size_t floats = size_t(std::min(count, c.vertices)) * (which == 0 ? 1 : 3);
        // A base value plus a few individual edits (keeps inputs short for big cloths).
        const float base = which == 0 ? sane_float(0, 10) : which == 1 ? sane_float(-1, 1) : sane_float(-3, 3);
        std::vector<float> start = read_positions(c);
        for (size_t i = 0; i < floats; ++i) data[i] = which == 1 ? start[i] + base : base;
        const int edits = in_.ConsumeIntegralInRange<int>(0, 4);
        for (int e = 0; e < edits && floats > 0; ++e)
            data[in_.ConsumeIntegralInRange<size_t>(0, floats - 1)] = which == 0 ? maybe_bad(0, 100) : maybe_bad(-3, 3);
        Snapshot before = snapshot(c);
        const float* ptr = rarely() ? nullptr : data.data();
        drape_status s = which == 0 ? drape_cloth_set_inverse_masses(c.handle, ptr, count)
                       : which == 1 ? drape_cloth_set_positions(c.handle, ptr, count)
                                    : drape_cloth_set_velocities(c.handle, ptr, count);
        if (checked(s) != DRAPE_OK) expect_unchanged(c, before);
        else read_positions(c);
    }

    void pins() {
        const int k = pick_cloth();
        drape_pin pin[4];
        const uint32_t n = in_.ConsumeIntegralInRange<uint32_t>(0, 4);
        const uint32_t vertices = k < 0 ? 4 : cloths_[k].vertices;
        for (uint32_t i = 0; i < n; ++i) {
            pin[i].struct_size = struct_size(sizeof(drape_pin));
            pin[i].vertex = rarely() ? in_.ConsumeIntegral<uint32_t>() : in_.ConsumeIntegralInRange<uint32_t>(0, vertices);
            for (float& f : pin[i].position) f = maybe_bad(-2, 2);
        }
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            expect_refused(c, checked(drape_cloth_set_pins(c, pin, n)));
            return;
        }
        Snapshot before = snapshot(cloths_[k]);
        drape_status s = checked(drape_cloth_set_pins(cloths_[k].handle, rarely() ? nullptr : pin, n));
        if (s != DRAPE_OK) expect_unchanged(cloths_[k], before);
    }

    void release_pins() {
        const int k = pick_cloth();
        uint32_t v[4];
        const uint32_t n = in_.ConsumeIntegralInRange<uint32_t>(0, 4);
        const uint32_t vertices = k < 0 ? 4 : cloths_[k].vertices;
        for (uint32_t i = 0; i < n; ++i)
            v[i] = rarely() ? in_.ConsumeIntegral<uint32_t>() : in_.ConsumeIntegralInRange<uint32_t>(0, vertices);
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            expect_refused(c, checked(drape_cloth_release_pins(c, v, n)));
            return;
        }
        Snapshot before = snapshot(cloths_[k]);
        drape_status s = checked(drape_cloth_release_pins(cloths_[k].handle, rarely() ? nullptr : v, n));
        if (s != DRAPE_OK) expect_unchanged(cloths_[k], before);
    }

    float dt() {
        static const float nice[] = {1 / 60.f, 1 / 30.f, 1 / 120.f, 0.1f, 1.0f, 1e-6f};
        return in_.ConsumeBool() ? in_.PickValueInArray(nice) : maybe_bad(1e-4f, 1.0f);
    }

    void step_cloth() {
        const int k = pick_cloth();
        const float h = dt();
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            expect_refused(c, checked(drape_cloth_step(c, h)));
            return;
        }
        const Cloth& c = cloths_[k];
        std::vector<float> before = read_positions(c);
        const int frames = in_.ConsumeIntegralInRange<int>(1, 4);
        for (int f = 0; f < frames; ++f) {
            drape_status s = checked(drape_cloth_step(c.handle, h));
            std::vector<float> after = read_positions(c);  // finite, always
            if (s == DRAPE_ERROR_UNSTABLE) {
                // Rolled back: the state from before this step.
                CHECK(std::memcmp(after.data(), before.data(), after.size() * sizeof(float)) == 0);
            }
            before.swap(after);
        }
        stats(c);
    }

    void step_world() {
        drape_world* w = pick_world();
        drape_status s = checked(drape_world_step(w, dt()));
        if (std::find(worlds_.begin(), worlds_.end(), w) == worlds_.end())
            CHECK(s == DRAPE_ERROR_NULL_POINTER || s == DRAPE_ERROR_INVALID_HANDLE);
        for (const Cloth& c : cloths_) read_positions(c);
    }

    void stats(const Cloth& c) {
        drape_stats st{};
        st.struct_size = sizeof st;
        CHECK(checked(drape_cloth_get_stats(c.handle, &st)) == DRAPE_OK);
        CHECK(std::isfinite(st.max_strain) && std::isfinite(st.rms_strain));
    }

    void read() {
        const int k = pick_cloth();
        drape_vertex_layout l{};
        l.struct_size = struct_size(sizeof l);
        l.stride = in_.ConsumeBool() ? 4 * in_.ConsumeIntegralInRange<uint32_t>(0, 12) : in_.ConsumeIntegral<uint32_t>();
        l.position_offset = in_.ConsumeBool() ? 4 * in_.ConsumeIntegralInRange<int32_t>(-1, 8) : in_.ConsumeIntegral<int32_t>();
        l.normal_offset = in_.ConsumeBool() ? 4 * in_.ConsumeIntegralInRange<int32_t>(-1, 8) : in_.ConsumeIntegral<int32_t>();
        if (l.position_offset < -1) l.position_offset = in_.ConsumeBool() ? -1 : l.position_offset;
        if (l.normal_offset < -1) l.normal_offset = in_.ConsumeBool() ? -1 : l.normal_offset;
        if (k < 0) {
            drape_cloth* c = bad_cloth();
            char buf[64];
            expect_refused(c, checked(drape_cloth_read(c, &l, buf, sizeof buf)));
            return;
        }
        const Cloth& c = cloths_[k];
        // The buffer is exactly dst_size bytes on the heap, so ASan sees any write past it.
        const size_t exact = size_t(c.vertices) * std::min<uint32_t>(l.stride, 1024);
        size_t size = exact;
        if (rarely()) size = in_.ConsumeIntegralInRange<size_t>(0, exact);
        std::vector<unsigned char> buf(std::max<size_t>(size, 1), 0xAB);
        drape_status s = checked(drape_cloth_read(c.handle, rarely() ? nullptr : &l, buf.data(), size));
        if (s != DRAPE_OK) return;
        for (uint32_t v = 0; v < c.vertices; ++v) {
            for (int32_t off : {l.position_offset, l.normal_offset}) {
                if (off < 0) continue;
                float xyz[3];
                std::memcpy(xyz, buf.data() + size_t(v) * l.stride + off, 12);
                CHECK(std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]));
            }
        }
    }

    void queries() {
        uint32_t avail = 0;
        const uint32_t backend = in_.ConsumeIntegralInRange<uint32_t>(0, 4);
        drape_status s = checked(drape_backend_available(backend, rarely() ? nullptr : &avail));
        if (backend > DRAPE_BACKEND_GLES) CHECK(s != DRAPE_OK);
        const int k = pick_cloth();
        drape_cloth* c = k < 0 ? bad_cloth() : cloths_[k].handle;
        drape_cloth_info info{sizeof info};
        drape_stats st{};
        st.struct_size = struct_size(sizeof st);
        drape_params p{};
        drape_status a = checked(drape_cloth_get_info(c, rarely() ? nullptr : &info));
        drape_status b = checked(drape_cloth_get_stats(c, &st));
        drape_status d = checked(drape_cloth_get_params(c, &p));
        if (k < 0) {
            expect_refused(c, a);
            expect_refused(c, b);
            expect_refused(c, d);
        }
        CHECK(checked(drape_params_default(nullptr)) == DRAPE_ERROR_NULL_POINTER);
    }

    // ---- API added by other issues (compiled in when the header has it) -------------------
    void extensions() {
#ifdef DRAPE_MAX_COLLIDERS
        const int k = pick_cloth();
        drape_cloth* c = k < 0 ? bad_cloth() : cloths_[k].handle;
        drape_status s = DRAPE_OK;
        Snapshot before;
        if (k >= 0) before = snapshot(cloths_[k]);
        switch (in_.ConsumeIntegralInRange<int>(0, 5)) {
            case 0: {  // colliders
                const uint32_t n = rarely() ? DRAPE_MAX_COLLIDERS + 1 : in_.ConsumeIntegralInRange<uint32_t>(0, 4);
                std::vector<drape_collider> col(n);
                for (uint32_t i = 0; i < n; ++i) {
                    drape_collider& q = col[i];
                    q.struct_size = struct_size(sizeof q);
                    q.shape = in_.ConsumeIntegralInRange<uint32_t>(0, 4);
                    q.id = in_.ConsumeIntegralInRange<uint32_t>(0, 5);
                    for (float& f : q.position) f = maybe_bad(-2, 2);
                    if (in_.ConsumeBool()) {
                        q.rotation[0] = q.rotation[1] = q.rotation[2] = 0;
                        q.rotation[3] = 1;
                    } else {
                        for (float& f : q.rotation) f = maybe_bad(-1, 1);
                    }
                    for (float& f : q.size) f = maybe_bad(0, 2);
                    q.margin = maybe_bad(0, 0.1f);
                    q.friction = maybe_bad(0, 1);
                }
                s = drape_cloth_set_colliders(c, rarely() ? nullptr : col.data(), n);
                break;
            }
            case 1: {
                drape_sleep_desc d{struct_size(sizeof d), maybe_bad(0, 1), maybe_bad(0, 2)};
                s = drape_cloth_set_sleep(c, rarely() ? nullptr : &d);
                break;
            }
            case 2: s = drape_cloth_wake(c); break;
            case 3: {
                drape_owner o{};
                CHECK(checked(drape_owner_default(&o)) == DRAPE_OK);
                o.struct_size = struct_size(sizeof o);
                for (float& f : o.position) f = maybe_bad(-3, 3);
                if (in_.ConsumeBool()) for (float& f : o.rotation) f = maybe_bad(-1, 1);
                o.linear_inertia = maybe_bad(0, 1);
                o.angular_inertia = maybe_bad(0, 1);
                o.teleport_distance = maybe_bad(0.01f, 3);
                s = drape_cloth_set_owner(c, rarely() ? nullptr : &o);
                break;
            }
            case 4: {
                drape_view v = view();
                drape_touch t[3];
                const uint32_t n = in_.ConsumeIntegralInRange<uint32_t>(0, 3);
                for (uint32_t i = 0; i < n; ++i) {
                    CHECK(checked(drape_touch_default(&t[i])) == DRAPE_OK);
                    t[i].struct_size = struct_size(sizeof t[i]);
                    t[i].position[0] = maybe_bad(0, 640);
                    t[i].position[1] = maybe_bad(0, 480);
                    t[i].motion[0] = maybe_bad(-50, 50);
                    t[i].motion[1] = maybe_bad(-50, 50);
                    if (rarely()) t[i].amplitude = any_float();
                    if (rarely()) t[i].sigma = any_float();
                }
                s = drape_cloth_drag(c, rarely() ? nullptr : &v, t, rarely() ? 17 : n);
                break;
            }
            default: {
                drape_view v = view();
                const uint32_t id = in_.ConsumeIntegralInRange<uint32_t>(0, 17);
                float p[2] = {maybe_bad(0, 640), maybe_bad(0, 480)};
                switch (in_.ConsumeIntegralInRange<int>(0, 2)) {
                    case 0: {
                        uint32_t vert = 0;
                        s = drape_cloth_grab(c, &v, id, p, maybe_bad(0, 500), rarely() ? nullptr : &vert);
                        if (s == DRAPE_OK && k >= 0)
                            CHECK(vert == UINT32_MAX || vert == DRAPE_GRAB_ON_GPU || vert < cloths_[k].vertices);
                        break;
                    }
                    case 1: s = drape_cloth_grab_move(c, &v, id, p); break;
                    default: s = drape_cloth_grab_release(c, id); break;
                }
                break;
            }
        }
        checked(s);
        if (k < 0) expect_refused(c, s);
        else if (s != DRAPE_OK) expect_unchanged(cloths_[k], before);
        else read_positions(cloths_[k]);
#endif
    }

#ifdef DRAPE_MAX_COLLIDERS
    // A camera at (0,0,3) looking down -z at the origin, 640x480, 60 degree fov; or junk.
    drape_view view() {
        drape_view v{};
        v.struct_size = struct_size(sizeof v);
        for (int i = 0; i < 4; ++i) v.world[i * 5] = v.view[i * 5] = 1.0f;
        v.view[14] = -3.0f;
        const float f = 1.0f / std::tan(0.5f * 1.0471976f), aspect = 640.0f / 480.0f, n = 0.1f, fa = 100.0f;
        v.projection[0] = f / aspect;
        v.projection[5] = f;
        v.projection[10] = (fa + n) / (n - fa);
        v.projection[11] = -1.0f;
        v.projection[14] = 2.0f * fa * n / (n - fa);
        v.viewport[0] = 640;
        v.viewport[1] = 480;
        const int edits = rarely() ? in_.ConsumeIntegralInRange<int>(1, 4) : 0;
        for (int e = 0; e < edits; ++e) {
            float* m = in_.ConsumeBool() ? v.projection : in_.ConsumeBool() ? v.view : v.world;
            m[in_.ConsumeIntegralInRange<int>(0, 15)] = any_float();
        }
        if (rarely()) v.viewport[in_.ConsumeIntegralInRange<int>(0, 1)] = any_float();
        return v;
    }
#endif

    FuzzedDataProvider& in_;
    std::vector<drape_world*> worlds_;
    std::vector<Cloth> cloths_;
    std::vector<drape_cloth*> stale_;
    long stack_junk_[8] = {};
    int chaos_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    Harness h(in);
    h.run();
    return 0;
}
