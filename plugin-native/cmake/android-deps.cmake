# Dependencies of the Android arm64-v8a build with the NDK's own toolchain file (preset
# android-arm64; included after project(drape) through CMAKE_PROJECT_drape_INCLUDE). UNTESTED here:
# the NDK cannot be installed on these machines (see unity-package/README.md, "Building the binaries").
include_guard(GLOBAL)

# GLM is header-only: use the host's copy through a directory that holds only glm (the host's
# /usr/include must not reach the NDK compiler). On a machine without it, pass
# -DDRAPE_GLM_INCLUDE_DIR=<dir containing glm/>.
set(DRAPE_GLM_INCLUDE_DIR "" CACHE PATH "Directory containing glm/ (default: the host's /usr/include/glm)")
set(_drape_host_headers ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${_drape_host_headers})
if(DRAPE_GLM_INCLUDE_DIR)
  set(_drape_glm ${DRAPE_GLM_INCLUDE_DIR}/glm)
else()
  set(_drape_glm /usr/include/glm)
endif()
file(CREATE_LINK ${_drape_glm} ${_drape_host_headers}/glm SYMBOLIC)
add_library(glm::glm INTERFACE IMPORTED)
set_target_properties(glm::glm PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${_drape_host_headers})
set(glm_DIR ${_drape_host_headers} CACHE PATH "" FORCE)
file(WRITE ${_drape_host_headers}/glmConfig.cmake "# glm::glm comes from android-deps.cmake\n")

# GLES: plugin-native/CMakeLists.txt asks pkg-config for "egl" and "glesv2". The NDK ships no .pc
# files, so give pkg-config ones that name the NDK sysroot's libraries (headers are on the NDK
# compiler's default path): EGL and GLESv3 (OpenGL ES 3.0, API 18+), and nothing from the host.
set(_drape_pc ${CMAKE_BINARY_DIR}/android-pkgconfig)
file(WRITE ${_drape_pc}/egl.pc "Name: egl\nDescription: Android NDK EGL\nVersion: 1.4\nLibs: -lEGL\nCflags:\n")
file(WRITE ${_drape_pc}/glesv2.pc "Name: glesv2\nDescription: Android NDK OpenGL ES 3.0\nVersion: 3.0\nLibs: -lGLESv3\nCflags:\n")
set(ENV{PKG_CONFIG_LIBDIR} ${_drape_pc})
set(ENV{PKG_CONFIG_PATH} "")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "")
