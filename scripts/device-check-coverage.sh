#!/usr/bin/env bash
# Runs ON THE GPU MACHINE (the device tool) and builds nothing: the staged build ("base") and
# every variant binary in .device-variants/NAME/tessera, in turn, over the code that measures
# coverage or clips to the view: analytic and silhouette anti-aliasing on the default scene at
# 4 and 16 samples, and the textured scene (whose floor the clip pass clips), at 1920x1080,
# medians of 3 runs of REPEAT frames, ROUNDS times with the binaries interleaved. Then renders
# the built-in scenes with each binary under every coverage setting and hashes the HDR and
# display images: a variant that should change no bit must give the base's. Results go to
# $OUT/log.txt as they are made. Pass carry [".gl", ".device-build", ".device-variants"].
#
#   device run: scripts/device-check-coverage.sh
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:?OUT must name the output folder (the device tool sets it)}
size=${SIZE:-1920x1080}
repeat=${REPEAT:-50}
source scripts/device-env.sh
log=$out/log.txt
work=$(mktemp -d)
say() { echo "$(date +%T) $*" | tee -a "$log"; }
binaries=("base:$bin/tessera")
for v in .device-variants/*/; do
  [[ -x $v/tessera ]] && binaries+=("$(basename "$v"):$PWD/$v/tessera")
done
point() {  # name binary args...
  local f=$1 exe=$2; shift 2
  if timeout 90 "$exe" bench --device gpu --size "$size" --runs 3 --repeat "$repeat" \
      --warmup-ms 500 --backends compute --quiet --json "$work/$f.json" "$@"; then
    say "$f $(python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))['results'][0]
p = r['passes_ms']
print('total %.4f ms (spread %s %%): shade %.4f outline %.4f clip %.4f' % (r['total_ms'],
      r.get('run_spread_pct'), p['shade'], p['outline'], p['clip']))" "$work/$f.json")"
  else
    say "$f FAILED or timed out (status $?)"
  fi
}
say "start; binaries: ${binaries[*]}"
# Warm the clocks (shared/NOTES.md: about 10 s of a heavy load).
timeout 60 "$bin/tessera" bench --device gpu --scene grid --objects 100000 --size "$size" \
  --backends hardware --repeat 20 --warmup-ms 3000 --quiet
for r in $(seq "${ROUNDS:-2}"); do
  for b in "${binaries[@]}"; do
    name=${b%%:*} exe=${b#*:}
    for s in 4 16; do
      point "${name}_r${r}_analytic_s$s" "$exe" --scene spheres --samples "$s" --aa-coverage analytic
      point "${name}_r${r}_silhouette_s$s" "$exe" --scene spheres --samples "$s" --aa-coverage silhouette
    done
    point "${name}_r${r}_textured_s1" "$exe" --scene textured
  done
done
for b in "${binaries[@]}"; do
  name=${b%%:*} exe=${b#*:}
  for scene in spheres lights textured environment metals; do
    for args in "--samples 1" "--samples 4 --aa-coverage count" "--samples 4 --aa-coverage analytic" \
        "--samples 16 --aa-coverage analytic" "--samples 4 --aa-coverage silhouette" \
        "--samples 16 --aa-coverage silhouette"; do
      f=$work/img
      if timeout 90 "$exe" render --device gpu --scene "$scene" --size "$size" $args \
          --out "$f.png" --hdr-out "$f.pfm" > /dev/null; then
        say "image ${name} ${scene} ${args} hdr $(sha256sum < "$f.pfm" | cut -c1-16) display $(sha256sum < "$f.png" | cut -c1-16)"
      else
        say "image ${name} ${scene} ${args} FAILED or timed out"
      fi
    done
  done
done
say "done"
