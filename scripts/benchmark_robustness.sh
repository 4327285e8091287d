#!/usr/bin/env bash
# The robustness benchmark of issue 17 ("Must show"; figures in docs/robustness_results.md): how the
# pipeline degrades as the odometry gets worse and the scene gets barer. Builds junction_sfm,
# make_sequence and evaluate_wireframe (Release), generates every sequence into $WORK (replaced
# each run), runs junction_sfm and evaluate_wireframe on each, two sequences at a time, and prints
# markdown tables on stdout (scripts/robustness_tables.py).
#
#   scripts/benchmark_robustness.sh
#   SEEDS="1 2" LEVELS="1 6" scripts/benchmark_robustness.sh
#   BUILD=build-other WORK=/tmp/elsewhere SFM_FLAGS="--floor_prior=off" scripts/benchmark_robustness.sh
#
# Sequences: every scene x variant x level x seed, 60 frames (FRAMES), made by
#   make_sequence --scene=<scene> --trajectory=<trajectory> --frames=60 --seed=<seed>
#                 --odometry_noise_scale=<level> [--sparse]
# SCENES      "room:loop corridor:straight corridor:turns" (scene:trajectory pairs)
# VARIANTS    "full sparse" (sparse: make_sequence --sparse, few objects and bare walls)
# LEVELS      "1 3 6 10": the factor on every odometry noise term of the generator's default (2 %
#             scale error, 1 % distance noise, 0.002 rad/frame heading noise, 0.001 rad/frame bias)
# SEEDS       "1 2 3"
# JOBS        2: sequences generated and reconstructed at once (the machine has 2 cores)
# SFM_FLAGS   extra junction_sfm flags
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
work=${WORK:-/tmp/robustness_benchmark}
scenes=${SCENES:-room:loop corridor:straight corridor:turns}
variants=${VARIANTS:-full sparse}
levels=${LEVELS:-1 3 6 10}
seeds=${SEEDS:-1 2 3}
frames=${FRAMES:-60}
jobs=${JOBS:-2}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target junction_sfm make_sequence evaluate_wireframe -j2 >&2
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
mkdir -p "$work"
manifest="$work/manifest.txt"
: >"$manifest"

# One sequence: generate, reconstruct, evaluate. A failure of junction_sfm is recorded in its log
# (the tables show it), not fatal: the benchmark is about where the pipeline breaks.
run_one() {  # name scene trajectory variant level seed
  local name=$1 scene=$2 trajectory=$3 variant=$4 level=$5 seed=$6
  local sparse=()
  [ "$variant" = sparse ] && sparse=(--sparse)
  rm -rf "$work/$name.out"
  if ! "$build/bin/make_sequence" --output "$work/$name" --overwrite --frames="$frames" --seed="$seed" \
    --scene="$scene" --trajectory="$trajectory" --odometry_noise_scale="$level" "${sparse[@]}" \
    >/dev/null 2>"$work/$name.log"; then
    echo "benchmark_robustness.sh: make_sequence failed for $name ($work/$name.log)" >&2
    return 0
  fi
  echo "junction_sfm on $name" >&2
  # shellcheck disable=SC2086  # SFM_FLAGS is a list of flags
  if "$build/bin/junction_sfm" --sequence "$work/$name" --output "$work/$name.out" --progress=false \
    ${SFM_FLAGS:-} 2>"$work/$name.log"; then
    "$build/bin/evaluate_wireframe" --sequence "$work/$name" --output "$work/$name.out" \
      >"$work/$name.out/wireframe_eval.json" 2>>"$work/$name.log" || rm -f "$work/$name.out/wireframe_eval.json"
  else
    rm -f "$work/$name.out/metrics.json"
  fi
}

running=0
for pair in $scenes; do
  scene=${pair%%:*}
  trajectory=${pair#*:}
  for variant in $variants; do
    for level in $levels; do
      for seed in $seeds; do
        name="$scene-$trajectory-$variant-x$level-s$seed"
        echo "$name $scene-$trajectory $variant $level $seed" >>"$manifest"
        run_one "$name" "$scene" "$trajectory" "$variant" "$level" "$seed" &
        running=$((running + 1))
        if [ "$running" -ge "$jobs" ]; then
          wait -n
          running=$((running - 1))
        fi
      done
    done
  done
done
wait

echo "Commit $commit (at the start of the run); $frames frames; SFM_FLAGS='${SFM_FLAGS:-}'."
echo
/usr/bin/python3 scripts/robustness_tables.py "$work" "$manifest"
