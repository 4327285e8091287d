#!/usr/bin/env bash
# Reproduces the tables of docs/segments.md: builds benchmark_segments (Release) and runs it from
# the repository's top directory on the VGG Corridor images (../shared/data/vgg-corridor) and the
# default generated sequence's images (with their truth), single thread.
#
#   scripts/benchmark_segments.sh [report.md [more benchmark_segments flags]]
#   BUILD=build-other scripts/benchmark_segments.sh      # another build directory
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
report=${1:-segments_run.md}
shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSFM_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target benchmark_segments -j2
"$build/bin/benchmark_segments" --images_dir sequences/default/images --output "$report" "$@"
