#!/usr/bin/env bash
# Windows x86_64: the native suite cross-built with mingw-w64 (preset windows-x64-tests, which
# inherits the drape.dll preset windows-x64) and run under Wine (Debian's wine64), headless.
# Each test binary runs with drape.dll next to it: drape_hardening_tests first, then drape_tests as
# two shards at once, after wineboot has made the prefix.
# Every test of drape_tests and drape_hardening_tests runs (~35 s under Wine on a loaded 2-core
# machine). Not run: the soak binary (it measures the heap with glibc's mallinfo2, which mingw
# lacks) and the GLES tests (GLES is off on Windows).
set -euo pipefail
cd "$(dirname "$0")/.."

wine=$(command -v wine64 || command -v wine || echo /usr/lib/wine/wine64)
wineserver=$(command -v wineserver || echo /usr/lib/wine/wineserver64)
[ -x "$wine" ] || { echo "windows-tests: wine64 not found (bash .ci/deps.sh installs it)" >&2; exit 1; }

cmake --preset windows-x64-tests >/dev/null
cmake --build --preset windows-x64-tests -j "$(nproc)" --target drape_tests drape_hardening_tests
bin=build/windows-x64-tests/bin
# The tests must load the drape.dll built here (import table of the test binary).
imports=$(x86_64-w64-mingw32-objdump -p "$bin/drape_tests.exe")
grep -q "DLL Name: drape.dll" <<<"$imports"
[ -f "$bin/drape.dll" ]

export WINEPREFIX=$PWD/build/windows-x64-tests/wineprefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
trap '"$wineserver" -k 2>/dev/null || true' EXIT
# The prefix on its own first: once (1 of 4 runs, session 17) the test binary that created it passed
# its tests and then hung at exit, waiting on the wineserver. Bounded: a hung wineboot is killed (the
# prefix is written by then) and the tests start on a fresh server.
timeout 120 "$wine" wineboot --init >/dev/null 2>&1 || { "$wineserver" -k 2>/dev/null || true; }
# A test binary's run (shard index of total: GoogleTest's sharding, each test in exactly one shard)
# in the background, its output in a file (Wine's own processes keep inherited descriptors open).
start() {
  GTEST_SHARD_INDEX=$2 GTEST_TOTAL_SHARDS=$3 "$wine" "$bin/$1.exe" >"build/windows-x64-tests/$1.$2.log" 2>&1 </dev/null &
  pids+=($!)
}
status=0
finish() {
  local log=build/windows-x64-tests/$1.$2.log
  if wait "$4" && grep -qE '^\[  PASSED  \] [1-9]' "$log"; then
    grep -E '^\[  PASSED  \]|tests? from .* ran' "$log" | sed "s/^/windows-tests: $1 shard $2\/$3: /"
  else
    grep -E '^\[  FAILED  \]|Failure|error' "$log" | head -40 || tail -40 "$log"
    echo "windows-tests: $1 shard $2/$3 failed under Wine (log: $log)" >&2
    status=1
  fi
}
pids=()
start drape_hardening_tests 0 1
finish drape_hardening_tests 0 1 "${pids[0]}"
# drape_tests took ~75 s of the stage's ~160 s in one process: one shard per core.
pids=()
start drape_tests 0 2
start drape_tests 1 2
finish drape_tests 0 2 "${pids[0]}"
finish drape_tests 1 2 "${pids[1]}"
exit $status
