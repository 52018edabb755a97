// OpenGL ES 3.0 transform-feedback backend: a Cloth whose state lives in GL buffers (the shared
// CPU copy, Cloth::x_ and d_, is refreshed on demand).
//
// Data on the GPU (per cloth; W = kTexWidth texels per texture row):
//   particle buffers x4 (ping-pong, roles rotate like the CPU step's x/d/spare/spare2). The state is
//     as on the CPU (kernels.h): positions x and displacements d over the last substep, one vec4
//     record per particle (xyz + inverse mass). PBD/XPBD displacement iterates are records of
//     R vec4s, R = 1 or, for XPBD, 1 + ceil(slots/4) (record + lambdas per slot); every buffer is
//     sized for R, and its layout follows its current role. The mass-spring pass and the last
//     constraint iteration write x and d at once (separate-attribs transform feedback);
//   one RGBA32F texture per particle buffer, refreshed on the GPU after every pass that writes the
//     buffer (GL_PIXEL_UNPACK_BUFFER + glTexSubImage2D): neighbours are read with texelFetch;
//   RGBA32UI textures: neighbour table (index, rest bits, group), particle info (count, active,
//     triangles), incident triangles (normals);
//   kinematic start (copied on the GPU at step start) and pin targets (uploaded when pins move);
//   tethers: per particle (anchor index, length bits), uploaded when they change; the tether pass
//     (one more transform-feedback pass per substep, x and d into the spare pair) runs only when
//     the cloth has tethers (max_stretch > 0 and kinematic particles), as on the CPU.
//   IMPLICIT's coarse levels (gles_coarse.h): one RGBA32UI table (aggregates, coarse matrices, the
//     coarsest level's inverse), cooked on the CPU when h, the springs or the masses change, and a
//     buffer of per-level residuals and corrections with its RGBA32F texture (refreshed after each
//     coarse pass).
// Positions on the GPU are local, relative to Cloth::origin as on the CPU (float-safe far from the
// caller's origin); the output pass adds the origin, and re-centring shifts them in a GPU pass.
// Nothing is read back on the step path; pull() (explicit readback, get_stats, setters that need
// the current state) maps the two state buffers (x, d) once.
//
// Two modes. Immediate: a GL ES 3 context is current on the thread that creates and steps the
// cloth (tests, samples). RenderThread (Unity): the main thread only records steps and edits; the
// GL work runs when the Unity render event fires (render_thread_tick) on the render thread.
#pragma once

#include "backend/gles/gl_loader.h"  // GL ES 3.0 + EGL, loaded at run time
#include "backend/gles/gles_coarse.h"
#include "backend/gles/gles_self_collide.h"
#include "backend/gles/sim_uniforms.h"  // generated from tools/abi/abi.py

#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "core/cloth.h"
#include "core/drag.h"  // kMaxGrabs
#include "shaders/layout.h"  // DRAPE_TEX_WIDTH

