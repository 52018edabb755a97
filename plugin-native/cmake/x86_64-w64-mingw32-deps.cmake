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

# Tests (preset windows-x64-tests, run under Wine by .ci/windows-tests.sh): Eigen is header-only
# (its config names /usr/include/eigen3, Eigen headers only); GoogleTest is built from
# /usr/src/googletest with mingw (Debian's libgtest-dev ships Linux libraries only).
if(DRAPE_BUILD_TESTS)
  set(Eigen3_DIR /usr/share/eigen3/cmake CACHE PATH "" FORCE)
  set(INSTALL_GTEST OFF CACHE BOOL "" FORCE)
  set(BUILD_GMOCK OFF CACHE BOOL "" FORCE)
  set(gtest_disable_pthreads ON CACHE BOOL "" FORCE)  # Win32 threads in gtest itself
  add_subdirectory(/usr/src/googletest ${CMAKE_BINARY_DIR}/googletest EXCLUDE_FROM_ALL)
  foreach(_t gtest gtest_main)
    if(NOT TARGET GTest::${_t})
      add_library(GTest::${_t} ALIAS ${_t})
    endif()
  endforeach()
  file(WRITE ${CMAKE_BINARY_DIR}/gtest-config/GTestConfig.cmake
       "# Targets come from x86_64-w64-mingw32-deps.cmake (googletest built from source).\n")
  set(GTest_DIR ${CMAKE_BINARY_DIR}/gtest-config CACHE PATH "" FORCE)
endif()
