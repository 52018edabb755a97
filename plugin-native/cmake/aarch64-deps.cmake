# Dependencies of the aarch64 cross build (included after project(drape) by the toolchain file).
include_guard(GLOBAL)

# GLM: its Debian config points at /usr/include, which must not reach the cross compiler's
# include path (host glibc headers). Give it a directory that holds only glm.
set(_drape_host_headers ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${_drape_host_headers})
file(CREATE_LINK /usr/include/glm ${_drape_host_headers}/glm SYMBOLIC)
add_library(glm::glm INTERFACE IMPORTED)
set_target_properties(glm::glm PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${_drape_host_headers})
set(glm_DIR /usr/share/cmake/glm CACHE PATH "" FORCE)  # its config sees glm::glm and returns

# Eigen (tests only): the config's include dir is /usr/include/eigen3, Eigen headers only.
set(Eigen3_DIR /usr/share/eigen3/cmake CACHE PATH "" FORCE)

# GoogleTest from source, compiled for aarch64; find_package(GTest) then finds these targets
# through a config file that defines nothing.
set(INSTALL_GTEST OFF CACHE BOOL "" FORCE)
set(BUILD_GMOCK ON CACHE BOOL "" FORCE)
add_subdirectory(/usr/src/googletest ${CMAKE_BINARY_DIR}/googletest EXCLUDE_FROM_ALL)
foreach(_t gtest gtest_main gmock gmock_main)  # googletest >= 1.11 defines GTest::* itself
  if(NOT TARGET GTest::${_t})
    add_library(GTest::${_t} ALIAS ${_t})
  endif()
endforeach()
file(WRITE ${CMAKE_BINARY_DIR}/gtest-config/GTestConfig.cmake
     "# Targets come from aarch64-deps.cmake (googletest built from source).\n")
set(GTest_DIR ${CMAKE_BINARY_DIR}/gtest-config CACHE PATH "" FORCE)
