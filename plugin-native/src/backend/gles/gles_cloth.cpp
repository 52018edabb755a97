#include "backend/gles/gles_cloth.h"

#include <EGL/egl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <optional>
#include <set>

#include <glm/geometric.hpp>

#include "backend/gles/shaders.h"  // generated from shaders/*.glsl
#include "backend/gles/sim_uniforms.h"  // generated from tools/abi/abi.py
#include "core/drag.h"
#include "core/params.h"
#include "shaders/layout.h"

namespace drape::gles {
namespace {

/// XPBD lambdas ride in the record as vec4s, as many as sim.vert.glsl declares (layout.h).
constexpr uint32_t kMaxLambdaVec4 = DRAPE_MAX_LAMBDA_VEC4;

enum Pass { kMassSpring = 0, kPredict = 1, kConstraint = 2, kCommit = 3, kTether = 4, kInteract = 5, kMove = 6, kStill = 7,
            kCoarseRestrict = 8, kCoarseDown = 9, kCoarseSolve = 10, kCoarseUp = 11, kProlong = 12, kCommitProlong = 13 };
// kCommit: last iteration; kProlong, kCommitProlong: IMPLICIT's iteration that adds the coarse correction.
bool is_coarse(int pass) { return pass >= kCoarseRestrict && pass <= kCoarseUp; }
// Uniforms outside the DrapeSim block (sim_uniforms.h): per substep, per collider set, per rigid
// move. u_x / u_aux: the texture units of the pass's input buffers (see kNbrUnit).
enum Uniform {
    uSubstep, uShapes, uShapeCount, uDragViews, uTouches, uTouchCount, uMoveRot, uMovePivot, uMoveTo,
    uMoveKeepVelocity, uStillLimit2, uX, uAux, uChebyshev, uCoarse, kUniformCount
};
const char* const kUniformNames[kUniformCount] = {
    "u_substep", "u_shapes",     "u_shape_count", "u_drag_views",         "u_touches", "u_touch_count",
    "u_move_rot", "u_move_pivot", "u_move_to",     "u_move_keep_velocity", "u_still_limit2", "u_x", "u_aux",
    "u_chebyshev", "u_coarse"};
static_assert(kUniformCount <= GlesCloth::kMaxUniforms, "GlesCloth::Program::u holds every location");
// Attribute locations (bound before linking).
enum Attrib {
    aX = 0, aAux = 1, aKStart = 2, aKTarget = 3, aLambda0 = 4, aTetherAnchor = 12, aTetherLength = 13,
    aParticle = 0, aKeep0 = 1
};
constexpr int kMaxAttribs = 16;
// IMPLICIT's iterate record: displacement iterate, previous iterate (a_prev), target (a_target).
constexpr uint32_t kImplicitRecordVec4 = 3;
// IMPLICIT on GLES (sim.vert.glsl DRAPE_PASS_IMPLICIT): `iterations` block-Jacobi steps under-relaxed
// by gamma, accelerated by Chebyshev for the interval [-rho, rho] (Wang 2015). Neither changes the
// fixed point (the exact equilibrium), only how fast it is reached, and whether time stepping on
// an unfinished solve is stable. The block-Jacobi matrix D^-1 H has its eigenvalues below 2
// (sim.vert.glsl jacobi_step) and above 0 unless compressed springs outweigh the mass term, so the damped step's lie in (1 - 2 gamma, 1) and
// gamma = (1 + rho) / 2 puts them in (-rho, 1), where the iteration leaves an error component a share P(lambda) of its
// start, |P| <= 1/T_K(1/rho) on [-rho, rho]. A substep starts from the inertia d_prev, so a stiff
// mode (implicit Euler's answer ~ -x) continues as x' = p e, e' = -x + 2 p e (e = x + d): stable
// for p > -1/3, but at p = -1/4 it decays only by 0.81 per substep with alternating sign, and in
// motion the nonlinear springs kept it going: a cloth stayed in a stretched oscillation (GlesImplicit.
// SwungAndJerkedCurtainDoesNotStayStretched; a stiff cloth dropped from two corners, 33^2, 1e5 N/m:
// max strain 1.25 at the end of 3 s). At p >= -0.1 it decays by 0.43 per substep (the dropped
// cloth: 0.012). rho is therefore the largest whose Chebyshev polynomial stays above
// -kImplicitChebyshevFloor: T_K(1/rho) = 1 / floor (8 iterations: rho = 0.935; a fixed rho = 0.95
// blew up with fewer than 6 iterations per substep).
// Block Jacobi alone moves the cloth's smooth modes (stretch carried from the pins across the cloth)
// by D^-1 A ~ (m/h^2) / (sum of k) per pass, ~1e-3 at 257^2: the curtain swung about its rest state
// for seconds (65^2: 27 % off after 2 s; 257^2: 12 % after 10 s). So each substep runs one V-cycle of
// the coarse levels after its first iteration (run_coarse, gles_coarse.h), and the second iteration
// (kProlong) adds the correction to the iterate and the previous iterate (so the Chebyshev
// recurrence goes on from the corrected pair) before its Jacobi step: a multiplicative coarse
// correction, which changes no fixed point either. Measured: 65^2 curtain within 1e-4 after 2 s;
// 33^2 drop from two corners 0.022 m rms from the CPU's answer (0.12 without, XPBD 0.14).
// Stability with the correction: the Chebyshev bound above covers the Jacobi steps only. The coarse
// matrices are Galerkin products P^T A P of A (gles_coarse.h), which charges each spring k + kd/h
// across as well as along; the Hessian H charges k (1 - L/l) < k across, so H <= A, and with an
// exact coarse solve the correction's error propagation I - P (P^T A P)^-1 P^T H is H-symmetric
// with eigenvalues in [0, 1] wherever H is positive definite: it falls short, never overshoots. The
// V-cycle only approximates that solve: the coarsest level exactly, the others by one Jacobi
// smoothing of weight 2/3, non-expansive in the level's A norm (a Galerkin level of an M-matrix
// has D^-1 A <= 2). These bounds hold in different norms, so nothing here proves their product
// stable: that rests on the tests (GlesImplicit's stress at 1e5 N/m with 1/10 s steps and a 1 x 1
// budget, the swung and jerked curtain) on llvmpipe, softpipe and zink.
constexpr double kImplicitChebyshevFloor = 0.1;
struct Chebyshev {
    float rho, gamma;
};
Chebyshev implicit_chebyshev(uint32_t iterations) {
    const double rho = 1.0 / std::cosh(std::acosh(1.0 / kImplicitChebyshevFloor) / double(iterations));
    return {float(rho), float(0.5 * (1.0 + rho))};
}
// Texture units, bound once per step (begin_passes): particle texture b on unit b, so a pass picks
// its inputs by pointing u_x / u_aux at a buffer's unit; then the tables, whose samplers are set
// once when a program is linked. kSetupUnit: creating and uploading textures outside the passes.
// Units 0 .. kSetupUnit are saved and restored for the caller.
constexpr int kNbrUnit = 4, kInfoUnit = 5, kTrisUnit = 6, kSetupUnit = 7;
static_assert(kSelfRestUnit == kSetupUnit + 1, "self-collision's units follow (gles_self_collide.h)");
// IMPLICIT's coarse table and vectors: on the units of the output pass's triangles and of the set-up,
// which no pass of the substep loop samples (gpu_step binds them after the grabs, the triangles back
// after the loop).
constexpr int kCoarseTableUnit = kTrisUnit, kCoarseVecUnit = kSetupUnit;
static_assert(kCoarseVecUnit == kCoarseTableUnit + 1, "gpu_step binds them as a pair");
constexpr struct {
    const char* name;
    GLint unit;
} kSamplers[] = {{"u_nbr", kNbrUnit},         {"u_info", kInfoUnit},
                 {"u_tris", kTrisUnit},       {"u_pick_target", kSetupUnit},
                 {"u_coarse_table", kCoarseTableUnit}, {"u_coarse_vec", kCoarseVecUnit}};
static_assert(GlesCloth::kPickUnit == kSetupUnit, "the grab pass binds the pick target on the setup unit");
// Inputs of a pass beyond x and aux (GlesCloth::vertex_array); bits above the two buffer indices.
enum PassInputs : uint32_t {
    kIterateRecords = 1u << 4,   // x holds displacement-iterate records (+ XPBD lambdas)
    kKinematicInputs = 1u << 5,  // a_kstart, a_ktarget
    kTetherInputs = 1u << 6,     // a_tether_anchor, a_tether_length
    kGrabTargets = 1u << 7,      // a_ktarget from gl_.grab_targets (a grab is held), not gl_.targets
};

std::atomic<bool> g_render_device{false};

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}
std::set<GlesCloth*>& registry() {
    static std::set<GlesCloth*> s;
    return s;
}
// GL objects whose cloth died without their context current: freed when it is next current.
struct Grave {
    GlObjects objects;
};
std::mutex& grave_mutex() {
    static std::mutex m;
    return m;
}
std::vector<Grave>& graveyard() {
    static std::vector<Grave> g;
    return g;
}

void delete_now(GlObjects& o) {
    glDeleteBuffers(4, o.buffers);
    glDeleteTextures(4, o.textures);
    GLuint tex[3] = {o.nbr_tex, o.info_tex, o.tri_tex};
    glDeleteTextures(3, tex);
    GLuint bufs[8] = {o.kstart, o.targets, o.vertex_to_particle, o.scratch, o.tethers, o.uniforms, o.staging, o.grab_targets};
    glDeleteBuffers(8, bufs);
    glDeleteTextures(1, &o.pick_tex);
    GLuint coarse_tex[2] = {o.coarse_table, o.coarse_vec_tex};
    glDeleteTextures(2, coarse_tex);
    glDeleteBuffers(2, o.coarse_vec);
    if (o.coarse_vao) o.vaos.push_back(o.coarse_vao);
    glDeleteRenderbuffers(1, &o.pick_depth);
    if (o.pick_fbo) glDeleteFramebuffers(1, &o.pick_fbo);
    o.vaos.push_back(o.out_vao);
    glDeleteVertexArrays(GLsizei(o.vaos.size()), o.vaos.data());
    if (o.queries[0]) glDeleteQueries(3, o.queries);
    if (o.fbo) glDeleteFramebuffers(1, &o.fbo);
    if (o.rbo) glDeleteRenderbuffers(1, &o.rbo);
    for (GLuint p : o.programs) glDeleteProgram(p);
    delete_self_collide_gl(o.self);
    o = GlObjects{};
}

void free_graves() {
    const EGLContext current = eglGetCurrentContext();
    if (current == EGL_NO_CONTEXT) return;
    std::lock_guard<std::mutex> lock(grave_mutex());
    auto& g = graveyard();
    for (size_t k = 0; k < g.size();) {
        if (g[k].objects.context == current) {
            delete_now(g[k].objects);
            g.erase(g.begin() + std::ptrdiff_t(k));
        } else {
            ++k;
        }
    }
}

void drain_gl_errors() {
    for (int k = 0; k < 32 && glGetError() != GL_NO_ERROR; ++k) {
    }
}

}  // namespace

Result gl_error(const char* where) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return {};
    drain_gl_errors();
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", unsigned(e));
    return {DRAPE_ERROR_GL, std::string("OpenGL ES error ") + code + " in " + where};
}

