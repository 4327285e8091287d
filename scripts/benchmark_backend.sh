#!/usr/bin/env bash
# Reproduces the tables of docs/backend_results.md (issue 5, "Must show"): builds junction_sfm,
# make_sequence, import_sequence and evaluate_wireframe (Release), prepares the sequences in $WORK
# (replaced each run), runs junction_sfm on each and prints markdown tables on stdout.
#
#   scripts/benchmark_backend.sh
#   BUILD=build-other WORK=/tmp/elsewhere scripts/benchmark_backend.sh
#   SFM_FLAGS="--floor_prior=off" scripts/benchmark_backend.sh   # extra junction_sfm flags
#
# Sequences (fixed seeds: the same bytes every run):
#   room-loop            make_sequence --scene=room --trajectory=loop --frames=60 --seed=1
#   corridor             make_sequence --scene=corridor --trajectory=straight --frames=60 --seed=1
#   corridor-turns       make_sequence --scene=corridor --trajectory=turns --frames=60 --seed=1
#   room-loop-heading    room-loop with heading drift only: --odometry_scale_error=0 --odometry_distance_sigma=0
#   corridor-heading     corridor with heading drift only (same flags)
#   vgg-corridor         import_sequence --format vgg --input ../shared/data/vgg-corridor --seed 1
#   strecha-entry-P10    import_sequence --format strecha --input ../shared/data/strecha-entry-P10 --seed 1
#                        (768 px wide, the importer's default --max_width)
# The generated ones use the generator's default odometry noise (2 % scale error, 1 % distance
# noise, 0.002 rad/frame heading noise, 0.001 rad/frame heading bias) unless stated.
# Then the export checks on the room loop's output: scripts/check_colmap_model.sh (colmap
# model_analyzer) and scripts/check_wireframe_open3d.py (Open3D read_line_set).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
work=${WORK:-/tmp/backend_benchmark}
vgg=${VGG_DIR:-../shared/data/vgg-corridor}
strecha=${STRECHA_DIR:-../shared/data/strecha-entry-P10}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSFM_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target junction_sfm make_sequence import_sequence evaluate_wireframe -j2 >&2
mkdir -p "$work"

generate() {  # name, make_sequence flags...
  local name=$1
  shift
  "$build/bin/make_sequence" --output "$work/$name" --overwrite --frames=60 --seed=1 "$@" >/dev/null
}
generate room-loop --scene=room --trajectory=loop
generate corridor --scene=corridor --trajectory=straight
generate corridor-turns --scene=corridor --trajectory=turns
generate room-loop-heading --scene=room --trajectory=loop --odometry_scale_error=0 --odometry_distance_sigma=0
generate corridor-heading --scene=corridor --trajectory=straight --odometry_scale_error=0 --odometry_distance_sigma=0
sequences="room-loop corridor corridor-turns room-loop-heading corridor-heading"
if [ -d "$vgg" ]; then
  "$build/bin/import_sequence" --format vgg --input "$vgg" --output "$work/vgg-corridor" --overwrite --seed 1 2>/dev/null
  sequences="$sequences vgg-corridor"
else
  echo "benchmark_backend.sh: $vgg not found; left out" >&2
fi
if [ -d "$strecha" ]; then
  "$build/bin/import_sequence" --format strecha --input "$strecha" --output "$work/strecha-entry-P10" --overwrite \
    --seed 1 --max_width 768 2>/dev/null
  sequences="$sequences strecha-entry-P10"
else
  echo "benchmark_backend.sh: $strecha not found; left out" >&2
fi

for name in $sequences; do
  echo "junction_sfm on $name" >&2
  # shellcheck disable=SC2086  # SFM_FLAGS is a list of flags
  "$build/bin/junction_sfm" --sequence "$work/$name" --output "$work/$name.out" --progress=false ${SFM_FLAGS:-} \
    2>"$work/$name.log"
  if [ -d "$work/$name/truth" ]; then
    "$build/bin/evaluate_wireframe" --sequence "$work/$name" --output "$work/$name.out" >"$work/$name.out/wireframe_eval.json"
  fi
done

/usr/bin/python3 - "$work" $sequences <<'EOF'
import json, os, struct, sys
work, names = sys.argv[1], sys.argv[2:]

def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])

def fmt(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, int):
        return str(value)
    return f"{value:.{digits}g}"

def verdict(ok):
    return "met" if ok else "**missed**"

rows = []
for name in names:
    m = json.load(open(os.path.join(work, name + ".out", "metrics.json")))
    w = None
    wpath = os.path.join(work, name + ".out", "wireframe_eval.json")
    if os.path.exists(wpath):
        w = json.load(open(wpath))
    width, height = png_size(os.path.join(work, name, "images", "000000.png"))
    jpf = m["junctions_per_frame"]
    jpf = (sum(jpf) / len(jpf) if jpf else 0.0) if isinstance(jpf, list) else jpf
    rows.append((name, m, w, width, height, jpf))

print("### Sequences and reconstruction\n")
print("| sequence | frames | size | junctions/frame | tracks | points | lines | unobservable lines |")
print("|---|---|---|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    print(f"| {name} | {m['frames']} | {width}x{height} | {jpf:.1f} | {m['tracks']} | {m['points3d']} | "
          f"{m['lines3d']} | {m['unobservable_lines']} |")

print("\n### Drift: odometry -> refined, and the goals\n")
print("Goals: generated sequences refined ATE <= 1/5 of the odometry's and refined rotation RPE <= 1/2;"
      " VGG and Strecha refined ATE below the odometry's.\n")
