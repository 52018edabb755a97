// Pick-and-hold grabs on the GLES backend, without readback (GlesCloth members; the passes are
// shaders/grab.vert.glsl). The calls record what the finger does; the next step picks on the GPU
// (Cloth::grab's search drawn into a pick target of one texel per slot, the nearest kept by the
// depth test) and holds the picked particle as a moving pin: a grab pass at the start of every
// step while held sets its inverse mass to 0 and writes the pin targets the passes read, the
// finger unprojected at the depth it was picked at (Cloth::grab_move). A release restores the
// inverse mass and keeps the velocity (Cloth::grab_release). Which vertex was picked is never
// known on the CPU: drape_cloth_grab returns DRAPE_GRAB_ON_GPU. Tethers stay anchored to the pins
// (the CPU also anchors them to a grabbed vertex).
#include <cstring>

#include <glm/matrix.hpp>

#include "backend/gles/gles_cloth.h"

namespace drape::gles {

// ---- the calls: the touch's slot now (calling thread), the GL side's part as an edit ----------

uint32_t GlesCloth::grab(const drape_view& view, uint32_t touch_id, const float position[2], float pick_radius) {
    uint32_t slot = kMaxGrabs;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const Grab& g : ix_.grabs)
            if (g.touch_id == touch_id) slot = g.particle;  // a live id keeps its slot
        if (slot == kMaxGrabs) {
            bool used[kMaxGrabs] = {};
            for (const Grab& g : ix_.grabs) used[g.particle] = true;
            for (slot = 0; slot < kMaxGrabs && used[slot]; ++slot) {
            }
            if (slot == kMaxGrabs) return UINT32_MAX;  // the API allows kMaxGrabs: never
            ix_.grabs.push_back({touch_id, slot, 0.0});
        }
    }
    const glm::vec2 at(position[0], position[1]);
    edit(Access::NoState, [this, slot, view, at, pick_radius](Cloth&) {
        GpuGrab& g = gpu_grabs_[slot];
        if (g.held) g.release_pending = true;  // a live id releases what it held first
        g.held = false;
        g.pick_pending = true;
        g.moved = false;
        g.pick_view = view;
        g.pick_at = at;
        g.radius = pick_radius;
        wake();
    });
    return DRAPE_GRAB_ON_GPU;
}

bool GlesCloth::grab_move(const drape_view& view, uint32_t touch_id, const float position[2]) {
    uint32_t slot = kMaxGrabs;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const Grab& g : ix_.grabs)
            if (g.touch_id == touch_id) slot = g.particle;
    }
    if (slot == kMaxGrabs) return false;
    const glm::vec2 at(position[0], position[1]);
    edit(Access::NoState, [this, slot, view, at](Cloth&) {
        GpuGrab& g = gpu_grabs_[slot];
        if (!g.held && !g.pick_pending) return;  // its pick went with a lost context
        if (g.moved && g.at == at && std::memcmp(&g.view, &view, sizeof view) == 0) return;  // no move, no wake
        g.moved = true;
        g.view = view;
        g.at = at;
        wake();
    });
    return true;
}

void GlesCloth::grab_release(uint32_t touch_id) {
    uint32_t slot = kMaxGrabs;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (size_t k = 0; k < ix_.grabs.size(); ++k)
            if (ix_.grabs[k].touch_id == touch_id) {
                slot = ix_.grabs[k].particle;
                ix_.grabs.erase(ix_.grabs.begin() + long(k));
                break;
            }
    }
    if (slot == kMaxGrabs) return;  // unknown id
    edit(Access::NoState, [this, slot](Cloth&) {
        GpuGrab& g = gpu_grabs_[slot];
        if (g.held) g.release_pending = true;
        g.held = g.pick_pending = g.moved = false;
        wake();
    });
}

// ---- the step's part (GL thread, context current) ---------------------------------------------