namespace {

/// Saves the GL state a step touches and restores it (Unity caches GL state).
struct StateGuard {
    GLint program, vao, array_buffer, unpack, copy_read, copy_write, tf_buffer, draw_fbo, active_tex;
    GLint uniform_buffer, block_buffer, block_start, block_size;  // generic and DrapeSim's indexed binding
    GLint viewport[4];  // the sleep check draws into the cloth's 1x1 target
    GLboolean scissor;
    GLint tex[kSetupUnit + 1];
    GLboolean discard;
    StateGuard() {
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer);
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack);
        glGetIntegerv(GL_COPY_READ_BUFFER_BINDING, &copy_read);
        glGetIntegerv(GL_COPY_WRITE_BUFFER_BINDING, &copy_write);
        glGetIntegerv(GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, &tf_buffer);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active_tex);
        glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer);
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kSimUniformsBinding, &block_buffer);
        glGetIntegeri_v(GL_UNIFORM_BUFFER_START, kSimUniformsBinding, &block_start);
        glGetIntegeri_v(GL_UNIFORM_BUFFER_SIZE, kSimUniformsBinding, &block_size);
        for (int u = 0; u <= kSetupUnit; ++u) {
            glActiveTexture(GL_TEXTURE0 + GLenum(u));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex[u]);
        }
        discard = glIsEnabled(GL_RASTERIZER_DISCARD);
        glGetIntegerv(GL_VIEWPORT, viewport);
        scissor = glIsEnabled(GL_SCISSOR_TEST);
    }
    ~StateGuard() {
        for (int u = 0; u <= kSetupUnit; ++u) {
            glActiveTexture(GL_TEXTURE0 + GLenum(u));
            glBindTexture(GL_TEXTURE_2D, GLuint(tex[u]));
        }
        glActiveTexture(GLenum(active_tex));
        if (discard) glEnable(GL_RASTERIZER_DISCARD); else glDisable(GL_RASTERIZER_DISCARD);
        glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
        if (scissor) glEnable(GL_SCISSOR_TEST);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fbo));
        if (block_size > 0)
            glBindBufferRange(GL_UNIFORM_BUFFER, kSimUniformsBinding, GLuint(block_buffer), block_start, block_size);
        else
            glBindBufferBase(GL_UNIFORM_BUFFER, kSimUniformsBinding, GLuint(block_buffer));
        glBindBuffer(GL_UNIFORM_BUFFER, GLuint(uniform_buffer));
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, GLuint(tf_buffer));
        glBindBuffer(GL_COPY_WRITE_BUFFER, GLuint(copy_write));
        glBindBuffer(GL_COPY_READ_BUFFER, GLuint(copy_read));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack));
        glBindVertexArray(GLuint(vao));
        glBindBuffer(GL_ARRAY_BUFFER, GLuint(array_buffer));
        glUseProgram(GLuint(program));
    }
};

Result compile(GLenum stage, const std::string& source, const char* name, GLuint* out) {
    GLuint s = glCreateShader(stage);
    const char* src = source.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        return {DRAPE_ERROR_GL, std::string("compiling ") + name + " failed: " + log};
    }
    *out = s;
    return {};
}

/// Inserts the variant's #defines right after the #version line.
std::string with_defines(const char* source, const std::string& defines) {
    std::string s(source);
    const size_t eol = s.find('\n');
    return s.substr(0, eol + 1) + defines + s.substr(eol + 1);
}

/// The driver's layout of the uniform block must be the generated one (std140 fixes it; a driver
/// that disagreed would feed every pass wrong parameters without an error).
Result check_block_layout(GLuint program, GLuint block) {
    GLint size = 0;
    glGetActiveUniformBlockiv(program, block, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    std::string wrong;
    if (size != GLint(sizeof(SimUniforms)))
        wrong = " size " + std::to_string(size) + " (expected " + std::to_string(sizeof(SimUniforms)) + ")";
    for (const auto& m : kSimUniformsMembers) {
        GLuint index = GL_INVALID_INDEX;
        glGetUniformIndices(program, 1, &m.glsl, &index);
        if (index == GL_INVALID_INDEX) continue;  // unused by this program
        GLint offset = -1;
        glGetActiveUniformsiv(program, 1, &index, GL_UNIFORM_OFFSET, &offset);
        if (offset != GLint(m.offset))
            wrong += std::string(" ") + m.glsl + " at " + std::to_string(offset) + " (expected " + std::to_string(m.offset) + ")";
    }
    if (wrong.empty()) return {};
    return {DRAPE_ERROR_GL, std::string("uniform block ") + kSimUniformsName +
                                " is laid out differently by this driver than in sim_uniforms.h:" + wrong};
}

}  // namespace

Result link(const std::string& vs_source, const char* name, const std::vector<std::string>& varyings,
            GLenum buffer_mode, const std::vector<std::pair<GLuint, const char*>>& attribs, GLuint* out,
            const char* fs_source, const char* fs_name) {
    GLuint vs = 0, fs = 0;
    if (Result r = compile(GL_VERTEX_SHADER, vs_source, name, &vs); !r.ok()) return r;
    if (Result r = compile(GL_FRAGMENT_SHADER, fs_source ? fs_source : shaders::discard_frag,
                           fs_name ? fs_name : "discard.frag.glsl", &fs);
        !r.ok()) {
        glDeleteShader(vs);
        return r;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    for (auto& a : attribs) glBindAttribLocation(p, a.first, a.second);
    std::vector<const char*> names;
    for (auto& v : varyings) names.push_back(v.c_str());
    glTransformFeedbackVaryings(p, GLsizei(names.size()), names.data(), buffer_mode);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(p, sizeof log, nullptr, log);
        glDeleteProgram(p);
        return {DRAPE_ERROR_GL, std::string("linking ") + name + " failed: " + log};
    }
    // What never changes for this program: sampler units and the uniform block's binding point.
    glUseProgram(p);
    for (const auto& s : kSamplers)
        if (const GLint at = glGetUniformLocation(p, s.name); at >= 0) glUniform1i(at, s.unit);
    if (const GLuint block = glGetUniformBlockIndex(p, kSimUniformsName); block != GL_INVALID_INDEX) {
        glUniformBlockBinding(p, block, kSimUniformsBinding);
        if (Result r = check_block_layout(p, block); !r.ok()) {
            glDeleteProgram(p);
            return r;
        }
    }
    *out = p;
    return {};
}

namespace {

/// Uniform vectors of the simulation's own (u_substep, the DrapeSim block's share), generously;
/// colliders add 5 each.
constexpr GLint kOwnUniformVectors = 64;
/// A touch drag's uniforms (sim.vert.glsl DRAPE_DRAG; records in layout.h).
constexpr uint32_t kDragUniformVectors = GlesCloth::kMaxDragCalls * DRAPE_DRAG_VIEW_VEC4 + kMaxTouches * DRAPE_TOUCH_VEC4;

/// The GL ES limits the backend relies on and what it needs of each, all within OpenGL ES 3.0's
/// guaranteed minimums (after //). A device below one is refused when a cloth starts.
struct Limit {
    GLenum name;
    const char* label;
    GLint need;
};
const Limit kLimits[] = {
    {GL_MAX_TEXTURE_SIZE, "GL_MAX_TEXTURE_SIZE", GLint(kTexWidth)},  // 2048: rows of kTexWidth texels
    {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", 4},  // 16: u_x, u_aux, u_nbr, u_info
    {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", kSetupUnit + 1},  // 32: units in use
    {GL_MAX_VERTEX_ATTRIBS, "GL_MAX_VERTEX_ATTRIBS", kMaxAttribs},  // 16: locations up to aTetherLength; 1 + 15 kept chunks
    {GL_MAX_VERTEX_OUTPUT_COMPONENTS, "GL_MAX_VERTEX_OUTPUT_COMPONENTS", 64},  // 64: output records of 64 words
    {GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS, "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS", 2},  // 4: v_x, v_d
    {GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_COMPONENTS, "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_COMPONENTS", 4},  // 4: a vec4
    {GL_MAX_TRANSFORM_FEEDBACK_INTERLEAVED_COMPONENTS, "GL_MAX_TRANSFORM_FEEDBACK_INTERLEAVED_COMPONENTS",
     64},  // 64: output records up to 256 bytes
    {GL_MAX_VERTEX_UNIFORM_VECTORS, "GL_MAX_VERTEX_UNIFORM_VECTORS", kOwnUniformVectors + 4 * DRAPE_COLLIDER_VEC4},  // 256: 4 colliders
    {GL_MAX_VERTEX_UNIFORM_BLOCKS, "GL_MAX_VERTEX_UNIFORM_BLOCKS", 1},  // 12: DrapeSim
    {GL_MAX_UNIFORM_BLOCK_SIZE, "GL_MAX_UNIFORM_BLOCK_SIZE", GLint(sizeof(SimUniforms))},  // 16384
};

Result check_limits() {
    for (const Limit& l : kLimits) {
        GLint have = 0;
        glGetIntegerv(l.name, &have);
        if (have < l.need)
            return {DRAPE_ERROR_BACKEND_UNAVAILABLE, std::string("this OpenGL ES device offers ") + l.label + " = " +
                                                         std::to_string(have) + ", the GLES backend needs at least " +
                                                         std::to_string(l.need) + " (OpenGL ES 3.0 guarantees that)"};
    }
    // Every vertex-stage value is highp (the shaders say so); the CPU twin computes in float.
    GLint range[2] = {}, precision = 0;
    glGetShaderPrecisionFormat(GL_VERTEX_SHADER, GL_HIGH_FLOAT, range, &precision);
    if (precision < 23)
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "this OpenGL ES device's vertex-stage highp float has " +
                                                     std::to_string(precision) +
                                                     " bits of precision, the GLES backend needs 23 (IEEE float, as "
                                                     "OpenGL ES 3.0 guarantees)"};
    return {};
}

}  // namespace

uint32_t rows_for(uint64_t texels) { return uint32_t(std::max<uint64_t>(1, (texels + kTexWidth - 1) / kTexWidth)); }

GLuint make_texture(GLenum internal, uint32_t rows) {
    GLuint t = 0;
    glGenTextures(1, &t);
    glActiveTexture(GL_TEXTURE0 + kSetupUnit);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal, kTexWidth, GLsizei(rows));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

/// Uploads RGBA32UI texels (padded to whole rows here) through the pixel-unpack buffer `staging`:
/// client memory enters GL only through glBufferData / glBufferSubData, which is how the GL call
/// budget test tells uploads from the GPU-side texture refreshes (glTexSubImage2D from a buffer).
void upload_uint_texture(GLuint t, GLuint staging, uint32_t rows, std::vector<uint32_t>& texels) {
    texels.resize(size_t(kTexWidth) * rows * 4, 0u);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, staging);
    glBufferData(GL_PIXEL_UNPACK_BUFFER, GLsizeiptr(texels.size() * 4), texels.data(), GL_STREAM_DRAW);
    glActiveTexture(GL_TEXTURE0 + kSetupUnit);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kTexWidth, GLsizei(rows), GL_RGBA_INTEGER, GL_UNSIGNED_INT, nullptr);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

bool GlObjects::empty() const {
    return !buffers[0] && !textures[0] && !nbr_tex && !staging && programs.empty();
}

bool context_current(std::string* why) {
    if (eglGetCurrentContext() == EGL_NO_CONTEXT) {
        if (why) *why = "no EGL context is current on this thread";
        return false;
    }
    const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (!v || std::strncmp(v, "OpenGL ES ", 10) != 0 || v[10] < '3' || v[10] > '9') {
        if (why) *why = std::string("the current context is not OpenGL ES 3.x (GL_VERSION: ") + (v ? v : "none") + ")";
        return false;
    }
    return true;
}

void set_render_thread_device(bool ready) { g_render_device = ready; }
bool render_thread_device_ready() { return g_render_device; }

void render_thread_tick() {
    if (!context_current()) return;
    free_graves();
    std::lock_guard<std::mutex> lock(registry_mutex());
    for (GlesCloth* c : registry())
        if (c->mode() == GlesCloth::Mode::RenderThread) c->run_pending();
}

