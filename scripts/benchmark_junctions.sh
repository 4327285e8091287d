#!/usr/bin/env bash
# Reproduces the tables of docs/junction_results.md and docs/endpoint_model.md: builds
# benchmark_junctions (Release) and runs it from the repository's top directory. It generates its
# three sequences into /tmp/junction_benchmark (replaced each run) and reads ../shared/data/vgg-corridor.
#
#   scripts/benchmark_junctions.sh [report.md [more benchmark_junctions flags]]
#   BUILD=build-other scripts/benchmark_junctions.sh      # another build directory
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
report=${1:-junction_results_run.md}
shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target benchmark_junctions detect_junctions -j2
"$build/bin/benchmark_junctions" --output "$report" "$@"
