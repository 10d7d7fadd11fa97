#!/usr/bin/env bash
# Builds Tessera if needed and renders a scene: the default sphere grid to out/spheres.png
# unless other `tessera render` options are given (see build/host/tessera render --help).
set -euo pipefail
cd "$(dirname "$0")/.."
# Only the tool: a render needs none of the test suite's objects.
scripts/build.sh --target tessera >/dev/null
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
if (($# == 0)); then
  mkdir -p out
  set -- --out out/spheres.png
fi
exec build/host/tessera render "$@"