print("| sequence | ATE odometry | ATE refined | ATE ratio | ATE goal | RPE trans odometry | RPE trans refined | "
      "RPE rot odometry (rad) | RPE rot refined (rad) | rot ratio | rot goal |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    ao, ar = m["ate_odometry_m"], m["ate_refined_m"]
    ro, rr = m["rpe_odometry"], m["rpe_refined"] or {"trans_m": None, "rot_rad": None}
    ate_ratio = ar / ao if ao and ar is not None else None
    rot_ratio = rr["rot_rad"] / ro["rot_rad"] if ro["rot_rad"] and rr["rot_rad"] is not None else None
    generated = w is not None
    if ate_ratio is None:
        ate_goal = "-"
    elif generated:
        ate_goal = verdict(ate_ratio <= 0.2) + " (<= 0.2)"
    else:
        ate_goal = verdict(ate_ratio < 1) + " (< 1)"
    rot_goal = (verdict(rot_ratio <= 0.5) + " (<= 0.5)") if generated and rot_ratio is not None else "-"
    print(f"| {name} | {fmt(ao)} | {fmt(ar)} | {fmt(ate_ratio, 2)} | {ate_goal} | {fmt(ro['trans_m'])} | "
          f"{fmt(rr['trans_m'])} | {fmt(ro['rot_rad'])} | {fmt(rr['rot_rad'])} | {fmt(rot_ratio, 2)} | {rot_goal} |")

print("\n### Shape and scale: ATE after a similarity (metrics.json ate_sim3_*, sim3_scale_*)\n")
print("| sequence | Sim(3) ATE odometry | Sim(3) ATE refined | scale odometry | scale refined |")
print("|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    print(f"| {name} | {fmt(m.get('ate_sim3_odometry_m'))} | {fmt(m.get('ate_sim3_refined_m'))} | "
          f"{fmt(m.get('sim3_scale_odometry'), 4)} | {fmt(m.get('sim3_scale_refined'), 4)} |")

print("\n### Floor prior (metrics.json floor_prior)\n")
print("| sequence | used | floor points | floor lines | plane z when found m | odometry scale | report |")
print("|---|---|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    f = m.get("floor_prior")
    if not f:
        print(f"| {name} | - | - | - | - | - | - |")
        continue
    print(f"| {name} | {'yes' if f['used'] else 'no'} | {f['points']} | {f['lines']} | {fmt(f['plane_z_m'])} | "
          f"{fmt(f['odometry_scale'], 4)} | {f['report']} |")

print("\n### Wireframe against the truth (generated sequences)\n")
print("Precision (share): wireframe vertices within 5 cm of a true edge, goal 0.9 (no alignment: the odometry"
      " starts on the true first pose). Completeness: share of the seen true edges' length within 5 cm of a"
      " reconstructed edge (docs/metrics.md), goal 0.80 in rooms and 0.70 in corridors; also per true edge"
      " direction (along the motion, across it, vertical); edge precision: share of the reconstructed edges'"
      " length within 5 cm of a true edge. In view: the share of the seen length that some frame sees (the"
      " completeness' ceiling) and the completeness of that part. Diagnostic: the share with the map scaled about"
      " the first camera by the scale that best maps the refined camera positions onto the true ones"
      " (evaluate_wireframe's \"scaled\").\n")
print("| sequence | vertices | edges | within 5 cm | share | goal | median distance m | 90th pct m | "
      "completeness | goal | along | across | vertical | in view | completeness in view | edge length within 5 cm |"
      " scaled: scale | share |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    if w is None:
        continue
    s = w.get("scaled") or {}
    share, completeness = w["share"], w.get("completeness")
    bar = 0.80 if name.startswith("room") else 0.70
    d = w.get("by_direction", {})
    directions = " | ".join(fmt(d.get(k, {}).get("completeness"), 2) for k in ("along", "across", "vertical"))
    print(f"| {name} | {w['vertices']} | {w['edges']} | {w['within']} | {fmt(share)} | "
          f"{verdict(share is not None and share >= 0.9)} | {fmt(w['median_m'])} | {fmt(w['p90_m'])} | "
          f"{fmt(completeness)} | {verdict(completeness is not None and completeness >= bar)} (>= {bar}) | "
          f"{directions} | {fmt(w.get('in_view_share'))} | {fmt(w.get('completeness_in_view'))} | "
          f"{fmt(w.get('edge_share'))} | {fmt(s.get('scale'), 4)} | {fmt(s.get('share'))} |")

print("\n### Time (s, from metrics.json time_s; the machine's 2 cores are shared)\n")
print("Goal: a 60-frame 640x480 generated sequence in under 2 s in total.\n")
print("| sequence | frames | size | frontend | matching | backend | total | goal |")
print("|---|---|---|---|---|---|---|---|")
for name, m, w, width, height, jpf in rows:
    t = m["time_s"]
    goal = verdict(t["total"] < 2.0) if w is not None and m["frames"] >= 60 and (width, height) == (640, 480) else "-"
    print(f"| {name} | {m['frames']} | {width}x{height} | {fmt(t['frontend'])} | {fmt(t['matching'])} | "
          f"{fmt(t['backend'])} | {fmt(t['total'])} | {goal} |")
EOF

echo
echo "### Export checks on $work/room-loop.out"
echo
echo '```'
echo "\$ scripts/check_colmap_model.sh $work/room-loop.out/colmap"
scripts/check_colmap_model.sh "$work/room-loop.out/colmap" 2>&1 | sed 's/^[IWE][0-9]* [0-9:.]* *[0-9]* [a-z_.]*:[0-9]*\] //' || true
echo "\$ /usr/bin/python3 scripts/check_wireframe_open3d.py $work/room-loop.out/wireframe.ply"
/usr/bin/python3 scripts/check_wireframe_open3d.py "$work/room-loop.out/wireframe.ply" 2>&1 || true
echo '```'
