#!/usr/bin/env bash
# report.html in a real browser: a 10-frame generated run's report loaded by headless Chromium must
# draw its 3D view (view3d.js sets data-view3d="drawn" after the first frame, with the count of
# canvas pixels that differ from the white background: at least 0.2 % and at most 90 % of the canvas,
# so neither blank nor uniform) with no console error; and the same check must fail on a copy whose
# import map lacks three.js. Saves a screenshot of the whole page (scripts/screenshot_report.sh).
#   report_browser_test.sh <junction_sfm> <make_sequence> <source dir> <scratch dir>
# Exit 77 (ctest: skipped) where chromium is not installed.
set -euo pipefail
junction_sfm=$1 make_sequence=$2 source_dir=$3 scratch=$4
if ! command -v chromium >/dev/null; then
  echo "SKIPPED: chromium is not installed (apt-get install -y chromium; scripts/test.sh installs it)"
  exit 77
fi
rm -rf "$scratch" && mkdir -p "$scratch"
"$make_sequence" --output "$scratch/seq" --frames 10 --seed 1 >"$scratch/make_sequence.log" 2>&1
"$junction_sfm" --sequence "$scratch/seq" --output "$scratch/out" >"$scratch/junction_sfm.log" 2>&1

# Loads the page, prints "drawn <pixels> <canvas pixels>" and the console's errors; returns 1 when the
# view did not draw or the console reported an error.
check_page() {
  local page=$1 name=$2 profile
  profile=$(mktemp -d)
  # Software WebGL (SwiftShader) on a machine without a GPU: the page is our own, trusted content.
  timeout 60 chromium --headless --no-sandbox --disable-gpu --use-angle=swiftshader \
    --enable-unsafe-swiftshader --no-first-run --disable-background-networking --disable-component-update \
    --disable-sync --user-data-dir="$profile" --window-size=1200,900 --virtual-time-budget=10000 \
    --enable-logging=stderr --v=0 \
    --dump-dom "file://$(realpath "$page")" >"$scratch/$name.dom.html" 2>"$scratch/$name.chromium.log" || true
  rm -rf "$profile"
  local div drawn canvas errors
  div=$(grep -o '<div id="view3d"[^>]*>' "$scratch/$name.dom.html" || true)
  drawn=$(sed -n 's/.*data-drawn-pixels="\([0-9]*\)".*/\1/p' <<<"$div")
  canvas=$(sed -n 's/.*data-canvas-pixels="\([0-9]*\)".*/\1/p' <<<"$div")
  errors=$(grep ':CONSOLE' "$scratch/$name.chromium.log" | grep -Ei 'uncaught|error|failed' || true)
  echo "$name: drawn ${drawn:-none} of ${canvas:-none} canvas pixels"
  [[ -n $errors ]] && echo "$name: console errors:" && echo "$errors"
  [[ $div == *'data-view3d="drawn"'* && -n $drawn && -n $canvas && -z $errors ]] || return 1
  ((drawn * 1000 >= canvas * 2 && drawn * 10 <= canvas * 9))
}

report=$scratch/out/report.html
echo "report.html: $(stat -c %s "$report") bytes"
if ! check_page "$report" report; then
  echo "FAIL: the 3D view of $report did not draw, or the console reported an error"
  exit 1
fi

# The check itself can fail: without three.js in the import map the module cannot load.
sed 's|"three/core":"data:|"three/missing":"data:|' "$report" >"$scratch/broken.html"
if check_page "$scratch/broken.html" broken; then
  echo "FAIL: the check passed a page whose import map lacks three.js"
  exit 1
fi

"$source_dir/scripts/screenshot_report.sh" "$report" "$scratch/report.png" >/dev/null
[[ -s $scratch/report.png ]] || { echo "FAIL: no screenshot"; exit 1; }
echo "PASS; screenshot: $scratch/report.png"
