#!/usr/bin/env bash
# Runs drape_bench and turns its CSV into plots and REPORT.md (tests/bench/README.md).
#   bash tests/bench/run.sh [--quick] [--out DIR] [--only throughput,threads,precision,rest,stiff,fall,stress,vibration,stages]
# Needs a release build (bash .ci/build.sh release); DRAPE_BENCH overrides the binary's path.
set -euo pipefail
out=bench-out
args=()
while (($#)); do
  case "$1" in
    --out) out=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
bin=${DRAPE_BENCH:-build/release/tests/bench/drape_bench}
"$bin" --out "$out" "${args[@]}"
# Debian's python3 has python3-matplotlib (.ci/deps.sh); a python3 earlier on PATH may not.
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" "$(dirname "$0")/plot.py" "$out"
