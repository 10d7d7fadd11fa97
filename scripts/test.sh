#!/usr/bin/env bash
# Builds Tessera if needed and runs the whole test suite (GoogleTest through ctest) on
# lavapipe with the Khronos validation layer. Exit status 0 only if every test passes.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
jobs=$(nproc 2>/dev/null || echo 2)
cd build
ctest --output-on-failure -j "$jobs" --timeout 600
