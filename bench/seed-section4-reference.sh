#!/usr/bin/env bash
# The seed's section 4 on the multibody reference, in full
# (docs/seed-section4.md): for each friction case the seed's run-up from rest
# and three steady operating points, each with its convergence runs (the
# tolerance tightened 10x and 100x), 2 s of the seed's RK4 at dt = 1e-6 s and
# 19 IAAFT surrogates per signal, and the largest exponent of the
# reference's own equations by two trajectories over the window (5 s; 3.5 s
# for case 1's run-up, whose window is 4 s); then the claim-by-claim table and the
# per-point numbers of docs/seed-section4.md, as markdown.
#
# About an hour of CPU on one core; runs are cached under CACHE_DIR, so a
# second call only analyses.
#
# Usage: bench/seed-section4-reference.sh [OUT_DIR] [CACHE_DIR] [BUILD_DIR]
#        (defaults: build/seed-section4, OUT_DIR/reference-cache, build/host-release)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/seed-section4}
cache=${2:-$out/reference-cache}
build=${3:-build/host-release}
. bench/build-host.sh
build_host "$build" cvtplant
mkdir -p "$out" "$cache"
cvt="$build/tools/cvtplant"
full=(--convergence 10,100 --rk4 2 --surrogates 19 --cache-dir "$cache" --json)
# The run-ups: the seed's windows (case 1: the last 4000 samples of 10 s;
# case 2: 10,000 samples after a 2 s transient of 12 s).
nice -n 10 "$cvt" analyze seed-section4 --reference --case 1 --benettin 3.5 --out-dir "$out/case1-run-up" "${full[@]}" \
  >"$out/case1-run-up.json"
nice -n 10 "$cvt" analyze seed-section4 --reference --case 2 --benettin 5 --out-dir "$out/case2-run-up" "${full[@]}" \
  >"$out/case2-run-up.json"
# Steady points: two where both wraps grip, one in the run-up's sliding regime
# (case 1: the driver wrap in gross slip, as over the seed's case-1 window;
# case 2: the driven wrap slipping, as at 4.5-5 s of its run-up). A 4 s
# transient after the release.
nice -n 10 "$cvt" analyze seed-section4 --reference --case 1 --steady 30,100,300:80 --t-transient 4 --benettin 5 \
  --out-dir "$out/case1-steady" "${full[@]}" >"$out/case1-steady.json"
nice -n 10 "$cvt" analyze seed-section4 --reference --case 2 --steady 30,100,130:64 --t-transient 4 --benettin 5 \
  --out-dir "$out/case2-steady" "${full[@]}" >"$out/case2-steady.json"

python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
runs = ["case1-run-up", "case1-steady", "case2-run-up", "case2-steady"]
print("| claim | run | window | stationary | verdict | claim verdict |")
print("|---|---|---|---|---|---|")
for name in runs:
    j = json.load(open(f"{out}/{name}.json"))
    for s in j["scenarios"]:
        if "error" in s:
            print(f"| | case {j['case']} {s['name']} | | | {s['error']} | |")
            continue
        w = s["window"]
        for g in s["signals"]:
            for c in g.get("claims", []):
                print(f"| {c['claim']} | case {j['case']} {s['name']} | {w['t_begin_s']:g}-{w['t_end_s']:g} s "
                      f"| {'yes' if g['stationarity']['stationary'] else 'no'} | {g['verdict']['verdict']} "
                      f"({g['verdict']['kind']}) | {c['verdict']} |")
print()
print("| case | run | signal | mean | std | stationary | seed embedding | AMI/FNN embedding | lines | K | DET | "
      "Rosenstein (seed d, m) [1/s] | Wolf (seed d, m) [1/s] | surrogates: NLPE rank, TRA p | separation rate [1/s] "
      "| two trajectories [1/s] | verdict |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for name in runs:
    j = json.load(open(f"{out}/{name}.json"))
    for s in j["scenarios"]:
        if "error" in s:
            continue
        for g in s["signals"]:
            if g.get("constant"):
                continue
            se, de = g["seed_embedding"], g["data_embedding"]
            li = g["lines"]
            sur = g.get("surrogates", {}).get("statistics", [])
            nl = next((x for x in sur if x["name"] == "prediction_error"), None)
            tr = next((x for x in sur if x["name"] == "time_reversal_asymmetry"), None)
            wo = g.get("wolf", {}).get(f"m{se['m']}", {})
            wolf = "%.3g +- %.2g" % (wo["lambda"], wo["ci95"]) if "lambda" in wo else ("no estimate" if "error" in wo else "-")
            e = s.get("equation_exponent")
            ex = "-" if not e else (e["failure"] if e["failure"] else "%.3g +- %.2g" % (e["lambda_per_s"], e["ci95_per_s"]))
            rates = []
            for c in g["convergence"]:
                for k in ("separation_from_base", "separation_from_previous"):
                    if k in c and c[k]["exponential_growth"]:
                        rates.append("%.2f" % c[k]["exponential"]["slope"])
                    elif k in c and c[k]["differ"] and not c[k]["saturated"]:
                        rates.append("<%.2f" % c[k]["rate_bound_per_s"])
            print(f"| {j['case']} | {s['name']} | {g['signal']} | {g['stats']['mean']:.4g} | {g['stats']['std']:.3g} "
                  f"| {'yes' if g['stationarity']['stationary'] else 'no'} "
                  f"| {se['classification']} (d {se['tau']}, m {se['m']}) | {de['classification']} (d {de['tau']}, m {de['m']}) "
                  f"| {100 * li['power_fraction_in_lines']:.1f} %{', all link-rate harmonics' if li['all_explained'] else ''} "
                  f"| {se['test01']['K']:.2f} | {se['rqa']['DET']:.2f} "
                  f"| {se['rosenstein']['lambda']:.3g} +- {se['rosenstein']['ci95']:.2g}{'' if se['rosenstein']['fit']['scaling_region'] else ' (no scaling region)'} "
                  f"| {wolf} | {nl['rank_low'] if nl else '-'} of {len(nl['surrogates']) + 1 if nl else '-'}, {tr['p'] if tr else '-'} "
                  f"| {', '.join(rates) or '-'} | {ex} | {g['verdict']['verdict']} ({g['verdict']['kind']}) |")
PY
