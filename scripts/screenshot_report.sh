#!/usr/bin/env bash
# Renders a report.html to a PNG with Debian's headless chromium (apt-get install chromium), to look
# at a report without a desktop browser.
#   scripts/screenshot_report.sh <report.html or output directory> [out.png] [height in px, 7000]
set -euo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 <report.html or output directory> [out.png] [height]" >&2
  exit 2
fi
report=$1
[[ -d $report ]] && report=$report/report.html
[[ -f $report ]] || { echo "$report: no such file" >&2; exit 1; }
out=${2:-${report%.html}.png}
height=${3:-7000}
command -v chromium >/dev/null || { echo "chromium is not installed (apt-get install -y chromium)" >&2; exit 1; }
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
# No network, no first-run work, a throw-away profile: the page is self-contained.
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
  --disable-component-update --disable-sync --hide-scrollbars --user-data-dir="$profile" \
  --use-angle=swiftshader --enable-unsafe-swiftshader --virtual-time-budget=10000 \
  --screenshot="$out" --window-size=1200,"$height" "file://$(realpath "$report")" 2>/dev/null
echo "$out"
