#!/usr/bin/env bash
# Builds and runs every test: GoogleTest through ctest, NUnit through dotnet test.
# Each stage says when it starts and how long it took, and the end lists them all (CI has a
# 30-minute budget for this script: the list shows where the time goes).
set -euo pipefail
timings=()
stage() {
  local name=$1 t0=$SECONDS
  shift
  echo "== npm test: $name ($(date -u +%H:%M:%S))"
  "$@"
  timings+=("$(printf '%5d s  %s' $((SECONDS - t0)) "$name")")
}

stage "build" bash .ci/build.sh release
stage "native tests" ctest --preset release
# The GLES tests again on Mesa's softpipe and zink (on lavapipe) drivers (llvmpipe above).
stage "GLES on softpipe" ctest --preset softpipe
stage "GLES on zink" ctest --preset zink
# C#: package checks, Unity compile checks, NUnit tests of Drape.Core.
stage "C#" bash .ci/dotnet-test.sh
# Benchmark smoke run (quick mode, < 1 min): keeps drape_bench and its plots working; no timing checks.
stage "bench smoke" bash tests/bench/run.sh --quick --out build/release/bench-quick
# Hardening: native suite under ASan+UBSan+LSan, libFuzzer on the C ABI (60 s under CI),
# threading tests under TSan, native suite on arm64 under qemu-user. Parts: .ci/hardening.sh asan|fuzz|tsan|arm64
stage "hardening" bash .ci/hardening.sh
# Unity source plug-in (Android/iOS players, no NDK): up to date, compiles for iOS, builds as IL2CPP
# would for arm64 and passes the arm64 suite under qemu. Windows: native suite under Wine.
stage "Unity source plug-in" bash .ci/unity-source.sh check arm64
stage "Windows under Wine" bash .ci/windows-tests.sh

echo "== npm test: all passed; time per stage:"
printf '%s\n' "${timings[@]}"