namespace drape::gles {

/// Texels per row of every texture (shaders/layout.h). One width for all textures: one texel().
constexpr uint32_t kTexWidth = DRAPE_TEX_WIDTH;

/// True when an OpenGL ES >= 3.0 context is current on this thread; otherwise *why says why.
bool context_current(std::string* why = nullptr);

/// Unity GLES device state (set by the plug-in interface on the render thread).
void set_render_thread_device(bool ready);
bool render_thread_device_ready();
/// Runs all recorded GL work of RenderThread cloths and frees released GL objects. Render thread.
void render_thread_tick();
/// Device shutdown: every RenderThread cloth keeps its state on the CPU and frees its GL objects.
void render_thread_shutdown();
/// Every GL context GLES cloths used is gone (drape_gles_context_lost): each cloth forgets its GL
/// object names without deleting them and rebuilds from its CPU copy on its next GL work; GL
/// objects of destroyed cloths waiting for their context are forgotten too. Any thread; no GL call.
void context_lost();

/// GL objects of one cloth (names; 0 = none).
struct GlObjects {
    GLuint buffers[4] = {};
    GLuint textures[4] = {};
    GLuint nbr_tex = 0, info_tex = 0, tri_tex = 0;
    GLuint kstart = 0, targets = 0, vertex_to_particle = 0, scratch = 0, tethers = 0;
    GLuint uniforms = 0;  ///< the DrapeSim uniform block (SimUniforms)
    GLuint staging = 0;   ///< pixel-unpack buffer that table textures are uploaded through
    GLuint out_vao = 0;   ///< the output pass's inputs
    GLuint fbo = 0, rbo = 0;  ///< own 1x1 target (headless passes, the sleep check's points)
    GLuint queries[3] = {};   ///< the sleep check's occlusion queries (GlesCloth::kStillQueries)
    /// Grabs (gles_grab.cpp): pick target (RGBA32UI texture + depth renderbuffer, one texel per
    /// slot) and the pin targets the passes read while a grab is held.
    GLuint pick_fbo = 0, pick_tex = 0, pick_depth = 0, grab_targets = 0;
    std::vector<GLuint> programs;
    std::vector<GLuint> vaos;  ///< per pass configuration (GlesCloth::vertex_array)
    SelfCollideGl self;        ///< self-collision's (gles_self_collide.h)
    /// IMPLICIT's coarse levels (gles_coarse.h): table texture, two vector buffers (the passes
    /// alternate, GlesCloth::coarse_pass) and their texture, and the attribute-less vertex array
    /// their passes draw with.
    GLuint coarse_table = 0, coarse_vec[2] = {}, coarse_vec_tex = 0, coarse_vao = 0;
    void* context = nullptr;  ///< EGLContext they were made in
    bool empty() const;
};
/// Deletes them now (context current) or when a context they belong to is next current.
void release_gl(GlObjects& objects);

// gles_cloth.cpp's GL helpers that the self-collide passes (gles_self_collide.cpp) use too.
/// DRAPE_ERROR_GL naming `where` if GL reported an error (all pending errors cleared).
Result gl_error(const char* where);
/// Compiles and links a program: vertex source vs and a fragment stage (fs_source named fs_name, or
/// discard.frag.glsl), transform-feedback varyings, attribute locations; samplers of the
/// simulation's tables and the DrapeSim block bound.
Result link(const std::string& vs_source, const char* name, const std::vector<std::string>& varyings,
            GLenum buffer_mode, const std::vector<std::pair<GLuint, const char*>>& attribs, GLuint* out,
            const char* fs_source = nullptr, const char* fs_name = nullptr);
/// Rows of kTexWidth texels that hold `texels`.
uint32_t rows_for(uint64_t texels);
/// A kTexWidth x rows texture, nearest filtering (made on the setup unit).
GLuint make_texture(GLenum internal, uint32_t rows);
/// Uploads RGBA32UI texels (padded to whole rows here) through the pixel-unpack buffer `staging`.
void upload_uint_texture(GLuint t, GLuint staging, uint32_t rows, std::vector<uint32_t>& texels);

class GlesCloth final : public Cloth {
public:
    enum class Mode { Immediate, RenderThread };
    static constexpr int kMaxUniforms = 16;  ///< uniforms outside the DrapeSim block per program

    GlesCloth(World& world, std::shared_ptr<const Description> description, Mode mode);
    ~GlesCloth() override;

    Mode mode() const { return mode_; }
    /// Immediate mode: creates GL objects and compiles the current variant (DRAPE_ERROR_GL + log).
    Result init_gl();

