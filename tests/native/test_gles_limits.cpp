// The GLES backend checks every OpenGL ES limit it relies on when a cloth starts, and refuses a
// device below one with DRAPE_ERROR_BACKEND_UNAVAILABLE and a message naming the limit. Mesa meets
// ES 3.0's minimums, so the test lowers one limit at a time: it swaps the library's
// glGetIntegerv (or glGetShaderPrecisionFormat) for one that reports less (drape_gl_replace).
#include <GLES3/gl3.h>

#include <string>

#include "drape_test_util.h"
#include "gles_test_util.h"

using namespace drape_test;

namespace {

PFNGLGETINTEGERVPROC g_real_get_integer = nullptr;
GLenum g_lowered = 0;
GLint g_lowered_to = 0;
/// One limit glGetIntegerv reports lowered, and the name the library's refusal must give it.
struct LoweredLimit {
    GLenum name;
    const char* label;
    GLint value;
    void apply() const { g_lowered = name, g_lowered_to = value; }
    /// The refusal names the limit and the value it saw.
    bool named_in(const std::string& message) const {
        return message.find(std::string(label) + " = " + std::to_string(value)) != std::string::npos;
    }
};
void GL_APIENTRY get_integer_lowered(GLenum name, GLint* out) {
    g_real_get_integer(name, out);
    if (name == g_lowered) *out = g_lowered_to;
}

PFNGLGETSHADERPRECISIONFORMATPROC g_real_precision = nullptr;
void GL_APIENTRY precision_mediump_only(GLenum stage, GLenum type, GLint* range, GLint* precision) {
    g_real_precision(stage, type, range, precision);
    if (stage == GL_VERTEX_SHADER && type == GL_HIGH_FLOAT) *precision = 10;  // what mediump guarantees
}

/// Puts the library's real entry point back at the end of the scope.
struct Restore {
    const char* name;
    void* real;
    ~Restore() { drape_gl_replace(name, real); }
};

class GlesLimits : public WithHeadlessGles<> {
protected:
    /// Status of creating a 4x4 GLES cloth; the message in *message.
    drape_status create(std::string* message) {
        WorldPtr w = make_world(1);
        drape_cloth_desc d{sizeof d, DRAPE_BACKEND_GLES, 1.0f};
        const drape_grid_desc g = grid_desc(4, 4, 1.0f, 1.0f);
        drape_cloth* c = nullptr;
        const drape_status s = drape_cloth_create_grid(w.get(), &d, &g, &c);
        *message = s == DRAPE_OK ? "" : drape_last_error();
        EXPECT_EQ(c == nullptr, s != DRAPE_OK);
        return s;
    }
};

}  // namespace

