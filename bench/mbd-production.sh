#!/usr/bin/env bash
# The multibody reference's speed on the production-like set
# (docs/mbd.md#speed, docs/mbd-production.md), per manoeuvre a ratio
# controller drives, and on the seed's 10 s cases: CPU time of the run after
# the release (the settle and the start at speed apart), steps, the energy
# ledger, and the ratio of CPU to simulated time (below 0.5: twice real time).
# Medians of REPS runs (default 1), one job at a time, one core each; with
# SOLVERS (default chain,klu: the BDF's linear solvers, docs/mbd.md#linear-algebra)
# the runs of one manoeuvre alternate between them, so each ratio comes from
# runs made under the same load. ONLY (comma-separated names) limits the
# manoeuvres.
#
# Manoeuvres (production set, started at speed with the ratio lock; driven
# clamping 12.5 kN, the envelope's floor; driver clamping near the force that
# holds ratio 1.5 at 40-60 N m):
#   hold-150      150 rad/s, 60 N m, road load, 2 s at a held force ratio
#   steps-150     the same with the driver clamping stepped up, then down
#   hold-100      100 rad/s, 40 N m, 2 s
#   sweep-150     a 17.5 s ratio sweep by the force ratio (the SIL sweep's
#                 length), upshift then downshift and back
#
# Usage: bench/mbd-production.sh [BUILD_DIR] [REPS] [SOLVERS]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/host-release}
reps=${2:-1}
solvers=${3:-chain,klu}
only=${ONLY:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. bench/build-host.sh
build_host "$build" cvtplant
cli=$build/tools/cvtplant

run() {  # name t_end args...
  local name=$1 t=$2
  shift 2
  [ -z "$only" ] || [[ ",$only," == *",$name,"* ]] || return 0
  for rep in $(seq "$reps"); do
    for solver in ${solvers//,/ }; do
      echo "$name ($t s), $solver, run $rep of $reps..." >&2
      "$cli" mbd "$@" --t-end "$t" --linear-solver "$solver" --json >"$work/${name}_${solver}_$rep.json" || true
    done
  done
}

P=(--set production --clamp2-N 12500)
run hold-150 2 "${P[@]}" --clamp-N 11300 --tau-in 60 --tau-load 0 --road-load 0,0.9,0 --omega0 150,100
run steps-150 2 "${P[@]}" --clamp-N 0:11300,0.5:11300,0.51:12500,1.2:12500,1.21:10200 --tau-in 60 --tau-load 0 \
  --road-load 0,0.9,0 --omega0 150,100
run hold-100 2 "${P[@]}" --clamp-N 11300 --tau-in 40 --tau-load 60 --omega0 100,66.7
run sweep-150 17.5 "${P[@]}" --clamp-N 0:11300,0.5:11300,2.5:12900,4:12900,7:10000,9:10000,10:11300,17.5:11300 \
  --tau-in 60 --tau-load 0 --road-load 0,0.9,0 --omega0 150,100
run seed-case1 10 --case 1
run seed-case2 10 --case 2

python3 - "$work" "$solvers" <<'PY'
import json, statistics, sys, glob, os
work, solvers = sys.argv[1], sys.argv[2].split(",")
print("| manoeuvre | solver | runs | simulated [s] | CPU after the release [s] | CPU / simulated | start CPU [s] | steps | steps per simulated s | ledger residual | status | CPU vs " + solvers[-1] + " |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for name in ["hold-150", "steps-150", "hold-100", "sweep-150", "seed-case1", "seed-case2"]:
    cpu = {}
    for solver in solvers:
        runs = [json.load(open(f)) for f in sorted(glob.glob(os.path.join(work, f"{name}_{solver}_*.json")))]
        if runs:
            cpu[solver] = statistics.median(r["cpu_s"] - r.get("settle_cpu_s", 0) for r in runs)
    for solver in solvers:
        runs = [json.load(open(f)) for f in sorted(glob.glob(os.path.join(work, f"{name}_{solver}_*.json")))]
        if not runs:
            continue
        start = statistics.median(r.get("settle_cpu_s", 0) for r in runs)
        r = runs[0]
        t = r["t_reached_s"]
        st = r["status"] if r["status"] == "ok" else "failed: " + r["failure"]["quantity"]
        rel = f"{cpu[solver] / cpu[solvers[-1]]:.2f}" if solvers[-1] in cpu else ""
        c = cpu[solver]
        print(f"| {name} | {solver} | {len(runs)} | {t:g} | {c:.2f} | {c / t:.2f} | {start:.2f} | {r['steps']} | {r['steps'] / t:.0f} | {r['energy_residual_rel']:.1e} | {st} | {rel} |")
PY
