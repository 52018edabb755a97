# Cross toolchain: Debian's mingw-w64 GCC (package g++-mingw-w64-x86-64), Windows x86_64 drape.dll
# for the Unity Editor and players on Windows. The -posix compilers are used because the CPU
# backend's thread pool needs std::thread (the -win32 variants lack it); libgcc, libstdc++ and
# winpthread are linked statically so drape.dll needs only Windows' own DLLs. GLES is off for
# Windows (Unity on Windows renders with D3D11/12 or Vulkan, which the GLES backend cannot write).
# Presets: windows-x64 (the DLL), windows-x64-tests (the native suite, run under Wine by
# .ci/windows-tests.sh).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc-posix)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-static -static-libgcc -static-libstdc++")

set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# After project(drape): header-only GLM from the host, and "drape.dll" (not "libdrape.dll"), the
# name Unity's [DllImport("drape")] looks for on Windows.
set(CMAKE_PROJECT_drape_INCLUDE ${CMAKE_CURRENT_LIST_DIR}/x86_64-w64-mingw32-deps.cmake)
