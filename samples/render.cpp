// Headless pictures of the demo scenes with the GLES backend: each cloth's simulation
// writes positions + normals straight into the vertex buffer that is drawn (no CPU copy); frames
// are rendered offscreen on Mesa (surfaceless EGL), saved as PNG (stb_image_write), and ImageMagick
// turns each scene into an animated GIF.  Usage: drape_render [out_dir=demo-out] [frames=90]
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "drape/drape.h"

namespace {

constexpr int kWidth = 480, kHeight = 360;

#define CHECK(call)                                                                         \
    do {                                                                                    \
        drape_status s_ = (call);                                                           \
        if (s_ != DRAPE_OK) {                                                               \
            std::fprintf(stderr, "%s failed (%d): %s\n", #call, int(s_), drape_last_error()); \
            std::exit(1);                                                                   \
        }                                                                                   \
    } while (0)

const char* kVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_mvp;
out vec3 v_normal;
out vec3 v_world;
void main() { v_normal = a_normal; v_world = a_position; gl_Position = u_mvp * vec4(a_position, 1.0); }
)";
const char* kFs = R"(#version 300 es
precision mediump float;
in vec3 v_normal;
in vec3 v_world;
uniform vec3 u_color;
uniform vec3 u_eye;
out vec4 o_color;
void main() {
    vec3 n = normalize(v_normal);
    if (dot(n, u_eye - v_world) < 0.0) n = -n;  // two-sided cloth
    vec3 l = normalize(vec3(0.4, 0.9, 0.6));
    float diffuse = max(dot(n, l), 0.0);
    // pow() is undefined below 0: a rounding |n| > 1 gave NaN (black) specks in folds.
    float rim = pow(clamp(1.0 - dot(n, normalize(u_eye - v_world)), 0.0, 1.0), 3.0);
    // Checker by world position shows the folds.
    float check = mod(floor(v_world.x * 8.0) + floor(v_world.y * 8.0) + floor(v_world.z * 8.0), 2.0);
    vec3 base = u_color * (0.85 + 0.15 * check);
    o_color = vec4(base * (0.25 + 0.75 * diffuse) + 0.15 * rim, 1.0);
}
)";

GLuint compile(GLenum stage, const char* src) {
    GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        std::fprintf(stderr, "shader: %s\n", log);
        std::exit(1);
    }
    return s;
}

struct Scene {
    const char* name;
    uint32_t cols, rows;
    drape_grid_desc grid;
    std::vector<drape_pin> pins;
    drape_params params;
    glm::vec3 color, eye, target;
};

Scene hanging() {
    Scene s{"hanging", 32, 32, {}, {}, {}, {0.85f, 0.3f, 0.25f}, {0.5f, 1.0f, 2.2f}, {0.5f, 0.55f, -0.3f}};
    s.grid = {sizeof(drape_grid_desc), s.cols, s.rows, 1.0f, 1.0f, {0, 1.2f, 0}, {1, 0, 0}, {0, 0, -1}};
    s.pins = {{sizeof(drape_pin), 0, {0, 1.2f, 0}}, {sizeof(drape_pin), s.cols - 1, {1, 1.2f, 0}}};
    drape_params_default(&s.params);
    return s;
}