Result GlesCloth::prepare_grabs() {
    bool work = false, pick = false;
    grabs_on_gpu_ = false;
    for (const GpuGrab& g : gpu_grabs_) {
        work = work || g.pick_pending || g.held || g.release_pending;
        pick = pick || g.pick_pending;
        grabs_on_gpu_ = grabs_on_gpu_ || g.pick_pending || g.held;
    }
    if (!work) return {};
    if (!grab_program_) {
        const std::string defines = "#define DRAPE_PASS_GRAB 1\n#define DRAPE_GRABS " + std::to_string(kMaxGrabs) + "\n";
        if (Result r = link_grab_program(defines, false, &grab_program_); !r.ok()) return r;
        grab_u_ = glGetUniformLocation(grab_program_, "u_grab");
        grab_uniforms_set_.clear();
    }
    if (!gl_.grab_targets) {
        glGenBuffers(1, &gl_.grab_targets);
        glBindBuffer(GL_ARRAY_BUFFER, gl_.grab_targets);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(topo_.particle_count) * sizeof(glm::vec3)), nullptr,
                     GL_DYNAMIC_COPY);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
    }
    if (pick && !pick_program_) {
        const std::string defines = "#define DRAPE_PASS_PICK 1\n#define DRAPE_GRABS " + std::to_string(kMaxGrabs) + "\n";
        if (Result r = link_grab_program(defines, true, &pick_program_); !r.ok()) return r;
        pick_u_ = glGetUniformLocation(pick_program_, "u_pick");
    }
    if (pick && !gl_.pick_fbo) {
        // One texel per slot: RGBA32UI colour (renderable in ES 3.0) and a float depth buffer.
        glGenTextures(1, &gl_.pick_tex);
        glActiveTexture(GL_TEXTURE0 + kPickUnit);
        glBindTexture(GL_TEXTURE_2D, gl_.pick_tex);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32UI, GLsizei(kMaxGrabs), 1);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        GLint rb = 0, fb = 0;
        glGetIntegerv(GL_RENDERBUFFER_BINDING, &rb);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
        glGenRenderbuffers(1, &gl_.pick_depth);
        glBindRenderbuffer(GL_RENDERBUFFER, gl_.pick_depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, GLsizei(kMaxGrabs), 1);
        glBindRenderbuffer(GL_RENDERBUFFER, GLuint(rb));
        glGenFramebuffers(1, &gl_.pick_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl_.pick_fbo);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, gl_.pick_tex, 0);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, gl_.pick_depth);
        const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(fb));
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return {DRAPE_ERROR_GL, "the grab pick target (RGBA32UI + DEPTH_COMPONENT32F) is incomplete on this GL"};
        pick_target_cleared_ = false;
    }
    return {};  // GL errors: the step's check
}

void GlesCloth::grab_pass(bool release) {
    // u_grab per slot (grab.vert.glsl): A, B of the finger's unprojection, (state, serial).
    grab_uniforms_.assign(3 * kMaxGrabs, glm::vec4(0.0f));
    for (uint32_t s = 0; s < kMaxGrabs; ++s) {
        GpuGrab& g = gpu_grabs_[s];
        float state = 0;
        if (g.held) state = g.moved ? 2.0f : 1.0f;
        else if (release && g.release_pending) state = 3.0f;
        if (release) g.release_pending = false;
        if (state == 0) continue;
        grab_uniforms_[3 * s + 2] = glm::vec4(state, float(g.serial), 0.0f, 0.0f);
        if (state == 2) {
            // drag.cpp from_screen at NDC depth z, split into two homogeneous points (in double,
            // with the cloth's origin as it is now): p(z) = inv_mvp (ndc, z, 1) = A + z B.
            const ScreenMapping m = make_screen_mapping(g.view, origin_);
            const glm::dvec2 ndc = glm::dvec2(g.at) / m.viewport * 2.0 - 1.0;
            grab_uniforms_[3 * s] = glm::vec4(m.inv_mvp * glm::dvec4(ndc, 0.0, 1.0));
            grab_uniforms_[3 * s + 1] = glm::vec4(m.inv_mvp[2]);
        }
    }
    if (used_program_ != grab_program_) {
        glUseProgram(grab_program_);
        used_program_ = grab_program_;
    }
    if (grab_uniforms_ != grab_uniforms_set_) {  // set only when a finger, slot or origin changed
        glUniform4fv(grab_u_, GLsizei(grab_uniforms_.size()), &grab_uniforms_[0].x);
        grab_uniforms_set_ = grab_uniforms_;
    }
    glActiveTexture(GL_TEXTURE0 + kPickUnit);
    glBindTexture(GL_TEXTURE_2D, gl_.pick_tex);
    active_unit_ = kPickUnit;
    // Positions (cur) -> spare, which becomes cur; targets -> gl_.grab_targets.
    const size_t n = topo_.particle_count;
    const GLuint vao = grab_vertex_array();
    glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, gl_.buffers[g_[2]], 0, GLsizeiptr(n * sizeof(Particle)));
    glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 1, gl_.grab_targets, 0, GLsizeiptr(n * sizeof(glm::vec3)));
    feedback_draw(vao, uint32_t(n), gl_.buffers[g_[2]], gl_.grab_targets);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 1, 0);
    tex_stale_[g_[2]] = true;
    std::swap(g_[0], g_[2]);
}