TEST_F(GlesLimits, ADeviceBelowALimitIsRefusedByName) {
    g_real_get_integer =
        reinterpret_cast<PFNGLGETINTEGERVPROC>(drape_gl_replace("glGetIntegerv", reinterpret_cast<void*>(&get_integer_lowered)));
    ASSERT_NE(g_real_get_integer, nullptr);
    Restore restore{"glGetIntegerv", reinterpret_cast<void*>(g_real_get_integer)};
    // One below what the backend needs (an ES 2 class device has no vertex texture units at all).
    const LoweredLimit lowered[] = {
        {GL_MAX_TEXTURE_SIZE, "GL_MAX_TEXTURE_SIZE", 1023},
        {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", 0},
        {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", 7},
        {GL_MAX_VERTEX_ATTRIBS, "GL_MAX_VERTEX_ATTRIBS", 15},
        {GL_MAX_VERTEX_OUTPUT_COMPONENTS, "GL_MAX_VERTEX_OUTPUT_COMPONENTS", 63},
        {GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS, "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS", 1},
        {GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_COMPONENTS, "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_COMPONENTS", 3},
        {GL_MAX_TRANSFORM_FEEDBACK_INTERLEAVED_COMPONENTS, "GL_MAX_TRANSFORM_FEEDBACK_INTERLEAVED_COMPONENTS", 63},
        {GL_MAX_VERTEX_UNIFORM_VECTORS, "GL_MAX_VERTEX_UNIFORM_VECTORS", 83},
        {GL_MAX_VERTEX_UNIFORM_BLOCKS, "GL_MAX_VERTEX_UNIFORM_BLOCKS", 0},
        {GL_MAX_UNIFORM_BLOCK_SIZE, "GL_MAX_UNIFORM_BLOCK_SIZE", 64},
    };
    std::string message;
    for (const auto& l : lowered) {
        l.apply();
        EXPECT_EQ(create(&message), DRAPE_ERROR_BACKEND_UNAVAILABLE) << l.label;
        EXPECT_TRUE(l.named_in(message)) << message;
    }
    // The real device (Mesa, ES 3.0 minimums and more) is accepted.
    g_lowered = 0;
    EXPECT_DRAPE_OK(create(&message));
}

TEST_F(GlesLimits, ADeviceWithoutFullPrecisionHighpIsRefused) {
    g_real_precision = reinterpret_cast<PFNGLGETSHADERPRECISIONFORMATPROC>(
        drape_gl_replace("glGetShaderPrecisionFormat", reinterpret_cast<void*>(&precision_mediump_only)));
    ASSERT_NE(g_real_precision, nullptr);
    Restore restore{"glGetShaderPrecisionFormat", reinterpret_cast<void*>(g_real_precision)};
    std::string message;
    EXPECT_EQ(create(&message), DRAPE_ERROR_BACKEND_UNAVAILABLE);
    EXPECT_NE(message.find("highp float has 10 bits"), std::string::npos) << message;
}

TEST_F(GlesLimits, ReplacingAnEntryPointTheLibraryDoesNotUseChangesNothing) {
    EXPECT_EQ(drape_gl_replace("glNotAFunction", reinterpret_cast<void*>(&get_integer_lowered)), nullptr);
    EXPECT_EQ(drape_gl_replace(nullptr, nullptr), nullptr);
    std::string message;
    EXPECT_DRAPE_OK(create(&message));
}

// Self-collision needs more than a cloth without it (13 vertex texture units for its hash layers,
// 17 texture units in all, ...): a device below one of those still runs cloths, but the first step
// with self-collision on fails with the limit's name, and the cloth steps again once it is off.
TEST_F(GlesLimits, SelfCollisionBelowALimitFailsItsStepByName) {
    g_real_get_integer =
        reinterpret_cast<PFNGLGETINTEGERVPROC>(drape_gl_replace("glGetIntegerv", reinterpret_cast<void*>(&get_integer_lowered)));
    ASSERT_NE(g_real_get_integer, nullptr);
    Restore restore{"glGetIntegerv", reinterpret_cast<void*>(g_real_get_integer)};
    const LoweredLimit lowered[] = {
        {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", 12},
        {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", 16},
        {GL_MAX_COLOR_ATTACHMENTS, "GL_MAX_COLOR_ATTACHMENTS", 0},
        {GL_MAX_DRAW_BUFFERS, "GL_MAX_DRAW_BUFFERS", 0},
        {GL_MAX_TEXTURE_IMAGE_UNITS, "GL_MAX_TEXTURE_IMAGE_UNITS", 0},
    };
    for (const auto& l : lowered) {
        l.apply();
        WorldPtr w = make_world(1);
        drape_cloth* c = make_grid(w.get(), grid_desc(8, 8, 0.5f, 0.5f), 0.1f, DRAPE_BACKEND_GLES);
        ASSERT_NE(c, nullptr) << l.label;
        EXPECT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60)) << l.label;
        drape_self_collision_desc sc{};
        sc.struct_size = sizeof sc;
        sc.enabled = 1;
        sc.thickness = 0.05f;
        ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
        EXPECT_EQ(drape_cloth_step(c, 1.0f / 60), DRAPE_ERROR_BACKEND_UNAVAILABLE) << l.label;
        const std::string message = drape_last_error();
        EXPECT_TRUE(l.named_in(message)) << message;
        EXPECT_NE(message.find("self-collision"), std::string::npos) << message;
        sc.enabled = 0;
        ASSERT_DRAPE_OK(drape_cloth_set_self_collision(c, &sc));
        EXPECT_DRAPE_OK(drape_cloth_step(c, 1.0f / 60)) << l.label;
    }
    g_lowered = 0;
}
