#!/usr/bin/env bash
# The output directory as one unit under interruption and concurrency (SPEC section 2; issue 18,
# items 2 and 3). Starts junction_sfm on the default sequence cut to a few frames, waits for the
# named stage in its log (junction_sfm.log in the staging directory beside the output), signals
# it, and inspects what is left:
#   1. SIGINT during the front end, no earlier output: no output directory, nothing beside it.
#   2. SIGINT during the back end, over an earlier output: the earlier output byte for byte.
#   3. SIGTERM while the outputs are written, over an earlier output: the earlier output or the new
#      one whole (never a mix), nothing beside it.
#   4. Two runs into one directory at once: the second refused with one line; the first complete.
#   5. SIGKILL (no cleanup possible), then a normal run: it succeeds and removes the killed run's
#      staging directory.
# Usage: interruption_test.sh <junction_sfm binary> <repository> <scratch dir>
set -u
set -m  # job control: background runs do not ignore SIGINT, as they would in a plain script
binary=$1; repository=$2; scratch=$3
rm -rf "$scratch"; mkdir -p "$scratch"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The default sequence cut to $1 frames.
cut_sequence() {
  local frames=$1 dir=$scratch/seq$1
  mkdir -p "$dir"
  cp "$repository/sequences/default/sequence.yaml" "$dir/"
  ln -s "$repository/sequences/default/images" "$dir/images"
  grep -v '^#' "$repository/sequences/default/images.txt" | head -n "$frames" > "$dir/images.txt"
  grep -v '^#' "$repository/sequences/default/odometry.txt" | head -n "$frames" > "$dir/odometry.txt"
  grep -v '^#' "$repository/sequences/default/groundtruth.txt" | head -n "$frames" > "$dir/groundtruth.txt"
  echo "$dir"
}

# A checksum of every file under $1 except the log (its lines carry times), with names.
tree_sum() { (cd "$1" && find . -type f ! -name junction_sfm.log -print0 | sort -z | xargs -0 sha1sum) ; }

# Waits (at most 120 s) until the log of the run writing into $1 holds the pattern $2.
wait_for_stage() {
  local output=$1 pattern=$2 parent name
  parent=$(dirname "$output"); name=$(basename "$output")
  for _ in $(seq 1 12000); do
    if grep -q -- "$pattern" "$parent"/."$name".staging-*/junction_sfm.log 2>/dev/null; then return 0; fi
    sleep 0.01
  done
  return 1
}

# Nothing in $1's parent but the names given after it.
expect_beside() {
  local output=$1; shift
  local parent expected actual
  parent=$(dirname "$output")
  expected=$(printf '%s\n' "$@" | sort)
  actual=$(ls -A "$parent" | sort)
  [ "$expected" = "$actual" ] || fail "beside $output: expected [$expected], found [$actual]"
}

# Background runs call the binary directly, so $! is its pid (a shell function would run in a subshell).
run() { "$binary" --progress=false "$@"; }

seq6=$(cut_sequence 6)
seq40=$(cut_sequence 40)

# 1. SIGINT during the front end, no earlier output.
mkdir -p "$scratch/case1"
out=$scratch/case1/out
"$binary" --progress=false --sequence="$seq40" --output="$out" 2> "$scratch/case1.err" &
pid=$!
wait_for_stage "$out" "^I.*] sequence " || fail "case 1: the run never started"
kill -INT $pid; wait $pid; status=$?
[ $status -eq 130 ] || fail "case 1: exit status $status, expected 130"
expect_beside "$out"
grep -q "interrupted" "$scratch/case1.err" || fail "case 1: no 'interrupted' line on stderr"

# 2. SIGINT during the back end, over an earlier output.
mkdir -p "$scratch/case2"
out=$scratch/case2/out
run --sequence="$seq6" --output="$out" 2> /dev/null || fail "case 2: the first run failed"
before=$(tree_sum "$out")
"$binary" --progress=false --sequence="$seq40" --output="$out" 2> /dev/null &
pid=$!
wait_for_stage "$out" "] tracks: " || fail "case 2: the back end never started"
kill -INT $pid; wait $pid; status=$?
[ $status -eq 130 ] || fail "case 2: exit status $status, expected 130"
[ "$(tree_sum "$out")" = "$before" ] || fail "case 2: the earlier output changed"
expect_beside "$out" out

# 3. SIGTERM while the outputs are written, over an earlier output.
mkdir -p "$scratch/case3"
out=$scratch/case3/out
run --sequence="$seq6" --output="$out" 2> /dev/null || fail "case 3: the first run failed"
before=$(tree_sum "$out")
"$binary" --progress=false --sequence="$seq40" --output="$out" 2> /dev/null &
pid=$!
wait_for_stage "$out" "] writing the outputs" || fail "case 3: the outputs were never written"
kill -TERM $pid; wait $pid; status=$?
after=$(tree_sum "$out")
if [ $status -eq 143 ]; then
  echo "case 3: interrupted while writing the outputs"
  [ "$after" = "$before" ] || fail "case 3: interrupted, yet the earlier output changed"
else
  echo "case 3: the run finished before the signal (exit $status)"
  # The run finished before the signal arrived: then the output is the new run's, whole.
  grep -q '"frames": 40' "$out/metrics.json" || fail "case 3: exit $status and not the new output"
fi
expect_beside "$out" out

# 4. Two runs into one directory at once.
mkdir -p "$scratch/case4"
out=$scratch/case4/out
"$binary" --progress=false --sequence="$seq40" --output="$out" 2> "$scratch/case4a.err" &
pid=$!
wait_for_stage "$out" "^I.*] sequence " || fail "case 4: the first run never started"
run --sequence="$seq6" --output="$out" 2> "$scratch/case4b.err"; status=$?
[ $status -ne 0 ] || fail "case 4: the second run was not refused"
[ "$(wc -l < "$scratch/case4b.err")" -eq 1 ] || fail "case 4: the refusal is not one line: $(cat "$scratch/case4b.err")"
grep -q "another junction_sfm run (pid $pid) is writing" "$scratch/case4b.err" || fail "case 4: $(cat "$scratch/case4b.err")"
wait $pid || fail "case 4: the first run failed"
grep -q '"frames": 40' "$out/metrics.json" || fail "case 4: the output is not the first run's"
expect_beside "$out" out

# 5. SIGKILL leaves a staging directory; the next run removes it.
mkdir -p "$scratch/case5"
out=$scratch/case5/out
"$binary" --progress=false --sequence="$seq6" --output="$out" 2> /dev/null &
pid=$!
wait_for_stage "$out" "^I.*] sequence " || fail "case 5: the run never started"
kill -KILL $pid; wait $pid 2> /dev/null
run --sequence="$seq6" --output="$out" 2> /dev/null || fail "case 5: the run after the kill failed"
expect_beside "$out" out

if [ $failures -ne 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "all 5 interruption and concurrency cases pass"