void render_thread_shutdown() {
    {
        std::lock_guard<std::mutex> lock(registry_mutex());
        for (GlesCloth* c : registry())
            if (c->mode() == GlesCloth::Mode::RenderThread) c->drop_gl();
    }
    free_graves();
}

void context_lost() {
    {
        std::lock_guard<std::mutex> lock(registry_mutex());
        for (GlesCloth* c : registry()) c->forget_gl();
    }
    // Their names may be reused by the next context (even its EGLContext handle may be): never
    // delete them there.
    std::lock_guard<std::mutex> lock(grave_mutex());
    graveyard().clear();
}

void release_gl(GlObjects& objects) {
    if (objects.empty()) return;
    if (eglGetCurrentContext() == objects.context) {
        delete_now(objects);
        return;
    }
    // Not their context: freed when it is next current on a thread that calls into Drape.
    std::lock_guard<std::mutex> lock(grave_mutex());
    graveyard().push_back({objects});
    objects = GlObjects{};
}

GlesCloth::GlesCloth(World& world, std::shared_ptr<const Description> description, Mode mode)
    : Cloth(world, DRAPE_BACKEND_GLES, std::move(description)), mode_(mode) {
    // Incident triangles per particle, in triangle order (the order Cloth::read_cpu_copy sums them).
    std::vector<uint32_t> incident(topo_.particle_count, 0);
    for (uint32_t p : topo_.triangles) ++incident[p];
    for (uint32_t c : incident) tri_slots_ = std::max(tri_slots_, c);
    // Every cloth (both modes) is told when its context is lost; render events run RenderThread ones.
    std::lock_guard<std::mutex> lock(registry_mutex());
    registry().insert(this);
}

GlesCloth::~GlesCloth() {
    {
        std::lock_guard<std::mutex> lock(registry_mutex());
        registry().erase(this);
    }
    // Deleted now where the cloth's context is current (immediate mode); otherwise (Unity main
    // thread) on the render thread's next event.
    release_gl(gl_);
}

uint32_t GlesCloth::record_vec4() const {
    if (params_.model == DRAPE_MODEL_IMPLICIT) return kImplicitRecordVec4;
    return params_.model == DRAPE_MODEL_XPBD ? 1 + (topo_.nbr.slots + 3) / 4 : 1;
}

Result GlesCloth::init_gl() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (Result r = ensure_gl(); !r.ok()) return r;
    StateGuard guard;
    if (Result r = sync_gpu(); !r.ok()) return r;
    Program* p = nullptr;
    const int first = params_.model == DRAPE_MODEL_MASS_SPRING ? kMassSpring : kPredict;
    if (Result r = program(first, &p); !r.ok()) return r;
    if (first == kPredict)
        for (int pass : {kConstraint, kCommit})
            if (Result r = program(pass, &p); !r.ok()) return r;
    if (has_tethers())
        if (Result r = program(kTether, &p); !r.ok()) return r;
    return gl_error("creating the GLES cloth");
}

Result GlesCloth::ensure_gl() {
    if (gl_ready_) return {};
    std::string why;
    if (!context_current(&why))
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE,
                context_lost_ ? "GLES cloth: its GL context was lost and no new one is current (" + why +
                                    "); it resumes from its CPU copy once one is"
                              : "GLES cloth: " + why};
    if (Result r = check_limits(); !r.ok()) return r;
    free_graves();
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    const uint32_t n = topo_.particle_count;
    const uint64_t biggest = std::max<uint64_t>({uint64_t(n) * (1 + kMaxLambdaVec4), uint64_t(n) * topo_.nbr.slots,
                                                 uint64_t(n) * tri_slots_});
    if (rows_for(biggest) > uint32_t(max_size))
        return {DRAPE_ERROR_INVALID_ARGUMENT, "cloth too large for GLES textures (" + std::to_string(biggest) +
                                                  " texels, limit " + std::to_string(uint64_t(max_size) * kTexWidth) + ")"};
    glGetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &max_vertex_uniform_vectors_);
    drain_gl_errors();
    gl_.context = eglGetCurrentContext();
    glGenBuffers(1, &gl_.staging);
    glGenBuffers(1, &gl_.targets);
    glGenBuffers(1, &gl_.vertex_to_particle);
    glGenBuffers(1, &gl_.kstart);
    glGenBuffers(1, &gl_.tethers);
    glGenBuffers(1, &gl_.uniforms);
    glBindBuffer(GL_UNIFORM_BUFFER, gl_.uniforms);
    glBufferData(GL_UNIFORM_BUFFER, sizeof(SimUniforms), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    uniforms_uploaded_ = false;
    info_uploaded_.clear();
    tethers_uploaded_.clear();
    targets_uploaded_.clear();
    // Static tables.
    const NeighbourTable& nb = topo_.nbr;
    const uint32_t nbr_rows = rows_for(uint64_t(n) * nb.slots);
    gl_.nbr_tex = make_texture(GL_RGBA32UI, nbr_rows);
    std::vector<uint32_t> texels(size_t(n) * nb.slots * 4);
    for (size_t s = 0; s < size_t(n) * nb.slots; ++s) {
        uint32_t rest_bits;
        std::memcpy(&rest_bits, &nb.rest[s], 4);
        texels[4 * s] = nb.index[s];
        texels[4 * s + 1] = rest_bits;
        texels[4 * s + 2] = nb.group[s];
    }
    upload_uint_texture(gl_.nbr_tex, gl_.staging, nbr_rows, texels);
    const uint32_t tri_rows = rows_for(uint64_t(n) * tri_slots_);
    gl_.tri_tex = make_texture(GL_RGBA32UI, tri_rows);
    texels.assign(size_t(n) * tri_slots_ * 4, 0u);
    std::vector<uint32_t> fill(n, 0);
    const auto& tri = topo_.triangles;
    for (size_t k = 0; k + 2 < tri.size(); k += 3)
        for (int c = 0; c < 3; ++c) {
            const uint32_t p = tri[k + c];
            uint32_t* t = &texels[(size_t(p) * tri_slots_ + fill[p]++) * 4];
            t[0] = tri[k];
            t[1] = tri[k + 1];
            t[2] = tri[k + 2];
        }
    upload_uint_texture(gl_.tri_tex, gl_.staging, tri_rows, texels);
    gl_.info_tex = make_texture(GL_RGBA32UI, rows_for(n));
    glBindBuffer(GL_ARRAY_BUFFER, gl_.vertex_to_particle);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(topo_.vertex_to_particle.size() * 4), topo_.vertex_to_particle.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    record_ = 0;  // particle buffers are (re)made by sync_gpu for the model's record size
    gl_ready_ = true;
    context_lost_ = false;
    state_dirty_ = targets_dirty_ = info_dirty_ = true;
    return gl_error("creating GLES objects");
}

Result GlesCloth::sync_gpu() {
    const uint32_t n = topo_.particle_count;
    const uint32_t want = record_vec4();
    if (want != record_) {
        if (gpu_newer_ && record_ != 0)
            if (Result r = pull(); !r.ok()) return r;
        drop_pass_objects();  // they name the old buffers, with the old record stride
        glDeleteBuffers(4, gl_.buffers);
        glDeleteTextures(4, gl_.textures);
        record_ = want;
        // Every buffer can hold iterate records (R vec4s); state records use the first n vec4s.
        tex_rows_ = rows_for(uint64_t(n) * record_);
        const GLsizeiptr bytes = GLsizeiptr(tex_rows_) * kTexWidth * 16;
        glGenBuffers(4, gl_.buffers);
        for (int b = 0; b < 4; ++b) {
            glBindBuffer(GL_ARRAY_BUFFER, gl_.buffers[b]);
            glBufferData(GL_ARRAY_BUFFER, bytes, nullptr, GL_DYNAMIC_COPY);
            gl_.textures[b] = make_texture(GL_RGBA32F, tex_rows_);
        }
        glBindBuffer(GL_ARRAY_BUFFER, gl_.kstart);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(n) * sizeof(Particle)), nullptr, GL_DYNAMIC_COPY);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        state_dirty_ = true;
    }
    if (state_dirty_) push_state();
    // An edit marks targets and tables dirty; each is uploaded only if it really changed (Unity
    // pushes colliders every frame, which changes none of them).
    if (targets_dirty_) {
        if (kinematic_target_ != targets_uploaded_) {
            glBindBuffer(GL_ARRAY_BUFFER, gl_.targets);
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(glm::vec3)), kinematic_target_.data(), GL_DYNAMIC_DRAW);
            glBindBuffer(GL_ARRAY_BUFFER, 0);
            targets_uploaded_ = kinematic_target_;
        }
        targets_dirty_ = false;
    }
    if (info_dirty_) {
        std::vector<uint32_t>& texels = table_scratch_;  // kept: no allocation after the first edit
        texels.assign(size_t(n) * 4, 0u);
        for (uint32_t i = 0; i < n; ++i) {
            texels[4 * i] = topo_.nbr.count[i];
            texels[4 * i + 1] = active_count_[i];
            const float w = pinned_[i] ? 0.0f : base_inverse_mass_[i];  // what a grab's release restores
            std::memcpy(&texels[4 * i + 3], &w, 4);
        }
        for (uint32_t p : topo_.triangles) ++texels[4 * p + 2];  // incident triangles
        if (texels != info_uploaded_) {
            info_uploaded_ = texels;
            coarse_key_[0] = 0;  // masses or pins changed: the coarse levels are cooked again
            upload_uint_texture(gl_.info_tex, gl_.staging, rows_for(n), texels);
        }
        // Tethers change only with the set of kinematic particles or max_stretch.
        texels.resize(size_t(n) * 2);
        for (uint32_t i = 0; i < n; ++i) {
            texels[2 * i] = tether_anchor_[i];
            std::memcpy(&texels[2 * i + 1], &tether_length_[i], 4);
        }
        if (texels != tethers_uploaded_) {
            glBindBuffer(GL_ARRAY_BUFFER, gl_.tethers);
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(texels.size() * 4), texels.data(), GL_DYNAMIC_DRAW);
            glBindBuffer(GL_ARRAY_BUFFER, 0);
            tethers_uploaded_ = texels;
        }
        info_dirty_ = false;
    }
    return gl_error("uploading cloth state");
}

void GlesCloth::push_state() {
    // State records (positions x -> role cur, displacements d -> role disp) are one vec4 each.
    const uint32_t n = topo_.particle_count;
    const Particle* const sources[2] = {x_.data(), d_.data()};
    for (int k = 0; k < 2; ++k) {
        glBindBuffer(GL_ARRAY_BUFFER, gl_.buffers[g_[k]]);
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(n) * sizeof(Particle)), sources[k]);
        tex_stale_[g_[k]] = true;
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    state_dirty_ = false;
    gpu_newer_ = false;
}

void GlesCloth::refresh(int b) {
    if (!tex_stale_[b]) return;
    if (active_unit_ != b) {
        glActiveTexture(GL_TEXTURE0 + GLenum(b));  // texture b lives on unit b (begin_passes)
        active_unit_ = b;
    }
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, gl_.buffers[b]);
    unpack_buffer_ = gl_.buffers[b];
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kTexWidth, GLsizei(tex_rows_), GL_RGBA, GL_FLOAT, nullptr);
    tex_stale_[b] = false;
}

