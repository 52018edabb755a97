// GL call budget of the GLES backend: the GL calls of N steady frames, counted by the library's GL
// loader (every entry point counts its calls; drape_gl_call_count reads them). A frame is what
// the Unity component does each frame: (re)push the colliders, step, write the mesh's vertex
// buffer. Over the counted frames nothing may be read back from GPU memory, nothing uploaded
// unless the caller changed it, and each transform-feedback pass costs a fixed, small number of
// calls (vertex arrays and transform-feedback objects made once, textures bound once per step).
#include <GLES3/gl3.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "drape_test_util.h"
#include "gles_test_util.h"

using namespace drape_test;

namespace {

/// Calls of the entry points a frame's verdicts look at.
struct GlCalls {
    uint64_t total = 0, draws = 0, uniforms = 0, reads = 0, uploads = 0, refreshes = 0, texture_binds = 0,
             attrib_setup = 0;
    static GlCalls now() {
        auto n = [](const char* name) { return drape_gl_call_count(name); };
        GlCalls c;
        c.total = n(nullptr);
        c.draws = n("glDrawArrays");
        c.uniforms = n("glUniform1i") + n("glUniform1f") + n("glUniform2f") + n("glUniform3fv") + n("glUniform4fv");
        // The loader has no glReadPixels or glGetBufferSubData: mapping is the only way to read.
        c.reads = n("glMapBufferRange");
        // Client memory enters GL only through these (table textures go through a staging buffer).
        c.uploads = n("glBufferData") + n("glBufferSubData");
        // Texture refreshes from a buffer, on the GPU (every glTexSubImage2D reads a bound buffer).
        c.refreshes = n("glTexSubImage2D");
        c.texture_binds = n("glBindTexture") + n("glActiveTexture");
        c.attrib_setup = n("glEnableVertexAttribArray") + n("glDisableVertexAttribArray") +
                         n("glVertexAttribPointer") + n("glVertexAttribIPointer");
        return c;
    }
    GlCalls per_frame_since(const GlCalls& start, uint64_t frames) const {
        GlCalls d;
        d.total = (total - start.total) / frames;
        d.draws = (draws - start.draws) / frames;
        d.uniforms = (uniforms - start.uniforms) / frames;
        d.reads = (reads - start.reads) / frames;
        d.uploads = (uploads - start.uploads) / frames;
        d.refreshes = (refreshes - start.refreshes) / frames;
        d.texture_binds = (texture_binds - start.texture_binds) / frames;
        d.attrib_setup = (attrib_setup - start.attrib_setup) / frames;
        return d;
    }
};

std::ostream& operator<<(std::ostream& os, const GlCalls& c) {
    return os << c.total << " calls (" << c.draws << " draws, " << c.uniforms << " uniforms, " << c.refreshes
              << " texture refreshes, " << c.texture_binds << " texture binds/unit switches, " << c.attrib_setup
              << " attribute set-ups, " << c.uploads << " uploads, " << c.reads << " reads)";
}

enum class Extra { None, Tethers, CollidersAndTethers, DragAndTethers, GrabAndTethers, SelfCollision, SelfCollisionOff };

struct BudgetCase {
    const char* name;
    drape_model model;
    Extra extra;
};

class GlesCallBudget : public WithHeadlessGles<::testing::TestWithParam<BudgetCase>> {};

// Per pass, apart from uniforms: program (1), vertex array (1), binding at most two outputs in place
// of the last pass's and unbinding the second (3: GlesCloth::bind_outputs), begin + draw + end (3),
// unbinding the refresh buffer (1), and refreshing at most two input textures (unit switch + buffer
// bind + copy: 3 each) = 15. Per frame, apart from passes: the
// caller's GL state saved and restored (8 texture units and 14 bindings, about 60 calls), textures
// bound on their units once, error checks, the output buffer's size check, the pin-start copy.
constexpr uint64_t kCallsPerPass = 15;
constexpr uint64_t kCallsPerFrame = 100;
// Uniforms per pass: u_substep (IMPLICIT's iterations: u_chebyshev) and the two input samplers'
// units, or the colliders' two. The
// parameters live in a uniform block, uploaded only when they change.
constexpr uint64_t kUniformsPerPass = 3;

// IMPLICIT's coarse correction (sim.vert.glsl DRAPE_PASS_COARSE, gles_coarse.h): one V-cycle per
// substep, each pass one point per node of a level: restrict to level 1, down to each coarser level,
// the dense solve at the coarsest, up to level 1 (the next iteration adds the correction). So its
// draws per substep are the level sizes L down and back up, L + reverse(L): 2 |L| passes, with L as
// the cook leaves it: each level at most 4/5 of the one above (it stops where aggregation stalls),
// only the last within kCoarsestNodes.
constexpr uint32_t kCoarsestNodes = 128;
std::vector<GLsizei>* g_draw_counts = nullptr;  // the counted frames' draws' point counts
PFNGLDRAWARRAYSPROC g_driver_draw = nullptr;
void GL_APIENTRY record_draw(GLenum mode, GLint first, GLsizei count) {
    if (g_draw_counts) g_draw_counts->push_back(count);
    g_driver_draw(mode, first, count);
}

/// The coarse levels' sizes (L) that one V-cycle per substep drew, from the draws other than the
/// particle passes' (`particles` points each); empty if there were none or they were no V-cycle.
std::vector<GLsizei> coarse_levels(const std::vector<GLsizei>& draws, GLsizei particles) {
    std::vector<GLsizei> seq;
    for (GLsizei c : draws)
        if (c != particles) seq.push_back(c);
    size_t depth = 1;  // the solve repeats the coarsest level's size
    while (depth < seq.size() && seq[depth] != seq[depth - 1]) ++depth;
    if (seq.empty() || depth == seq.size()) return {};
    std::vector<GLsizei> levels(seq.begin(), seq.begin() + std::ptrdiff_t(depth));
    for (size_t k = 0; k < seq.size(); ++k) {
        const size_t at = k % (2 * depth);
        if (seq[k] != levels[at < depth ? at : 2 * depth - 1 - at]) return {};
    }
    return levels;
}

// Self-collision: a draw per hash layer (gles_self_collide.h kSelfLayers) and the collide pass.
constexpr uint64_t kSelfHashLayers = 8;
constexpr uint32_t cols = 32, rows = 32;

/// The GL calls per frame of the case's cloth over its counted frames (after warm-up frames), with a
/// grab the same frames with the finger still, its stats and positions after them.
void count_frames(const BudgetCase& bc, GlCalls* per_frame, GlCalls* still, drape_stats* st, std::vector<float>* x,
                  std::vector<GLsizei>* draws) {
    WorldPtr w = make_world(1);
    drape_grid_desc g = grid_desc(cols, rows, 1.0f, 1.0f);
    g.origin[1] = 1.0f;
    drape_cloth* c = make_grid(w.get(), g, 0.5f, DRAPE_BACKEND_GLES);
    ASSERT_NE(c, nullptr);
    drape_params p{};
    ASSERT_DRAPE_OK(drape_params_default(&p));
    p.model = bc.model;
    p.iterations = 4;
    const bool tethers = bc.extra != Extra::None && bc.extra != Extra::SelfCollision && bc.extra != Extra::SelfCollisionOff;
    p.max_stretch = tethers ? 0.1f : 0.0f;
    if (bc.model == DRAPE_MODEL_PBD) {
        p.stiffness[0] = p.stiffness[1] = 1.0f;  // PBD stiffness is a fraction
        p.stiffness[2] = 0.2f;
        p.damping = 0.5f;  // the predict pass with dashpots reads textures
    }
    ASSERT_DRAPE_OK(drape_cloth_set_params(c, &p));
    drape_pin pins[2] = {{sizeof(drape_pin), 0, {0, 1, 0}}, {sizeof(drape_pin), cols - 1, {1, 1, 0}}};
    ASSERT_DRAPE_OK(drape_cloth_set_pins(c, pins, 2));
    // Unity-like vertex stream: position, normal, uv (copied through on the GPU).
    const uint32_t n = cols * rows;
    const drape_vertex_layout layout{sizeof(drape_vertex_layout), 32, 0, 12};
    GLuint vbo = 0;
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n) * 32, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    ASSERT_DRAPE_OK(drape_cloth_set_output_buffer(c, vbo, &layout));
    if (bc.extra == Extra::SelfCollision || bc.extra == Extra::SelfCollisionOff) {
        drape_self_collision_desc sc{};
        sc.struct_size = sizeof sc;
        sc.enabled = 1;
        sc.thickness = 0.03f;
        ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
        if (bc.extra == Extra::SelfCollisionOff) {
            ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));  // its GL objects made
            sc.enabled = 0;
            ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
        }
    }

    // Orthographic identity view: sim (x, y) in [-1, 1] on a 200 x 200 px screen.
    drape_view ortho{};
    ortho.struct_size = sizeof ortho;
    for (int k = 0; k < 16; k += 5) ortho.world[k] = ortho.view[k] = ortho.projection[k] = 1;
    ortho.viewport[0] = ortho.viewport[1] = 200;
    bool finger_moves = true;
    float finger_x = 120.0f;
    auto frame = [&](int f) {
        if (bc.extra == Extra::CollidersAndTethers) {
            // A sphere under the sheet, moving every frame, pushed every frame as Unity does.
            drape_collider s{};
            s.struct_size = sizeof s;
            s.id = 1;
            s.shape = DRAPE_COLLIDER_SPHERE;
            s.size[0] = 0.2f;
            s.position[0] = 0.5f + 0.001f * float(f);
            s.position[1] = 0.5f;
            s.position[2] = -0.5f;
            s.rotation[3] = 1.0f;
            ASSERT_DRAPE_OK(drape_cloth_set_colliders(c, &s, 1));
        }
        if (bc.extra == Extra::DragAndTethers) {
            // A finger dragging across the sheet every frame (orthographic identity view): the
            // drag is evaluated on the GPU from uniforms, nothing read back or uploaded.
            drape_touch t{};
            ASSERT_DRAPE_OK(drape_touch_default(&t));
            t.position[0] = 100.0f + float(f);
            t.position[1] = 150.0f;
            t.motion[0] = 1.0f;
            ASSERT_DRAPE_OK(drape_cloth_drag(c, &ortho, &t, 1));
        }
        if (bc.extra == Extra::GrabAndTethers) {
            // A finger holding a vertex near the sheet's middle (picked on the GPU in the first
            // frame), moving every frame: the grab pass's finger uniform, nothing read or uploaded.
            if (finger_moves) finger_x = 120.0f + float(f);
            const float at[2] = {finger_x, 200.0f};
            uint32_t got = 0;
            if (f == 0) ASSERT_DRAPE_OK(drape_cloth_grab(c, &ortho, 1, at, 10.0f, &got));
            else ASSERT_DRAPE_OK(drape_cloth_grab_move(c, &ortho, 1, at));
        }
        ASSERT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60));
    };
    // Programs, vertex arrays, first uploads. The grab pass swaps two buffers' roles once more per
    // step: their roles cycle over more frames before every pass configuration has its vertex array.
    const int warm_up = bc.extra == Extra::GrabAndTethers ? 4 : 3, counted = 5;
    for (int f = 0; f < warm_up; ++f) frame(f);
    const GlCalls start = GlCalls::now();
    g_driver_draw = reinterpret_cast<PFNGLDRAWARRAYSPROC>(drape_gl_replace("glDrawArrays", reinterpret_cast<void*>(&record_draw)));
    g_draw_counts = draws;
    for (int f = warm_up; f < warm_up + counted; ++f) frame(f);
    g_draw_counts = nullptr;
    drape_gl_replace("glDrawArrays", reinterpret_cast<void*>(g_driver_draw));
    *per_frame = GlCalls::now().per_frame_since(start, counted);
    if (bc.extra == Extra::GrabAndTethers) {
        // The same frames with the finger still (compared by the test).
        finger_moves = false;
        const GlCalls still_start = GlCalls::now();
        for (int f = warm_up + counted; f < warm_up + 2 * counted; ++f) frame(f);
        *still = GlCalls::now().per_frame_since(still_start, counted);
    }
    *st = stats_of(c);  // after counting: reading stats reads the GPU state back
    *x = positions(c);
    glDeleteBuffers(1, &vbo);
}

