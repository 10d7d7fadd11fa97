#!/usr/bin/env bash
# Builds binaries that run on the GPU machine (Ubuntu 24.04: libstdc++ linked statically) in
# build-device/, and stages them with the Vulkan loader and glvnd packages in two folders that
# git ignores: .gl/ (Debian packages to unpack there) and .device-build/ (binaries and
# libbenchmark). Pass both to the device tool's `carry`; on the machine run
#   for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; export LD_LIBRARY_PATH=$PWD/.device-build
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# In a fresh clone .git/info/ may not exist yet, and in a worktree the file lives elsewhere.
exclude=$(git rev-parse --git-path info/exclude)
mkdir -p "$(dirname "$exclude")"
touch "$exclude"
for d in /.gl/ /.device-build/ /.device-before/; do grep -qx "$d" "$exclude" || echo "$d" >> "$exclude"; done
if [[ ! -f .gl/libvulkan1_1.3.239.0-1_amd64.deb || ! -f .gl/libglvnd0_1.6.0-1_amd64.deb ]]; then
  lists=$(mktemp -d)
  mkdir -p .gl "$lists/partial"
  o="-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=$lists"
  apt-get $o update >/dev/null
  # The NVIDIA Vulkan driver (libGLX_nvidia) needs the glvnd dispatch libraries.
  (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null)
fi
[[ -f build-device/CMakeCache.txt ]] ||
  cmake -S . -B build-device -DCMAKE_BUILD_TYPE=Release -DTESSERA_STATIC_RUNTIME=ON -DTESSERA_BUILD_TESTS=OFF >/dev/null
cmake --build build-device -j "$(nproc)" --target tessera tessera_bench tessera_minimal_graphics \
  tessera_import_bench
rm -rf .device-build && mkdir -p .device-build
cp build-device/host/tessera build-device/bench/tessera_bench \
  build-device/bench/tessera_minimal_graphics build-device/bench/tessera_import_bench .device-build/
# The largest sample glb, for scripts/device-bench-import.sh (the GPU machine has no assimp models).
cp /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb .device-build/
cp "$(ldd build-device/bench/tessera_bench | awk '/libbenchmark/ {print $3}')" .device-build/
# The window's libraries (GLFW, FreeType and what they load: X11, PNG, ...) are not on the GPU
# machine: every shared library `tessera` needs beyond glibc, the C++ runtime (Ubuntu's is newer)
# and the Vulkan loader goes along.
ldd build-device/host/tessera build-device/bench/tessera_import_bench | awk '$3 ~ /^\// {print $3}' |
  grep -Ev '/(libc|libm|libdl|librt|libpthread|ld-linux[^/]*|libvulkan|libstdc\+\+|libgcc_s)\.so' |
  sort -u | xargs -r cp -L -t .device-build/
du -sh .gl .device-build
