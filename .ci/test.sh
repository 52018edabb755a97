#!/usr/bin/env bash
# Builds and runs every test: GoogleTest through ctest, NUnit through dotnet test.
set -euo pipefail
bash .ci/build.sh release
ctest --preset release
# The GLES tests again on Mesa's softpipe and zink (on lavapipe) drivers (llvmpipe above).
ctest --preset softpipe
ctest --preset zink

# C#: package checks, Unity compile checks, NUnit tests of Drape.Core.
bash .ci/dotnet-test.sh
# Benchmark smoke run (quick mode, < 1 min): keeps drape_bench and its plots working; no timing checks.
bash tests/bench/run.sh --quick --out build/release/bench-quick
# Hardening: native suite under ASan+UBSan+LSan, libFuzzer on the C ABI (60 s under CI),
# threading tests under TSan, native suite on arm64 under qemu-user. Parts: .ci/hardening.sh asan|fuzz|tsan|arm64
bash .ci/hardening.sh
# Unity source plug-in (Android/iOS players, no NDK): up to date, compiles for iOS, builds as IL2CPP
# would for arm64 and passes the arm64 suite under qemu. Windows: native suite under Wine.
bash .ci/unity-source.sh check arm64
bash .ci/windows-tests.sh
