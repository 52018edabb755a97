// OpenGL ES 3.0 and EGL entry points of the GLES backend, loaded at run time (dlopen of the
// system's GLES and EGL libraries + dlsym, eglGetProcAddress as fallback), so that libdrape and
// the Unity source plug-in link against no GL library at build time.
//
// The entry points live in namespace drape::gles under the GL names, so the backend's unqualified
// calls (glBindBuffer(...)) reach them and not the global prototypes. Each one counts its calls
// (one relaxed atomic add; drape_gl_call_count reads them for tests and the bench, which check
// that a steady frame reads nothing back and uploads nothing). No prototypes are declared
// (GL_GLES_PROTOTYPES 0, EGL_EGL_PROTOTYPES 0): a GL function missing from the lists below is a
// compile error in the backend ("was not declared"); add it here, with its PFN type.
//
// Loading happens on the first eglGetCurrentContext() call, which every GL path makes first
// (context_current, release_gl). If a library or a function is missing, eglGetCurrentContext()
// keeps returning EGL_NO_CONTEXT, so the GLES backend reports itself unavailable; load_error()
// says why.
#pragma once

#ifndef GL_GLES_PROTOTYPES
#define GL_GLES_PROTOTYPES 0
#endif
#ifndef EGL_EGL_PROTOTYPES
#define EGL_EGL_PROTOTYPES 0
#endif
#include <EGL/egl.h>
#include <GLES3/gl3.h>

#include <atomic>
#include <cstdint>

#define DRAPE_GL_FUNCTIONS(X) \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture) \
  X(PFNGLATTACHSHADERPROC, glAttachShader) \
  X(PFNGLBEGINQUERYPROC, glBeginQuery) \
  X(PFNGLBEGINTRANSFORMFEEDBACKPROC, glBeginTransformFeedback) \
  X(PFNGLBINDATTRIBLOCATIONPROC, glBindAttribLocation) \
  X(PFNGLBINDBUFFERPROC, glBindBuffer) \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase) \
  X(PFNGLBINDBUFFERRANGEPROC, glBindBufferRange) \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer) \
  X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer) \
  X(PFNGLBINDTEXTUREPROC, glBindTexture) \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) \
  X(PFNGLBUFFERDATAPROC, glBufferData) \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData) \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus) \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv) \
  X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv) \
  X(PFNGLCOLORMASKPROC, glColorMask) \
  X(PFNGLCOMPILESHADERPROC, glCompileShader) \
  X(PFNGLCOPYBUFFERSUBDATAPROC, glCopyBufferSubData) \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram) \
  X(PFNGLCREATESHADERPROC, glCreateShader) \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers) \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers) \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram) \
  X(PFNGLDELETEQUERIESPROC, glDeleteQueries) \
  X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers) \
  X(PFNGLDELETESHADERPROC, glDeleteShader) \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures) \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays) \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc) \
  X(PFNGLDEPTHMASKPROC, glDepthMask) \
  X(PFNGLDEPTHRANGEFPROC, glDepthRangef) \
  X(PFNGLDISABLEPROC, glDisable) \
  X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, glDisableVertexAttribArray) \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays) \
  X(PFNGLENABLEPROC, glEnable) \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray) \
  X(PFNGLENDQUERYPROC, glEndQuery) \
  X(PFNGLENDTRANSFORMFEEDBACKPROC, glEndTransformFeedback) \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer) \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D) \
  X(PFNGLGENBUFFERSPROC, glGenBuffers) \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers) \
  X(PFNGLGENQUERIESPROC, glGenQueries) \
  X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers) \
  X(PFNGLGENTEXTURESPROC, glGenTextures) \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays) \
  X(PFNGLGETACTIVEUNIFORMBLOCKIVPROC, glGetActiveUniformBlockiv) \
  X(PFNGLGETACTIVEUNIFORMSIVPROC, glGetActiveUniformsiv) \
  X(PFNGLGETBOOLEANVPROC, glGetBooleanv) \
  X(PFNGLGETBUFFERPARAMETERIVPROC, glGetBufferParameteriv) \
  X(PFNGLGETERRORPROC, glGetError) \
  X(PFNGLGETFLOATVPROC, glGetFloatv) \
  X(PFNGLGETINTEGERI_VPROC, glGetIntegeri_v) \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv) \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog) \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv) \
  X(PFNGLGETQUERYOBJECTUIVPROC, glGetQueryObjectuiv) \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog) \
  X(PFNGLGETSHADERPRECISIONFORMATPROC, glGetShaderPrecisionFormat) \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv) \
  X(PFNGLGETSTRINGPROC, glGetString) \
  X(PFNGLGETUNIFORMBLOCKINDEXPROC, glGetUniformBlockIndex) \
  X(PFNGLGETUNIFORMINDICESPROC, glGetUniformIndices) \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation) \
  X(PFNGLISBUFFERPROC, glIsBuffer) \
  X(PFNGLISENABLEDPROC, glIsEnabled) \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram) \
  X(PFNGLMAPBUFFERRANGEPROC, glMapBufferRange) \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei) \
  X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage) \
  X(PFNGLSHADERSOURCEPROC, glShaderSource) \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri) \
  X(PFNGLTEXSTORAGE2DPROC, glTexStorage2D) \
  X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D) \
  X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, glTransformFeedbackVaryings) \
  X(PFNGLUNIFORM1FPROC, glUniform1f) \
  X(PFNGLUNIFORM1IPROC, glUniform1i) \
  X(PFNGLUNIFORM2FPROC, glUniform2f) \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv) \
  X(PFNGLUNIFORM4FVPROC, glUniform4fv) \
  X(PFNGLUNIFORMBLOCKBINDINGPROC, glUniformBlockBinding) \
  X(PFNGLUNMAPBUFFERPROC, glUnmapBuffer) \
  X(PFNGLUSEPROGRAMPROC, glUseProgram) \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer) \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer) \
  X(PFNGLVIEWPORTPROC, glViewport) \

