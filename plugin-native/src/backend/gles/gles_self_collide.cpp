#include "backend/gles/gles_self_collide.h"

#include <cstring>
#include <string>
#include <vector>

#include "backend/gles/gles_cloth.h"
#include "backend/gles/shaders.h"  // generated from shaders/*.glsl
#include "core/self_collision.h"   // kSelfExcludeRest

namespace drape::gles {
namespace {

/// Sampler units of the collide pass's textures beyond the simulation's (set once at link).
constexpr int kVertexUnits = 5 + int(kSelfLayers);  // u_x, u_aux, u_nbr, u_info, u_rest, layers

/// The limits the self-collide passes rely on beyond the backend's (gles_cloth.cpp check_limits),
/// all within OpenGL ES 3.0's guaranteed minimums (after //).
Result check_self_limits(uint32_t rows) {
    const struct {
        GLenum name;
        const char* label;
        GLint need;
    } limits[] = {
        {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", kVertexUnits},  // 16
        {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS",
         kSelfLayerUnit0 + GLint(kSelfLayers)},                                                   // 32: units 0..16
        {GL_MAX_TEXTURE_IMAGE_UNITS, "GL_MAX_TEXTURE_IMAGE_UNITS", 1},                         // 16: u_prev
        {GL_MAX_COLOR_ATTACHMENTS, "GL_MAX_COLOR_ATTACHMENTS", 1},                             // 4
        {GL_MAX_DRAW_BUFFERS, "GL_MAX_DRAW_BUFFERS", 1},                                       // 4
        {GL_MAX_TEXTURE_SIZE, "GL_MAX_TEXTURE_SIZE", GLint(rows)},                             // 2048: hash rows
    };
    auto below = [](const char* label, GLint have, GLint need) {
        return Result{DRAPE_ERROR_BACKEND_UNAVAILABLE,
                      std::string("this OpenGL ES device offers ") + label + " = " + std::to_string(have) +
                          ", self-collision on the GLES backend needs at least " + std::to_string(need) +
                          " (OpenGL ES 3.0 guarantees that)"};
    };
    for (const auto& l : limits) {
        GLint have = 0;
        glGetIntegerv(l.name, &have);
        if (have < l.need) return below(l.label, have, l.need);
    }
    GLint viewport[2] = {};  // the hash layers are drawn whole
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    if (viewport[0] < GLint(kTexWidth)) return below("GL_MAX_VIEWPORT_DIMS width", viewport[0], GLint(kTexWidth));
    if (viewport[1] < GLint(rows)) return below("GL_MAX_VIEWPORT_DIMS height", viewport[1], GLint(rows));
    float points[2] = {};  // one texel per particle: points of size 1
    glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, points);
    if (!(points[0] <= 1.0f && points[1] >= 1.0f))
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "this OpenGL ES device cannot draw points of size 1 "
                                                 "(GL_ALIASED_POINT_SIZE_RANGE), which self-collision on the GLES "
                                                 "backend needs (OpenGL ES 3.0 guarantees it)"};
    GLint range[2] = {}, precision = 0;  // particle indices compared in the fragment stage
    glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_HIGH_INT, range, &precision);
    if (range[0] < 31 || range[1] < 30)
        return {DRAPE_ERROR_BACKEND_UNAVAILABLE, "this OpenGL ES device's fragment-stage highp int has a range of 2^" +
                                                     std::to_string(range[1]) +
                                                     ", self-collision on the GLES backend needs 32-bit integers (as "
                                                     "OpenGL ES 3.0 guarantees)"};
    return {};
}

