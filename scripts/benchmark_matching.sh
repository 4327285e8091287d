#!/usr/bin/env bash
# Reproduces the tables of docs/matching_results.md: builds make_sequence, import_sequence,
# match_junctions and benchmark_matching (Release), prepares the sequences in $WORK (replaced each
# run) and runs the benchmark from the repository's top directory.
#
#   scripts/benchmark_matching.sh [report.md [more benchmark_matching flags]]
#   BUILD=build-other WORK=/tmp/elsewhere scripts/benchmark_matching.sh
#
# Sequences (fixed seeds, so the same bytes every run):
#   corridor  make_sequence --scene=corridor --trajectory=straight --frames=30 --seed=11
#   room      make_sequence --scene=room --trajectory=loop --frames=30 --seed=12
#   vgg       import_sequence --format vgg --input ../shared/data/vgg-corridor (odometry seed 1)
# Fig. 6-style pictures of the Table 2 pairs (wrong matches numbered in red) go to $WORK/pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
work=${WORK:-/tmp/matching_benchmark}
vgg=${VGG_DIR:-../shared/data/vgg-corridor}
report=${1:-matching_results_run.md}
shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSFM_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target make_sequence import_sequence match_junctions benchmark_matching -j2
mkdir -p "$work"
"$build/bin/make_sequence" --output "$work/corridor" --overwrite --scene=corridor --trajectory=straight \
  --frames=30 --seed=11
"$build/bin/make_sequence" --output "$work/room" --overwrite --scene=room --trajectory=loop --frames=30 --seed=12
generated="$work/corridor,$work/room"
vgg_flags=()
if [ -d "$vgg" ]; then
  "$build/bin/import_sequence" --format vgg --input "$vgg" --output "$work/vgg" --overwrite --seed 1 2>/dev/null
  vgg_flags=(--vgg_sequence "$work/vgg" --vgg_dir "$vgg")
else
  echo "benchmark_matching.sh: $vgg not found; the VGG parts are left out" >&2
fi
"$build/bin/benchmark_matching" --generated "$generated" "${vgg_flags[@]}" --image_dir "$work/pictures" \
  --output "$report" "$@"
