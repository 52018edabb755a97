#!/usr/bin/env bash
# The Unity source plug-in: unity-package/Plugins/Source/Drape.cpp, the native library as one C++
# translation unit that IL2CPP compiles into Android (arm64) and iOS players (no NDK needed).
#   sync   regenerate it from plugin-native/ (sources, headers, embedded shaders) and glm
#   check  fail if the committed file is stale; compile it for iOS's configuration (no GLES);
#          check that libdrape.so (release) links against no GL library
#   arm64  compile the committed file as IL2CPP does for Android arm64 (clang, C++17, -Os,
#          -fPIC, hidden visibility, exceptions on; -fno-rtti on top; warnings off: Eigen's are
#          many once it is no system header) into libdrape.so linked with
#          --no-undefined, compare its exports with the CMake-built library, then run the arm64
#          native suite (test binaries of the arm64 preset) against it under qemu-user
# Usage: bash .ci/unity-source.sh [sync|check|arm64]...   (no argument: check arm64)
set -euo pipefail
cd "$(dirname "$0")/.."

out=unity-package/Plugins/Source/Drape.cpp
work=build/unity-source
# IL2CPP's clang flags for Android (Unity 2022.3 build log) that change code generation; the
# standard is not visible in that log, so C++17 is passed (Drape.cpp #errors below C++17).
il2cpp_flags=(-std=c++17 -fPIC -Os -fvisibility=hidden -fexceptions -funwind-tables -fstack-protector
              -fomit-frame-pointer -fno-strict-overflow -ffunction-sections -fdata-sections -DNDEBUG)

generate() { # <output file>
  cmake --preset release >/dev/null
  cmake --build --preset release --target drape_generated_sources >/dev/null
  python3 .ci/unity-source.py build/release/drape-source-manifest.txt "$1"
}

run_sync() {
  generate "$out"
  echo "unity-source: wrote $out ($(wc -c <"$out") bytes)"
}

run_check() {
  mkdir -p "$work"
  generate "$work/Drape.cpp"
  if ! cmp -s "$work/Drape.cpp" "$out"; then
    diff -u "$out" "$work/Drape.cpp" | grep -E '^[-+]#line 1 ' | head -20 || true
    echo "unity-source: $out is stale (plugin-native/, shaders/ or glm changed): run bash .ci/unity-source.sh sync" >&2
    return 1
  fi
  # iOS: the same file without the GLES backend (it is on for __ANDROID__ only).
  g++ "${il2cpp_flags[@]}" -fno-rtti -w -fsyntax-only "$out"
  # libdrape.so: GL ES and EGL come from dlopen at run time, never from the link.
  local lib=build/release/plugin-native/libdrape.so
  cmake --build --preset release -j "$(nproc)" --target drape >/dev/null
  if readelf -d "$lib" | grep -E 'NEEDED.*(GLES|EGL|libGL)' ||
     nm -D --undefined-only "$lib" | grep -E ' (gl|egl)[A-Z]'; then
    echo "unity-source: $lib links against GL" >&2
    return 1
  fi
  echo "unity-source: $out is up to date; iOS configuration compiles; libdrape.so has no GL link dependency"
}

run_arm64() {
  local dir=$work/arm64
  mkdir -p "$dir/gl-headers"
  # GL ES / EGL headers only (arch-independent), not the host's whole /usr/include.
  for d in EGL GLES3 KHR; do ln -sfn "/usr/include/$d" "$dir/gl-headers/$d"; done
  local cxx=(clang++-14 --target=aarch64-linux-gnu)
  # The Android configuration (GLES backend compiled in, as __ANDROID__ turns it on), linked like
  # libil2cpp.so: every symbol resolved (no GL library on the link line).
  "${cxx[@]}" "${il2cpp_flags[@]}" -fno-rtti -w -DDRAPE_WITH_GLES=1 -isystem "$dir/gl-headers" \
    -c "$out" -o "$dir/Drape.o"
  "${cxx[@]}" -shared -o "$dir/libdrape.so" "$dir/Drape.o" -Wl,--no-undefined -Wl,-z,defs -Wl,--gc-sections -pthread -ldl
  if readelf -d "$dir/libdrape.so" | grep -E 'NEEDED.*(GLES|EGL|libGL)'; then
    echo "unity-source: the source plug-in links against GL" >&2
    return 1
  fi
  # Same C ABI as the CMake-built library (Unity entry points renamed in the source plug-in).
  cmake --build --preset release -j "$(nproc)" --target drape >/dev/null
  exports() { nm -D --defined-only "$1" | awk '$2 == "T" {print $3}' | sed 's/^DrapeUnityPlugin/UnityPlugin/' | sort; }
  if ! diff <(exports build/release/plugin-native/libdrape.so) <(exports "$dir/libdrape.so"); then
    echo "unity-source: exports differ from the CMake-built libdrape.so" >&2
    return 1
  fi
  # Native suite: the arm64 preset's test binaries, loading this library instead of their own.
  cmake --preset arm64 >/dev/null
  cmake --build --preset arm64 -j "$(nproc)" --target drape_tests drape_hardening_tests drape_soak_tests
  local abs_dir
  abs_dir=$(cd "$dir" && pwd)
  local loaded
  loaded=$(LD_LIBRARY_PATH=$abs_dir qemu-aarch64 -L /usr/aarch64-linux-gnu -E LD_TRACE_LOADED_OBJECTS=1 \
           build/arm64/tests/native/drape_tests)
  if ! grep -q "libdrape.so => $abs_dir/libdrape.so" <<<"$loaded"; then
    echo "unity-source: the arm64 tests do not load $dir/libdrape.so" >&2
    return 1
  fi
  # Not run again here: the arm64 preset's exclusions and the tests that took over ~10 s each
  # under qemu on the loaded CI machine (physics references, collisions, self-collision, sleep,
  # owner, soak); the hardening arm64 step runs those its preset keeps against the CMake-built library, which
  # computes the same bits (no FP contraction, no fast-math in either build). Abi.*: checks of
  # generated files, not of the library (and their python3 is run through qemu in this build).
  local slow='R10Undamped|R11Xpbd|R12Xpbd|ThreadedEqualsSingleThreaded|R4Equilibrium|R9Momentum|FarFromOrigin'
  slow+='|Tethers.BoundStretch|FollowMovingPins|ForcedInstabilityRollsBack|Collision.RestingContact'
  slow+='|Collision.FastSphere|Collision.FrictionHolds|Collision.FrictionlessEdges|Collision.FrictionalSphere|Collision.ClothDraped'
  slow+='|Collision.NoOrFar|SelfCollision.Folding'
  slow+='|SelfCollision.Threaded|SelfCollision.OffByDefault|Sleep.EveryChange|Sleep.Asleep|Sleep.Unchanged'
  slow+='|Owner.Teleport|Owner.Inertia|Threading.WorldSteps|Soak|^Abi\.|RestState'
  LD_LIBRARY_PATH=$abs_dir ctest --preset arm64 -E "$slow"
}

steps=("$@")
((${#steps[@]})) || steps=(check arm64)
for s in "${steps[@]}"; do
  t0=$SECONDS
  echo "== unity-source: $s"
  "run_$s"
  echo "== unity-source: $s passed in $((SECONDS - t0)) s"
done
