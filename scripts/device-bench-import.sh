#!/usr/bin/env bash
# Runs ON THE GPU MACHINE's CPUs (the device tool; an idle 16-core host, unlike the shared 2-core
# development VM) and builds nothing: tessera_import_bench and the sample glb come staged by
# scripts/stage-device.sh (pass carry [".gl", ".device-build"]). Issue 10's loading figures:
# the glb against tinygltf alone (3 rounds of 10 interleaved repetitions), the generated
# 10^7-triangle OBJ against tinyobjloader (one case per process, for its peak memory, 3 rounds),
# and texture decoding and mip building on every core against one thread (wall time).
# Writes each case's JSON and printed table packed in $OUT/import.tar.gz; prints them too.
#
#   device run: scripts/device-bench-import.sh        (OBJ_TRIANGLES=N to change 10^7;
#                                                      PARTS="gltf obj textures" the default)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
bin=$PWD/.device-build
export LD_LIBRARY_PATH=$bin TESSERA_GLB_BENCH_FILE=$bin/2CylinderEngine.glb
export TESSERA_OBJ_BENCH_TRIANGLES=${OBJ_TRIANGLES:-10000000}
work=$(mktemp -d)
# Packed however the script ends (a time limit keeps what was measured).
trap 'tar -C "$work" -czf "$out/import.tar.gz" --exclude=./tmp .' EXIT
export TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
nproc | tee "$work/nproc.txt"
# An earlier build's bench in .device-before/ (if staged there) runs in the same rounds, so that
# before and after are measured on the same machine state.
versions=(after)
[[ -x $PWD/.device-before/tessera_import_bench ]] && versions=(before after)
run() {  # run VERSION TAG FILTER [ARGS...]: one process
  local b=$bin version=$1 tag=$2 filter=$3
  shift 3
  [[ $version == before ]] && b=$PWD/.device-before
  LD_LIBRARY_PATH=$b "$b/tessera_import_bench" --benchmark_filter="$filter" \
    --benchmark_out="$work/${version}_$tag.json" --benchmark_out_format=json "$@" 2>&1 |
    tee "$work/${version}_$tag.txt" | grep -v '^\*\*\*' || true
}
parts=" ${PARTS:-gltf obj textures} "
for round in 1 2 3; do
  [[ $parts == *" gltf "* ]] || break
  for v in "${versions[@]}"; do
    run "$v" "gltf_$round" 'BM_(TinyGltfAlone|TinyGltfOnMappedFile|ImportGltf)/' \
      --benchmark_repetitions=10 --benchmark_enable_random_interleaving=true \
      --benchmark_report_aggregates_only=true
  done
done
# Peak memory, one case per process (the high-water mark is the process's).
for f in TinyGltfAlone TinyGltfOnMappedFile ImportGltf; do
  [[ $parts == *" gltf "* ]] || break
  for v in "${versions[@]}"; do run "$v" "memory_$f" "^BM_$f/" --benchmark_repetitions=3; done
done
for round in 1 2 3; do
  [[ $parts == *" obj "* ]] || break
  for v in "${versions[@]}"; do
    b=$bin
    [[ $v == before ]] && b=$PWD/.device-before
    for f in $(LD_LIBRARY_PATH=$b "$b/tessera_import_bench" --benchmark_list_tests |
               grep -E '^BM_(TinyObj|ImportObj)' | sed 's,/.*,,' | sort -u); do
      run "$v" "obj_${f}_$round" "^$f/" --benchmark_repetitions=1
    done
  done
done
if [[ $parts == *" textures "* ]]; then
  run after textures 'Textures|Mip' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
fi
rm -rf "$TMPDIR"
