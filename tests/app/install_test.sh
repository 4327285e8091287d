#!/usr/bin/env bash
# cmake --install (issue 18, "Build"): the six user programs land in <prefix>/bin and run from
# there; the installed junction_sfm's --help fits in 80 lines and its default --sequence is the
# copy installed under <prefix>/share/junction_sfm/default, not the source tree; a run of the
# installed program on a 3-frame cut of that copy, from the PATH, succeeds.
# Usage: install_test.sh <cmake> <build dir> <scratch dir>
set -u
cmake=$1; build=$2; scratch=$3
rm -rf "$scratch"; mkdir -p "$scratch"
prefix=$scratch/prefix
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$cmake" --install "$build" --prefix "$prefix" > "$scratch/install.log" 2>&1 || { cat "$scratch/install.log"; exit 1; }
for program in junction_sfm make_sequence import_sequence detect_junctions match_junctions evaluate_wireframe; do
  [ -x "$prefix/bin/$program" ] || fail "$prefix/bin/$program not installed"
done
sequence=$prefix/share/junction_sfm/default
[ -f "$sequence/sequence.yaml" ] || fail "$sequence/sequence.yaml not installed"

export PATH=$prefix/bin:$PATH
cd "$scratch" || exit 1
junction_sfm --help > help.txt 2>&1 || fail "installed junction_sfm --help exits $?"
lines=$(wc -l < help.txt)
[ "$lines" -lt 80 ] || fail "installed junction_sfm --help is $lines lines (limit 79)"
grep -qF -- "--sequence=$sequence " help.txt || fail "default --sequence is not $sequence: $(grep -- --sequence= help.txt)"
junction_sfm --version 2>&1 | grep -q "junction_sfm version" || fail "installed junction_sfm --version"

# The installed sequence cut to 3 frames: the program runs from the PATH, away from the build tree.
mkdir -p cut
cp "$sequence/sequence.yaml" cut/
ln -s "$sequence/images" cut/images
for file in images.txt odometry.txt; do grep -v '^#' "$sequence/$file" | head -n 3 > "cut/$file"; done
junction_sfm --sequence=cut --output=out --progress=false 2> run.txt || fail "installed run: $(tail -n 1 run.txt)"
[ -f out/trajectory_refined.txt ] || fail "installed run wrote no out/trajectory_refined.txt"

[ "$failures" -eq 0 ] && echo "install test: all checks passed"
exit "$failures"