    /// Immediate: steps on the GPU now. RenderThread: records the step; returns an error the
    /// render thread met since the last call (then cleared).
    Result step(float dt) override;
    /// Applies a setter now (state pulled first if the GPU copy is newer and the setter reads it),
    /// or (RenderThread, when it must wait for GPU state) on the render thread.
    Result edit(Access access, std::function<void(Cloth&)> fn) override;
    /// drape_cloth_read / get_stats: CPU copy, pulled first when stale (needs the context).
    Result read(const drape_vertex_layout& layout, void* dst) override;
    Result stats(drape_stats* out) override;
    Result set_output(uint32_t gl_buffer, const drape_vertex_layout& layout) override;
    /// Explicit readback: copies the GPU state into the CPU copy (RenderThread: at the next event).
    Result readback() override;
    Result supports(Feature feature) const override;
    /// Records the touches (and the view, in the cloth's frame when applied) for the next step's
    /// first interaction pass, which evaluates the drag on the GPU: no readback. At most
    /// kMaxDragCalls calls and kMaxTouches touches between two steps.
    Result drag(const drape_view& view, std::vector<drape_touch> touches) override;
    static constexpr uint32_t kMaxDragCalls = 4;
    /// Pick-and-hold on the GPU (gles_grab.cpp), no readback: the call records the pick (returns
    /// DRAPE_GRAB_ON_GPU), the next step finds the vertex in a pass and holds it (a pass at the
    /// start of each step while held); moves and releases apply at the next step too. The touch id
    /// holds its slot until released, whether or not the pick found a vertex.
    uint32_t grab(const drape_view& view, uint32_t touch_id, const float position[2], float pick_radius) override;
    bool grab_move(const drape_view& view, uint32_t touch_id, const float position[2]) override;
    void grab_release(uint32_t touch_id) override;
    /// Texture unit the grab pass samples the pick target on (gles_cloth.cpp: kSetupUnit, free
    /// while the passes run).
    static constexpr int kPickUnit = 7;
    /// Sleep checks in flight at most (steps whose result has not arrived yet); a step finding
    /// them all in flight issues none.
    static constexpr int kStillQueries = 3;
    /// IMPLICIT's automatic budget on GLES: kAutoIterationsImplicitGles cheap Jacobi passes per
    /// substep (its substeps: core substeps_for, also what drape_estimate_stability reports).
    uint32_t iterations_for() const override;
    /// GL work needs the caller's context: stepped on the thread that steps the world.
    bool steps_on_pool_thread() const override { return false; }

    /// RenderThread: run the recorded work (render thread, context current).
    void run_pending();
    /// RenderThread: device lost; keep the state on the CPU.
    void drop_gl();
    /// The context of its GL objects is gone: forget them (no GL call) and resume, on the next GL
    /// work in a new context, from the CPU copy (state at the last readback or CPU-side write).
    void forget_gl();

private:
    friend class GlesSelfCollide;  // its passes use the buffers, textures and pass helpers below
    struct Op {
        float dt = 0;                          // > 0: a step
        std::function<void(Cloth&)> edit;      // else an edit
        Access access = Access::NoState;
        bool readback = false;
    };
    struct Program {
        GLuint id = 0;
        GLint u[kMaxUniforms] = {};  ///< locations of kUniformNames (gles_cloth.cpp)
        GLint unit_x = -1, unit_aux = -1;  ///< texture units u_x and u_aux are set to now
        glm::vec4 value[kMaxUniforms] = {};  ///< what set_uniform last set (where `set` has its bit)
        uint32_t set = 0;
    };

