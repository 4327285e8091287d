#!/usr/bin/env bash
# A fleet of robot logs as a batch of independent junction_sfm runs (issue 20, "Beyond one
# machine"; docs/user_guide.md, "Many logs"): one output directory per log and a summary table.
#
#   scripts/batch.sh run <manifest> <out root>         every log, GNU parallel on this machine
#   scripts/batch.sh one <manifest> <line> <out root>  the log on line <line> (1-based) of the
#                                                      manifest: what each parallel job and each
#                                                      Slurm array task (scripts/batch.sbatch) runs
#   scripts/batch.sh summary <manifest> <out root>     <out root>/summary.md from the runs' files
#
# Manifest: one sequence directory per line, optionally followed by a name (default: the
# directory's base name); blank lines and lines starting with # are skipped. Each log writes
# <out root>/<name>/ (junction_sfm's output directory), <name>.log (its stderr) and <name>.time
# (/usr/bin/time: user s, system s, wall s, peak RSS kB, exit status).
# JOBS: runs at once (default: the cores / THREADS); THREADS: junction_sfm --threads of each run
# (default 1: independent runs use the cores better than threads inside one run);
# JUNCTION_SFM: the program (default build/bin/junction_sfm, built when missing).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
threads=${THREADS:-1}
program=${JUNCTION_SFM:-$repo/build/bin/junction_sfm}

usage() {
  sed -n '2,18p' "$0" >&2
  exit 2
}

# The manifest's entries as "<sequence dir>\t<name>", in order.
entries() {
  [ -f "$1" ] || { echo "batch.sh: $1: manifest not found" >&2; exit 1; }
  awk '!/^[[:space:]]*(#|$)/ { name = $2; if (name == "") { n = split($1, p, "/"); name = p[n] };
       print $1 "\t" name }' "$1"
}

run_one() {  # manifest, line, out root
  local entry sequence name
  entry=$(entries "$1" | sed -n "${2}p")
  [ -n "$entry" ] || { echo "batch.sh: $1: no entry $2" >&2; exit 1; }
  sequence=${entry%%$'\t'*}
  name=${entry#*$'\t'}
  mkdir -p "$3"
  local status=0
  /usr/bin/time -f "%U %S %e %M %x" -o "$3/$name.time" \
    "$program" --sequence "$sequence" --output "$3/$name" --threads="$threads" --progress=false \
    2>"$3/$name.log" || status=$?
  echo "batch.sh: $name: exit $status" >&2
  return $status
}

summary() {  # manifest, out root
  local lines
  mapfile -t lines < <(entries "$1")
  /usr/bin/python3 - "$2" "${lines[@]}" >"$2/summary.md" <<'EOF'
import json, os, sys
root = sys.argv[1]
rows = ["| log | status | frames | wall s | CPU s | peak RSS MB | tracks | points | lines | ATE odometry m | ATE refined m |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]
for entry in sys.argv[2:]:
    sequence, name = entry.split("\t")
    time_path = os.path.join(root, name + ".time")
    if not os.path.exists(time_path):
        rows.append(f"| {name} | not run |" + " |" * 9)
        continue
    # GNU time puts "Command exited with non-zero status N" before the fields when the run fails.
    fields = open(time_path).read().split()
    user, system, wall, rss, code = float(fields[-5]), float(fields[-4]), float(fields[-3]), int(fields[-2]), fields[-1]
    metrics_path = os.path.join(root, name, "metrics.json")
    if code != "0" or not os.path.exists(metrics_path):
        log = open(os.path.join(root, name + ".log")).read().strip().splitlines()
        why = log[-1].replace("|", "/") if log else ""
        rows.append(f"| {name} | failed (exit {code}): {why} |" + " |" * 9)
        continue
    m = json.load(open(metrics_path))
    def fmt(value):
        return "-" if value is None else f"{value:.3f}"
    rows.append(f"| {name} | ok | {m['frames']} | {wall:.1f} | {user + system:.1f} | {rss / 1024:.0f} | "
                f"{m['tracks']} | {m['points3d']} | {m['lines3d']} | {fmt(m.get('ate_odometry_m'))} | "
                f"{fmt(m.get('ate_refined_m'))} |")
print("\n".join(rows))
EOF
  cat "$2/summary.md"
}

[ $# -ge 1 ] || usage
command=$1
shift
case $command in
  one)
    [ $# -eq 3 ] || usage
    run_one "$@"
    ;;
  run)
    [ $# -eq 2 ] || usage
    # GNU parallel: Debian's package `parallel`, installed here (as root) when missing.
    (source "$repo/scripts/setup.sh" && sfm_install_benchmark_package parallel parallel) || exit 1
    if [ ! -x "$program" ]; then
      cmake -S "$repo" -B "$repo/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build "$repo/build" --target junction_sfm -j2 >&2
    fi
    count=$(entries "$1" | wc -l)
    jobs=${JOBS:-$(($(nproc) / threads > 0 ? $(nproc) / threads : 1))}
    mkdir -p "$2"
    # One job per manifest line; a failed log does not stop the others (the summary shows it).
    # --joblog records each job's start, duration and exit status.
    seq 1 "$count" | parallel --jobs "$jobs" --joblog "$2/joblog.tsv" "$0" one "$1" {} "$2" || true
    summary "$1" "$2"
    ;;
  summary)
    [ $# -eq 2 ] || usage
    summary "$@"
    ;;
  *)
    usage
    ;;
esac
