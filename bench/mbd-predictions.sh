#!/usr/bin/env bash
# Runs the seed's 10 s scenario for both friction cases through the figures
# command (docs/mbd.md#what-the-model-shows) and prints, as markdown, the
# window means that docs/mbd.md compares with the design predictions: driver
# axial force (mean and peak to peak), slip on each wrap, links in the driver
# wrap, strand tensions, the chain's speed in the driver wrap (omega1 r1 minus
# the driver slip) and its centrifugal tension m' v^2 (m' = N m / pitch line,
# the chain's mass per metre), and the speed ratio (mean omega1 / mean omega2).
# The PNGs (seed Figs. 13-14, the chain at --picture-t) stay in OUT_DIR.
#
# Usage: bench/mbd-predictions.sh [OUT_DIR] [BUILD_DIR]
#        (defaults: build/mbd-figures, build/host-release)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/mbd-figures}
build=${2:-build/host-release}
. bench/build-host.sh
build_host "$build" cvtplant
"$build/tools/cvtplant" mbd figures --out-dir "$out" --t-end 10 --picture-t 7.5 --json >"$out.json"

python3 - "$out" <<'PY'
import csv, math, sys
out = sys.argv[1]
r1 = 0.0762                                 # driver pitch radius [m] (seed section 4)
mass_per_m = 44 * 0.1125 / 1.6013780        # 44 links of Table 1 on the pitch line [kg/m] (docs/mbd.md#geometry)
windows = [(0.0, 1.0), (0.5, 1.0), (1, 2), (2, 3), (4, 4.5), (5, 5.5), (5.5, 6), (6, 7), (7, 8), (8, 9), (9, 9.5),
           (9.5, 10)]
print("| case | window [s] | F_ax1 mean [kN] | F_ax1 peak to peak [kN] | slip driver [m/s] | slip driven [m/s] "
      "| links in driver wrap | T_tight [N] | T_slack [N] | chain speed [m/s] | m' v^2 [N] | ratio mean omega1 / mean omega2 |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for c in (1, 2):
    rows = list(csv.DictReader(open(f"{out}/case{c}.csv")))
    t = [float(r["t_s"]) for r in rows]

    def col(k):
        return [float(r[k]) for r in rows]

    w1, w2, fax = col("omega1_rad_s"), col("omega2_rad_s"), col("F_ax1_N")
    s1, s2, n1 = col("slip1_m_s"), col("slip2_m_s"), col("wrap_links1")
    tt, ts = col("T_tight_N"), col("T_slack_N")
    v = [w * r1 - s for w, s in zip(w1, s1)]  # nan where no bolt is in the driver wrap

    def mean(v, a, b):
        x = [x for x, tt_ in zip(v, t) if a - 1e-9 <= tt_ <= b + 1e-9 and not math.isnan(x)]
        return sum(x) / len(x) if x else float("nan")

    def p2p(v, a, b):
        x = [x for x, tt_ in zip(v, t) if a - 1e-9 <= tt_ <= b + 1e-9]
        return max(x) - min(x)

    def ratio(a, b):
        i1 = i2 = 0.0
        for k in range(1, len(t)):
            if a - 1e-9 <= t[k - 1] and t[k] <= b + 1e-9:
                dt = t[k] - t[k - 1]
                i1 += 0.5 * dt * (w1[k] + w1[k - 1])
                i2 += 0.5 * dt * (w2[k] + w2[k - 1])
        return i1 / i2

    for a, b in windows:
        print(f"| {c} | {a:g}-{b:g} | {mean(fax, a, b) / 1e3:.2f} | {p2p(fax, a, b) / 1e3:.2f} | {mean(s1, a, b):.3f} | "
              f"{mean(s2, a, b):.3f} | {mean(n1, a, b):.1f} | {mean(tt, a, b):.0f} | {mean(ts, a, b):.0f} | "
              f"{mean(v, a, b):.2f} | {mass_per_m * mean(v, a, b) ** 2:.0f} | {ratio(a, b):.3f} |")
    print(f"| {c} | at 10 s | | | | | | | | | | {w1[-1] / w2[-1]:.3f} (omega1/omega2) |")
PY
