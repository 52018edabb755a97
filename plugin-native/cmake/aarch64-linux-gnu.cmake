# Cross toolchain: Debian's aarch64-linux-gnu GCC (package g++-aarch64-linux-gnu), the Android
# arm64 proxy (hardening). Tests run under qemu-user: ctest prefixes every test command
# with CMAKE_CROSSCOMPILING_EMULATOR (no binfmt_misc needed). Preset: arm64.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)

# Libraries and headers from the arm64 sysroot only; programs (glslangValidator) from the host.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Host-only packages the build needs for aarch64: header-only GLM and Eigen are used from the
# host (arch-independent), GoogleTest is built from /usr/src/googletest (Debian's libgtest-dev
# ships x86-64 libraries only). See aarch64-deps.cmake, run right after project().
set(CMAKE_PROJECT_drape_INCLUDE ${CMAKE_CURRENT_LIST_DIR}/aarch64-deps.cmake)
