#!/usr/bin/env bash
# The C# part of `npm test` (needs the native library from `bash .ci/build.sh release`):
#  1. the Unity package's .meta files (complete, unique, no orphans) and version, plus a self-test
#     proving that check fails on broken trees;
#  2. compile checks of unity-package/Runtime, Editor and Samples~ against the signature-only Unity
#     stand-ins (tests/dotnet/UnityStandIn, checked against Unity's C# reference source by its
#     unity_api.py), with legacy input and Input System, as Unity 2022.3 and as 6000.5;
#  3. NUnit tests of Drape.Core (unity-package/Tests/Core + tests/dotnet) against libdrape.so;
#  4. NUnit tests of the MonoBehaviours against the stand-in's minimal behaviour and libdrape.so.
# NuGet packages (NUnit, NUnit3TestAdapter, Microsoft.NET.Test.Sdk) are restored by dotnet from the
# registry into ~/.nuget/packages; later runs restore from that cache without the network.
set -euo pipefail
cd "$(dirname "$0")/.."
export DOTNET_CLI_TELEMETRY_OPTOUT=1 DOTNET_NOLOGO=1 DOTNET_SKIP_FIRST_TIME_EXPERIENCE=1
if ! command -v dotnet >/dev/null; then
  echo "drape: the .NET SDK (dotnet) is required for the C# tests and is not on PATH" >&2
  exit 1
fi

node .ci/unity-meta.mjs selftest
node .ci/unity-meta.mjs check unity-package --root-version package.json

# Each compile check twice: as Unity 2022.3 and as 6000.5 (its UNITY_*_OR_NEWER defines; the
# stand-ins mark APIs Obsolete, or Obsolete as an error, where that version's reference source does).
for unity in 2022.3 6000.5; do
  dotnet build tests/dotnet/CompileCheck/Drape.Editor.CompileCheck.csproj -nologo -v quiet -p:UnityVersion=$unity
  dotnet build tests/dotnet/CompileCheck/Drape.Runtime.CompileCheck.csproj -nologo -v quiet -p:UnityVersion=$unity -p:DrapeInput=InputSystem
  dotnet build tests/dotnet/CompileCheck/Drape.Samples.CompileCheck.csproj -nologo -v quiet -p:UnityVersion=$unity
done

# The native library name P/Invokes use per Unity platform ("__Internal" where IL2CPP compiles the sources).
bash tests/dotnet/library-name.sh

dotnet test tests/dotnet/Drape.Core.Tests/Drape.Core.Tests.csproj -nologo -v quiet
# The MonoBehaviours run against the stand-in (legacy input, Unity 2022.3 defines).
dotnet test tests/dotnet/Drape.Runtime.Tests/Drape.Runtime.Tests.csproj -nologo -v quiet
