#!/usr/bin/env bash
# Hardening checks, run by .ci/test.sh (so by `npm test` and .ci/run):
#   asan   native suite (unit, physics, GLES on Mesa, soak, threading, fuzz corpus replay) under
#          AddressSanitizer + UndefinedBehaviorSanitizer + LeakSanitizer, halt on first report; the
#          asan test preset leaves out the long runs whose code shorter tests also reach (rest states
#          against Newton, threaded-equals-single bit checks, the fine cloth's tethers, friction on a
#          box, GLES IMPLICIT's drop and CPU comparison, the GLES self-collision fold, MASS_SPRING's
#          33x20 GLES parity; 20 soak rounds instead of 40) and the ABI file check
#   fuzz   libFuzzer over the C ABI for DRAPE_FUZZ_SECONDS (60 under CI, 20 otherwise)
#   tsan   threading tests (label tsan) under ThreadSanitizer
#   arm64  native suite cross-compiled for aarch64, run under qemu-user (slow physics references,
#          the longest physics runs (47-390 s each under qemu: resting contact, friction and the
#          IMPLICIT friction substeps, a fine cloth's tethers, every change waking a cloth; their code
#          runs in the shorter collision, tether and sleep tests), the self-collision threaded bit
#          check and GLES excluded: see the arm64 test preset)
# Usage: bash .ci/hardening.sh [asan|fuzz|tsan|arm64]...   (no argument: all four)
set -euo pipefail
cd "$(dirname "$0")/.."

run_asan() {
  bash .ci/build.sh asan
  ctest --preset asan
}

run_fuzz() {
  local seconds=${DRAPE_FUZZ_SECONDS:-$([ -n "${CI:-}" ] && echo 60 || echo 20)}
  local work=build/asan/fuzz
  [ -x build/asan/tests/fuzz/drape_fuzz_api ] || bash .ci/build.sh asan
  # New units go to a scratch corpus; the seeds in the repository stay as they are.
  mkdir -p "$work/corpus" "$work/artifacts"
  if ! ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1 \
       UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
       build/asan/tests/fuzz/drape_fuzz_api "$work/corpus" tests/fuzz/corpus tests/fuzz/regressions \
         -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 -print_final_stats=1 \
         -artifact_prefix="$work/artifacts/" 2>"$work/log.txt"; then
    grep -v '^#[0-9]' "$work/log.txt" | tail -60
    echo "hardening: the fuzzer found a problem; reproducer(s) in $work/artifacts/." >&2
    echo "  Replay: build/asan/tests/fuzz/drape_fuzz_api <file> (DRAPE_FUZZ_TRACE=1 prints the calls)." >&2
    echo "  Keep it in tests/fuzz/regressions/ and add a test to tests/native/test_fuzz_regressions.cpp." >&2
    return 1
  fi
  grep -E '^(Done|stat::)' "$work/log.txt" || true
}

run_tsan() {
  cmake --preset tsan >/dev/null
  cmake --build --preset tsan -j "$(nproc)" --target drape_hardening_tests
  ctest --preset tsan
}

run_arm64() {
  cmake --preset arm64 >/dev/null
  cmake --build --preset arm64 -j "$(nproc)"
  ctest --preset arm64
}

steps=("$@")
((${#steps[@]})) || steps=(asan fuzz tsan arm64)
for s in "${steps[@]}"; do
  t0=$SECONDS
  echo "== hardening: $s"
  "run_$s"
  echo "== hardening: $s passed in $((SECONDS - t0)) s"
done
