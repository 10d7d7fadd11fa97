#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing. Issue 13's measurements in one
# session, 1920x1080:
#   1. before and after, per pass: the binaries staged by scripts/stage-device.sh in
#      .device-build (after) and a copy of an earlier staging in .device-before (before), run in
#      turn, point by point, compute backend only: grid at 1, 1000 and 10^6 objects (fixed cost,
#      setup), scatter at 10^5 and 10^6 (overdraw), the default scene at 1 and 4 samples;
#   2. the "done when" sweep with the new binaries: `tessera bench --runs 3`, both backends,
#      over grid (1 ... 10^6), scatter (10 ... 10^6), huge and yardstick, and the minimal
#      graphics program on the yardstick's layout.
# Pass carry [".gl", ".device-build", ".device-before"]. Writes everything packed in
# $OUT/issue13.tar.gz and prints the summary tables last. SKIP_BEFORE=1 leaves out part 1,
# SKIP_SWEEPS=1 part 2.
#
#   device run: scripts/device-bench-issue13.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
repeat=${REPEAT:-20}
source scripts/device-env.sh
before=$PWD/.device-before
work=$(mktemp -d)
# Packed however the script ends (a time limit keeps what was measured).
trap 'tar -C "$work" -czf "$out/issue13.tar.gz" --exclude=./tmp .' EXIT
"$bin/tessera" devices | tee "$work/devices.txt"
# Clocks up before anything is timed.
"$bin/tessera" bench --device gpu --scene grid --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet

point() {  # point TAG BIN ARGS...: one compute-only measurement, 3 runs
  local tag=$1 b=$2
  shift 2
  LD_LIBRARY_PATH=$b "$b/tessera" bench --device gpu --size "$size" --backends compute \
    --repeat "$repeat" --runs 3 --warmup-ms 500 --json "$work/$tag.json" "$@" > "$work/$tag.txt"
}
if [[ -z ${SKIP_BEFORE:-} && -x $before/tessera ]]; then
  for case in "grid 1,1000,1000000" "scatter 100000,1000000" "spheres 1 1" "spheres 1 4"; do
    set -- $case
    for version in before after; do
      b=$bin
      [[ $version == before ]] && b=$before
      if [[ $1 == spheres ]]; then
        point "pass_${version}_spheres_s$3" "$b" --scene spheres --samples "$3"
      else
        point "pass_${version}_$1" "$b" --scene "$1" --objects "$2"
      fi
    done
  done
fi

sweep() {  # sweep SCENE OBJECTS
  "$bin/tessera" bench --device gpu --scene "$1" --objects "$2" --size "$size" \
    --backends compute,hardware --repeat "$repeat" --runs 3 --warmup-ms 500 \
    --json "$work/sweep_$1.json" --csv "$work/sweep_$1.csv" --chart "$work/sweep_$1.svg" |
    tee "$work/sweep_$1.txt"
}
if [[ -z ${SKIP_SWEEPS:-} ]]; then
  sweep grid 1,10,49,100,1000,10000,100000,1000000
  sweep yardstick 1,10,49,100,1000,10000,100000
  sweep scatter 10,1000,100000,1000000
  sweep huge 1,4,16,64,256
  "$bin/tessera_minimal_graphics" --device gpu --objects 1,10,49,100,1000,10000,100000 \
    --size "$size" --repeat "$repeat" --runs 3 --warmup-ms 500 --json "$work/minimal.json" \
    --csv "$work/minimal.csv" > "$work/minimal.txt"
fi

# Summaries: per-pass medians before/after, then each sweep's ratio lines.
for f in "$work"/pass_after_*.json; do
  tag=${f##*/pass_after_}
  tag=${tag%.json}
  [[ -f $work/pass_before_$tag.json ]] || continue
  python3 - "$work/pass_before_$tag.json" "$f" "$tag" <<'EOF' || true
import json, sys
rows = lambda f: {r["objects"]: r for r in json.load(open(f))["results"]}
before, after, tag = rows(sys.argv[1]), rows(sys.argv[2]), sys.argv[3]
for n in after:
    b, a = before.get(n), after[n]
    bp = b["passes_ms"] if b else {}
    ap = a["passes_ms"]
    passes = [k for k in list(bp) + [k for k in ap if k not in bp] if ap.get(k) or bp.get(k)]
    print(f"{tag} N={n}: total {b['total_ms'] if b else float('nan'):.3f} -> {a['total_ms']:.3f} ms; "
          + ", ".join(f"{k} {bp.get(k, 0):.3f}->{ap.get(k, 0):.3f}" for k in passes))
EOF
done
[[ -f $work/minimal.txt ]] && cat "$work/minimal.txt"
grep -h "faster\|slower" "$work"/sweep_*.txt || true