Result make_objects(GlObjects& gl, uint32_t n, uint32_t slots, const std::vector<glm::vec3>& rest) {
    SelfCollideGl& o = gl.self;
    // Buckets: a power of two >= 4n (few cells share one: each holds only kSelfLayers), whole rows.
    uint32_t buckets = kTexWidth;
    while (buckets < 4 * n) buckets *= 2;
    const uint32_t rows = buckets / kTexWidth;
    if (Result r = check_self_limits(rows); !r.ok()) return r;
    for (uint32_t k = 0; k < kSelfLayers; ++k) {
        o.layers[k] = make_texture(GL_R32UI, rows);
        glGenFramebuffers(1, &o.fbos[k]);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, o.fbos[k]);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, o.layers[k], 0);
        if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return {DRAPE_ERROR_BACKEND_UNAVAILABLE,
                    "self-collision on the GLES backend: this device cannot draw into an R32UI texture (OpenGL ES 3.0 "
                    "guarantees it)"};
    }
    o.rows = rows;
    std::vector<uint32_t> texels(size_t(n) * 4, 0u);
    for (uint32_t i = 0; i < n; ++i) std::memcpy(&texels[4 * size_t(i)], &rest[i], sizeof(glm::vec3));
    const uint32_t rest_rows = rows_for(n);
    o.rest = make_texture(GL_RGBA32UI, rest_rows);
    upload_uint_texture(o.rest, gl.staging, rest_rows, texels);

    // Programs. The hash: layer 0, later layers (DRAPE_PEEL); the collide pass (two outputs).
    auto with = [](const char* source, const std::string& defines) {
        std::string s(source);
        const size_t eol = s.find('\n');
        return s.substr(0, eol + 1) + defines + s.substr(eol + 1);
    };
    const std::vector<std::pair<GLuint, const char*>> attribs{{0, "a_x"}, {1, "a_aux"}};
    const std::string peel_fs = with(shaders::self_hash_frag, "#define DRAPE_PEEL 1\n");
    if (Result r = link(shaders::self_hash_vert, "self_hash.vert.glsl", {}, GL_INTERLEAVED_ATTRIBS, attribs,
                        &o.first, shaders::self_hash_frag, "self_hash.frag.glsl");
        !r.ok())
        return r;
    gl.programs.push_back(o.first);
    if (Result r = link(shaders::self_hash_vert, "self_hash.vert.glsl", {}, GL_INTERLEAVED_ATTRIBS, attribs,
                        &o.peel, peel_fs.c_str(), "self_hash.frag.glsl");
        !r.ok())
        return r;
    gl.programs.push_back(o.peel);
    o.u_prev = glGetUniformLocation(o.peel, "u_prev");
    const std::string collide_defines = "#define DRAPE_SLOTS " + std::to_string(slots) +
                                        "\n#define DRAPE_SELF_LAYERS " + std::to_string(kSelfLayers) + "\n";
    if (Result r = link(with(shaders::self_collide_vert, collide_defines), "self_collide.vert.glsl", {"v_x", "v_d"},
                        GL_SEPARATE_ATTRIBS, attribs, &o.collide);
        !r.ok())
        return r;
    gl.programs.push_back(o.collide);
    o.u_collide_x = glGetUniformLocation(o.collide, "u_x");
    o.u_collide_aux = glGetUniformLocation(o.collide, "u_aux");
    glUseProgram(o.collide);  // samplers of the own textures, fixed
    glUniform1i(glGetUniformLocation(o.collide, "u_rest"), kSelfRestUnit);
    for (uint32_t k = 0; k < kSelfLayers; ++k)
        glUniform1i(glGetUniformLocation(o.collide, ("u_layer" + std::to_string(k)).c_str()), kSelfLayerUnit0 + GLint(k));
    return gl_error("creating the GLES self-collision objects");
}

}  // namespace

void delete_self_collide_gl(SelfCollideGl& o) {
    glDeleteTextures(GLsizei(kSelfLayers), o.layers);
    glDeleteFramebuffers(GLsizei(kSelfLayers), o.fbos);
    glDeleteTextures(1, &o.rest);
    o = SelfCollideGl{};  // programs are in GlObjects::programs
}

