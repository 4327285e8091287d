#!/usr/bin/env bash
# Install what is missing, build (Release, build/), and run the whole test suite with ctest.
#   scripts/test.sh              the Release build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UBSan build in build-asan/
set -euo pipefail
source "$(dirname "$0")/setup.sh"
# Headless Chromium loads report.html in report_browser_test (skipped without it).
sfm_install_benchmark_package chromium chromium || true
# Open3D and a virtual X server: render_wireframe_test (scripts/render_wireframe.py; skipped without).
/usr/bin/python3 -c "import open3d" 2>/dev/null || sfm_apt_install python3-open3d || true
sfm_install_benchmark_package xvfb xvfb-run || true
build_dir=build
cmake_args=()
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-asan
  cmake_args=(-DSFM_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo)
  export ASAN_OPTIONS=detect_leaks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  shift
fi
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}" >&2
fi
cmake --build "$build_dir" -j"$(nproc)"
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "$@"
