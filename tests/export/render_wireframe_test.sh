#!/usr/bin/env bash
# scripts/render_wireframe.py on a 10-frame generated run: Open3D (read_line_set, legacy Visualizer
# under xvfb-run) must write a PNG of the asked size whose non-white pixels are 0.2 % to 50 % of it
# (neither blank nor a filled frame), and must fail with one line naming the file on a missing
# wireframe.ply.
#   render_wireframe_test.sh <junction_sfm> <make_sequence> <source dir> <scratch dir>
# Exit 77 (ctest: skipped) where python3-open3d or xvfb is not installed.
set -euo pipefail
junction_sfm=$1 make_sequence=$2 source_dir=$3 scratch=$4
if ! /usr/bin/python3 -c "import open3d" 2>/dev/null || ! command -v xvfb-run >/dev/null; then
  echo "SKIPPED: needs python3-open3d and xvfb (apt-get install -y python3-open3d xvfb; scripts/test.sh installs them)"
  exit 77
fi
rm -rf "$scratch" && mkdir -p "$scratch"
"$make_sequence" --output "$scratch/seq" --frames 10 --seed 1 >"$scratch/make_sequence.log" 2>&1
"$junction_sfm" --sequence "$scratch/seq" --output "$scratch/out" >"$scratch/junction_sfm.log" 2>&1
# Without DISPLAY the script runs itself under xvfb-run, as on a server.
env -u DISPLAY /usr/bin/python3 "$source_dir/scripts/render_wireframe.py" "$scratch/out" "$scratch/seq" \
  "$scratch/wireframe.png" --width 400 --height 300
/usr/bin/python3 - "$scratch/wireframe.png" <<'PY'
import sys
import numpy as np
import open3d as o3d
image = np.asarray(o3d.io.read_image(sys.argv[1]))
assert image.shape[:2] == (300, 400), f"size {image.shape}"
share = float(np.mean(np.any(image < 250, axis=2)))
print(f"non-white share {share:.4f}")
sys.exit(0 if 0.002 <= share <= 0.5 else 1)
PY
mkdir -p "$scratch/empty"
if env -u DISPLAY /usr/bin/python3 "$source_dir/scripts/render_wireframe.py" "$scratch/empty" "$scratch/seq" \
  "$scratch/none.png" 2>"$scratch/missing.err"; then
  echo "render_wireframe.py accepted a directory without wireframe.ply" && exit 1
fi
grep -q "wireframe.ply: no such file" "$scratch/missing.err" || { cat "$scratch/missing.err"; exit 1; }
echo "render_wireframe_test: ok"