Result GlesSelfCollide::prepare(GlesCloth& c) {
    SelfCollideGl& o = c.gl_.self;
    if (!o.collide) {
        GLint fbo = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
        Result r = make_objects(c.gl_, c.topo_.particle_count, c.topo_.nbr.slots, c.topo_.rest_position);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(fbo));
        c.used_program_ = 0;
        if (!r.ok()) {
            delete_self_collide_gl(c.gl_.self);  // made again, checked again, at the next step
            return r;
        }
    }
    const SelfCollision& s = c.sc_;
    if (s.thickness != o.thickness || s.friction != o.friction) {
        // The setting's uniforms (a new setting; never on a steady frame).
        const float cell = kSelfCellGles * s.thickness;  // also the collide pass's reach
        const float inv_cell = 1.0f / cell;
        const GLint mask = GLint(kTexWidth * o.rows - 1);
        const float exclude = kSelfExcludeRest * s.thickness;
        for (GLuint p : {o.first, o.peel, o.collide}) {
            glUseProgram(p);
            glUniform1f(glGetUniformLocation(p, "u_inv_cell"), inv_cell);
            glUniform1i(glGetUniformLocation(p, "u_mask"), mask);
        }
        for (GLuint p : {o.first, o.peel}) {
            glUseProgram(p);
            glUniform2f(glGetUniformLocation(p, "u_texel_ndc"), 2.0f / float(kTexWidth), 2.0f / float(o.rows));
        }
        glUseProgram(o.collide);
        const float contact[4] = {s.thickness, exclude * exclude, s.friction, cell * cell};
        glUniform4fv(glGetUniformLocation(o.collide, "u_contact"), 1, contact);
        o.thickness = s.thickness;
        o.friction = s.friction;
        c.used_program_ = 0;
    }
    return gl_error("preparing GLES self-collision");
}

GlesSelfCollide::StepScope::StepScope(GlesCloth& c) : c_(c) {
    const SelfCollideGl& o = c.gl_.self;
    glGetBooleanv(GL_COLOR_WRITEMASK, mask_);
    for (int u = 0; u <= int(kSelfLayers); ++u) {
        glActiveTexture(GL_TEXTURE0 + GLenum(kSelfRestUnit + u));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &saved_[u]);
        glBindTexture(GL_TEXTURE_2D, u == 0 ? o.rest : o.layers[u - 1]);
    }
    c.active_unit_ = kSelfRestUnit + int(kSelfLayers);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);  // restored by the step's StateGuard, with the viewport
    glViewport(0, 0, GLsizei(kTexWidth), GLsizei(o.rows));
}

GlesSelfCollide::StepScope::~StepScope() {
    for (int u = 0; u <= int(kSelfLayers); ++u) {
        glActiveTexture(GL_TEXTURE0 + GLenum(kSelfRestUnit + u));
        glBindTexture(GL_TEXTURE_2D, GLuint(saved_[u]));
    }
    c_.active_unit_ = kSelfRestUnit + int(kSelfLayers);
    glColorMask(mask_[0], mask_[1], mask_[2], mask_[3]);
}

void GlesSelfCollide::run(GlesCloth& c, int x, int d, int out_x, int out_d) {
    SelfCollideGl& o = c.gl_.self;
    const GLsizei n = GLsizei(c.topo_.particle_count);
    const GLuint vao = c.vertex_array(x, d, 0);
    c.bind_outputs(out_x, out_d);  // before the hash reads x and d (GlesCloth::bind_outputs)
    // Hash: the particles as points, layer by layer, into the layer textures.
    glDisable(GL_RASTERIZER_DISCARD);
    c.bind_vertex_array(vao);
    static const GLuint kEmpty[4] = {0, 0, 0, 0};
    for (uint32_t k = 0; k < kSelfLayers; ++k) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, o.fbos[k]);
        glClearBufferuiv(GL_COLOR, 0, kEmpty);
        if (k <= 1) glUseProgram(k == 0 ? o.first : o.peel);
        if (k >= 1) glUniform1i(o.u_prev, kSelfLayerUnit0 + GLint(k) - 1);
        glDrawArrays(GL_POINTS, 0, n);
    }
    // Back to a target that no pass samples (a layer attached while the collide pass reads it would
    // be a feedback loop, even with the rasterizer off).
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, c.own_framebuffer());
    glEnable(GL_RASTERIZER_DISCARD);
    // Collide: x, d -> out_x, out_d.
    glUseProgram(o.collide);
    c.used_program_ = o.collide;
    if (o.unit_x != x) {
        glUniform1i(o.u_collide_x, x);  // particle texture b lives on unit b (GlesCloth::begin_passes)
        o.unit_x = x;
    }
    if (o.unit_aux != d) {
        glUniform1i(o.u_collide_aux, d);
        o.unit_aux = d;
    }
    c.draw(vao, out_x, out_d, x, d);
}

}  // namespace drape::gles
