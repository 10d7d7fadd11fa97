#!/usr/bin/env bash
# Checks the installed package the way a user's project sees it: installs build/ into a
# temporary prefix, configures and builds examples/render_spheres against it with
# find_package(Tessera), runs its program once on lavapipe and its GoogleTest image test, and
# checks that no installed or consuming binary links the Vulkan loader.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install build --prefix "$prefix" >/dev/null
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S examples/render_spheres -B "$work/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" "${launcher[@]}" >/dev/null
cmake --build "$work/build" -j "$(nproc 2>/dev/null || echo 2)" >/dev/null

for binary in "$prefix/bin/tessera" "$work/build/render_spheres" "$work/build/render_spheres_test"; do
  if readelf -d "$binary" | grep -q 'NEEDED.*libvulkan'; then
    echo "check-package: $binary links the Vulkan loader" >&2
    exit 1
  fi
done
"$prefix/bin/tessera" scenes >/dev/null
"$work/build/render_spheres" "$work/spheres.png" lavapipe
[[ -s "$work/spheres.png" ]]
(cd "$work/build" && ctest --output-on-failure)
echo "check-package: the installed package builds, links and renders"