namespace drape::gles {

/// One GL ES entry point: the driver's function and how often it was called.
template <typename Fn>
struct GlEntry;
template <typename R, typename... A>
struct GlEntry<R(GL_APIENTRYP)(A...)> {
    R(GL_APIENTRYP fn)(A...) = nullptr;
    std::atomic<uint64_t> calls{0};
    R operator()(A... a) {
        calls.fetch_add(1, std::memory_order_relaxed);
        return fn(a...);
    }
};

#define DRAPE_GL_DECLARE(type, name) extern GlEntry<type> name;
DRAPE_GL_FUNCTIONS(DRAPE_GL_DECLARE)
#undef DRAPE_GL_DECLARE

/// Returns the current EGL context; loads the GL and EGL entry points on its first call (thread
/// safe). EGL_NO_CONTEXT when they could not be loaded (see load_error()).
EGLContext eglGetCurrentContext();

/// Why loading failed (loads first if needed); empty when it succeeded.
const char* load_error();

}  // namespace drape::gles

/// Calls the library made to the GL ES entry point `name` (e.g. "glDrawArrays") since it loaded
/// them, from every thread; name NULL: all entry points together; 0 for names it does not use. For
/// tests and the bench (declared there, not in drape.h: a diagnostic, not part of the C ABI).
extern "C" __attribute__((visibility("default"))) uint64_t drape_gl_call_count(const char* name);

/// Replaces the driver function behind entry point `name` by `fn` (loading first) and returns the
/// one it replaced; NULL, and nothing replaced, for a name the library does not use. For tests
/// (a device that reports lower limits, a failing call); no GL work may run meanwhile.
extern "C" __attribute__((visibility("default"))) void* drape_gl_replace(const char* name, void* fn);