TEST_P(GlesCallBudget, SteadyFramesReadNothingUploadNothingAndCostAFixedNumberOfCallsPerPass) {
    const BudgetCase bc = GetParam();
    GlCalls per_frame, still;
    drape_stats st{};
    std::vector<float> x;
    std::vector<GLsizei> draws;
    count_frames(bc, &per_frame, &still, &st, &x, &draws);
    if (HasFatalFailure()) return;
    uint64_t passes_per_substep = bc.model == DRAPE_MODEL_MASS_SPRING ? 1 : 1 + st.iterations;
    const std::vector<GLsizei> levels = coarse_levels(draws, GLsizei(cols * rows));
    if (bc.model == DRAPE_MODEL_IMPLICIT) {
        ASSERT_FALSE(levels.empty()) << "IMPLICIT draws one coarse V-cycle per substep";
        GLsizei above = GLsizei(cols * rows - 2);  // free particles
        for (size_t k = 0; k < levels.size(); ++k) {
            EXPECT_LE(5 * levels[k], 4 * above) << "level " << k + 1;
            EXPECT_EQ(levels[k] <= GLsizei(kCoarsestNodes), k + 1 == levels.size()) << "level " << k + 1;
            above = levels[k];
        }
        passes_per_substep += 2 * levels.size();
    } else {
        EXPECT_TRUE(levels.empty()) << "only IMPLICIT has coarse passes";
    }
    if (bc.extra != Extra::None && bc.extra != Extra::SelfCollision && bc.extra != Extra::SelfCollisionOff)
        ++passes_per_substep;                                           // tethers
    if (bc.extra == Extra::SelfCollision) passes_per_substep += kSelfHashLayers + 1;  // hash layers, collide
    if (bc.extra == Extra::CollidersAndTethers) ++passes_per_substep;   // collisions
    uint64_t passes = st.substeps * passes_per_substep + 1;             // + the output pass
    if (bc.extra == Extra::DragAndTethers) ++passes;                    // drag: first substep
    if (bc.extra == Extra::GrabAndTethers) ++passes;                    // the grab pass
    std::cout << "[ gl calls ] " << bc.name << ", " << cols << "x" << rows << ", " << st.substeps << " substeps, "
              << passes << " passes per frame (" << 2 * levels.size() << " coarse a substep): " << per_frame << "\n";

    EXPECT_EQ(per_frame.reads, 0u);
    EXPECT_EQ(per_frame.uploads, 0u);
    EXPECT_EQ(per_frame.draws, passes);
    EXPECT_LE(per_frame.draws, st.substeps * (passes_per_substep + 2));
    EXPECT_EQ(per_frame.attrib_setup, 0u) << "vertex arrays are made once per pass configuration";
    EXPECT_LE(per_frame.refreshes, 2 * passes);
    EXPECT_LE(per_frame.total - per_frame.uniforms, kCallsPerPass * passes + kCallsPerFrame);
    EXPECT_LE(per_frame.uniforms, kUniformsPerPass * passes);
    if (bc.extra == Extra::GrabAndTethers) {
        // The same frames with the finger still: the moving finger costs its one uniform update
        // per frame, and nothing else.
        std::cout << "[ gl calls ] " << bc.name << ", finger still: " << still << "\n";
        EXPECT_EQ(per_frame.uniforms, still.uniforms + 1);
        EXPECT_EQ(per_frame.total, still.total + 1);
        EXPECT_EQ(still.uploads + still.reads, 0u);
    }
    // Still simulating (parity with the CPU is test_gles.cpp's): the sheet's middle fell.
    EXPECT_LT(x[size_t(rows / 2 * cols + cols / 2) * 3 + 1], 1.0f) << "the sheet fell under gravity";
    if (bc.extra == Extra::SelfCollisionOff) {
        // Switched off, self-collision costs no GL call: the same counts as a cloth never told of it.
        GlCalls never, unused;
        drape_stats st_never{};
        std::vector<float> x_never;
        std::vector<GLsizei> draws_never;
        count_frames({"never", bc.model, Extra::None}, &never, &unused, &st_never, &x_never, &draws_never);
        EXPECT_EQ(per_frame.total, never.total);
        EXPECT_EQ(per_frame.draws, never.draws);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Frames, GlesCallBudget,
    ::testing::Values(BudgetCase{"MassSpring", DRAPE_MODEL_MASS_SPRING, Extra::None},
                      BudgetCase{"MassSpring_Tethers", DRAPE_MODEL_MASS_SPRING, Extra::Tethers},
                      BudgetCase{"MassSpring_Colliders", DRAPE_MODEL_MASS_SPRING, Extra::CollidersAndTethers},
                      BudgetCase{"Pbd", DRAPE_MODEL_PBD, Extra::None},
                      BudgetCase{"Pbd_Tethers", DRAPE_MODEL_PBD, Extra::Tethers},
                      BudgetCase{"Pbd_Colliders", DRAPE_MODEL_PBD, Extra::CollidersAndTethers},
                      BudgetCase{"Xpbd", DRAPE_MODEL_XPBD, Extra::None},
                      BudgetCase{"Xpbd_Tethers", DRAPE_MODEL_XPBD, Extra::Tethers},
                      BudgetCase{"Xpbd_Colliders", DRAPE_MODEL_XPBD, Extra::CollidersAndTethers},
                      BudgetCase{"MassSpring_Drag", DRAPE_MODEL_MASS_SPRING, Extra::DragAndTethers},
                      BudgetCase{"Xpbd_Drag", DRAPE_MODEL_XPBD, Extra::DragAndTethers},
                      BudgetCase{"MassSpring_Grab", DRAPE_MODEL_MASS_SPRING, Extra::GrabAndTethers},
                      BudgetCase{"Xpbd_Grab", DRAPE_MODEL_XPBD, Extra::GrabAndTethers},
                      BudgetCase{"Implicit_Grab", DRAPE_MODEL_IMPLICIT, Extra::GrabAndTethers},
                      BudgetCase{"Implicit", DRAPE_MODEL_IMPLICIT, Extra::None},
                      BudgetCase{"Implicit_Tethers", DRAPE_MODEL_IMPLICIT, Extra::Tethers},
                      BudgetCase{"Implicit_Colliders", DRAPE_MODEL_IMPLICIT, Extra::CollidersAndTethers},
                      BudgetCase{"Xpbd_SelfCollision", DRAPE_MODEL_XPBD, Extra::SelfCollision},
                      BudgetCase{"Implicit_SelfCollision", DRAPE_MODEL_IMPLICIT, Extra::SelfCollision},
                      BudgetCase{"Xpbd_SelfCollisionOff", DRAPE_MODEL_XPBD, Extra::SelfCollisionOff}),
    [](const ::testing::TestParamInfo<BudgetCase>& info) { return std::string(info.param.name); });

}  // namespace
