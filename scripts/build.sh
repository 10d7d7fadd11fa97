#!/usr/bin/env bash
# Installs what is missing, then configures and builds Tessera (Release) in build/.
# Incremental: a second run rebuilds only what changed. Uses ccache when it is installed.
# `--target T` first builds only T and what it needs (scripts/render.sh: `tessera`, without
# the test suite); other arguments go to CMake's configure step.
# Says on stderr what it is doing, one line a step, so that callers that hide the build's own
# output (scripts/render.sh) do not look stuck during a first build of several minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache caches the tests' precompiled-header compilations only with this (tests/CMakeLists.txt).
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}
target=()
if [[ ${1:-} == --target ]]; then
  (($# >= 2)) || { echo "build.sh: --target needs a target name" >&2; exit 2; }
  target=(--target "$2")
  shift 2
fi
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
# A cache without the generator's file is a configure that was cut short (Ctrl+C, or another
# configure at the same moment): configure again rather than build nothing.
if [[ ! -f build/CMakeCache.txt || ! ( -f build/Makefile || -f build/build.ninja ) ]]; then
  echo "build: configuring build/ (Release)" >&2
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
elif (($# > 0)); then
  cmake -S . -B build "$@" >/dev/null
fi
progress=0
if [[ -x build/host/tessera ]]; then
  echo "build: updating build/ (rebuilds what changed, if anything)" >&2
else
  progress=1
  echo "build: building Tessera in build/ with $jobs jobs; the first build takes several" \
    "minutes (about 4 on an idle 2-core machine)" >&2
fi
# In a first build whose own output is hidden (stdout not a terminal, as in scripts/render.sh),
# its progress also goes to stderr every tenth, so that the build does not look stuck.
last=0
cmake --build build -j "$jobs" "${target[@]}" | while IFS= read -r line; do
  printf '%s\n' "$line"
  if ((progress)) && [[ ! -t 1 && $line =~ ^\[\ *([0-9]+)%\] ]]; then
    step=$((BASH_REMATCH[1] / 10 * 10))
    if ((step > last)); then
      last=$step
      echo "build: $step %" >&2
    fi
  fi
done
