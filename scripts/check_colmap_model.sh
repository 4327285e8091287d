#!/usr/bin/env bash
# Checks a COLMAP text model (e.g. <output>/colmap from junction_sfm) by letting COLMAP itself read
# it: `colmap model_analyzer` loads cameras.txt, images.txt and points3D.txt and prints the model's
# statistics; it fails if COLMAP cannot read the files or their tracks do not match.
#   scripts/check_colmap_model.sh <model dir>
# Needs COLMAP on PATH (Debian: apt-get install colmap).
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: $0 <directory with cameras.txt images.txt points3D.txt>" >&2
  exit 2
fi
dir=$1
for file in cameras.txt images.txt points3D.txt; do
  if [ ! -f "$dir/$file" ]; then
    echo "$dir/$file: missing (expected a COLMAP text model)" >&2
    exit 1
  fi
done
if ! command -v colmap >/dev/null; then
  echo "colmap: not found on PATH (Debian: apt-get install colmap)" >&2
  exit 1
fi
# COLMAP links Qt even for its command-line tools; no display is needed for model_analyzer.
QT_QPA_PLATFORM=${QT_QPA_PLATFORM:-offscreen} colmap model_analyzer --path "$dir"
