#!/usr/bin/env bash
# Builds and runs every test: GoogleTest through ctest, NUnit through dotnet test.
set -euo pipefail
bash .ci/build.sh release
ctest --preset release

# C#: package checks, Unity compile checks, NUnit tests of Drape.Core (issue 4).
bash .ci/dotnet-test.sh
