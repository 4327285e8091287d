#!/usr/bin/env bash
# Issue 20 "Must show": junction_sfm over the sequence length (docs/scaling_results.md). Builds
# junction_sfm and make_sequence (Release), generates each sequence in $WORK, runs junction_sfm on
# it once per thread count under /usr/bin/time and prints a markdown table on stdout.
#
#   scripts/benchmark_scaling.sh
#   FRAMES="60 120 240 480 960 1920" THREADS="1 2" scripts/benchmark_scaling.sh
#   BUILD=build-other WORK=/tmp/elsewhere scripts/benchmark_scaling.sh
#
# Sequences (640x480, seed 1, the generator's default odometry noise):
#   corridor-N    make_sequence --scene=corridor --trajectory=straight --frames=N
#   room-loop-N   make_sequence --scene=room --trajectory=loop --frames=N  (96 frames a lap)
# Columns: CPU s (user + system) and peak RSS of the run on the first thread count, wall s on each,
# whether every thread count wrote the same trajectory_refined.txt, tracks.csv and wireframe.ply,
# the refined ATE over the odometry's, and for the room loop the loop-return error: at each frame
# where the true camera is back at its start, the distance between the refined and the true camera
# displacement since frame 0 (one figure per lap).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
work=${WORK:-/tmp/scaling_benchmark}
frames=${FRAMES:-60 120 240 480 960}
threads=${THREADS:-1 2}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target junction_sfm make_sequence -j2 >&2
mkdir -p "$work"
results="$work/results.tsv"
: >"$results"

for scene in corridor room-loop; do
  case $scene in
    corridor) scene_flags="--scene=corridor --trajectory=straight" ;;
    room-loop) scene_flags="--scene=room --trajectory=loop" ;;
  esac
  for n in $frames; do
    name="$scene-$n"
    echo "make_sequence $name" >&2
    # shellcheck disable=SC2086  # scene_flags is a list of flags
    "$build/bin/make_sequence" --output "$work/$name" --overwrite --frames="$n" --seed=1 $scene_flags >/dev/null
    for t in $threads; do
      echo "junction_sfm on $name, $t threads" >&2
      /usr/bin/time -f "%U %S %e %M" -o "$work/$name.t$t.time" \
        "$build/bin/junction_sfm" --sequence "$work/$name" --output "$work/$name.t$t" --threads="$t" \
        --progress=false 2>"$work/$name.t$t.log"
      printf "%s\t%s\t%s\t%s\t%s\n" "$scene" "$n" "$t" "$work/$name.t$t" "$(cat "$work/$name.t$t.time")" \
        >>"$results"
    done
  done
done

/usr/bin/python3 - "$results" <<'EOF'
import filecmp, json, math, os, sys

def tum(path):
    poses = []
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            poses.append([float(v) for v in line.split()[1:4]])
    return poses

def loop_returns(out):
    truth = tum(os.path.join(out, "trajectory_groundtruth.txt"))
    refined = tum(os.path.join(out, "trajectory_refined.txt"))
    d = [math.dist(p, truth[0]) for p in truth]
    errors = []
    for f in range(1, len(d) - 1):
        if d[f] < 0.1 and d[f] <= d[f - 1] and d[f] < d[f + 1]:
            moved_truth = [a - b for a, b in zip(truth[f], truth[0])]
            moved_refined = [a - b for a, b in zip(refined[f], refined[0])]
            errors.append(math.dist(moved_truth, moved_refined))
    if len(d) > 1 and d[-1] < 0.1 and d[-1] < d[-2]:
        errors.append(math.dist([a - b for a, b in zip(truth[-1], truth[0])],
                                [a - b for a, b in zip(refined[-1], refined[0])]))
    return errors

runs = {}
for line in open(sys.argv[1]):
    scene, n, t, out, user, system, wall, rss = line.split()
    runs.setdefault((scene, int(n)), []).append((int(t), out, float(user) + float(system), float(wall), int(rss)))

names = ("trajectory_refined.txt", "tracks.csv", "wireframe.ply")
counts = sorted({t for rs in runs.values() for t, *_ in rs})
print("| sequence | frames | CPU s | CPU ms/frame | " + " | ".join(f"wall s, {t} thr" for t in counts)
      + " | speed-up | same outputs | peak RSS MB | ATE ratio | loop-return error m (per lap) |")
print("|---|---|---|---|" + "---|" * len(counts) + "---|---|---|---|---|")
for (scene, n), rs in sorted(runs.items()):
    rs.sort()
    first = rs[0]
    same = all(filecmp.cmp(os.path.join(first[1], f), os.path.join(r[1], f), shallow=False)
               for r in rs[1:] for f in names)
    m = json.load(open(os.path.join(first[1], "metrics.json")))
    ratio = m["ate_refined_m"] / m["ate_odometry_m"] if m.get("ate_odometry_m") else float("nan")
    walls = {t: wall for t, _, _, wall, _ in rs}
    speed = f"{walls[rs[0][0]] / walls[rs[-1][0]]:.2f}x" if len(rs) > 1 else "-"
    returns = " ".join(f"{e:.3f}" for e in loop_returns(first[1])) if scene == "room-loop" else "-"
    print(f"| {scene} | {n} | {first[2]:.1f} | {1000 * first[2] / n:.0f} | "
          + " | ".join(f"{walls[t]:.1f}" for t in counts)
          + f" | {speed} | {'yes' if same else '**no**'} | {first[4] / 1024:.0f} | {ratio:.3f} | {returns or '-'} |")
EOF