    Result ensure_gl();
    Result sync_gpu();
    Result gpu_step(float dt);
    Result apply_edit(Access access, const std::function<void(Cloth&)>& fn);
    void bind_framebuffer();
    /// GL state every pass relies on, set once per step: framebuffer, rasterizer discard, all
    /// textures on their units (particle texture b on unit b).
    void begin_passes();
    Result pull();
    void push_state();
    /// Copies buffer b into its texture (on the GPU) if a pass wrote it since: called right
    /// before a pass that fetches b's records as neighbours.
    void refresh(int b);
    /// Makes p current with u_x / u_aux on the units of buffers x / aux (-1: not sampled).
    void use_program(Program& p, int x, int aux);
    /// Sets uniform u (u_chebyshev: v.xy, else a vec4) of the current program p, unless it holds v
    /// already or p lacks it.
    void set_uniform(Program& p, int u, const glm::vec4& v);
    /// Binds vao unless it is bound (since begin_passes).
    void bind_vertex_array(GLuint vao);
    /// Vertex array reading buffer x (own record: iterate records with their lambdas when `inputs`
    /// has kIterateRecords) and aux (state records), plus the inputs `inputs` names. Made once.
    GLuint vertex_array(int x, int aux, uint32_t inputs);
    /// One transform-feedback draw over the particles into buffer out (out2 < 0: one interleaved
    /// iterate record per particle) or out and out2 (one state record each, separate attribs),
    /// fetching buffers read_x and read_aux as textures (-1: none; refreshed after the outputs are
    /// bound, see bind_outputs). The outputs stay bound until the next pass binds its own.
    void draw(GLuint vao, int out, int out2, int read_x = -1, int read_aux = -1);
    /// Binds a pass's outputs (as draw says) in place of the last pass's, before anything reads the
    /// pass's inputs. A buffer bound for transform feedback must not be read or written through
    /// another binding meanwhile (OpenGL ES 3.0.6 section 2.15.2: "if a buffer object is
    /// simultaneously bound to a transform feedback buffer binding point and elsewhere in the GL,
    /// any writes to or reads from the buffer generate undefined values"), and the next pass reads
    /// what this one wrote: binding the next outputs first moves it off the binding in the same call
    /// that a separate unbind after each draw would cost. Index 1 is unbound when the pass has one
    /// output (its last buffer may be an input).
    void bind_outputs(int out, int out2);
    /// Binds `size` bytes of `buffer` from `offset` to transform-feedback index k (buffer 0:
    /// unbinds it), unless that is bound already: bind_outputs' two indices, a coarse pass's section.
    void bind_output(int k, GLuint buffer, GLintptr offset = 0, GLsizeiptr size = 0);
    /// Takes every buffer off the transform-feedback bindings: after the passes, before other GL
    /// work reads them.
    void unbind_outputs();
    /// Copies the rows the last coarse pass wrote into the coarse vector texture (after the next
    /// pass bound its outputs, see bind_outputs).
    void flush_coarse();
    /// Begin, draw `count` points, end, with the transform-feedback buffers (`written`,
    /// `written2`) already bound.
    void feedback_draw(GLuint vao, uint32_t count, GLuint written, GLuint written2 = 0);
    void drop_pass_objects();
    bool predict_has_dashpot() const;
    Result program(int pass, Program** out);
    Result output_program(Program** out);
    /// Uploads the DrapeSim block when a value changed (parameters, substep h) and binds it.
    void use_uniforms(float h);
    /// One transform-feedback pass over the particles: reads buffers x and aux, writes `out` (and
    /// `out2` >= 0 for the two-output passes: out gets v_x, out2 v_d). sub: u_substep; chebyshev:
    /// IMPLICIT's u_chebyshev (this iteration's weight, the Jacobi step's under-relaxation).
    void run_pass(Program& p, int x, int aux, int out, int out2, bool constraint, const glm::vec4& sub,
                  const glm::vec2& chebyshev = glm::vec2(1.0f));
    /// A RigidMove of the GPU state (owner transform, re-centring): x and d into the spare pair,
    /// which becomes x and d.
    void move_gpu_state(Program& p, const RigidMove& m);
    /// Cloth::move_state: the CPU copy now, the GPU state by the moves queued here before the next
    /// GL work that uses it (the next step or readback; GL may not be current now).
    void move_state(const RigidMove& m) override;
    Result run_gpu_moves();
    /// Sleep on the GPU, without waiting: counts the results of earlier steps' still checks that
    /// have arrived, oldest first (count_still); true when the cloth falls asleep now.
    bool poll_still();
    /// This step's still check (Cloth::interaction_end_step on the GPU): an occlusion query over
    /// points drawn only for particles that moved more than threshold * h over the last substep.
    void issue_still(Program& p, float dt);
    /// Pin targets and inverse masses on the GPU: kinematic particles, or a grab held on the GPU.
    bool kinematic_on_gpu() const { return !kinematic_.empty() || grabs_on_gpu_; }
    // ---- grabs (gles_grab.cpp) ----
    /// One grab slot as the GL work sees it (edits and steps, under mutex_).
    struct GpuGrab {
        bool pick_pending = false;     ///< pick at the next step (pick_view, pick_at, radius)
        bool held = false;             ///< the pick texel of `serial` is held (if it found a vertex)
        bool release_pending = false;  ///< the next step releases what pick `serial` held
        bool moved = false;            ///< a finger was given since the pick (view, at)
        uint32_t serial = 0;           ///< pick number (0: none yet); the pick texel records it
        drape_view pick_view{}, view{};
        glm::vec2 pick_at{0.0f}, at{0.0f};
        float radius = 0;
    };
    /// Before the step's programs are chosen: whether a grab is held on the GPU this step
    /// (grabs_on_gpu_), and the grab programs compiled (or the pick target made) if so.
    Result prepare_grabs();
    /// After begin_passes, before the step's kinematic start is taken: releases and holds (the
    /// grab pass), then the pending picks and a second grab pass that holds what they found.
    void run_grabs();
    /// One grab pass (cur -> spare, targets -> gl_.grab_targets); releases the pending releases
    /// if `release`.
    void grab_pass(bool release);
    /// Context or device gone: the picks went with it; inverse masses back to the CPU's.
    void drop_gpu_grabs();
    // Hooks into the passes' set-up for gles_grab.cpp (gles_cloth.cpp).
    Result link_grab_program(const std::string& defines, bool pick, GLuint* out);
    GLuint grab_vertex_array();  ///< cur, disp and the CPU's pin targets (kinematic inputs)
    /// The own 1x1 framebuffer, made on first use.
    GLuint own_framebuffer();
    /// kernels::tether: reads state buffers x and d, writes them to out_x and out_d.
    void run_tether(Program& p, int x, int d, int out_x, int out_d);
    /// IMPLICIT's coarse levels for substep h: cooked and uploaded when h, the springs or the masses
    /// changed since (before begin_passes: it uploads through the setup unit).
    Result prepare_coarse(float h);
    /// One V-cycle of the coarse correction from the iterate records in buffer `in` (substep start in
    /// `cur`) up to level 1's correction, which the next iteration (kProlong) adds. p: the restrict,
    /// down, solve and up programs.
    void run_coarse(Program* const p[4], int in, int cur);
    /// One pass over `count` nodes of a coarse level into the vector buffer at texel `write`
    /// (copied into its texture by the next pass, flush_coarse); u_coarse = offsets.
    void coarse_pass(Program& p, int x, int aux, const glm::vec4& offsets, uint32_t write, uint32_t count);
    bool has_tethers() const { return params_.max_stretch > 0 && !kinematic_.empty(); }
    /// CpuCloth::collide: drag share (first substep, `drag`: drag_views_, drag_touches_) and colliders (shape_data_,
    /// `shapes` of them) on x and d, written to out_x and out_d.
    void run_interact(Program& p, int x, int d, int out_x, int out_d, bool drag, uint32_t shapes);
    /// Substeps of a step of dt: Cloth::substeps_for, but IMPLICIT's automatic substeps are at most
    /// kMaxContactSubstepImplicitGles long while a collider that is not a plane may reach the cloth:
    /// its bounds over the step touch tethered_reach, or that is unknown.
    uint32_t gles_substeps_for(float dt) const;
    /// Adds to `reach` bounds that hold the whole cloth throughout this step, from the tethers and
    /// the pins' paths (the CPU sees no GPU position); false when it cannot tell.
    bool tethered_reach(Aabb& reach) const;
    /// Colliders of substep `sub` as CpuCloth::collide builds them (no broad phase: the
    /// CPU does not see the GPU positions) into shape_data_ (5 vec4 each); returns their count.
    uint32_t build_shapes(uint32_t sub, uint32_t substeps);
    Result write_output();
    void compute_cpu_stats();
    uint32_t record_vec4() const;
    const std::string& variant_defines(int pass) const;  ///< in defines_scratch_
    mutable std::string defines_scratch_;