void GlesCloth::begin_passes() {
    bind_framebuffer();
    glEnable(GL_RASTERIZER_DISCARD);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const GLuint units[kTrisUnit + 1] = {gl_.textures[0], gl_.textures[1], gl_.textures[2], gl_.textures[3],
                                         gl_.nbr_tex,     gl_.info_tex,    gl_.tri_tex};
    for (int u = 0; u <= kTrisUnit; ++u) {
        glActiveTexture(GL_TEXTURE0 + GLenum(u));
        glBindTexture(GL_TEXTURE_2D, units[u]);
    }
    active_unit_ = kTrisUnit;
    used_program_ = 0;
    bound_vao_ = 0;
    unpack_buffer_ = 0;
    feedback_[0] = feedback_[1] = {};  // every pass sequence ends with unbind_outputs
    coarse_written_.buffer = 0;       // and the coarse rows are copied before it ends
}

void GlesCloth::use_program(Program& p, int x, int aux) {
    if (used_program_ != p.id) {
        glUseProgram(p.id);
        used_program_ = p.id;
    }
    if (x >= 0 && p.unit_x != x) {
        glUniform1i(p.u[uX], x);
        p.unit_x = x;
    }
    if (aux >= 0 && p.unit_aux != aux) {
        glUniform1i(p.u[uAux], aux);
        p.unit_aux = aux;
    }
}

void GlesCloth::set_uniform(Program& p, int u, const glm::vec4& v) {
    if (p.u[u] < 0 || ((p.set >> u & 1u) && p.value[u] == v)) return;
    if (u == uChebyshev)  // the one vec2
        glUniform2f(p.u[u], v.x, v.y);
    else
        glUniform4fv(p.u[u], 1, &v.x);
    p.value[u] = v;
    p.set |= 1u << u;
}

GLuint GlesCloth::vertex_array(int x, int aux, uint32_t inputs) {
    const uint32_t key = uint32_t(x) | uint32_t(aux) << 2 | inputs;
    if (auto it = vaos_.find(key); it != vaos_.end()) return it->second;
    constexpr GLsizei kState = GLsizei(sizeof(Particle));  // x, d, substep start, kstart
    const GLsizei stride = inputs & kIterateRecords ? GLsizei(record_ * sizeof(Particle)) : kState;
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    bound_vao_ = vao;
    glBindBuffer(GL_ARRAY_BUFFER, gl_.buffers[x]);
    glEnableVertexAttribArray(aX);
    glVertexAttribPointer(aX, 4, GL_FLOAT, GL_FALSE, stride, nullptr);
    if (inputs & kIterateRecords)
        for (uint32_t k = 0; k + 1 < record_; ++k) {
            glEnableVertexAttribArray(aLambda0 + k);
            glVertexAttribPointer(aLambda0 + k, 4, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(size_t(16) * (k + 1)));
        }
    glBindBuffer(GL_ARRAY_BUFFER, gl_.buffers[aux]);
    glEnableVertexAttribArray(aAux);
    glVertexAttribPointer(aAux, 4, GL_FLOAT, GL_FALSE, kState, nullptr);
    if (inputs & kKinematicInputs) {
        glBindBuffer(GL_ARRAY_BUFFER, gl_.kstart);
        glEnableVertexAttribArray(aKStart);
        glVertexAttribPointer(aKStart, 3, GL_FLOAT, GL_FALSE, kState, nullptr);
        glBindBuffer(GL_ARRAY_BUFFER, inputs & kGrabTargets ? gl_.grab_targets : gl_.targets);
        glEnableVertexAttribArray(aKTarget);
        glVertexAttribPointer(aKTarget, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
    }
    if (inputs & kTetherInputs) {
        glBindBuffer(GL_ARRAY_BUFFER, gl_.tethers);
        glEnableVertexAttribArray(aTetherAnchor);
        glVertexAttribIPointer(aTetherAnchor, 1, GL_UNSIGNED_INT, 8, nullptr);
        glEnableVertexAttribArray(aTetherLength);
        glVertexAttribPointer(aTetherLength, 1, GL_FLOAT, GL_FALSE, 8, reinterpret_cast<const void*>(size_t(4)));
    }
    gl_.vaos.push_back(vao);
    vaos_.emplace(key, vao);
    return vao;
}

void GlesCloth::bind_vertex_array(GLuint vao) {
    if (bound_vao_ == vao) return;
    glBindVertexArray(vao);
    bound_vao_ = vao;
}

void GlesCloth::feedback_draw(GLuint vao, uint32_t count, GLuint written, GLuint written2) {
    if (unpack_buffer_ && (unpack_buffer_ == written || unpack_buffer_ == written2)) {
        // A buffer must not be bound elsewhere while transform feedback writes it (ES 3.0 2.15.2);
        // an input left bound for its texture refresh may stay.
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        unpack_buffer_ = 0;
    }
    bind_vertex_array(vao);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, GLsizei(count));
    glEndTransformFeedback();
}

void GlesCloth::bind_outputs(int out, int out2) {
    // On the default transform feedback (transform-feedback objects made once per output pair
    // were measured wrong on softpipe: 1.3e-3 m off after one step).
    const size_t n = topo_.particle_count;
    // Separate attribs: one state record each; interleaved: one displacement-iterate record.
    bind_output(0, gl_.buffers[out], 0, GLsizeiptr(n * (out2 >= 0 ? 1 : record_) * sizeof(Particle)));
    bind_output(1, out2 >= 0 ? gl_.buffers[out2] : 0, 0, GLsizeiptr(n * sizeof(Particle)));
}

void GlesCloth::bind_output(int k, GLuint buffer, GLintptr offset, GLsizeiptr size) {
    Feedback& f = feedback_[k];
    if (!buffer) {
        if (f.buffer) glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, GLuint(k), 0);
        f = {};
        return;
    }
    if (f.buffer == buffer && f.offset == offset && f.size == size) return;
    glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, GLuint(k), buffer, offset, size);
    f = {buffer, offset, size};
}

void GlesCloth::unbind_outputs() {
    for (int k = 0; k < 2; ++k) bind_output(k, 0);
}

void GlesCloth::draw(GLuint vao, int out, int out2, int read_x, int read_aux) {
    bind_outputs(out, out2);
    if (read_x >= 0) refresh(read_x);
    if (read_aux >= 0) refresh(read_aux);
    flush_coarse();
    feedback_draw(vao, uint32_t(topo_.particle_count), gl_.buffers[out], out2 >= 0 ? gl_.buffers[out2] : 0);
    tex_stale_[out] = true;
    if (out2 >= 0) tex_stale_[out2] = true;
}

void GlesCloth::drop_pass_objects() {
    glDeleteVertexArrays(GLsizei(gl_.vaos.size()), gl_.vaos.data());
    gl_.vaos.clear();
    vaos_.clear();
    bound_vao_ = 0;
    for (bool& stale : tex_stale_) stale = true;
}

Result GlesCloth::pull() {
    if (!gpu_newer_) return {};
    std::string why;
    if (!context_current(&why))
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "reading a GLES cloth back needs its GL context: " + why};
    if (Result r = run_gpu_moves(); !r.ok()) return r;
    const uint32_t n = topo_.particle_count;
    Particle* const targets[2] = {x_.data(), d_.data()};  // from GPU roles cur (x) and disp (d)
    GLint bound = 0;
    glGetIntegerv(GL_COPY_READ_BUFFER_BINDING, &bound);
    for (int k = 0; k < 2; ++k) {
        glBindBuffer(GL_COPY_READ_BUFFER, gl_.buffers[g_[k]]);
        const auto* src = static_cast<const Particle*>(
            glMapBufferRange(GL_COPY_READ_BUFFER, 0, GLsizeiptr(size_t(n) * sizeof(Particle)), GL_MAP_READ_BIT));
        if (!src) {
            Result r = gl_error("glMapBufferRange (readback)");
            glBindBuffer(GL_COPY_READ_BUFFER, GLuint(bound));
            return r.ok() ? Result{DRAPE_ERROR_GL, "glMapBufferRange returned NULL (readback)"} : r;
        }
        std::memcpy(targets[k], src, size_t(n) * sizeof(Particle));  // state records
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, GLuint(bound));
    gpu_newer_ = false;
    compute_cpu_stats();
    return gl_error("reading back");
}

void GlesCloth::compute_cpu_stats() {
    // The CPU step's finite check, on the read-back copy (the GPU step has no verify pass); the
    // strain statistics come with the energies when read (Cloth::stats_of_cpu_copy).
    const Particle* x = x_.data();
    bool finite = true;
    for (uint32_t i = 0; i < topo_.particle_count; ++i)
        if (!(std::isfinite(x[i].x) && std::isfinite(x[i].y) && std::isfinite(x[i].z))) finite = false;
    stats_.non_finite = finite ? 0 : 1;
}

bool GlesCloth::predict_has_dashpot() const { return params_.model == DRAPE_MODEL_PBD && params_.damping > 0; }

const std::string& GlesCloth::variant_defines(int pass) const {
    // Built in a kept buffer (appends within its capacity): looking a program up each pass of
    // each step allocates nothing after the first frame.
    const bool xpbd = params_.model == DRAPE_MODEL_XPBD;
    std::string& d = defines_scratch_;
    d.clear();
    auto define = [&d](const char* name, long value) {
        char line[96];
        const int n = std::snprintf(line, sizeof line, "#define %s %ld\n", name, value);
        d.append(line, size_t(n));
    };
    if (pass == kMassSpring) d += "#define DRAPE_PASS_MASS_SPRING 1\n";
    const bool implicit = params_.model == DRAPE_MODEL_IMPLICIT;
    if (pass == kPredict) d += implicit ? "#define DRAPE_PASS_PREDICT 1\n#define DRAPE_IMPLICIT 1\n"
                                        : "#define DRAPE_PASS_PREDICT 1\n";
    if (pass == kConstraint || pass == kCommit)
        d += implicit ? "#define DRAPE_PASS_IMPLICIT 1\n" : "#define DRAPE_PASS_CONSTRAINT 1\n";
    if (pass == kCommit || pass == kCommitProlong) d += "#define DRAPE_COMMIT 1\n";
    if (pass == kProlong || pass == kCommitProlong) d += "#define DRAPE_PASS_IMPLICIT 1\n#define DRAPE_PROLONG 1\n";
    static const char* const kCoarseKinds[] = {"RESTRICT", "DOWN", "SOLVE", "UP"};
    if (is_coarse(pass)) {
        d += "#define DRAPE_PASS_COARSE 1\n#define DRAPE_COARSE_";
        d += kCoarseKinds[pass - kCoarseRestrict];
        d += " 1\n";
    }
    if (pass == kTether) d += "#define DRAPE_PASS_TETHER 1\n";
    if (pass == kMove) d += "#define DRAPE_PASS_MOVE 1\n";
    if (pass == kStill) d += "#define DRAPE_PASS_STILL 1\n";
    if (pass == kInteract) {
        d += "#define DRAPE_PASS_INTERACT 1\n";
        if (drag_variant_) {
            d += "#define DRAPE_DRAG 1\n";
            define("DRAPE_DRAG_VIEWS", long(kMaxDragCalls));
            define("DRAPE_MAX_TOUCHES", long(kMaxTouches));
        }
        define("DRAPE_SHAPES", long(shape_capacity_));
    }
    if (pass == kPredict && predict_has_dashpot()) d += "#define DRAPE_DASHPOT 1\n";
    if (xpbd) d += "#define DRAPE_XPBD 1\n";
    if (pass < kConstraint && kinematic_on_gpu()) d += "#define DRAPE_KINEMATIC 1\n";
    define("DRAPE_SLOTS", long(topo_.nbr.slots));
    define("DRAPE_RECORD", long(record_vec4()));
    define("DRAPE_LAMBDA_VEC4", long(xpbd ? record_vec4() - 1 : 1));
    return d;
}

