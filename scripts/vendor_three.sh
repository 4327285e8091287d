#!/usr/bin/env bash
# Refreshes the copy of three.js that report.html inlines (pipeline/report/vendor/three/) from the npm
# registry: the minified module build, OrbitControls and the licence of one release.
#   scripts/vendor_three.sh [version, 0.185.1]
# 0.185.1 is the last release that ships build/*.min.js. The copy is committed, so that a fresh
# clone builds without npm or a network (docs/report.md).
set -euo pipefail
version=${1:-0.185.1}
cd "$(dirname "$0")/.."
command -v npm >/dev/null || { echo "npm is not installed (apt-get install -y npm)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@$version" >/dev/null && tar xzf "three-$version.tgz")
out=pipeline/report/vendor/three
for f in build/three.core.min.js build/three.module.min.js examples/jsm/controls/OrbitControls.js LICENSE; do
  [[ -f $work/package/$f ]] || { echo "three@$version has no $f" >&2; exit 1; }
  cp "$work/package/$f" "$out/"
done
echo "$version" > "$out/VERSION"
echo "$out: three@$version"
