#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the binaries come staged by
# scripts/stage-device.sh (pass carry [".gl", ".device-build"]). Makes the H200 speed-against-
# accuracy charts of docs/tradeoffs.md: each argument names one, `spheres`, `grid` or
# `textured`, run with the command docs/tradeoffs.md prints above it (each limited to
# LIMIT seconds, default 280). Writes each chart's JSON, SVG and printed table packed in
# $OUT/tradeoff.tar.gz.
#
#   device run: scripts/device-tradeoff.sh spheres grid
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
limit=${LIMIT:-280}
source scripts/device-env.sh
work=$(mktemp -d)
"$bin/tessera" devices | tee "$work/devices.txt"
for chart in "$@"; do
  case $chart in
    spheres) args=(--scene spheres --knob brdf,tessellation,lod,samples,hdr,small-triangle,tile-size
                   --size 1920x1080) ;;
    grid) args=(--scene grid --objects 10000 --knob tessellation,lod,samples,small-triangle,tile-size
                --size 1920x1080) ;;
    textured) args=(--scene textured --knob anisotropy,brdf,lod,samples --size 256x144 --truth-samples 4) ;;
    *) echo "unknown chart '$chart': spheres, grid or textured" >&2; exit 2 ;;
  esac
  name=tradeoff_h200_${chart}_all
  timeout "$limit" "$bin/tessera" tradeoff --device gpu "${args[@]}" --repeat 20 --rounds 3 \
    --json "$work/$name.json" --chart "$work/$name.svg" 2>&1 | tee "$work/$name.txt" ||
    echo "chart $chart: stopped or failed (exit ${PIPESTATUS[0]})" | tee -a "$work/$name.txt"
done
tar -C "$work" -czf "$out/tradeoff.tar.gz" .
