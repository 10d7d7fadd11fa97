#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the default scene at 1920x1080
# and SAMPLES samples with coverage COVERAGE, for the staged build and every variant binary in
# .device-variants/NAME/tessera (copies of scripts/stage-device.sh's tessera built from edited
# shaders), each in turn, ROUNDS times, plus the staged build's 1 sample and 4-sample count
# frames, medians of 3 runs of REPEAT frames. Pass carry [".gl", ".device-build",
# ".device-variants"]. Writes $OUT/variants.tar.gz and prints frame and pass medians.
#
#   device run: scripts/device-bench-variants.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
repeat=${REPEAT:-50}
samples=${SAMPLES:-4}
coverage=${COVERAGE:-silhouette}
rounds=${ROUNDS:-2}
source scripts/device-env.sh
work=$(mktemp -d)
trap 'tar -C "$work" -czf "$out/variants.tar.gz" .' EXIT
"$bin/tessera" bench --device gpu --scene grid --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet
point() {  # name binary samples coverage
  "$2" bench --device gpu --scene spheres --size "$size" --samples "$3" --aa-coverage "$4" \
    --backends compute --repeat "$repeat" --runs 3 --warmup-ms 500 --json "$work/$1.json" > "$work/$1.txt"
}
for r in $(seq "$rounds"); do
  point "r${r}_base_s1_count" "$bin/tessera" 1 count
  point "r${r}_base_s${samples}_count" "$bin/tessera" "$samples" count
  point "r${r}_base_s${samples}_$coverage" "$bin/tessera" "$samples" "$coverage"
  for v in .device-variants/*/; do
    [[ -x $v/tessera ]] && point "r${r}_$(basename "$v")_s${samples}_$coverage" "$v/tessera" "$samples" "$coverage"
  done
done
python3 - "$work" <<'PY'
import json, sys, pathlib
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    p = json.loads(f.read_text())
    p = (p.get("points") or p.get("results") or p)[0]
    passes = {k: v for k, v in p["passes_ms"].items() if v}
    print(f"{f.stem:34s} frame {p['total_ms']:.3f} ms (spread {p['run_spread_pct']:.1f} %)  " +
          " ".join(f"{k} {v:.3f}" for k, v in passes.items() if k in ('shade', 'outline', 'raster_small')))
PY