void GlesCloth::run_grabs() {
    bool hold = false, pick = false;
    for (const GpuGrab& g : gpu_grabs_) {
        hold = hold || g.held || g.release_pending;
        pick = pick || g.pick_pending;
    }
    // Releases first: a particle released now may be picked again now (Cloth::grab releases a
    // live id first); held ones are held again, so that the pick skips them.
    if (hold) grab_pass(true);
    if (!pick) return;
    // The caller's fragment state that the pick needs changed (the StateGuard restores framebuffer,
    // viewport and scissor).
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST), depth_mask = GL_TRUE, color_mask[4] = {};
    GLint depth_func = GL_LESS, framebuffer = 0;
    GLfloat depth_range[2] = {0.0f, 1.0f};
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func);
    glGetFloatv(GL_DEPTH_RANGE, depth_range);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl_.pick_fbo);
    glViewport(0, 0, GLsizei(kMaxGrabs), 1);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_RASTERIZER_DISCARD);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);  // the last of equally near particles wins, as in Cloth::grab's search
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthRangef(0.0f, 1.0f);
    if (!pick_target_cleared_) {  // serial 0 everywhere: no slot's pick yet
        const GLuint zero[4] = {};
        glClearBufferuiv(GL_COLOR, 0, zero);
        pick_target_cleared_ = true;
    }
    const GLfloat far = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far);
    glUseProgram(pick_program_);
    used_program_ = pick_program_;
    bind_vertex_array(grab_vertex_array());
    for (uint32_t s = 0; s < kMaxGrabs; ++s) {
        GpuGrab& g = gpu_grabs_[s];
        if (!g.pick_pending) continue;
        grab_serial_ = grab_serial_ % 0xFFFFFFu + 1;  // 1 .. 2^24 - 1: exact as a float uniform
        g.serial = grab_serial_;
        g.pick_pending = false;
        g.held = true;
        const ScreenMapping m = make_screen_mapping(g.pick_view, origin_);
        glm::vec4 u[6];
        for (int c = 0; c < 4; ++c) u[c] = glm::vec4(m.mvp[c]);
        u[4] = glm::vec4(g.pick_at, g.radius * g.radius, (2.0f * float(s) + 1.0f) / float(kMaxGrabs) - 1.0f);
        u[5] = glm::vec4(float(m.viewport.x), float(m.viewport.y), float(g.serial), 0.0f);
        glUniform4fv(pick_u_, 6, &u[0].x);
        glDrawArrays(GL_POINTS, 0, GLsizei(topo_.particle_count));
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(framebuffer));
    glEnable(GL_RASTERIZER_DISCARD);
    if (!depth_test) glDisable(GL_DEPTH_TEST);
    glDepthFunc(GLenum(depth_func));
    glDepthMask(depth_mask);
    glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
    glDepthRangef(depth_range[0], depth_range[1]);
    grab_pass(false);  // hold what the picks found from this step on
}

void GlesCloth::drop_gpu_grabs() {
    bool held = false;
    for (GpuGrab& g : gpu_grabs_) {
        held = held || g.held || g.release_pending;
        g.held = g.release_pending = false;  // a pending pick is still to be made
    }
    grabs_on_gpu_ = false;
    grab_program_ = pick_program_ = 0;
    grab_uniforms_set_.clear();
    pick_target_cleared_ = false;
    if (!held) return;
    // A readback may have copied a held particle's inverse mass 0: the CPU's again.
    for (uint32_t i = 0; i < topo_.particle_count; ++i) x_[i].w = d_[i].w = pinned_[i] ? 0.0f : base_inverse_mass_[i];
}

}  // namespace drape::gles
