# Sourced ON THE GPU MACHINE by the scripts/device-*.sh measurement scripts: checks that
# scripts/stage-device.sh staged the binaries, unpacks the Vulkan loader and glvnd packages it
# staged in .gl/, and points the loader at NVIDIA's driver when it does not find it alone.
# Sets `bin` (the staged binaries' folder).
bin=$PWD/.device-build
[[ -x $bin/tessera ]] || { echo "no staged binaries in $bin: run scripts/stage-device.sh first" >&2; exit 1; }
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export LD_LIBRARY_PATH=$bin
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if ! "$bin/tessera" devices 2>/dev/null | grep -qi nvidia && [[ -f $nvidia_icd ]]; then
  export VK_DRIVER_FILES=$nvidia_icd
fi
