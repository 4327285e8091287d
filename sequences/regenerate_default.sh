#!/bin/sh
# Rebuilds the default sequence (sequences/default) bit for bit: make_sequence with its default
# options (a 40-frame corridor, 640x480, no distortion, seed 1; see docs/generator.md).
# The generator test (tests/generator/default_sequence_test.cc) checks that the committed files
# are exactly what this makes.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target make_sequence -j2 >/dev/null
"$build/bin/make_sequence" --output "$root/sequences/default" --overwrite