    const Mode mode_;
    std::mutex mutex_;
    std::deque<Op> pending_;
    Result deferred_error_;

    GlObjects gl_;
    CoarseHierarchy coarse_;
    int coarse_flip_ = 0;  // the vector buffer the next coarse pass writes
    /// What coarse_ was cooked for (h 0: nothing uploaded in this context): substep, stiffness, damping.
    float coarse_key_[5] = {};
    std::map<std::string, Program> programs_;
    bool gl_ready_ = false;
    int g_[4] = {0, 1, 2, 3};  // GPU buffer roles: cur (x), disp (d), spare, spare2
    uint32_t record_ = 1;   // R of the allocated buffers
    uint32_t tex_rows_ = 0; // rows of the particle textures
    uint32_t tri_slots_ = 1;
    bool tex_stale_[4] = {true, true, true, true};  // buffer written since its texture was refreshed
    std::map<uint32_t, GLuint> vaos_;              // names in gl_.vaos by vertex_array's key
    GLuint used_program_ = 0;      // within begin_passes .. end of step
    int active_unit_ = -1;
    GLuint unpack_buffer_ = 0;     // bound to GL_PIXEL_UNPACK_BUFFER (a texture's source), 0: none
    struct Feedback {
        GLuint buffer = 0;  // 0: none
        GLintptr offset = 0;
        GLsizeiptr size = 0;
    } feedback_[2];  // bound to transform-feedback indices 0, 1 by the passes (bind_output)
    struct {
        GLuint buffer = 0;  // 0: nothing to copy
        uint32_t write = 0, count = 0;
    } coarse_written_;  // the last coarse pass's output, not yet in the texture (flush_coarse)
    GLuint bound_vao_ = 0;         // within begin_passes .. end of step, 0: unknown
    GLint max_vertex_uniform_vectors_ = 0;
    bool gpu_newer_ = false;       // CPU copy is stale
    // h_prev_ and fresh_ as they were when the CPU copy was last the state (before the GPU
    // stepped past it): what a cloth whose context was lost resumes with, together with x_ and d_.
    float cpu_h_prev_ = 1.0f;
    bool cpu_fresh_ = true;
    bool context_lost_ = false;    // forget_gl ran; no GL objects made since
    bool state_dirty_ = true;      // push CPU cur/disp
    bool targets_dirty_ = true;
    bool info_dirty_ = true;

