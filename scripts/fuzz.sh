#!/usr/bin/env bash
# Builds the libFuzzer targets (CMake preset `asan`: clang, address and undefined-behaviour
# sanitizers) and runs each for a while over seed corpora made from real files.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: 60 s; all targets)
#   targets: obj gltf glb scene_file bsp pk3
#
# BOUNCE_FUZZ_BUILD names a build folder configured with -DBOUNCE_FUZZ=ON and already built (the
# script then builds nothing); by default the script configures and builds the asan preset's
# build/asan. FUZZ_RUNS=N also stops each target after N executions (a campaign: FUZZ_RUNS=1000000
# with a generous time). The corpus each run grows is kept in BUILD/run/corpus/TARGET and reused
# by the next run; an input that crashes, leaks, hangs (10 s) or meets undefined behaviour
# (UBSAN_OPTIONS=halt_on_error=1) is saved in BUILD/run/artifacts and the script fails. Each
# target's executions and coverage are printed at the end (docs/reliability.md).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]} > 0)) || targets=(obj gltf glb scene_file bsp pk3)

build=${BOUNCE_FUZZ_BUILD:-build/asan}
if [[ -z ${BOUNCE_FUZZ_BUILD:-} ]]; then
  cmake --preset asan >/dev/null
  cmake --build "$build" -j2 --target fuzz_write_seeds $(printf 'fuzz_%s ' "${targets[@]}")
fi
runs=()
[[ -z ${FUZZ_RUNS:-} ]] || runs=(-runs="$FUZZ_RUNS")

run=$build/run
mkdir -p "$run/artifacts"
seeds_for() {  # fills $run/seeds/$1 with real files of that kind
  local dir="$run/seeds/$1" assimp=/usr/share/assimp/models
  rm -rf "$dir" && mkdir -p "$dir"
  case $1 in
    obj)  # the OBJ text, then "#mtl" and its material library (fuzz/fuzz_obj.cpp)
      for obj in scenes/cornell-box/cornell-box.obj scenes/models/cube.obj; do
        { cat "$obj"; printf '\n#mtl\n'; cat "${obj%.obj}.mtl"; } >"$dir/$(basename "$obj")"
      done
      [[ -d $assimp ]] && find "$assimp/OBJ" -name '*.obj' -size -64k -exec cp {} "$dir/" \; ;;
    gltf) [[ -d $assimp ]] && find "$assimp/glTF2" -name '*.gltf' -size -256k -exec cp --backup=numbered {} "$dir/" \; ;;
    glb)  [[ -d $assimp ]] && find "$assimp/glTF2" -name '*.glb' -size -256k -exec cp --backup=numbered {} "$dir/" \; ;;
    scene_file) cp scenes/*.bounce.json "$dir/" ;;
    bsp)  $build/fuzz/fuzz_write_seeds "$dir" "$run/seeds" ;;
    pk3)  $build/fuzz/fuzz_write_seeds "$run/seeds" "$dir" ;;
  esac
  true
}

failed=0
for t in "${targets[@]}"; do
  seeds_for "$t"
  mkdir -p "$run/corpus/$t"
  log="$run/$t.log"
  echo "fuzz_$t: ${seconds} s"
  if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 $build/fuzz/fuzz_$t "$run/corpus/$t" "$run/seeds/$t" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -max_len=1048576 \
      -print_final_stats=1 -artifact_prefix="$run/artifacts/$t-" "${runs[@]}" >"$log" 2>&1; then
    echo "fuzz_$t FAILED: see $log and $run/artifacts" >&2
    grep -a -E "ERROR|SUMMARY|Test unit written" "$log" | head -5 >&2 || true
    failed=1
  fi
  grep -a -E "stat::number_of_executed_units|stat::peak_rss_mb|cov: " "$log" | tail -3
  # Inputs slower than 10 s are saved but do not stop the run (a loaded machine slows any of
  # them): named here so that they are looked at.
  for slow in "$run/artifacts/$t-slow-unit-"*; do
    if [[ -e $slow ]]; then echo "fuzz_$t: a slow input was saved: $slow (time it alone)" >&2; fi
  done
done
exit $failed
