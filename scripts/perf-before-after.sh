#!/usr/bin/env bash
# Measures two builds of `tessera` on the same device in one session, interleaved (before,
# after, before, after), so that a change's per-pass GPU times can be compared without clock or
# thermal drift between separate runs. Writes one JSON per (build, round, sweep) to OUT_DIR and
# prints a side-by-side table of per-pass medians (the better of the two rounds per build).
#
#   scripts/perf-before-after.sh BEFORE_TESSERA AFTER_TESSERA OUT_DIR [DEVICE] [SIZE] [REPEAT]
#
# DEVICE is passed to --device (default gpu), SIZE to --size (default 1920x1080). On lavapipe
# set WARM=0 (no clock warm-up) and GRID=1,100 (fewer grid objects).
set -euo pipefail
before=$1 after=$2 out=$3 device=${4:-gpu} size=${5:-1920x1080} repeat=${6:-50}
mkdir -p "$out"

# SCENE:OBJECTS for a benchmark family; a built-in scene alone (bench takes no --objects for it).
sweeps=("spheres" "lights" "textured" "environment" "grid:${GRID:-1,1000,100000}")
run() {  # build label round
  local bin=$1 label=$2 round=$3
  for s in "${sweeps[@]}"; do
    local scene=${s%%:*} objects=()
    [[ $s == *:* ]] && objects=(--objects "${s#*:}")
    "$bin" bench --device "$device" --scene "$scene" "${objects[@]}" --size "$size" \
      --backends compute --repeat "$repeat" --warmup 5 --quiet \
      --json "$out/${label}_${round}_${scene}.json"
  done
}

# Warm the clocks up (a GPU starts at idle clocks; see shared notes): a few seconds of frames.
# Skipped on lavapipe (WARM=0), whose clocks need no warming.
if [[ ${WARM:-1} == 1 ]]; then
  "$after" bench --device "$device" --scene grid --objects 100000 --size "$size" \
    --backends compute --repeat 100 --warmup 5 --quiet >/dev/null
fi
for round in 1 2; do
  run "$before" before "$round"
  run "$after" after "$round"
done
command -v jq >/dev/null || { echo "jq missing: summarise $out elsewhere"; exit 0; }
echo "per-pass GPU medians (ms), best round of two: before -> after"
for s in "${sweeps[@]}"; do
  scene=${s%%:*}
  jq -n --arg scene "$scene" \
    --slurpfile b1 "$out/before_1_$scene.json" --slurpfile b2 "$out/before_2_$scene.json" \
    --slurpfile a1 "$out/after_1_$scene.json" --slurpfile a2 "$out/after_2_$scene.json" -r '
    def best(x; y): [x, y] | min;
    range(0; $b1[0].results | length) as $i
    | ($b1[0].results[$i]) as $r
    | "\($scene) objects=\($r.objects) total " +
      "\(best($b1[0].results[$i].total_ms; $b2[0].results[$i].total_ms)) -> " +
      "\(best($a1[0].results[$i].total_ms; $a2[0].results[$i].total_ms))",
      ($r.passes_ms | keys_unsorted[] as $p
       | "    \($p) \(best($b1[0].results[$i].passes_ms[$p]; $b2[0].results[$i].passes_ms[$p])) -> " +
         "\(best($a1[0].results[$i].passes_ms[$p] // 0; $a2[0].results[$i].passes_ms[$p] // 0))")'
done