Scene curtain() {
    Scene s{"curtain", 40, 30, {}, {}, {}, {0.25f, 0.45f, 0.85f}, {0.6f, 0.6f, 2.6f}, {0.6f, 0.5f, 0.0f}};
    s.grid = {sizeof(drape_grid_desc), s.cols, s.rows, 1.2f, 1.0f, {0, 1.1f, 0}, {1, 0, 0}, {0, -1, 0}};
    for (uint32_t c = 0; c < s.cols; c += 3)
        s.pins.push_back({sizeof(drape_pin), c, {1.2f * float(c) / float(s.cols - 1) * 0.8f, 1.1f, 0}});
    drape_params_default(&s.params);
    s.params.wind[2] = 2.5f;
    s.params.air_drag = 0.6f;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string out = argc > 1 ? argv[1] : "demo-out";
    const int frames = argc > 2 ? std::atoi(argv[2]) : 90;
    std::system(("mkdir -p '" + out + "'").c_str());
    // Mesa 22.3's llvmpipe rasterizer threads race on a freed fence (tests/native/gles_test_util.h):
    // render on this thread unless the run asks otherwise. A hardware driver ignores it.
    setenv("LP_NUM_THREADS", "0", 0);

    auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr) : EGL_NO_DISPLAY;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) {
        std::fprintf(stderr, "drape_render: no surfaceless EGL display\n");
        return 1;
    }
    eglBindAPI(EGL_OPENGL_ES_API);
    const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n);
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = n ? eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr) : EGL_NO_CONTEXT;
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        std::fprintf(stderr, "drape_render: no GLES 3 context\n");
        return 1;
    }
    // Offscreen target with depth.
    GLuint fbo, color_rb, depth_rb;
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &color_rb);
    glGenRenderbuffers(1, &depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kWidth, kHeight);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    GLuint prog = glCreateProgram();
    glAttachShader(prog, compile(GL_VERTEX_SHADER, kVs));
    glAttachShader(prog, compile(GL_FRAGMENT_SHADER, kFs));
    glLinkProgram(prog);

    drape_world_desc wd{sizeof wd, 1};
    drape_world* world = nullptr;
    CHECK(drape_world_create(&wd, &world));
    std::printf("drape_render: %s, %d frames per scene -> %s/\n", glGetString(GL_RENDERER), frames, out.c_str());
    for (Scene scene : {hanging(), curtain()}) {
        drape_cloth_desc cd{sizeof cd, DRAPE_BACKEND_GLES, 0.3f};
        drape_cloth* cloth = nullptr;
        CHECK(drape_cloth_create_grid(world, &cd, &scene.grid, &cloth));
        CHECK(drape_cloth_set_params(cloth, &scene.params));
        CHECK(drape_cloth_set_pins(cloth, scene.pins.data(), uint32_t(scene.pins.size())));
        const uint32_t verts = scene.cols * scene.rows;
        // The vertex buffer the simulation writes and the renderer draws (Unity's mesh buffer).
        GLuint vao, vbo, ibo;
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &vbo);
        glGenBuffers(1, &ibo);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(verts * 24), nullptr, GL_DYNAMIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, reinterpret_cast<void*>(12));
        std::vector<uint32_t> idx;
        for (uint32_t r = 0; r + 1 < scene.rows; ++r)
            for (uint32_t c = 0; c + 1 < scene.cols; ++c) {
                const uint32_t a = r * scene.cols + c, b = a + 1, d = a + scene.cols, e = d + 1;
                idx.insert(idx.end(), {a, d, b, b, d, e});
            }
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(idx.size() * 4), idx.data(), GL_STATIC_DRAW);
        glBindVertexArray(0);
        const drape_vertex_layout layout{sizeof layout, 24, 0, 12};
        CHECK(drape_cloth_set_output_buffer(cloth, vbo, &layout));

        const glm::mat4 mvp = glm::perspective(glm::radians(45.0f), float(kWidth) / kHeight, 0.05f, 20.0f) *
                              glm::lookAt(scene.eye, scene.target, glm::vec3(0, 1, 0));
        std::vector<uint8_t> pixels(size_t(kWidth) * kHeight * 4);
        double step_ms = 0;
        for (int f = 0; f < frames; ++f) {
            const auto t0 = std::chrono::steady_clock::now();
            CHECK(drape_cloth_step(cloth, 1.0f / 60));
            glFinish();  // timing only: wait for llvmpipe to finish the step
            step_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, kWidth, kHeight);
            glEnable(GL_DEPTH_TEST);
            glClearColor(0.93f, 0.94f, 0.96f, 1);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glUseProgram(prog);
            glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
            glUniform3fv(glGetUniformLocation(prog, "u_color"), 1, glm::value_ptr(scene.color));
            glUniform3fv(glGetUniformLocation(prog, "u_eye"), 1, glm::value_ptr(scene.eye));
            glBindVertexArray(vao);
            glDrawElements(GL_TRIANGLES, GLsizei(idx.size()), GL_UNSIGNED_INT, nullptr);
            glBindVertexArray(0);
            // Picture only (not the simulation path): read the rendered frame.
            glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
            char path[512];
            std::snprintf(path, sizeof path, "%s/%s_%03d.png", out.c_str(), scene.name, f);
            stbi_flip_vertically_on_write(1);
            if (!stbi_write_png(path, kWidth, kHeight, 4, pixels.data(), kWidth * 4)) {
                std::fprintf(stderr, "cannot write %s\n", path);
                return 1;
            }
        }
        std::printf("  %-8s %ux%u vertices, GLES step + glFinish: %.2f ms/frame (llvmpipe)\n", scene.name, scene.cols,
                    scene.rows, step_ms / frames);
        const std::string gif = out + "/" + scene.name + ".gif";
        const std::string cmd = "convert -delay 3 -loop 0 '" + out + "/" + scene.name + "_*.png' '" + gif + "'";
        if (std::system(cmd.c_str()) == 0)
            std::printf("  wrote %s\n", gif.c_str());
        else
            std::fprintf(stderr, "  ImageMagick convert failed; PNG frames are in %s\n", out.c_str());
        CHECK(drape_cloth_destroy(cloth));
        glDeleteBuffers(1, &vbo);
        glDeleteBuffers(1, &ibo);
        glDeleteVertexArrays(1, &vao);
    }
    CHECK(drape_world_destroy(world));
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return 0;
}
