#!/usr/bin/env bash
# Windows x86_64: the native suite cross-built with mingw-w64 (preset windows-x64-tests, which
# inherits the drape.dll preset windows-x64) and run under Wine (Debian's wine64), headless.
# Each test binary runs once (one Wine start each) with drape.dll next to it.
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
status=0
for t in drape_tests drape_hardening_tests; do
  log=build/windows-x64-tests/$t.log
  # Wine's own processes (wineserver) keep inherited descriptors open: output goes to a file.
  if "$wine" "$bin/$t.exe" >"$log" 2>&1 </dev/null &&
     grep -qE '^\[  PASSED  \] [1-9]' "$log"; then
    grep -E '^\[  PASSED  \]|tests? from .* ran' "$log" | sed "s/^/windows-tests: $t: /"
  else
    grep -E '^\[  FAILED  \]|Failure|error' "$log" | head -40 || tail -40 "$log"
    echo "windows-tests: $t failed under Wine (log: $log)" >&2
    status=1
  fi
done
exit $status
