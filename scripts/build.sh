#!/usr/bin/env bash
# Installs what is missing, then configures and builds Tessera (Release) in build/.
# Incremental: a second run rebuilds only what changed. Uses ccache when it is installed.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache caches the tests' precompiled-header compilations only with this (tests/CMakeLists.txt).
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
if [[ ! -f build/CMakeCache.txt ]]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
elif (($# > 0)); then
  cmake -S . -B build "$@" >/dev/null
fi
cmake --build build -j "$jobs"