Result GlesCloth::program(int pass, Program** out) {
    const std::string& defines = variant_defines(pass);
    auto it = programs_.find(defines);
    if (it == programs_.end()) {
        // Mass-spring and commit: positions and displacements into two buffers (separate attribs);
        // predict and constraint: one displacement-iterate record [+ lambdas] (interleaved).
        const bool two_outputs =
            pass == kMassSpring || pass == kCommit || pass == kCommitProlong || pass == kTether || pass == kInteract || pass == kMove;
        std::vector<std::string> varyings;
        if (two_outputs) varyings = {"v_x", "v_d"};
        else if (is_coarse(pass)) varyings = {"v_d"};  // one vec4 per coarse node
        else if (params_.model == DRAPE_MODEL_IMPLICIT && pass != kStill) varyings = {"v_d", "v_prev", "v_target"};  // iterate record
        else if (pass != kStill) varyings = {"v_d"};  // the sleep check draws, it feeds nothing back
        const bool xpbd = params_.model == DRAPE_MODEL_XPBD && (pass == kPredict || pass == kConstraint);
        if (xpbd)
            for (uint32_t k = 0; k + 1 < record_vec4(); ++k) varyings.push_back("v_lambda" + std::to_string(k));
        std::vector<std::pair<GLuint, const char*>> attribs{{aX, "a_x"}, {aAux, "a_aux"}, {aKStart, "a_kstart"},
                                                            {aKTarget, "a_ktarget"}};
        static const char* const lambda_names[kMaxLambdaVec4] = {"a_lambda0", "a_lambda1", "a_lambda2", "a_lambda3",
                                                                 "a_lambda4", "a_lambda5", "a_lambda6", "a_lambda7"};
        for (uint32_t k = 0; k < kMaxLambdaVec4; ++k) attribs.push_back({aLambda0 + k, lambda_names[k]});
        attribs.push_back({aLambda0, "a_prev"});  // IMPLICIT's record where XPBD's has lambdas
        attribs.push_back({aLambda0 + 1, "a_target"});
        attribs.push_back({aTetherAnchor, "a_tether_anchor"});
        attribs.push_back({aTetherLength, "a_tether_length"});
        Program p;
        if (Result r = link(with_defines(shaders::sim_vert, defines), "sim.vert.glsl", varyings,
                            two_outputs ? GL_SEPARATE_ATTRIBS : GL_INTERLEAVED_ATTRIBS, attribs, &p.id);
            !r.ok())
            return r;
        for (int u = 0; u < kUniformCount; ++u) p.u[u] = glGetUniformLocation(p.id, kUniformNames[u]);
        used_program_ = 0;  // link() made it current
        gl_.programs.push_back(p.id);
        it = programs_.emplace(defines, p).first;
    }
    *out = &it->second;
    return {};
}

Result GlesCloth::output_program(Program** out) {
    std::string d = "#define DRAPE_TRI_SLOTS " + std::to_string(tri_slots_) + "\n";
    if (out_layout_.position_offset >= 0) d += "#define DRAPE_WRITE_POSITION 1\n";
    if (out_layout_.normal_offset >= 0) d += "#define DRAPE_WRITE_NORMAL 1\n";
    std::string decls, copies;
    for (size_t k = 0; k < keeps_.size(); ++k) {
        const std::string type = keeps_[k].second == 1 ? "uint" : "uvec" + std::to_string(keeps_[k].second);
        decls += "in " + type + " a_keep" + std::to_string(k) + "; flat out " + type + " v_keep" + std::to_string(k) + "; ";
        copies += "v_keep" + std::to_string(k) + " = a_keep" + std::to_string(k) + "; ";
    }
    if (!keeps_.empty()) d += "#define DRAPE_KEEP_DECLS " + decls + "\n#define DRAPE_KEEP_COPY " + copies + "\n";
    const std::string key = "output\n" + d;
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        // Varyings in byte order of the record: every word of the stride is written.
        std::vector<std::string> varyings;
        const int words = int(out_layout_.stride / 4);
        size_t keep = 0;
        for (int w = 0; w < words;) {
            if (out_layout_.position_offset >= 0 && w == out_layout_.position_offset / 4) {
                varyings.push_back("v_position");
                w += 3;
            } else if (out_layout_.normal_offset >= 0 && w == out_layout_.normal_offset / 4) {
                varyings.push_back("v_normal");
                w += 3;
            } else {
                varyings.push_back("v_keep" + std::to_string(keep));
                w += keeps_[keep++].second;
            }
        }
        std::vector<std::string> keep_names;
        for (size_t k = 0; k < keeps_.size(); ++k) keep_names.push_back("a_keep" + std::to_string(k));
        std::vector<std::pair<GLuint, const char*>> attribs{{aParticle, "a_particle"}};
        for (size_t k = 0; k < keeps_.size(); ++k) attribs.push_back({GLuint(aKeep0 + k), keep_names[k].c_str()});
        Program p;
        if (Result r = link(with_defines(shaders::output_vert, d), "output.vert.glsl", varyings, GL_INTERLEAVED_ATTRIBS,
                            attribs, &p.id);
            !r.ok())
            return r;
        for (int u = 0; u < kUniformCount; ++u) p.u[u] = glGetUniformLocation(p.id, kUniformNames[u]);
        used_program_ = 0;  // link() made it current
        gl_.programs.push_back(p.id);
        it = programs_.emplace(key, p).first;
    }
    *out = &it->second;
    return {};
}

void GlesCloth::use_uniforms(float h) {
    SimUniforms u{};
    u.damping = params_.damping;
    u.air_drag = params_.air_drag;
    u.h = h;
    u.jacobi_coupling = kJacobiCoupling;
    for (int g = 0; g < DRAPE_GROUP_COUNT; ++g) {
        const float k = params_.stiffness[g];
        u.stiffness[g] = k;
        u.compliance[g] = xpbd_compliance(k, h);
        u.damping_ratio[g] = xpbd_damping_ratio(k, params_.damping, h);
    }
    for (int k = 0; k < 3; ++k) {
        u.gravity[k] = params_.gravity[k];
        u.wind[k] = params_.wind[k];
        u.origin[k] = float(origin_[k]);  // whole metres within 1e6 m: exact
    }
    if (!uniforms_uploaded_ || std::memcmp(&u, &uniforms_, sizeof u) != 0) {
        glBindBuffer(GL_UNIFORM_BUFFER, gl_.uniforms);
        glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof u, &u);
        uniforms_ = u;
        uniforms_uploaded_ = true;
    }
    glBindBufferBase(GL_UNIFORM_BUFFER, kSimUniformsBinding, gl_.uniforms);
}

void GlesCloth::run_pass(Program& p, int x, int aux, int out, int out2, bool constraint, const glm::vec4& sub,
                         const glm::vec2& chebyshev) {
    // Passes that fetch neighbours read x and aux as textures too (predict only with dashpots).
    const bool fetches = constraint || params_.model == DRAPE_MODEL_MASS_SPRING || predict_has_dashpot();
    use_program(p, x, aux);
    set_uniform(p, uSubstep, sub);
    set_uniform(p, uChebyshev, glm::vec4(chebyshev, 0.0f, 0.0f));
    if (p.u[uCoarse] >= 0)  // the iteration that adds the coarse correction: where it reads it
        set_uniform(p, uCoarse, glm::vec4(float(coarse_.levels[0].info), float(coarse_.levels[1].correction), 0.0f, 0.0f));
    const uint32_t inputs = constraint           ? kIterateRecords
                            : !kinematic_on_gpu() ? 0u
                                                  : kKinematicInputs | (grabs_on_gpu_ ? kGrabTargets : 0u);
    draw(vertex_array(x, aux, inputs), out, out2, fetches ? x : -1, fetches ? aux : -1);
}

void GlesCloth::move_gpu_state(Program& p, const RigidMove& m) {
    int& cur = g_[0];
    int& disp = g_[1];
    use_program(p, -1, -1);  // own records only: no texture
    const glm::vec4 rot = m.rot_xyzw();
    glUniform4fv(p.u[uMoveRot], 1, &rot.x);
    glUniform3fv(p.u[uMovePivot], 1, &m.pivot.x);
    glUniform3fv(p.u[uMoveTo], 1, &m.to.x);
    glUniform1f(p.u[uMoveKeepVelocity], m.keep_velocity ? 1.0f : 0.0f);
    draw(vertex_array(cur, disp, 0), g_[2], g_[3]);
    unbind_outputs();  // a move runs outside the substep loop: the passes after it read without binding outputs
    std::swap(cur, g_[2]);
    std::swap(disp, g_[3]);
}

void GlesCloth::move_state(const RigidMove& m) {
    Cloth::move_state(m);  // the CPU copy (the state while it is to be pushed; else kept consistent)
    for (glm::vec3& a : anchors_from_) a = m.apply(a);
    if (!state_dirty_) gpu_moves_.push_back(m);
}

Result GlesCloth::run_gpu_moves() {
    if (gpu_moves_.empty()) return {};
    if (state_dirty_) {  // the CPU copy, moved too, replaces the GPU state anyway
        gpu_moves_.clear();
        return {};
    }
    Program* p = nullptr;
    if (Result r = program(kMove, &p); !r.ok()) return r;
    StateGuard guard;
    begin_passes();
    for (const RigidMove& m : gpu_moves_) move_gpu_state(*p, m);
    gpu_moves_.clear();
    return gl_error("moving the GLES cloth");
}

Result GlesCloth::prepare_coarse(float h) {
    // A stale h only slows the correction (any A keeps the fixed point): cooked again, as the CPU
    // refactors, when h moved by more than kImplicitRefactor (frame times vary a little).
    const float key[5] = {h, params_.stiffness[0], params_.stiffness[1], params_.stiffness[2], params_.damping};
    if (coarse_key_[0] > 0 && std::fabs(h - coarse_key_[0]) <= kImplicitRefactor * coarse_key_[0] &&
        std::memcmp(key + 1, coarse_key_ + 1, sizeof key - sizeof key[0]) == 0)
        return {};
    const uint32_t n = topo_.particle_count;
    std::vector<float> w(n);
    for (uint32_t i = 0; i < n; ++i) w[i] = pinned_[i] ? 0.0f : base_inverse_mass_[i];  // as the info table
    coarse_ = cook_coarse(topo_.nbr, w, params_.stiffness, params_.damping, h, kTexWidth);
    std::memcpy(coarse_key_, key, sizeof key);
    GLuint tex[2] = {gl_.coarse_table, gl_.coarse_vec_tex};
    glDeleteTextures(2, tex);
    glDeleteBuffers(2, gl_.coarse_vec);
    gl_.coarse_table = gl_.coarse_vec_tex = gl_.coarse_vec[0] = gl_.coarse_vec[1] = 0;
    if (!coarse_.active()) return {};
    const uint32_t table_rows = rows_for(coarse_.table.size() / 4);
    gl_.coarse_table = make_texture(GL_RGBA32UI, table_rows);
    upload_uint_texture(gl_.coarse_table, gl_.staging, table_rows, coarse_.table);
    gl_.coarse_vec_tex = make_texture(GL_RGBA32F, coarse_.vector_texels / kTexWidth);
    glGenBuffers(2, gl_.coarse_vec);
    for (GLuint b : gl_.coarse_vec) {
        glBindBuffer(GL_ARRAY_BUFFER, b);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(coarse_.vector_texels) * 16), nullptr, GL_DYNAMIC_COPY);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    if (!gl_.coarse_vao) glGenVertexArrays(1, &gl_.coarse_vao);
    return gl_error("uploading the coarse levels");
}

