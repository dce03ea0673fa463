#!/usr/bin/env bash
# Regenerates the offline solvers' work-precision figures of
# docs/performance.md: the adaptive RODAS4 against Boost.Odeint rosenbrock4
# and CVODE BDF on the same right-hand side and Jacobian
# (bench/work_precision.cpp), and the per-frame cost of the real-time frame
# stepper against the peers taking one frame at a time.
#
# Usage: bench/work-precision.sh BUILD_DIR OUT_DIR [--quick]
#   BUILD_DIR  a configured build tree with benchmarks (e.g. build/host-release)
#   OUT_DIR    receives work-precision.csv, work-precision.md,
#              work-precision.png, frames.csv, frames.md
#   --quick    short runs, tolerances down to 1e-6 (the CI smoke; no figure
#              from it is meant to be quoted)
# CPU time is process time; the host is shared, so compare the ratios within
# one run (the load is written into the tables).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: bench/work-precision.sh BUILD_DIR OUT_DIR [--quick]" >&2
  exit 2
fi
build=$1
out=$2
quick=${3:-}
if [ -n "$quick" ] && [ "$quick" != "--quick" ]; then
  echo "work-precision.sh: unknown option '$quick'" >&2
  exit 2
fi
[ -f "$build/CMakeCache.txt" ] || { echo "work-precision.sh: $build is not a configured build tree" >&2; exit 2; }
mkdir -p "$out"
cmake --build "$build" --target work_precision >&2
exe=$build/bench/work_precision
# 2 s of each seed scene from rest (the transient and the steady run), 10 s
# of the oscillator's stick-slip cycle.
args=(--t-end 2)
[ -n "$quick" ] && args=(--quick --t-end 0.05)

load() { uptime | sed 's/.*load average: //'; }
echo "work-precision runs (load $(load))..." >&2
l0=$(load)
"$exe" wp "${args[@]}" >"$out/work-precision.csv"
"$exe" frames "${args[@]}" >"$out/frames.csv"
l1=$(load)

python3 - "$out" "$l0" "$l1" <<'EOF'
import csv, math, sys
out, l0, l1 = sys.argv[1], sys.argv[2], sys.argv[3]
rows = list(csv.DictReader(open(f"{out}/work-precision.csv")))
scenes = list(dict.fromkeys(r["scene"] for r in rows))
solvers = ["rodas4", "odeint-rosenbrock4", "cvode-bdf"]
levels = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]

def cost_at(pts, e):
    # Log-log interpolation of cost against error between the two runs
    # (consecutive tolerances) whose errors bracket e; the cheapest such.
    best = None
    for (e0, c0), (e1, c1) in zip(pts, pts[1:]):
        lo, hi = min(e0, e1), max(e0, e1)
        if lo <= e <= hi and e0 != e1:
            w = (math.log(e) - math.log(e0)) / (math.log(e1) - math.log(e0))
            c = math.exp(math.log(c0) + w * (math.log(c1) - math.log(c0)))
            best = c if best is None else min(best, c)
    return best

md = [f"Work-precision: CPU time per simulated second at equal error (relative RMS over frames and states,",
      f"docs/performance.md#error), interpolated between runs; load average {l0} before, {l1} after.", ""]
md.append("| scene | error | RODAS4 [us/s] | rosenbrock4 [us/s] | CVODE BDF [us/s] | best peer / RODAS4 |")
md.append("|---|---|---|---|---|---|")
for s in scenes:
    ref = [r for r in rows if r["scene"] == s and r["solver"] == "reference"]
    pts = {}
    for v in solvers:
        p = [(float(r["error"]), float(r["cpu_s_per_sim_s"])) for r in rows
             if r["scene"] == s and r["solver"] == v and r["status"] == "ok" and float(r["error"]) > 0
             and math.isfinite(float(r["error"]))]
        pts[v] = p
    for e in levels:
        c = {v: cost_at(pts[v], e) for v in solvers}
        fmt = lambda x: "-" if x is None else f"{1e6 * x:.0f}"
        peers = [c[v] for v in solvers[1:] if c[v] is not None]
        ratio = "-" if c["rodas4"] is None or not peers else f"{min(peers) / c['rodas4']:.2f}"
        md.append(f"| {s} | {e:.0e} | {fmt(c['rodas4'])} | {fmt(c['odeint-rosenbrock4'])} | {fmt(c['cvode-bdf'])} | {ratio} |")
    if ref:
        md.append(f"| {s} | reference's own error {float(ref[0]['error']):.1e} | | | | |")
md.append("")
md.append("'-': the solver's runs do not reach that error (or the reference's error is above it).")
open(f"{out}/work-precision.md", "w").write("\n".join(md) + "\n")

fr = list(csv.DictReader(open(f"{out}/frames.csv")))
fm = [f"Cost of one 1 ms frame, each timed alone (steady clock, ns); load average {l0} before, {l1} after.", "",
      "| scene | solver | frames | median [ns] | p99.9 [ns] | max [ns] | error |", "|---|---|---|---|---|---|---|"]
for r in fr:
    fm.append(f"| {r['scene']} | {r['solver']} | {r['frames']} | {r['median_ns']} | {r['p99_9_ns']} | {r['max_ns']} | {float(r['error']):.1e} |")
open(f"{out}/frames.md", "w").write("\n".join(fm) + "\n")

# Data blocks for gnuplot: one file per scene and solver.
for s in scenes:
    for v in solvers:
        with open(f"{out}/.wp-{s}-{v}.dat", "w") as f:
            for r in rows:
                if r["scene"] == s and r["solver"] == v and r["status"] == "ok" and math.isfinite(float(r["error"])):
                    f.write(f"{r['error']} {float(r['cpu_s_per_sim_s']) * 1e6}\n")
open(f"{out}/.wp-scenes", "w").write(" ".join(scenes))
EOF

scenes=$(cat "$out/.wp-scenes")
{
  echo "set terminal pngcairo size 1400,1000 font ',11'"
  echo "set output '$out/work-precision.png'"
  echo "set multiplot layout 2,2 title 'Work-precision, same right-hand side and Jacobian (load $l0)'"
  echo "set logscale xy; set format x '10^{%L}'; set format y '10^{%L}'; set grid"
  echo "set xlabel 'error: relative RMS over frames and states [-]'"
  echo "set ylabel 'CPU time per simulated second [us/s]'"
  echo "set key top right"
  for s in $scenes; do
    echo "set title '$s'"
    echo "plot '$out/.wp-$s-rodas4.dat' w lp pt 7 t 'RODAS4 (cvtplant)', \
'$out/.wp-$s-odeint-rosenbrock4.dat' w lp pt 5 t 'Boost.Odeint rosenbrock4', \
'$out/.wp-$s-cvode-bdf.dat' w lp pt 9 t 'CVODE BDF'"
  done
  echo "unset multiplot"
} | gnuplot
rm -f "$out"/.wp-*
cat "$out/work-precision.md" "$out/frames.md"
