#!/usr/bin/env bash
# Reproduces the tables of docs/junction_results.md and docs/endpoint_model.md: builds
# benchmark_junctions (Release) and runs it from the repository's top directory. It generates its
# three sequences into $WORK (replaced each run) and reads the VGG corridor from $VGG_DIR
# (default ../shared/data/vgg-corridor; the benchmark leaves VGG out when that is missing).
#
#   scripts/benchmark_junctions.sh [report.md [more benchmark_junctions flags]]
#   BUILD=build-other WORK=/tmp/elsewhere VGG_DIR=/data/vgg-corridor scripts/benchmark_junctions.sh
#
# WORK defaults to /tmp/junction_benchmark; a --work_dir or --vgg_dir among the flags still wins
# (they come later).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
work=${WORK:-/tmp/junction_benchmark}
vgg=${VGG_DIR:-../shared/data/vgg-corridor}
report=${1:-junction_results_run.md}
shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSFM_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target benchmark_junctions detect_junctions -j2
"$build/bin/benchmark_junctions" --output "$report" --work_dir "$work" --vgg_dir "$vgg" "$@"
