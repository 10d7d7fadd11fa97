#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing. Issue 12's anti-aliasing time
# bound: the default scene at 1920x1080, 1 sample against 4 samples with each coverage mode
# (count, analytic, silhouette, and silhouette with walks of 3 and 4 steps: STEP_POINTS), per
# pass, medians of 3 runs of REPEAT frames. With a staging
# in .device-before too (a copy of an earlier scripts/stage-device.sh), each point runs the
# before and after binaries in turn. Pass carry [".gl", ".device-build"(, ".device-before")].
# Writes $OUT/aa.tar.gz and prints a table of frame and per-pass medians last.
#
#   device run: scripts/device-bench-aa.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
repeat=${REPEAT:-50}
source scripts/device-env.sh
work=$(mktemp -d)
trap 'tar -C "$work" -czf "$out/aa.tar.gz" .' EXIT
"$bin/tessera" devices | tee "$work/devices.txt"
# Clocks up before anything is timed.
"$bin/tessera" bench --device gpu --scene grid --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet
versions=after
[[ -x $PWD/.device-before/tessera ]] && versions="before after"
# A third field is the silhouette walk's --aa-walk-steps, run by the new build alone.
for point in "1 count" "4 count" "4 analytic" "4 silhouette" ${STEP_POINTS:-"4 silhouette 3" "4 silhouette 4"}; do
  set -- $point
  steps=()
  name=s$1_$2
  [[ $# -ge 3 ]] && steps=(--aa-walk-steps "$3") && name=${name}_steps$3
  for version in $versions; do
    [[ $version == before && ${#steps[@]} -gt 0 ]] && continue
    b=$bin
    [[ $version == before ]] && b=$PWD/.device-before
    LD_LIBRARY_PATH=$b "$b/tessera" bench --device gpu --scene spheres --size "$size" \
      --samples "$1" --aa-coverage "$2" "${steps[@]}" --backends compute --repeat "$repeat" \
      --runs 3 --warmup-ms 500 --json "$work/${version}_$name.json" > "$work/${version}_$name.txt"
  done
done
python3 - "$work" <<'PY'
import json, sys, pathlib
rows = []
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    p = json.loads(f.read_text())
    p = (p.get("points") or p.get("results") or p)[0]
    passes = {k: v for k, v in p["passes_ms"].items() if v}
    rows.append((f.stem, p["total_ms"], p["run_spread_pct"], passes))
for name, total, spread, passes in rows:
    print(f"{name:24s} frame {total:.3f} ms (spread {spread:.1f} %)  " +
          " ".join(f"{k} {v:.3f}" for k, v in passes.items()))
PY
