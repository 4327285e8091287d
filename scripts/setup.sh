#!/usr/bin/env bash
# Shared set-up for run.sh and test.sh: install what is missing, configure, build.
# Usage: source scripts/setup.sh [build-dir] [extra cmake args...]
set -euo pipefail

SFM_PACKAGES=(build-essential cmake pkg-config libeigen3-dev libceres-dev libopencv-dev
  libopencv-contrib-dev libgflags-dev libgoogle-glog-dev libgtest-dev libgmock-dev libbenchmark-dev
  libzstd-dev liblz4-dev zlib1g-dev libsqlite3-dev libyaml-cpp-dev libfastcdr-dev
  librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libtf2-msgs-dev
  libtbb-dev)

# apt-get install of the packages given, as root; otherwise the command to run is printed and the
# function returns 1.
sfm_apt_install() {
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing $*" >&2
    apt-get update -q >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "$@" >&2
  else
    echo "setup: missing packages; run as root: apt-get install -y $*" >&2
    return 1
  fi
}

sfm_install_missing_packages() {
  local missing=()
  for package in "${SFM_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  sfm_apt_install "${missing[@]}" || exit 1
}

# A package that only a benchmark or a test needs (never one of the product's above, e.g. colmap for
# scripts/benchmark_real.sh, chromium for tests/report/report_browser_test.sh): installed when
# `command` is not on PATH (sfm_apt_install).
sfm_install_benchmark_package() {
  local package=$1 command=$2
  command -v "$command" >/dev/null && return 0
  sfm_apt_install "$package"
}

sfm_configure_and_build() {
  local build_dir=$1; shift
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >&2
  fi
  cmake --build "$build_dir" -j"$(nproc)" >&2
}

cd "$(dirname "${BASH_SOURCE[0]}")/.."
sfm_install_missing_packages
