#!/usr/bin/env bash
# `npm run pack`: builds the native library, stages the Unity package with its binaries and their
# .meta import settings (templates in unity-package/Plugins~/meta), checks the staged .meta files,
# and writes build/com.drape.cloth-<version>.tgz for Unity's "Add package from tarball...".
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh release
# Windows x86_64 drape.dll, cross-compiled with mingw-w64 (GLES off; see plugin-native/cmake/x86_64-w64-mingw32.cmake).
bash .ci/build.sh windows-x64
# Android and iOS players compile Plugins/Source/Drape.cpp (the source plug-in, in the repository).
# A prebuilt Android arm64-v8a libdrape.so needs the NDK (not installable here): built only where
# ANDROID_NDK_HOME is set, and used by Unity only with the scripting define DRAPE_ANDROID_PREBUILT.
if [ -n "${ANDROID_NDK_HOME:-}" ]; then bash .ci/build.sh android-arm64; fi

stage=build/unity-package-stage/package
rm -rf build/unity-package-stage
mkdir -p "$stage"
cp -a unity-package/. "$stage/"
rm -rf "$stage/Plugins~"

# Binaries built here, each with its folder metas and import settings.
add_plugin() { # <built file> <path inside the package>
  local built=$1 dest=$2 templates=unity-package/Plugins~/meta
  [ -f "$built" ] || return 0
  mkdir -p "$stage/$(dirname "$dest")"
  cp "$built" "$stage/$dest"
  cp "$templates/$dest.meta" "$stage/$dest.meta"
  local dir
  dir=$(dirname "$dest")
  while [ "$dir" != "." ]; do
    cp "$templates/$dir.meta" "$stage/$dir.meta"
    dir=$(dirname "$dir")
  done
  echo "drape: packed $dest"
}
add_plugin build/release/plugin-native/libdrape.so Plugins/Linux/x86_64/libdrape.so
add_plugin build/android-arm64/plugin-native/libdrape.so Plugins/Android/arm64-v8a/libdrape.so
add_plugin build/windows-x64/plugin-native/drape.dll Plugins/Windows/x86_64/drape.dll

node .ci/unity-meta.mjs check "$stage" --root-version package.json
version=$(node -p "require('./package.json').version")
tarball=$(cd build && npm pack "./unity-package-stage/package" --silent)
echo "drape: wrote build/$tarball (Unity: Package Manager > + > Add package from tarball...)"
listing=$(tar -tzf "build/$tarball")
grep -q "package/Plugins/Linux/x86_64/libdrape.so.meta" <<<"$listing"
grep -q "package/Plugins/Source/Drape.cpp.meta" <<<"$listing"
test "$tarball" = "com.drape.cloth-$version.tgz"
