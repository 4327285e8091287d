#!/usr/bin/env bash
# Install what is missing, build (Release, build/), and run junction_sfm on the default sequence
# into output/. Extra arguments go to junction_sfm (e.g. --sequence DIR --output DIR).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
sfm_configure_and_build build
exec build/bin/junction_sfm --output output "$@"
