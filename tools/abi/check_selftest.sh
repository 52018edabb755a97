#!/usr/bin/env bash
# Proves `generate.py --check` fails on a stale tree: copies the generated files, changes each in
# turn (drape.h and the shaders: a line inside a GENERATED block; outside them they are
# hand-written) and expects the check to fail.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
generated=(unity-package/Runtime/Core/Enums.cs unity-package/Runtime/Core/Structs.cs
           tests/dotnet/LayoutProbe/drape_layout_probe.c plugin-native/src/core/abi_tables.h
           plugin-native/src/backend/gles/sim_uniforms.h)
with_blocks=(plugin-native/include/drape/drape.h shaders/sim.vert.glsl shaders/output.vert.glsl shaders/layout.h)
copy() {
  local g
  for g in "${generated[@]}" "${with_blocks[@]}"; do mkdir -p "$tmp/$(dirname "$g")"; cp "$root/$g" "$tmp/$g"; done
}
copy
python3 "$root/tools/abi/generate.py" --check --root "$tmp" >/dev/null || { echo "fresh copy reported stale"; exit 1; }
for f in "${generated[@]}"; do
  copy
  printf '\n' >> "$tmp/$f"
  if python3 "$root/tools/abi/generate.py" --check --root "$tmp" 2>/dev/null >&2; then
    echo "check passed with $f changed"; exit 1
  fi
done
copy
sed -i 's/float damping;/float damping_changed;/' "$tmp/plugin-native/include/drape/drape.h"
if python3 "$root/tools/abi/generate.py" --check --root "$tmp" >/dev/null 2>&1; then
  echo "check passed with a GENERATED block edited by hand"; exit 1
fi
copy
sed -i 's/float u_damping;/float u_damping_changed;/' "$tmp/shaders/sim.vert.glsl"
if python3 "$root/tools/abi/generate.py" --check --root "$tmp" >/dev/null 2>&1; then
  echo "check passed with a shader's GENERATED block edited by hand"; exit 1
fi
copy
sed -i 's/#define DRAPE_COLLIDER_BOX 2/#define DRAPE_COLLIDER_BOX 5/' "$tmp/shaders/layout.h"
if python3 "$root/tools/abi/generate.py" --check --root "$tmp" >/dev/null 2>&1; then
  echo "check passed with a shader enum value in layout.h edited by hand"; exit 1
fi
echo "generate.py --check fails on every stale file"
