#!/usr/bin/env bash
# The multibody reference's speed behind the SIL bridge, per scenario
# (docs/sil.md#reference-speed): every SIL scenario in lock-step on the
# loopback bus with the example controller (`cvtplant-sil compare`, which
# also runs the real-time plant), and for each the CPU seconds of the
# reference's frames, the simulated seconds and their ratio (above 1: faster
# than real time); medians of REPS runs (default 3), one job at a time. The
# start-up of each scene (settle, spin-up, hold) is measured apart, in the
# first run, whose release states the later runs reuse. The goal beside each
# figure: twice real time, 0.5 s of CPU per simulated second.
#
# Usage: bench/sil-reference-speed.sh [BUILD_DIR] [REPS] [SCENARIOS]
#   SCENARIOS  as cvtplant-sil's --scenario (default all)
#        bench/sil-reference-speed.sh --table OUT_DIR...
#   the same table from comparisons already run (`cvtplant-sil compare
#   --out OUT_DIR`, one run per directory, the first one's start-ups shown)
# Prints a markdown table on stdout; progress on stderr.
set -euo pipefail
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "${1:-}" = --table ]; then
  shift
  [ $# -ge 1 ] || { echo "sil-reference-speed.sh: --table needs at least one compare output directory" >&2; exit 2; }
  reps=0
  for d in "$@"; do
    [ -s "$d/compare-scenarios.csv" ] || { echo "sil-reference-speed.sh: $d/compare-scenarios.csv: missing or empty" >&2; exit 2; }
    reps=$((reps + 1))
    cp "$d/compare-scenarios.csv" "$work/scenarios_$reps.csv"
  done
  table_only=1
else
  table_only=0
fi
cd "$(dirname "$0")/.."
if [ "$table_only" = 0 ]; then
build=${1:-build/host-release}
reps=${2:-3}
scenarios=${3:-all}
case $reps in ''|*[!0-9]*|0) echo "sil-reference-speed.sh: REPS must be a whole number >= 1, got '$reps'" >&2; exit 2;; esac
. bench/build-host.sh
build_host "$build" cvtplant-sil
sil=$build/hil/cvtplant-sil

for rep in $(seq "$reps"); do
  echo "run $rep of $reps: cvtplant-sil compare --scenario $scenarios..." >&2
  # One output directory: the first run makes the release states, the
  # others start from them. The verdicts do not matter here (exit 1 allowed).
  "$sil" compare --scenario "$scenarios" --out "$work/out" --no-report >"$work/table_$rep.txt" 2>"$work/err_$rep.txt" || true
  [ -s "$work/out/compare-scenarios.csv" ] || { cat "$work/err_$rep.txt" >&2; exit 1; }
  cp "$work/out/compare-scenarios.csv" "$work/scenarios_$rep.csv"
done
fi

python3 - "$work" "$reps" <<'EOF'
import csv, statistics, sys
work, reps = sys.argv[1], int(sys.argv[2])
runs = []
for r in range(1, reps + 1):
    with open("%s/scenarios_%d.csv" % (work, r), newline="") as f:
        runs.append({row["scenario"]: row for row in csv.DictReader(f)})
# The goal: twice real time, 0.5 s of CPU per simulated second.
print("| scenario | simulated [s] | reference CPU [s], median of %d (min-max) | CPU per simulated s | x real time | slower than the 2x goal by | start-up CPU [s] (first run) |" % reps)
print("|---|---|---|---|---|---|---|")
total_sim = total_cpu = 0.0
for name, first in runs[0].items():
    cpu = [float(r[name]["ref_step_cpu_s"]) for r in runs]
    sim = float(first["sim_s"])
    med = statistics.median(cpu)
    if sim <= 0 or med <= 0:  # the reference refused the scene or faulted at once
        print("| %s | %.2f | %.2f | - | - | - | %s |" % (name, sim, med, first["ref_release_cpu_s"]))
        continue
    total_sim += sim
    total_cpu += med
    start = first["ref_release_cpu_s"] if first["ref_release_cached"] == "0" else "cached"
    print("| %s | %.2f | %.2f (%.2f-%.2f) | %.2f | %.2f | %.1fx | %s |"
          % (name, sim, med, min(cpu), max(cpu), med / sim, sim / med, med / sim / 0.5, start))
print("| all | %.2f | %.2f | %.2f | %.2f | %.1fx | |"
      % (total_sim, total_cpu, total_cpu / total_sim, total_sim / total_cpu, total_cpu / total_sim / 0.5))
EOF
