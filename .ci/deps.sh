#!/usr/bin/env bash
# Installs the Debian packages Drape builds and tests with, only those missing (idempotent).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libglm-dev libgtest-dev googletest
  libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  mesa-vulkan-drivers  # lavapipe: the Vulkan device under Mesa's zink GL driver (zink test preset)
  glslang-tools libstb-dev python3-matplotlib
  imagemagick  # demo GIFs
  clang-14 libclang-rt-14-dev g++-aarch64-linux-gnu qemu-user  # sanitizers, libFuzzer, arm64 under qemu
  g++-mingw-w64-x86-64  # Windows x86_64 drape.dll for the Unity package (npm run pack)
  wine64  # Windows native suite under Wine (.ci/windows-tests.sh)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "drape: installing ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