    GLuint out_buffer_ = 0;
    drape_vertex_layout out_layout_{};
    std::vector<std::pair<int, int>> keeps_;  // (first word, words) of passthrough chunks
    // What the GPU holds of the tables an edit may change: uploaded again only when they differ.
    std::vector<uint32_t> table_scratch_;
    std::vector<uint32_t> info_uploaded_;     // per particle texels of gl_.info_tex
    std::vector<uint32_t> tethers_uploaded_;  // (anchor, length bits) per particle in gl_.tethers
    std::vector<glm::vec3> targets_uploaded_; // kinematic targets in gl_.targets
    SimUniforms uniforms_{};          // DrapeSim as last uploaded
    bool uniforms_uploaded_ = false;  // uniforms_ is in gl_.uniforms
    uint32_t shape_capacity_ = 0;  // DRAPE_SHAPES of the interaction program being asked for
    bool drag_variant_ = false;    // DRAPE_DRAG of the interaction program being asked for
    // Where the kinematic particles start the next step (tethered_reach): which, and where.
    std::vector<uint32_t> anchors_of_;
    std::vector<glm::vec3> anchors_from_;
    template <class At>
    void record_anchors(const At& at) {
        anchors_of_ = kinematic_;
        anchors_from_.resize(kinematic_.size());
        for (size_t k = 0; k < kinematic_.size(); ++k) anchors_from_[k] = at(kinematic_[k]);
    }
    // Per anchor its farthest tether, and whether every particle has one (tethered_reach), from the
    // tethers as refresh_backend last saw them.
    mutable std::vector<float> anchor_reach_;
    mutable bool all_tethered_ = false, reach_stale_ = true;
    void refresh_backend() override { reach_stale_ = true; }
    std::vector<float> shape_data_;
    struct StillQuery {
        float dt = 0;        // of the step it checked
        uint32_t wakes = 0;  // ix_.wakes when issued: stale after a wake
    };
    StillQuery still_[kStillQueries];  // ring over gl_.queries: still_first_, still_count_ in flight
    int still_first_ = 0, still_count_ = 0;
    std::vector<RigidMove> gpu_moves_;  // owner moves the GPU state has not had yet (in order)
    GpuGrab gpu_grabs_[kMaxGrabs];      // per slot; Grab::particle on this backend is the slot
    bool grabs_on_gpu_ = false;         // this step holds a grab on the GPU: targets from gl_.grab_targets
    uint32_t grab_serial_ = 0;          // picks so far
    GLuint grab_program_ = 0, pick_program_ = 0;
    GLint grab_u_ = -1, pick_u_ = -1;   // locations of u_grab, u_pick
    bool pick_target_cleared_ = false;  // the pick target's colour holds serial 0 or real picks
    std::vector<glm::vec4> grab_uniforms_, grab_uniforms_set_;  // u_grab to set, and as set
    // Drag of the calls since the last step, as the shader's u_drag_views / u_touches (records in
    // shaders/layout.h); consumed by the next step. The counts as recorded by drag() on
    // the calling thread (reset when a step is recorded) bound them.
    std::vector<glm::vec4> drag_views_, drag_touches_;
    uint32_t drag_calls_recorded_ = 0, drag_touches_recorded_ = 0;
};

}  // namespace drape::gles