void GlesCloth::coarse_pass(Program& p, int x, int aux, const glm::vec4& offsets, uint32_t write, uint32_t count) {
    use_program(p, x, aux);
    set_uniform(p, uCoarse, offsets);
    // Into the other vector buffer than the last pass: the one the texture is refreshed from may
    // stay on the pixel-unpack binding (only the texture is read, so which buffer holds a section's
    // last values does not matter). Outputs bound before the inputs are read (bind_outputs).
    const GLuint vec = gl_.coarse_vec[coarse_flip_];
    coarse_flip_ ^= 1;
    bind_output(0, vec, GLintptr(size_t(write) * 16), GLsizeiptr(size_t(count) * 16));
    bind_output(1, 0);
    if (x >= 0) refresh(x);
    if (aux >= 0) refresh(aux);
    flush_coarse();
    feedback_draw(gl_.coarse_vao, count, vec);
    coarse_written_ = {vec, write, count};
}

void GlesCloth::flush_coarse() {
    if (!coarse_written_.buffer) return;
    // The rows written, into the texture the next pass reads (sections start on whole rows).
    if (active_unit_ != kCoarseVecUnit) {
        glActiveTexture(GL_TEXTURE0 + GLenum(kCoarseVecUnit));
        active_unit_ = kCoarseVecUnit;
    }
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, coarse_written_.buffer);
    unpack_buffer_ = coarse_written_.buffer;
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, GLint(coarse_written_.write / kTexWidth), kTexWidth,
                    GLsizei(rows_for(coarse_written_.count)), GL_RGBA, GL_FLOAT,
                    reinterpret_cast<const void*>(size_t(coarse_written_.write) * 16));
    coarse_written_.buffer = 0;
}

void GlesCloth::run_coarse(Program* const p[4], int in, int cur) {
    const std::vector<CoarseLevel>& l = coarse_.levels;
    const size_t top = l.size() - 1;
    auto at = [](uint32_t a, uint32_t b = 0, uint32_t c = 0) { return glm::vec4(float(a), float(b), float(c), 0.0f); };
    coarse_pass(*p[0], in, cur, at(l[1].members), l[1].residual, l[1].count);
    for (size_t k = 1; k < top; ++k)
        coarse_pass(*p[1], -1, -1, at(l[k + 1].members, l[k].info, l[k].residual), l[k + 1].residual, l[k + 1].count);
    coarse_pass(*p[2], -1, -1, at(coarse_.dense, l[top].residual, l[top].count), l[top].correction, l[top].count);
    for (size_t k = top - 1; k >= 1; --k)
        coarse_pass(*p[3], -1, -1, at(l[k].info, l[k].residual, l[k + 1].correction), l[k].correction, l[k].count);
}

void GlesCloth::run_tether(Program& p, int x, int d, int out_x, int out_d) {
    use_program(p, x, -1);
    draw(vertex_array(x, d, kTetherInputs), out_x, out_d, x);  // x: the anchors' positions
}

bool GlesCloth::tethered_reach(Aabb& reach) const {
    // Each substep's tether pass leaves every particle within its tether length of its anchor, and
    // the anchors go from where they start (record_anchors, moved with the state) to their targets.
    // Unknown (false) without tethers, with a particle no pin reaches, when other particles became
    // kinematic since (their start is on the GPU), or while a grab or a drag moves particles.
    if (!has_tethers() || grabs_on_gpu_ || !drag_views_.empty() || anchors_of_ != kinematic_) return false;
    if (reach_stale_) {  // per anchor its farthest tether, once per change of tethers (refresh_backend)
        const uint32_t n = topo_.particle_count;
        anchor_reach_.assign(n, 0.0f);
        all_tethered_ = true;
        for (uint32_t i = 0; i < n; ++i) {
            all_tethered_ = all_tethered_ && tether_length_[i] >= 0.0f;
            float& r = anchor_reach_[tether_anchor_[i]];
            r = std::max(r, tether_length_[i]);
        }
        reach_stale_ = false;
    }
    if (!all_tethered_) return false;
    const float pad = kTetherReachPad + (sc_.enabled ? sc_.thickness : 0.0f);
    for (size_t k = 0; k < kinematic_.size(); ++k) {
        const float r = anchor_reach_[kinematic_[k]] + pad;
        reach.add(anchors_from_[k], r);
        reach.add(kinematic_target_[kinematic_[k]], r);
    }
    return true;
}

uint32_t GlesCloth::gles_substeps_for(float dt) const {
    const uint32_t planned = substeps_for(dt);
    if (params_.model != DRAPE_MODEL_IMPLICIT || params_.substeps > 0) return planned;
    auto edge_or_curve = [](const ColliderState& c) { return c.shape != DRAPE_COLLIDER_PLANE; };
    if (std::none_of(ix_.colliders.begin(), ix_.colliders.end(), edge_or_curve)) return planned;
    Aabb reach;
    bool near = !tethered_reach(reach);
    for (const ColliderState& c : ix_.colliders) near = near || (edge_or_curve(c) && touches(reach, c.at_substep(0, 1)));
    return near ? std::max(planned, gles_implicit_substeps(dt, kMaxContactSubstepImplicitGles)) : planned;
}

uint32_t GlesCloth::build_shapes(uint32_t sub, uint32_t substeps) {
    // Every collider is tested: the CPU's broad phase needs the cloth's bounds, which live on the
    // GPU (the narrow phase skips a particle that cannot have touched a collider after one distance
    // test).
    shape_data_.clear();
    for (const ColliderState& c : ix_.colliders) {
        const CollideShape s = c.at_substep(sub, substeps);
        const float rec[DRAPE_COLLIDER_VEC4 * 4] = {s.pos0.x, s.pos0.y, s.pos0.z, s.margin, s.pos1.x, s.pos1.y, s.pos1.z,
                                                    s.friction, s.rot0.x, s.rot0.y, s.rot0.z, s.rot0.w, s.rot1.x,
                                                    s.rot1.y, s.rot1.z, s.rot1.w, s.size.x, s.size.y, s.size.z,
                                                    float(s.shape)};
        shape_data_.insert(shape_data_.end(), std::begin(rec), std::end(rec));
    }
    return uint32_t(ix_.colliders.size());
}

void GlesCloth::run_interact(Program& p, int x, int d, int out_x, int out_d, bool drag, uint32_t shapes) {
    use_program(p, -1, -1);  // own records only: no texture
    if (shapes) {
        glUniform4fv(p.u[uShapes], GLsizei(shapes * DRAPE_COLLIDER_VEC4), shape_data_.data());
        glUniform1i(p.u[uShapeCount], GLint(shapes));
    }
    if (drag) {
        glUniform4fv(p.u[uDragViews], GLsizei(drag_views_.size()), &drag_views_[0].x);
        glUniform4fv(p.u[uTouches], GLsizei(drag_touches_.size()), &drag_touches_[0].x);
        glUniform1i(p.u[uTouchCount], GLint(drag_touches_.size() / DRAPE_TOUCH_VEC4));
    }
    draw(vertex_array(x, d, 0), out_x, out_d);
}

Result GlesCloth::drag(const drape_view& view, std::vector<drape_touch> touches) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (drag_calls_recorded_ + 1 > kMaxDragCalls || drag_touches_recorded_ + touches.size() > kMaxTouches)
            return {DRAPE_ERROR_INVALID_ARGUMENT,
                    "a GLES cloth takes at most " + std::to_string(kMaxDragCalls) + " drape_cloth_drag calls with " +
                        std::to_string(kMaxTouches) + " touches in all between two steps (the drag runs on the GPU)"};
        ++drag_calls_recorded_;
        drag_touches_recorded_ += uint32_t(touches.size());
    }
    return edit(Access::NoState, [this, view, t = std::move(touches)](Cloth&) {
        if (t.empty() || drag_views_.size() / DRAPE_DRAG_VIEW_VEC4 >= kMaxDragCalls ||
            drag_touches_.size() / DRAPE_TOUCH_VEC4 + t.size() > kMaxTouches)
            return;  // full only if a step failed before using them
        // The mapping takes local coordinates: the cloth's origin as it is when this is applied.
        const ScreenMapping m = make_screen_mapping(view, origin_);
        const float slot = float(drag_views_.size() / DRAPE_DRAG_VIEW_VEC4);  // records as layout.h says
        for (int c = 0; c < 4; ++c) drag_views_.push_back(glm::vec4(m.mvp[c]));
        for (int c = 0; c < 4; ++c) drag_views_.push_back(glm::vec4(m.inv_mvp[c]));
        drag_views_.push_back(glm::vec4(float(m.viewport.x), float(m.viewport.y), 0.0f, 0.0f));  // z: share, set by the step
        bool moves = false;
        for (const drape_touch& k : t) {
            drag_touches_.push_back(glm::vec4(k.position[0], k.position[1], k.motion[0], k.motion[1]));
            drag_touches_.push_back(glm::vec4(k.amplitude, k.sigma, slot, 0.0f));
            moves = moves || ((k.motion[0] != 0.0f || k.motion[1] != 0.0f) && k.amplitude > 0.0f);
        }
        if (moves) wake();
    });
}

Result GlesCloth::step(float dt) {
    std::lock_guard<std::mutex> lock(mutex_);
    drag_calls_recorded_ = drag_touches_recorded_ = 0;  // the step recorded now takes them
    if (mode_ == Mode::RenderThread) {
        Result r = deferred_error_;
        deferred_error_ = {};
        if (pending_.size() >= 256)
            return {DRAPE_ERROR_BACKEND_UNAVAILABLE,
                    "256 GLES steps are waiting for the render thread: issue the Drape render event every frame"};
        Op op;
        op.dt = dt;
        pending_.push_back(std::move(op));
        return r;
    }
    return gpu_step(dt);
}

