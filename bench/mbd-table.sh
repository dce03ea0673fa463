#!/usr/bin/env bash
# Regenerates the speed and accuracy table of docs/mbd.md#speed and prints it
# as markdown. For seed case 1 and case 2 (tau_in 100 N m, tau_load 50 N m):
#   - BDF (CVODE + KLU) at the default rtol over the seed's 10 s: CPU time
#     and wall time (medians of 3 runs), steps, energy-ledger residual;
#   - the seed's RK4 at dt = 1e-6 s timed over the first second and scaled
#     to 10 s (its cost per step is fixed; later in the run fewer bolts are in
#     contact, so the scaling errs on RK4's slow side by a few per cent);
#   - accuracy over the first second (before the chain's gross slip makes
#     trajectories sensitive to the last digit): the largest error of omega1,
#     omega2 and F_ax1 over the 1 ms samples, against RK4 at dt = 5e-7 s,
#     relative to the largest value of each;
#   - BDF at tighter tolerances, to find the one that matches RK4's accuracy.
# Runs on one core, one job at a time (about 3.5 minutes of CPU). Speed-ups are ratios
# of the process's CPU time, which on a shared, busy host stands for the wall
# time on an idle core; wall times are printed beside them.
#
# Usage: bench/mbd-table.sh [BUILD_DIR]     (default: build/host-release)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/host-release}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. bench/build-host.sh
build_host "$build" cvtplant
cli=$build/tools/cvtplant

for c in 1 2; do
  for rep in 1 2 3; do
    echo "case $c: BDF 10 s, run $rep of 3..." >&2
    "$cli" mbd --case "$c" --t-end 10 --json >"$work/bdf10_c${c}_$rep.json"
  done
  echo "case $c: RK4 dt 1e-6 over 1 s..." >&2
  "$cli" mbd --case "$c" --t-end 1 --method rk4 --dt 1e-6 --csv "$work/rk4_c$c.csv" --json >"$work/rk4_c$c.json"
  echo "case $c: reference RK4 dt 5e-7 over 1 s..." >&2
  "$cli" mbd --case "$c" --t-end 1 --method rk4 --dt 5e-7 --csv "$work/ref_c$c.csv" --json >"$work/ref_c$c.json"
  for r in 5e-7 1e-8 3e-10 1e-10 1e-11; do
    echo "case $c: BDF rtol $r over 1 s..." >&2
    "$cli" mbd --case "$c" --t-end 1 --rtol "$r" --csv "$work/bdf_c${c}_$r.csv" --json >"$work/bdf_c${c}_$r.json"
  done
done

python3 - "$work" <<'PY'
import csv, json, statistics, sys
w = sys.argv[1]

def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))

def errors(path, ref):
    rows = load(path)
    out = []
    for k in ("omega1_rad_s", "omega2_rad_s", "F_ax1_N"):
        scale = max(abs(float(r[k])) for r in ref)
        out.append(max(abs(float(a[k]) - float(b[k])) for a, b in zip(rows, ref)) / scale)
    return out

print("| case | method | 10 s CPU [s] | 10 s wall [s] | steps (10 s) | ledger residual | speed-up vs RK4 1e-6 (CPU) |")
print("|---|---|---|---|---|---|---|")
for c in (1, 2):
    runs = [json.load(open(f"{w}/bdf10_c{c}_{i}.json")) for i in (1, 2, 3)]
    cpu = statistics.median(r["cpu_s"] for r in runs)
    wall = statistics.median(r["wall_s"] for r in runs)
    rk4 = json.load(open(f"{w}/rk4_c{c}.json"))
    j = runs[0]
    print(f"| {c} | BDF ({j.get('linear_solver', 'klu')}) rtol {j['rtol']:g} | {cpu:.1f} | {wall:.1f} | {j['steps']} | "
          f"{max(r['energy_residual_rel'] for r in runs):.1e} | {10.0 * rk4['cpu_s'] / cpu:.1f}x |")
    print(f"| {c} | RK4 dt 1e-6 (1 s measured, x10) | {10 * rk4['cpu_s']:.0f} | {10 * rk4['wall_s']:.0f} | "
          f"{10 * rk4['steps']} | {rk4['energy_residual_rel']:.1e} (1 s) | 1x |")
print()
print("| case | method | first 1 s CPU [s] | err omega1 | err omega2 | err F_ax1 | speed-up vs RK4 1e-6 (CPU, 1 s) |")
print("|---|---|---|---|---|---|---|")
for c in (1, 2):
    ref = load(f"{w}/ref_c{c}.csv")
    rk4 = json.load(open(f"{w}/rk4_c{c}.json"))
    rows = [(f"RK4 dt 1e-6", f"{w}/rk4_c{c}")] + [(f"BDF rtol {r}", f"{w}/bdf_c{c}_{r}") for r in ("5e-7", "1e-8", "3e-10", "1e-10", "1e-11")]
    for name, base in rows:
        j = json.load(open(base + ".json"))
        e = errors(base + ".csv", ref)
        print(f"| {c} | {name} | {j['cpu_s']:.2f} | {e[0]:.1e} | {e[1]:.1e} | {e[2]:.1e} | "
              f"{rk4['cpu_s'] / j['cpu_s']:.1f}x |")
PY
