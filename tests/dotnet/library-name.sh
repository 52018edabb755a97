#!/usr/bin/env bash
# Which native library Drape.Core's P/Invokes name under each Unity platform's defines: builds
# unity-package/Runtime/Core with those defines and reads the module reference from the assembly's
# metadata. "__Internal" exactly where IL2CPP compiles unity-package/Plugins/Source into the player
# (iOS; Android with IL2CPP unless DRAPE_ANDROID_PREBUILT), "drape" everywhere else.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail=0
check() { # defines expected
  local dir="$out/$(echo "$1" | tr ';' '_')"
  dotnet build tests/dotnet/Drape.Core/Drape.Core.csproj -nologo -v quiet -p:DrapeUnityDefines="${1//;/%3B}" \
    -p:ArtifactsPath="$dir" >/dev/null
  local dll; dll=$(find "$dir" -name Drape.Core.dll | head -1)
  local got=drape
  if grep -q --text "__Internal" "$dll"; then got=__Internal; fi
  if [ "$got" = "$2" ]; then echo "ok   library-name: [$1] -> $got"; else echo "FAIL library-name: [$1] -> $got, expected $2"; fail=1; fi
}
check "UNITY_IOS" __Internal
check "UNITY_ANDROID;ENABLE_IL2CPP" __Internal
check "UNITY_ANDROID;ENABLE_IL2CPP;DRAPE_ANDROID_PREBUILT" drape
check "UNITY_ANDROID;ENABLE_MONO" drape
check "UNITY_IOS;UNITY_EDITOR" drape
check "UNITY_WEBGL;ENABLE_IL2CPP" drape
check "UNITY_TVOS;ENABLE_IL2CPP" drape
exit $fail