Result GlesCloth::gpu_step(float dt) {
    if (skip_step_asleep()) return {};  // asleep: no GL call at all
    const auto t0 = std::chrono::steady_clock::now();
    if (Result r = ensure_gl(); !r.ok()) return r;
    std::string why;
    if (!context_current(&why)) return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "GLES step: " + why};
    drain_gl_errors();
    StateGuard guard;
    if (state_dirty_) record_anchors([&](uint32_t k) { return glm::vec3(x_[k]); });  // the state comes from the CPU copy
    if (Result r = sync_gpu(); !r.ok()) return r;
    if (Result r = run_gpu_moves(); !r.ok()) return r;
    if (out_buffer_) {
        // The caller may have deleted or resized the buffer since: refuse before stepping.
        if (!glIsBuffer(out_buffer_))
            return {DRAPE_ERROR_GL, "output GL buffer " + std::to_string(out_buffer_) + " no longer exists"};
        GLint size = 0;
        glBindBuffer(GL_ARRAY_BUFFER, out_buffer_);
        glGetBufferParameteriv(GL_ARRAY_BUFFER, GL_BUFFER_SIZE, &size);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        const uint64_t need = uint64_t(topo_.vertex_count) * out_layout_.stride;
        if (uint64_t(size) < need)
            return {DRAPE_ERROR_BUFFER_TOO_SMALL, "output GL buffer holds " + std::to_string(size) +
                                                      " bytes, the layout needs " + std::to_string(need)};
    }
    if (Result r = prepare_grabs(); !r.ok()) return r;  // before the variants: a grab makes the step kinematic
    const drape_model model = drape_model(params_.model);
    const int first = model == DRAPE_MODEL_MASS_SPRING ? kMassSpring : kPredict;
    Program *p_first = nullptr, *p_constraint = nullptr, *p_commit = nullptr, *p_tether = nullptr;
    if (Result r = program(first, &p_first); !r.ok()) return r;
    if (has_tethers())  // else no tether program and no tether pass (CpuCloth::step's condition)
        if (Result r = program(kTether, &p_tether); !r.ok()) return r;
    Program* p_move = nullptr;  // compiled with the others: a first re-centre mid-game compiles nothing
    if (Result r = program(kMove, &p_move); !r.ok()) return r;
    Program* p_still = nullptr;
    if (ix_.sleep_threshold > 0)
        if (Result r = program(kStill, &p_still); !r.ok()) return r;
    if (still_count_ && poll_still()) {
        // Fell asleep on an earlier step's check, before this step, as the CPU cloth after that
        // step: velocities zeroed so that waking starts from rest, and no step.
        begin_passes();
        move_gpu_state(*p_move, {glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f), false});
        skip_step_asleep();
        return gl_error("GLES cloth falling asleep");
    }
    // Interaction (CpuCloth::collide): colliders in every substep, drag in the first.
    // Variants: DRAPE_SHAPES = collider capacity (power of two >= 4, 0 without colliders).
    Program *p_interact_first = nullptr, *p_interact = nullptr;
    const uint32_t shape_count = uint32_t(ix_.colliders.size());
    const bool dragging = !drag_views_.empty();
    uint32_t capacity = 0;
    if (shape_count) {
        capacity = 4;
        while (capacity < shape_count) capacity *= 2;
        const GLint drag_vectors = dragging ? GLint(kDragUniformVectors) : 0;
        if (kOwnUniformVectors + drag_vectors + GLint(capacity * DRAPE_COLLIDER_VEC4) > max_vertex_uniform_vectors_)
            return {DRAPE_ERROR_INVALID_ARGUMENT, std::to_string(shape_count) + " colliders need " +
                                                      std::to_string(capacity * DRAPE_COLLIDER_VEC4) + " uniform vectors (and a touch drag " +
                                                      std::to_string(drag_vectors) + "); this GL offers " +
                                                      std::to_string(max_vertex_uniform_vectors_) + " to vertex shaders"};
    }
    if (shape_count || dragging) {
        shape_capacity_ = capacity;
        drag_variant_ = dragging;
        if (Result r = program(kInteract, &p_interact_first); !r.ok()) return r;
        if (dragging && shape_count) {
            drag_variant_ = false;
            if (Result r = program(kInteract, &p_interact); !r.ok()) return r;
        } else if (!dragging) {
            p_interact = p_interact_first;
        }
    }
    if (first == kPredict) {
        if (Result r = program(kConstraint, &p_constraint); !r.ok()) return r;
        if (Result r = program(kCommit, &p_commit); !r.ok()) return r;
    }
    if (sc_.enabled)
        if (Result r = GlesSelfCollide::prepare(*this); !r.ok()) return r;
    const uint32_t substeps = gles_substeps_for(dt);
    const float h = dt / float(substeps);
    const uint32_t n = topo_.particle_count;
    Program* p_coarse[6] = {};  // restrict, down, solve, up; the iteration that prolongs, and its commit form
    if (model == DRAPE_MODEL_IMPLICIT) {
        if (Result r = prepare_coarse(h); !r.ok()) return r;
        if (coarse_.active())
            for (int k = 0; k < 6; ++k)
                if (Result r = program(kCoarseRestrict + k, &p_coarse[k]); !r.ok()) return r;
    }

    begin_passes();
    if (!gpu_newer_) {
        // The CPU copy is the state now: what a lost context resumes from (forget_gl).
        cpu_h_prev_ = h_prev_;
        cpu_fresh_ = fresh_;
    }
    run_grabs();  // may hold, release or pick particles: before their start is taken
    if (p_coarse[0]) {
        const GLuint coarse_tex[2] = {gl_.coarse_table, gl_.coarse_vec_tex};
        for (int k = 0; k < 2; ++k) {
            glActiveTexture(GL_TEXTURE0 + GLenum(kCoarseTableUnit + k));
            glBindTexture(GL_TEXTURE_2D, coarse_tex[k]);
        }
        active_unit_ = kCoarseVecUnit;
    }
    std::optional<GlesSelfCollide::StepScope> self_scope;  // self-collision's units and draw state (after the pick's)
    if (sc_.enabled) self_scope.emplace(*this);
    if (kinematic_on_gpu()) {
        // Kinematic particles move from where they are now (GPU copy, no readback).
        glBindBuffer(GL_COPY_READ_BUFFER, gl_.buffers[g_[0]]);
        glBindBuffer(GL_COPY_WRITE_BUFFER, gl_.kstart);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(size_t(n) * sizeof(Particle)));
    }
    // The drag's share in the first substep (CpuCloth::collide: offset / substeps), per view.
    for (size_t v = DRAPE_DRAG_VIEW_VEC4 - 1; v < drag_views_.size(); v += DRAPE_DRAG_VIEW_VEC4)
        drag_views_[v].z = 1.0f / float(substeps);
    use_uniforms(h);
    const Chebyshev chebyshev = implicit_chebyshev(iterations_for());
    // Buffer roles as CpuCloth::solve: cur (positions x), disp (displacements d), spare, spare2.
    int& cur = g_[0];
    int& disp = g_[1];
    int& spare = g_[2];
    int& spare2 = g_[3];
    for (uint32_t s = 0; s < substeps; ++s) {
        // Computed on the CPU exactly as CpuCloth::predict does, so the shader sees the same bits.
        const glm::vec4 sub(1.0f / h_prev_, h / h_prev_, verlet_accel_h(h, h_prev_, fresh_), float(s + 1) / float(substeps));
        if (model == DRAPE_MODEL_MASS_SPRING) {
            // x -> spare, d -> spare2 (kinematic particles placed in the same pass).
            run_pass(*p_first, cur, disp, spare, spare2, false, sub);
            std::swap(cur, spare);
            std::swap(disp, spare2);
        } else {
            // predict: displacements into spare; iterate spare <-> disp (free after predict); the
            // last iteration also writes positions, into spare2. So the iterates keep their two
            // buffers and the positions alternate between two: a pass's inputs are on one of two
            // texture units from substep to substep (one u_x / u_aux update, not two).
            run_pass(*p_first, cur, disp, spare, -1, false, sub);
            int in = spare, out = disp;
            float omega = 1.0f;  // IMPLICIT: Chebyshev weights (Wang 2015 eq. 12), 1 in the first iteration
            const float rho2 = chebyshev.rho * chebyshev.rho;
            // The coarse correction comes after the first iteration (before the only one of a 1-iteration budget).
            const uint32_t coarse_at = iterations_for() >= 2 ? 1 : 0;
            for (uint32_t it = 0; it < iterations_for(); ++it) {
                const bool prolong = p_coarse[0] && it == coarse_at;
                if (prolong) run_coarse(p_coarse, in, cur);
                if (it == 1) omega = 2.0f / (2.0f - rho2);
                else if (it > 1) omega = 4.0f / (4.0f - rho2 * omega);
                if (it + 1 == iterations_for())
                    run_pass(prolong ? *p_coarse[5] : *p_commit, in, cur, spare2, out, true, sub,
                             {omega, chebyshev.gamma});  // x -> spare2, d -> out
                else
                    run_pass(prolong ? *p_coarse[4] : *p_constraint, in, cur, out, -1, true, sub, {omega, chebyshev.gamma});
                std::swap(in, out);
            }
            // Positions went to spare2, displacements to `in`; `out` held the last iterate.
            const int old_cur = cur;
            cur = spare2;
            disp = in;
            spare = out;
            spare2 = old_cur;
        }
        if (p_tether) {
            // kernels::tether after the solve: x, d -> spare, spare2 (the CPU works in place).
            run_tether(*p_tether, cur, disp, spare, spare2);
            std::swap(cur, spare);
            std::swap(disp, spare2);
        }
        if (sc_.enabled) {
            // CpuCloth::self_collide after the solve and tethers: x, d -> spare, spare2.
            GlesSelfCollide::run(*this, cur, disp, spare, spare2);
            std::swap(cur, spare);
            std::swap(disp, spare2);
        }
        Program* p_int = s == 0 ? p_interact_first : p_interact;
        if (p_int) {
            const uint32_t shapes = shape_count ? build_shapes(s, substeps) : 0;
            ix_.collide_tests += uint64_t(n) * shapes;
            run_interact(*p_int, cur, disp, spare, spare2, s == 0 && dragging, shapes);
            std::swap(cur, spare);
            std::swap(disp, spare2);
        }
        h_prev_ = h;
        fresh_ = false;
    }
    unbind_outputs();
    if (p_coarse[0]) {  // the output pass's triangles back on their unit
        glActiveTexture(GL_TEXTURE0 + GLenum(kTrisUnit));
        glBindTexture(GL_TEXTURE_2D, gl_.tri_tex);
        active_unit_ = kTrisUnit;
    }
    gpu_newer_ = true;
    drag_views_.clear();
    drag_touches_.clear();
    advance_interaction();
    if (p_still) issue_still(*p_still, dt);  // compiled only when the cloth may sleep
    // Re-centre as CpuCloth::step does, without reading back: kinematic particles end the step on
    // their targets, which the CPU holds; a cloth without any decides from its last read-back copy
    // (shifted along with the state, so it stays consistent).
    const glm::vec3 shift = recentre_shift(kinematic_.empty() ? glm::vec3(x_[0])
                                                             : kinematic_target_[kinematic_[0]]);
    if (shift != glm::vec3(0.0f)) {
        move_gpu_state(*p_move, {glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(0.0f), -shift, true});
        shift_origin(shift);
        targets_dirty_ = true;
    }
    record_anchors([&](uint32_t k) { return kinematic_target_[k]; });  // where the next step starts them (re-centred)
    Result r = write_output();
    stats_.substeps = substeps;
    stats_.iterations = model == DRAPE_MODEL_MASS_SPRING ? 1 : iterations_for();
    stats_.step_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!r.ok()) return r;
    return gl_error("GLES step");
}

void GlesCloth::bind_framebuffer() {
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return;
    // No usable framebuffer (headless, no surface): draws fail even with rasterizer discard.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, own_framebuffer());
}

GLuint GlesCloth::own_framebuffer() {
    if (!gl_.fbo) {
        GLint rb = 0;
        glGetIntegerv(GL_RENDERBUFFER_BINDING, &rb);
        glGenRenderbuffers(1, &gl_.rbo);
        glBindRenderbuffer(GL_RENDERBUFFER, gl_.rbo);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
        glBindRenderbuffer(GL_RENDERBUFFER, GLuint(rb));
        glGenFramebuffers(1, &gl_.fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl_.fbo);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, gl_.rbo);
    }
    return gl_.fbo;
}

bool GlesCloth::poll_still() {
    while (still_count_ > 0) {
        const GLuint query = gl_.queries[still_first_];
        GLuint available = 0;
        glGetQueryObjectuiv(query, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return false;  // asked again at the next step: never waited for
        GLuint moved = 0;
        glGetQueryObjectuiv(query, GL_QUERY_RESULT, &moved);
        const StillQuery q = still_[still_first_];
        still_first_ = (still_first_ + 1) % kStillQueries;
        --still_count_;
        if (q.wakes != ix_.wakes) continue;  // woken since: a check of the old motion
        if (count_still(moved == 0, q.dt)) {
            still_count_ = 0;  // later checks saw steps that a CPU cloth would not have taken
            return true;
        }
    }
    return false;
}

void GlesCloth::issue_still(Program& p, float dt) {
    if (!(ix_.sleep_threshold > 0) || still_count_ == kStillQueries) return;
    if (!gl_.queries[0]) glGenQueries(kStillQueries, gl_.queries);
    const int slot = (still_first_ + still_count_) % kStillQueries;
    still_[slot] = {dt, ix_.wakes};
    ++still_count_;
    // Drawn into the cloth's own 1x1 target, never the caller's (restored by the StateGuard).
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, own_framebuffer());
    glViewport(0, 0, 1, 1);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_RASTERIZER_DISCARD);
    use_program(p, -1, -1);
    const float limit = ix_.sleep_threshold * h_prev_;  // as interaction_end_step
    glUniform1f(p.u[uStillLimit2], limit * limit);
    bind_vertex_array(vertex_array(g_[0], g_[1], 0));
    glBeginQuery(GL_ANY_SAMPLES_PASSED, gl_.queries[slot]);
    glDrawArrays(GL_POINTS, 0, GLsizei(topo_.particle_count));
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    glEnable(GL_RASTERIZER_DISCARD);
}

