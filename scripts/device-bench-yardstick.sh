#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the binaries come staged by
# scripts/stage-device.sh (run it here first; pass carry [".gl", ".device-build"]). Measures
# issue 13's yardstick in one session: the minimal graphics program (bench/minimal_graphics.cpp)
# and `tessera bench --scene yardstick` with both backends, 3 whole runs each, then the hardware
# baseline once more with --generic-shading (as it was before it was specialized to the scene),
# then the minimal program's ladder (--variant all: from the issue's program to the baseline's
# work one difference a rung, bench/minimal_graphics.cpp's kRungs) at N = 1 .. 1000, 3 whole
# runs with the same frames and warm-up. Writes JSON, CSV, an SVG chart and the printed tables
# under $OUT and prints two short tables last: each N's minimal, hardware and compute medians
# with their run-to-run spread; and each rung's median per N with its step over the rung
# before, the baseline of the same session (`tessera bench`) last.
#
# On the GPU about 4.5 minutes on the H200 (each point warms up >= 1 s, then 50 frames): the
# 3-second clock warm-up; minimal, compute and hardware at 7 counts x 3 runs and generic at 7
# (about 2 minutes, most of it the 1-second warm-ups); the ladder's 8 rungs x 5 counts x 3 runs
# (120 points, about 2.3 minutes). Scene uploads (10^5 spheres) add CPU time. A warm-up whose
# frame time does not settle stops at 4 x its time: were every ladder point to do so, the
# ladder would take about 8 minutes (LADDER_WARMUP_MS=500 halves that).
#
#   device run: scripts/device-bench-yardstick.sh        (SIZE=WxH to change 1920x1080;
#                                                        LADDER_OBJECTS=... the ladder's counts)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
objects=${OBJECTS:-1,10,49,100,1000,10000,100000}
ladder_objects=${LADDER_OBJECTS:-1,10,49,100,1000}
ladder_warmup_ms=${LADDER_WARMUP_MS:-1000}
tag=yardstick_${size}
source scripts/device-env.sh
[[ -x $bin/tessera_minimal_graphics ]] ||
  { echo "no staged tessera_minimal_graphics in $bin: run scripts/stage-device.sh" >&2; exit 1; }
"$bin/tessera" devices | tee "$out/devices.txt"

# Clocks up before anything is timed (a GPU starts at idle clocks): a few seconds of heavy
# frames. Each point then warms up by time as well (--warmup-ms).
"$bin/tessera" bench --device gpu --scene yardstick --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet

"$bin/tessera_minimal_graphics" --device gpu --objects "$objects" --size "$size" --repeat 50 \
  --runs 3 --warmup-ms 1000 --json "$out/minimal_$tag.json" --csv "$out/minimal_$tag.csv" |
  tee "$out/minimal_$tag.txt"
"$bin/tessera" bench --device gpu --scene yardstick --objects "$objects" --size "$size" \
  --backends compute,hardware --repeat 50 --runs 3 --warmup-ms 1000 \
  --json "$out/bench_$tag.json" --csv "$out/bench_$tag.csv" --chart "$out/bench_$tag.svg" |
  tee "$out/bench_$tag.txt"
"$bin/tessera" bench --device gpu --scene yardstick --objects "$objects" --size "$size" \
  --backends hardware --generic-shading --repeat 50 --warmup-ms 1000 \
  --json "$out/bench_${tag}_generic.json" --csv "$out/bench_${tag}_generic.csv" |
  tee "$out/bench_${tag}_generic.txt"

"$bin/tessera_minimal_graphics" --device gpu --variant all --objects "$ladder_objects" \
  --size "$size" --repeat 50 --runs 3 --warmup-ms "$ladder_warmup_ms" \
  --json "$out/ladder_$tag.json" --csv "$out/ladder_$tag.csv" | tee "$out/ladder_$tag.txt"

# The short tables: columns of the CSVs by name.
echo
echo "yardstick $size, medians of 3 runs (run-to-run spread), ms"
awk -F, '
  FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; file++; next }
  file == 1 { m[$2] = $col["total_ms"]; ms[$2] = $col["run_spread_pct"]; order[++n] = $2 }
  file == 2 { t[$3, $2] = $col["total_ms"]; s[$3, $2] = $col["run_spread_pct"] }
  file == 3 { g[$2] = $col["total_ms"] }
  END {
    printf "%8s %18s %18s %10s %14s %18s %10s\n", "objects", "minimal", "hardware",
           "hw/minimal", "hw generic", "compute", "hw/compute"
    for (k = 1; k <= n; ++k) {
      o = order[k]
      printf "%8s %10.3f (%4.1f%%) %10.3f (%4.1f%%) %10.2f %14.3f %10.3f (%4.1f%%) %10.2f\n",
             o, m[o], ms[o], t["hardware", o], s["hardware", o], t["hardware", o] / m[o], g[o],
             t["compute", o], s["compute", o], t["hardware", o] / t["compute", o]
    }
  }' "$out/minimal_$tag.csv" "$out/bench_$tag.csv" "$out/bench_${tag}_generic.csv" |
  tee "$out/summary_$tag.txt"

# The ladder: rung after rung (the CSV's order: every count of rung 0, then of rung 1, ...),
# then the hardware baseline of this session's `tessera bench` run at the same counts.
echo
echo "ladder, yardstick $size, medians of 3 runs, ms (step over the rung before)"
awk -F, '
  FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; file++; next }
  file == 1 {
    r = $col["variant"]; o = $col["objects"]
    if (!(r in name)) { rungs[++nr] = r; name[r] = $col["backend"] }
    if (!(o in seen)) { seen[o] = 1; counts[++nc] = o }
    ms[r, o] = $col["total_ms"]
  }
  file == 2 && $col["backend"] == "hardware" { hw[$col["objects"]] = $col["total_ms"] }
  END {
    printf "%-20s", "rung"
    for (k = 1; k <= nc; ++k) printf " %19s", counts[k]
    printf "\n"
    for (j = 1; j <= nr; ++j) {
      r = rungs[j]
      printf "%-20s", r " " name[r]
      for (k = 1; k <= nc; ++k) {
        o = counts[k]
        if (j == 1) printf " %19.3f", ms[r, o]
        else printf " %8.3f (%+8.3f)", ms[r, o], ms[r, o] - ms[rungs[j - 1], o]
      }
      printf "\n"
    }
    printf "%-20s", "hardware baseline"
    last = rungs[nr]
    for (k = 1; k <= nc; ++k) {
      o = counts[k]
      if (o in hw) printf " %8.3f (%+8.3f)", hw[o], hw[o] - ms[last, o]
      else printf " %19s", "-"
    }
    printf "\n"
  }' "$out/ladder_$tag.csv" "$out/bench_$tag.csv" | tee "$out/ladder_summary_$tag.txt"
