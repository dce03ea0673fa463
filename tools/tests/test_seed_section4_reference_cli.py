#!/usr/bin/env python3
"""`cvtplant analyze seed-section4 --reference`, short (docs/seed-section4.md#ci).

One steady operating point of seed case 1 (driver at 60 rad/s, a 1 s
transient, 1000 samples), one convergence run at a tenfold tighter tolerance,
5 surrogates and ten intervals of the two-trajectory exponent: a few seconds
of reference time. Checks the summary's
fields and what the reference must show there, not just that it ran:
  - every documented field is present, with its unit where it has one;
  - the links pass the middle of both wraps at the same rate (a closed chain
    in a steady state: the passages over the window differ by at most one),
    and the driver axial force's strongest spectral line is that rate
    (the link-passing ripple, docs/mbd.md);
  - the verdict follows its rules: a non-stationary signal is undecided, the
    claims map chaotic -> holds, regular -> does not hold, undecided ->
    cannot be decided;
  - every PNG listed is valid; summary.json equals the printed JSON;
  - bad input exits 2 with one line on stderr, before any run.
Usage: test_seed_section4_reference_cli.py CVTPLANT TMPDIR
"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_seed_section4_cli import check, exit_status, png_valid  # noqa: E402


def bad_input(binary, tmp):
    out = os.path.join(tmp, "bad")
    cases = [
        (["--reference", "--out-dir", out], "--case"),
        (["--reference", "--case", "1", "--scene", "seed-case1", "--out-dir", out], "exclude"),
        (["--reference", "--case", "1", "--steady", "1000", "--out-dir", out], "--steady"),
        (["--reference", "--case", "1", "--steady", "60:x", "--out-dir", out], "--steady"),
        (["--reference", "--case", "1", "--convergence", "0.5", "--out-dir", out], "--convergence"),
        (["--reference", "--case", "1", "--signals", "torque", "--out-dir", out], "torque"),
        (["--reference", "--case", "3", "--out-dir", out], "3"),
        (["--reference", "--case", "2", "--points", "20000", "--t-end", "5", "--out-dir", out], "window"),
        (["--reference", "--case", "1", "--max-steps", "10", "--out-dir", out], "--max-steps"),
    ]
    for args, word in cases:
        p = subprocess.run([binary, "analyze", "seed-section4"] + args, capture_output=True, text=True, timeout=60)
        lines = p.stderr.strip().splitlines()
        check(p.returncode == 2 and len(lines) == 1 and word in lines[0],
              "%s: exit 2 and one line naming %r (got %d: %r)" % (" ".join(args[:-2]), word, p.returncode, p.stderr.strip()))
    check(not os.path.exists(os.path.join(out, "reference-cache")) or not os.listdir(os.path.join(out, "reference-cache")),
          "bad input ran nothing")


def main():
    binary, tmp = sys.argv[1], sys.argv[2]
    os.makedirs(tmp, exist_ok=True)
    bad_input(binary, tmp)
    out = os.path.join(tmp, "case1")
    # A fresh cache: the runs are computed, not read back from an earlier build.
    shutil.rmtree(out, ignore_errors=True)
    cmd = [binary, "analyze", "seed-section4", "--reference", "--case", "1", "--steady", "60", "--points", "1000",
           "--t-transient", "1", "--convergence", "10", "--surrogates", "5", "--benettin", "0.2",
           "--signals", "F_ax1_N,omega1_rad_s",
           "--out-dir", out, "--json"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    check(p.returncode == 0, "exit 0 (stderr: %s)" % p.stderr.strip()[-300:])
    if p.returncode != 0:
        return 1
    j = json.loads(p.stdout)
    check(json.load(open(os.path.join(out, "summary.json"))) == j, "summary.json equals the printed JSON")
    check(j["case"] == 1 and j["points"] == 1000 and j["sample_s"] == 0.001, "case, points, sample interval")
    check(j["seed_choices"]["tau"] == 1 and j["seed_choices"]["m"] == 3 and j["seed_choices"]["delays"] == [1, 2, 3, 10],
          "the seed's case-1 choices: d = 1, m = 3, delays 1, 2, 3, 10")
    check(len(j["scenarios"]) == 1, "one scenario")
    s = j["scenarios"][0]
    check(s["name"] == "steady-w60" and s["kind"] == "steady", "scenario steady-w60")
    check(s["window"] == {"t_begin_s": 1.0, "t_end_s": 2.0, "points": 1000}, "window 1-2 s, 1000 points")
    check([r["numerics"] for r in s["runs"]] == ["BDF rtol 5e-07", "BDF rtol 5e-08"], "base run and the 10x run")
    for r in s["runs"]:
        check(r["failure"] is None and r["samples"] == 2001 and r["energy_residual_rel"] < 1e-6,
              "%s: 2001 samples, ledger %.2g below 1e-6" % (r["numerics"], r["energy_residual_rel"]))
    st = s["start"]
    check(st["omega1_rad_s"] == 60 and st["omega2_spinup_rad_s"] == 30, "start at 60 / 30 rad/s")
    check(abs(s["tau_in_Nm"] - st["holding_torque_Nm"]) < 1e-12, "the input torque is the hold's holding torque")
    op = s["operating_point"]
    check(abs(op["omega1_mean_rad_s"] - 60) < 0.5, "the driver stays at 60 rad/s (%.3f)" % op["omega1_mean_rad_s"])
    check(abs(op["driver_torque_mean_Nm"] - s["tau_in_Nm"]) < 0.02 * s["tau_in_Nm"],
          "steady: the chain takes the input torque off the driver (%.2f against %.2f N m)"
          % (op["driver_torque_mean_Nm"], s["tau_in_Nm"]))
    lr = s["link_rates"]
    check(abs(lr["driver_passages"] - lr["driven_passages"]) <= 1,
          "a closed chain: %d and %d passages through the two wraps" % (lr["driver_passages"], lr["driven_passages"]))
    check(abs(lr["ratio"] - 1) <= lr["ratio_resolution_rel"], "link-rate ratio 1 within %.2g" % lr["ratio_resolution_rel"])
    check(abs(lr["chain_lap_Hz"] * 44 - lr["driver_Hz"]) < 1e-9 * lr["driver_Hz"], "lap rate = link rate / 44")
    e = s["equation_exponent"]
    check(e["failure"] is None and e["intervals"] == 10 and e["t_start_s"] == 1.0 and e["rtol"] == 5e-9 and
          len(e["batch_lambda_per_s"]) == 10 and len(e["convergence"]["lambda_per_s"]) == 10,
          "two trajectories: 10 intervals of 20 ms from the window's start at rtol 5e-9")
    check(abs(e["convergence"]["lambda_per_s"][-1] - e["lambda_per_s"]) < 1e-9 * max(1, abs(e["lambda_per_s"])) and
          abs(sum(e["batch_lambda_per_s"]) / 10 - e["lambda_per_s"]) < 1e-9 * max(1, abs(e["lambda_per_s"])),
          "the exponent is the mean of its batches and the last running estimate (%.3g 1/s)" % e["lambda_per_s"])
    sigs = {g["signal"]: g for g in s["signals"]}
    check(set(sigs) == {"F_ax1_N", "omega1_rad_s"}, "the two signals asked for")
    for name, g in sigs.items():
        check(g["stats"]["unit"] == ("N" if name == "F_ax1_N" else "rad/s"), "%s: unit" % name)
        check(len(g["stationarity"]["windows"]) == 4, "%s: 4 stationarity windows" % name)
        se = g["seed_embedding"]
        check(se["tau"] == 1 and se["m"] == 3, "%s: the seed's embedding d = 1, m = 3" % name)
        check(g["fnn"]["m"] == list(range(1, 11)) and len(g["fnn"]["fraction"]) == 10, "%s: FNN m = 1..10" % name)
        check(g["surrogates"]["count"] == 5 and len(g["surrogates"]["statistics"]) == 3 and
              all(len(x["surrogates"]) == 5 and x["rank_low"] + x["rank_high"] <= 7 for x in g["surrogates"]["statistics"]),
              "%s: 5 surrogates, three statistics ranked" % name)
        check(len(g["convergence"]) == 1 and g["convergence"][0]["rtol"] == 5e-8 and
              "separation_from_base" in g["convergence"][0], "%s: the 10x run and its separation" % name)
        wolf = g["wolf"]
        check(set(wolf) == {"m3", "m10"} and all(
            math.isfinite(w["lambda"]) and w["m"] == int(k[1:]) and w["tau"] == 1 and w["evolve"] >= 1 and
            w["steps"] + w["collapsed"] == w["kept"] + w["replaced"] + w["relaxed"] + w["unreplaced"] + 1
            for k, w in wolf.items()), "%s: Wolf's exponent at m = 3 and 10, its steps accounted for" % name)
        v = g["verdict"]
        check(v["verdict"] in ("chaotic", "regular", "undecided"), "%s: verdict %s" % (name, v["verdict"]))
        if not g["stationarity"]["stationary"]:
            check(v["verdict"] == "undecided", "%s: not stationary, so undecided" % name)
        for c in g["claims"]:
            want = {"chaotic": "holds", "regular": "does not hold", "undecided": "cannot be decided"}[v["verdict"]]
            check(c["verdict"] == want, "%s: claim %r -> %s" % (name, c["words"], c["verdict"]))
        for f in g["figures"]:
            bad = png_valid(f)
            check(bad is None, "%s: %s is a valid PNG%s" % (name, os.path.basename(f), "" if bad is None else ": " + bad))
        check(len(g["figures"]) >= 10, "%s: %d figures" % (name, len(g["figures"])))
    fax = sigs["F_ax1_N"]
    check(len(fax["claims"]) == 1 and fax["claims"][0]["words"] == "chaotic", "case 1 F_ax1: the seed's claim 'chaotic'")
    top = fax["lines"]["lines_Hz"][0]
    check(abs(top - lr["driver_Hz"]) <= 2 * fax["lines"]["resolution_Hz"],
          "F_ax1's strongest line %.3f Hz is the link-passing rate %.3f Hz" % (top, lr["driver_Hz"]))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
