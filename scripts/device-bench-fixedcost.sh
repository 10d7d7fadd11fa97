#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the staged build ("base") and
# every variant binary in .device-variants/NAME/tessera, in turn, over the points that show a
# frame's fixed cost and the passes a change may move: grid 1 / 10 / 1,000 objects, scatter
# 10^5 / 10^6, the default scene at 1 and 4 samples, at 1920x1080, medians of 3 runs of REPEAT
# frames (GRID, SCATTER, SIZE, DEVICE change the points). With FRAME_ONLY_ENV set, the grid
# points are measured again with that variable set (the base build of the sixth round's first
# session read TESSERA_EXPERIMENT_FRAME_ONLY to time only the frame; `tessera bench` now does
# that itself, docs/performance.md). With HARDWARE set, the base binary's grid (HW_GRID) against
# the hardware baseline in one run. Then renders IMAGES (scene files or names) with each
# binary and hashes the HDR and display images: a variant that should change no bit must give
# the base's. RENDER_ARGS are added to every render (e.g. "--tile-lists counted"), each image is
# rendered once more with EXTRA_RENDER_ARGS if set (e.g. "--anisotropy 16"), TIMED names more
# scenes to time (compute only), and ROUNDS repeats the scatter points, the binaries in turn.
# Every result is appended to $OUT/log.txt and $OUT/points.jsonl as it is made, and every
# command has a time limit, so that a run cut short still returns what it measured.
# Pass carry [".gl", ".device-build", ".device-variants"].
#
#   device run: scripts/device-bench-fixedcost.sh
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
repeat=${REPEAT:-50}
device=${DEVICE:-gpu}
scatter=${SCATTER:-100000,1000000}
images=${IMAGES:-spheres}
limit=${LIMIT:-90}
[[ $device == gpu ]] && source scripts/device-env.sh
bin=${bin:-$PWD/.device-build}
log=$out/log.txt
work=$(mktemp -d)
say() { echo "$(date +%T) $*" | tee -a "$log"; }
binaries=("${BASE_NAME:-base}:$bin/tessera")
for v in .device-variants/*/; do
  [[ -x $v/tessera ]] && binaries+=("$(basename "$v"):$PWD/$v/tessera")
done
point() {  # name binary args...
  local f=$1 exe=$2; shift 2
  if timeout "$limit" "$exe" bench --device "$device" --size "$size" --runs 3 \
      --warmup-ms 500 --quiet --json "$work/$f.json" "$@"; then
    python3 - "$work/$f.json" "$f" >> "$out/points.jsonl" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for p in d.get("results") or d.get("points"):
    if p.get("backend") != "compute": continue
    print(json.dumps({"point": sys.argv[2], "objects": p.get("objects"), "total_ms": p["total_ms"],
                      "per_pass_total_ms": p.get("per_pass_total_ms"),
                      "min_ms": p.get("min_ms"), "max_ms": p.get("max_ms"),
                      "spread_pct": p.get("run_spread_pct"), "passes_ms": p["passes_ms"]}))
PY
    say "$f $(python3 -c "import json,sys; print(' '.join('%s:%.4f' % (p.get('objects'), p['total_ms']) for p in (json.load(open(sys.argv[1])).get('results') or []) if p['backend'] == 'compute'))" "$work/$f.json")"
  else
    say "$f FAILED or timed out (status $?)"
  fi
}
say "start; binaries: ${binaries[*]}"
# Warm the clocks (shared/NOTES.md: about 10 s of a heavy load).
[[ $device == gpu ]] && timeout 60 "$bin/tessera" bench --device gpu --scene grid --objects 100000 \
  --size "$size" --backends hardware --repeat 20 --warmup-ms 3000 --quiet
say "warm"
grid=${GRID:-1,10,1000}
# GRID_BACKENDS=compute,hardware keeps the clocks up between the compute path's short frames: the
# H200 measured the compute-only grid sweep with one run of three up to twice as slow.
for b in "${binaries[@]}"; do
  point "${b%%:*}_grid" "${b#*:}" --scene grid --objects "$grid" --repeat "$repeat" \
    --backends "${GRID_BACKENDS:-compute}"
done
if [[ -n ${FRAME_ONLY_ENV:-} ]]; then
  export "$FRAME_ONLY_ENV=1"
  for b in "${binaries[@]}"; do
    point "${b%%:*}_gridframeonly" "${b#*:}" --scene grid --objects "$grid" --repeat "$repeat" \
      --backends compute
  done
  unset "$FRAME_ONLY_ENV"
fi
for b in "${binaries[@]}"; do
  point "${b%%:*}_spheres" "${b#*:}" --scene spheres --repeat "$repeat" --backends compute
  point "${b%%:*}_spheres4" "${b#*:}" --scene spheres --samples 4 --repeat "$repeat" --backends compute
  for scene in ${TIMED:-}; do
    point "${b%%:*}_$(basename "$scene" .json)" "${b#*:}" --scene "$scene" --repeat "$repeat" \
      --backends compute
  done
done
# The first binary against the hardware baseline, in one run: compute / hardware ratios.
if [[ -n ${HARDWARE:-} ]]; then
  b=${binaries[0]}
  timeout 150 "${b#*:}" bench --device "$device" --size "$size" --scene grid --objects "${HW_GRID:-$grid}" \
    --backends compute,hardware --runs 3 --repeat "$repeat" --warmup-ms 500 --quiet \
    --json "$out/hardware_grid.json" && say "hardware: $(python3 -c "import json,sys; print(' '.join('%s:%.2fx' % (r['objects'], 1/r['ratio']) for r in json.load(open(sys.argv[1]))['compute_over_hardware']))" "$out/hardware_grid.json")"
fi
for r in $(seq "${ROUNDS:-1}"); do
  for b in "${binaries[@]}"; do
    point "${b%%:*}_scatter_r$r" "${b#*:}" --scene scatter --objects "$scatter" --repeat 10 --backends compute
  done
done
for b in "${binaries[@]}"; do
  name=${b%%:*} exe=${b#*:}
  for scene in $images; do
    tag=$(basename "$scene" .json)
    for s in 1 4; do
      for extra in "" ${EXTRA_RENDER_ARGS:+"$EXTRA_RENDER_ARGS"}; do
        f=$work/img_${name}_${tag}_s$s${extra:+_extra}
        if timeout "$limit" "$exe" render --device "$device" --scene "$scene" --size "$size" \
            --samples $s --out "$f.png" --hdr-out "$f.pfm" ${RENDER_ARGS:-} $extra > /dev/null; then
          say "image ${name}_${tag}_s$s${extra:+ $extra} hdr $(sha256sum < "$f.pfm" | cut -c1-16) display $(sha256sum < "$f.png" | cut -c1-16)"
        else
          say "image ${name}_${tag}_s$s${extra:+ $extra} FAILED or timed out"
        fi
      done
    done
  done
done
say "done"
