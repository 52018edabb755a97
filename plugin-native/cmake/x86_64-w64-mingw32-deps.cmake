# Dependencies of the mingw-w64 Windows cross build (included after project(drape) by the
# toolchain file x86_64-w64-mingw32.cmake).
include_guard(GLOBAL)

# GLM: its Debian config points at /usr/include, which must not reach the cross compiler's include
# path (host glibc headers). Give it a directory that holds only glm.
set(_drape_host_headers ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${_drape_host_headers})
file(CREATE_LINK /usr/include/glm ${_drape_host_headers}/glm SYMBOLIC)
add_library(glm::glm INTERFACE IMPORTED)
set_target_properties(glm::glm PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${_drape_host_headers})
set(glm_DIR /usr/share/cmake/glm CACHE PATH "" FORCE)  # its config sees glm::glm and returns

# Unity's DllImport("drape") loads drape.dll on Windows.
set(CMAKE_SHARED_LIBRARY_PREFIX "")
