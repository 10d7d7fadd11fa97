#!/usr/bin/env bash
# Installs Tessera's build and test dependencies from Debian 12 packages when any is missing.
# Quick when everything is present: one dpkg-query, no apt-get call.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libstb-dev libtinygltf-dev libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  libtinyobjloader-dev assimp-testmodels nlohmann-json3-dev libmeshoptimizer-dev
  # tessera view: the window, its overlay, and the X server its tests run under
  libglfw3-dev libx11-dev libimgui-dev libfreetype-dev xvfb
  # scripts/fuzz.sh: libFuzzer and the sanitizer runtimes
  clang-14 libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "setup: installing missing packages with apt-get (a few minutes): ${missing[*]}" >&2
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null; then
    sudo_cmd=(sudo)
  else
    echo "setup: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
