#!/usr/bin/env bash
# Builds the loader fuzzers (TESSERA_FUZZ=ON, clang-14, in build-fuzz/) and runs them all at
# once for SECONDS (default 60), at low priority. Exit status 0 only if no target crashed,
# leaked, hit a sanitizer report, an internal check, an uncaught exception or a timeout.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: gltf obj scene_json; default all)
# FUZZ_RUNS=N also stops each target after N executions (the long runs of docs/fuzzing.md).
# New inputs are kept in build-fuzz/corpus/TARGET; a failing input is written to
# build-fuzz/artifacts/ and its log to build-fuzz/fuzz-TARGET.log.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# A cache without the generator's file is a configure that was cut short (Ctrl+C, or another
# configure at the same moment): configure again rather than build nothing.
if [[ ! -f build-fuzz/CMakeCache.txt || ! ( -f build-fuzz/Makefile || -f build-fuzz/build.ninja ) ]]; then
  cmake -S . -B build-fuzz -DTESSERA_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 "${launcher[@]}" >/dev/null
fi
cmake --build build-fuzz -j "$(nproc 2>/dev/null || echo 2)"

targets=("$@")
if ((${#targets[@]} == 0)); then
  for t in gltf obj scene_json; do
    [[ -x build-fuzz/fuzz/${t}_fuzzer ]] && targets+=("$t")
  done
fi

# Seeds: the test data and Debian's assimp-testmodels, files up to the input size limit.
assimp=/usr/share/assimp/models
seed_files() {  # TARGET -> file names
  case $1 in
    gltf)
      find tests/data "$assimp/glTF2" -type f \( -name '*.gltf' -o -name '*.glb' \) \
        -size -16k 2>/dev/null ;;
    obj)
      find tests/data "$assimp/OBJ" -type f -name '*.obj' -size -16k 2>/dev/null ;;
    scene_json)
      find scenes tests/data -type f -name '*.json' -size -16k 2>/dev/null ;;
  esac
}
make_seeds() {  # TARGET DIR
  rm -rf "$2" && mkdir -p "$2"
  local f n=0
  while read -r f; do
    n=$((n + 1))
    if [[ $1 == obj ]]; then
      # The OBJ fuzzer's input is an OBJ, a line "#%fuzz.mtl", then the MTL it names.
      local mtl
      mtl=$(sed -n 's/^mtllib[ \t]\+//p' "$f" | head -n 1 | tr -d '\r')
      sed 's/^mtllib[ \t].*/mtllib fuzz.mtl/' "$f" >"$2/$n"
      if [[ -n $mtl && -f $(dirname "$f")/$mtl ]]; then
        printf '\n#%%fuzz.mtl\n' >>"$2/$n"
        cat "$(dirname "$f")/$mtl" >>"$2/$n"
      fi
    else
      cp "$f" "$2/$n"
    fi
  done < <(seed_files "$1")
}

declare -A max_len=([gltf]=16384 [obj]=8192 [scene_json]=8192)
declare -A dict=([gltf]=fuzz/gltf.dict [obj]=fuzz/obj.dict [scene_json]=fuzz/json.dict)
scratch=$(mktemp -d /dev/shm/tessera-fuzz.XXXXXX 2>/dev/null || mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export TESSERA_FUZZ_SCRATCH=$scratch
export UBSAN_OPTIONS=print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}
mkdir -p build-fuzz/artifacts
# The targets run at once, sharing the cores (on CI's 2 cores each gets about two thirds of one
# for SECONDS): one after another they cost three times SECONDS of wall time.
pids=()
for t in "${targets[@]}"; do
  make_seeds "$t" "build-fuzz/seeds/$t"
  mkdir -p "build-fuzz/corpus/$t"
  log=build-fuzz/fuzz-$t.log
  echo "fuzz: $t for ${seconds}s (log: $log)" >&2
  nice -n 10 "build-fuzz/fuzz/${t}_fuzzer" -max_total_time="$seconds" -max_len="${max_len[$t]}" \
    -dict="${dict[$t]}" -runs="${FUZZ_RUNS:--1}" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/$t-" \
    "build-fuzz/corpus/$t" "build-fuzz/seeds/$t" >"$log" 2>&1 &
  pids+=($!)
done
failed=()
for i in "${!targets[@]}"; do
  t=${targets[$i]}
  log=build-fuzz/fuzz-$t.log
  if wait "${pids[$i]}"; then
    echo "fuzz: $t:" >&2
    grep -E '^(Done|stat::number_of_executed_units|stat::peak_rss_mb)' "$log" >&2 || true
  else
    echo "fuzz: $t FAILED:" >&2
    grep -E 'ERROR|SUMMARY|runtime error|internal check|terminate|what\(\)|Test unit written' \
      "$log" >&2 || tail -n 30 "$log" >&2
    failed+=("$t")
  fi
done
if ((${#failed[@]} > 0)); then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