Result GlesCloth::write_output() {
    if (!out_buffer_) return {};
    Program* p = nullptr;
    if (Result r = output_program(&p); !r.ok()) return r;
    const uint32_t count = topo_.vertex_count;
    const GLsizeiptr bytes = GLsizeiptr(uint64_t(count) * out_layout_.stride);
    if (!keeps_.empty()) {
        // Bytes this pass does not own are copied through from a GPU-side copy of the buffer.
        glBindBuffer(GL_COPY_READ_BUFFER, out_buffer_);
        glBindBuffer(GL_COPY_WRITE_BUFFER, gl_.scratch);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, bytes);
    }
    if (!gl_.out_vao) {
        // Made once per output buffer and layout (set_output drops it).
        glGenVertexArrays(1, &gl_.out_vao);
        glBindVertexArray(gl_.out_vao);
        bound_vao_ = gl_.out_vao;
        glBindBuffer(GL_ARRAY_BUFFER, gl_.vertex_to_particle);
        glEnableVertexAttribArray(aParticle);
        glVertexAttribIPointer(aParticle, 1, GL_UNSIGNED_INT, 4, nullptr);
        if (!keeps_.empty()) {
            glBindBuffer(GL_ARRAY_BUFFER, gl_.scratch);
            for (size_t k = 0; k < keeps_.size(); ++k) {
                glEnableVertexAttribArray(GLuint(aKeep0 + k));
                glVertexAttribIPointer(GLuint(aKeep0 + k), keeps_[k].second, GL_UNSIGNED_INT,
                                       GLsizei(out_layout_.stride),
                                       reinterpret_cast<const void*>(size_t(keeps_[k].first) * 4));
            }
        }
    }
    refresh(g_[0]);
    use_uniforms(uniforms_.h);
    use_program(*p, g_[0], -1);
    glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out_buffer_, 0, bytes);
    feedback_draw(gl_.out_vao, count, out_buffer_);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    return gl_error("writing the output buffer");
}

Result GlesCloth::set_output(uint32_t buffer, const drape_vertex_layout& layout) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Which words of the record this pass does not own (copied through).
    std::vector<std::pair<int, int>> keeps;
    const int words = int(layout.stride / 4);
    for (int w = 0; w < words;) {
        if ((layout.position_offset >= 0 && w == layout.position_offset / 4) ||
            (layout.normal_offset >= 0 && w == layout.normal_offset / 4)) {
            w += 3;
            continue;
        }
        const int start = w;
        while (w < words && w - start < 4 && !(layout.position_offset >= 0 && w == layout.position_offset / 4) &&
               !(layout.normal_offset >= 0 && w == layout.normal_offset / 4))
            ++w;
        keeps.push_back({start, w - start});
    }
    if (1 + keeps.size() > size_t(kMaxAttribs))
        return {DRAPE_ERROR_INVALID_ARGUMENT, "layout has too many unrelated attributes to copy through (" +
                                                  std::to_string(keeps.size()) + " chunks, at most 15)"};
    if (layout.stride > 256)
        return {DRAPE_ERROR_INVALID_ARGUMENT, "GLES output stride must be <= 256 bytes (ES 3.0 transform feedback)"};
    auto apply = [this, buffer, layout, keeps]() -> Result {
        if (buffer) {
            if (!glIsBuffer(buffer))
                return {DRAPE_ERROR_INVALID_ARGUMENT, "GL buffer " + std::to_string(buffer) + " does not exist"};
            GLint bound = 0, size = 0;
            glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &bound);
            glBindBuffer(GL_ARRAY_BUFFER, buffer);
            glGetBufferParameteriv(GL_ARRAY_BUFFER, GL_BUFFER_SIZE, &size);
            glBindBuffer(GL_ARRAY_BUFFER, GLuint(bound));
            const uint64_t need = uint64_t(topo_.vertex_count) * layout.stride;
            if (uint64_t(size) < need)
                return {DRAPE_ERROR_BUFFER_TOO_SMALL, "GL buffer " + std::to_string(buffer) + " holds " +
                                                          std::to_string(size) + " bytes, the layout needs " +
                                                          std::to_string(need)};
            if (!keeps.empty()) {
                if (!gl_.scratch) glGenBuffers(1, &gl_.scratch);
                glBindBuffer(GL_COPY_WRITE_BUFFER, gl_.scratch);
                glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(need), nullptr, GL_DYNAMIC_COPY);
                glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
            }
        }
        out_buffer_ = buffer;
        out_layout_ = layout;
        keeps_ = keeps;
        glDeleteVertexArrays(1, &gl_.out_vao);  // made again for this buffer and layout
        gl_.out_vao = 0;
        if (!buffer) return {};
        StateGuard guard;
        if (Result r = sync_gpu(); !r.ok()) return r;
        begin_passes();
        return write_output();
    };
    if (mode_ == Mode::RenderThread) {
        Op op;
        op.edit = [apply, this](Cloth&) {
            Result r = apply();
            if (!r.ok()) deferred_error_ = r;
        };
        pending_.push_back(std::move(op));
        return {};
    }
    if (Result r = ensure_gl(); !r.ok()) return r;
    return apply();
}

Result GlesCloth::apply_edit(Access access, const std::function<void(Cloth&)>& fn) {
    if (access == Access::ReadsState && gpu_newer_)
        if (Result r = pull(); !r.ok()) return r;
    fn(*this);
    // The CPU copy is now the truth for positions (push), or only parameters/targets changed.
    if (access != Access::NoState) state_dirty_ = true;
    targets_dirty_ = info_dirty_ = true;
    return {};
}

Result GlesCloth::edit(Access access, std::function<void(Cloth&)> fn) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (mode_ == Mode::RenderThread && (!pending_.empty() || (access == Access::ReadsState && gpu_newer_))) {
        Op op;
        op.edit = std::move(fn);
        op.access = access;
        pending_.push_back(std::move(op));
        return {};
    }
    return apply_edit(access, fn);
}

Result GlesCloth::readback() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (mode_ == Mode::RenderThread) {
        Op op;
        op.readback = true;
        pending_.push_back(std::move(op));
        return {};
    }
    return pull();
}

Result GlesCloth::read(const drape_vertex_layout& layout, void* dst) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (gpu_newer_ && mode_ == Mode::Immediate)
        if (Result r = pull(); !r.ok()) return r;
    read_cpu_copy(layout, dst);
    return {};
}

Result GlesCloth::stats(drape_stats* out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (gpu_newer_ && mode_ == Mode::Immediate)
        if (Result r = pull(); !r.ok()) return r;
    stats_of_cpu_copy(out);
    return {};
}

Result GlesCloth::link_grab_program(const std::string& defines, bool pick, GLuint* out) {
    // The pick draws into the pick target (pick.frag.glsl); the grab pass feeds back the position
    // record and the pin target (separate buffers). Inputs at the state passes' locations.
    const std::vector<std::string> varyings = pick ? std::vector<std::string>{} : std::vector<std::string>{"v_x", "v_target"};
    Result r = link(with_defines(shaders::grab_vert, defines), "grab.vert.glsl", varyings, GL_SEPARATE_ATTRIBS,
                    {{aX, "a_x"}, {aKTarget, "a_ktarget"}}, out, pick ? shaders::pick_frag : shaders::discard_frag,
                    pick ? "pick.frag.glsl" : "discard.frag.glsl");
    if (!r.ok()) return r;
    used_program_ = 0;  // link() made it current
    gl_.programs.push_back(*out);
    return {};
}

GLuint GlesCloth::grab_vertex_array() { return vertex_array(g_[0], g_[1], kKinematicInputs); }

uint32_t GlesCloth::iterations_for() const {
    if (params_.model == DRAPE_MODEL_IMPLICIT && params_.iterations == 0) return kAutoIterationsImplicitGles;
    return Cloth::iterations_for();
}

Result GlesCloth::supports(Feature feature) const {
    switch (feature) {
    case Feature::ImplicitModel: return {};  // block Jacobi + Chebyshev passes (sim.vert.glsl)
    case Feature::XpbdModel:  // its lambdas ride in at most kMaxLambdaVec4 vec4 attributes
        if ((topo_.nbr.slots + 3) / 4 > kMaxLambdaVec4)
            return {DRAPE_ERROR_INVALID_ARGUMENT, "GLES XPBD supports up to 32 neighbours per vertex; this mesh has " +
                                                      std::to_string(topo_.nbr.slots)};
        return {};
    case Feature::Grab: return {};  // picked and held on the GPU (gles_grab.cpp)
    case Feature::Owner: return {};  // moved on the GPU (move_gpu_state)
    case Feature::Sleep: return {};  // checked on the GPU (issue_still, poll_still)
    case Feature::SelfCollision: return {};  // hash and collide passes (gles_self_collide.h)
    }
    return {};
}

void GlesCloth::run_pending() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_.empty() && gl_ready_) return;
    if (Result r = ensure_gl(); !r.ok()) {
        deferred_error_ = r;
        return;
    }
    while (!pending_.empty()) {
        Op op = std::move(pending_.front());
        pending_.pop_front();
        Result r;
        if (op.dt > 0) {
            r = gpu_step(op.dt);
        } else if (op.readback) {
            r = pull();
        } else {
            StateGuard guard;
            r = apply_edit(op.access, op.edit);
        }
        if (!r.ok()) deferred_error_ = r;
    }
}

void GlesCloth::drop_gl() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!gl_ready_) return;
    pull();  // keep the latest state on the CPU; re-uploaded on the next device
    drop_gpu_grabs();
    delete_now(gl_);
    coarse_key_[0] = 0;
    still_count_ = 0;
    programs_.clear();
    vaos_.clear();
    gl_ready_ = false;
    record_ = 0;
    state_dirty_ = targets_dirty_ = info_dirty_ = true;
}

void GlesCloth::forget_gl() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (gpu_newer_ && !state_dirty_) {
        // The GPU state went with the context: back to the step that the CPU copy holds (the
        // last readback), with the substep bookkeeping of that moment.
        h_prev_ = cpu_h_prev_;
        fresh_ = cpu_fresh_;
    }
    gpu_newer_ = false;
    gpu_moves_.clear();  // made on the CPU copy, which the cloth resumes from
    drop_gpu_grabs();
    still_count_ = 0;    // its queries went with the context
    gl_ = GlObjects{};  // names of a dead context: never deleted (the next context may reuse them)
    coarse_key_[0] = 0;
    programs_.clear();
    gl_ready_ = false;
    context_lost_ = true;
    record_ = 0;
    state_dirty_ = targets_dirty_ = info_dirty_ = true;
    uniforms_uploaded_ = false;
    vaos_.clear();
    for (bool& stale : tex_stale_) stale = true;
    used_program_ = 0;
    active_unit_ = -1;
    bound_vao_ = 0;
    unpack_buffer_ = 0;
    out_buffer_ = 0;  // a buffer of the lost context: the caller sets one of the new context
}

}  // namespace drape::gles
