#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the binaries come staged by
# scripts/stage-device.sh (pass carry [".gl", ".device-build"]). Measures issue 12's level of
# detail in one session: the grid family (N = 1 ... 10^6) and the default scene at 1920x1080,
# both backends, `--lod off` against `--lod auto` (0.5 px), 3 whole runs each. Writes the JSON,
# CSV and printed tables packed in $OUT/lod.tar.gz and prints a short table last.
#
#   device run: scripts/device-bench-lod.sh        (SIZE=WxH to change 1920x1080)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
objects=${OBJECTS:-1,10,100,1000,10000,100000,1000000}
source scripts/device-env.sh
work=$(mktemp -d)
"$bin/tessera" devices | tee "$work/devices.txt"
# Clocks up before anything is timed.
"$bin/tessera" bench --device gpu --scene grid --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet
for lod in off auto; do
  "$bin/tessera" bench --device gpu --scene grid --objects "$objects" --size "$size" \
    --backends compute,hardware --lod "$lod" --repeat 20 --runs 3 --warmup-ms 1000 \
    --json "$work/grid_lod_$lod.json" --csv "$work/grid_lod_$lod.csv" \
    --chart "$work/grid_lod_$lod.svg" | tee "$work/grid_lod_$lod.txt"
  "$bin/tessera" bench --device gpu --scene spheres --size "$size" \
    --backends compute,hardware --lod "$lod" --repeat 50 --runs 3 --warmup-ms 1000 \
    --json "$work/spheres_lod_$lod.json" --csv "$work/spheres_lod_$lod.csv" |
    tee "$work/spheres_lod_$lod.txt"
done
tar -C "$work" -czf "$out/lod.tar.gz" .
