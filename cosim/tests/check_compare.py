#!/usr/bin/env python3
"""ctest cosim.compare_short (docs/sil.md#compare): the closed-loop comparison
of two scenarios cut at 2.6 s on the loopback bus, and every output checked
against the others and against the two runs it compares:

- the exit status says whether every verdict agrees;
- compare-scenarios.csv and compare-criteria.csv carry each run's verdicts
  as its own JUnit file has them, criterion by criterion, the agreement and
  the difference against the bound computed as documented;
- each overlay compare-<scenario>.csv holds both runs' traces as their own
  CSV files have them, and compare-traces.csv's RMS differences are those of
  the overlay's columns;
- the HTML report embeds one figure per scenario (a PNG of 1100 x 1250);
- the reference's release states were kept (one per scene).

usage: check_compare.py CVTPLANT_SIL OUT_DIR
"""
import base64
import csv
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

SCENARIOS = ["slip-recovery", "tip-in"]  # in the scenario table's order
T_END = 2.6
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def junit_verdicts(path):
    out = {}
    for suite in ET.parse(path).getroot().iter("testsuite"):
        name = suite.get("name", "")
        name = name[4:] if name.startswith("sil.") else name
        cases = {}
        for c in suite.iter("testcase"):
            cases[c.get("name")] = ("FAIL" if c.find("failure") is not None
                                    else "not judged" if c.find("skipped") is not None else "pass")
        out[name] = cases
    return out


def num(s):
    return float(s) if s not in ("", None) else math.nan


def png_size(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", data[16:24])


def main():
    sil, out = sys.argv[1], sys.argv[2]
    shutil.rmtree(out, ignore_errors=True)
    t0 = time.time()
    r = subprocess.run([sil, "compare", "--scenario", ",".join(SCENARIOS), "--t-end", str(T_END), "--out", out],
                       capture_output=True, text=True)
    print(r.stdout)
    print(r.stderr, file=sys.stderr)
    print("compare: %.1f s wall, exit %d" % (time.time() - t0, r.returncode))
    check(r.returncode in (0, 1), "exit status 0 or 1, got %d" % r.returncode)
    if failures:
        return 1
    scen = read_csv(os.path.join(out, "compare-scenarios.csv"))
    crit = read_csv(os.path.join(out, "compare-criteria.csv"))
    traces = read_csv(os.path.join(out, "compare-traces.csv"))
    check([s["scenario"] for s in scen] == SCENARIOS, "compare-scenarios.csv holds %s" % SCENARIOS)
    all_agree = all(s["verdicts_agree"] == "1" for s in scen)
    check((r.returncode == 0) == all_agree, "exit status 0 exactly when every verdict agrees")
    check(("verdicts agree in %d of 2 scenarios" % sum(s["verdicts_agree"] == "1" for s in scen)) in r.stdout,
          "the table's closing line")
    junit = {side: junit_verdicts(os.path.join(out, d, "sil-junit.xml"))
             for side, d in (("rom", "rom"), ("ref", "reference"))}
    for s in scen:
        name = s["scenario"]
        rows = [c for c in crit if c["scenario"] == name]
        for side in ("rom", "ref"):
            cases = junit[side].get(name, {})
            check(set(cases) <= {c["criterion"] for c in rows}, "%s: every %s criterion in the table" % (name, side))
            suite_pass = all(v != "FAIL" for v in cases.values())
            check(s["verdict_" + side] == ("PASS" if suite_pass else "FAIL"), "%s: %s verdict as in JUnit" % (name, side))
            for c in rows:
                want = cases.get(c["criterion"], "absent")
                check(c["verdict_" + side] == want, "%s %s: %s verdict %s, JUnit %s" % (
                    name, c["criterion"], side, c["verdict_" + side], want))
        agree_rows = 0
        for c in rows:
            same = c["verdict_rom"] == c["verdict_ref"] and c["verdict_rom"] != "absent"
            check((c["agree"] == "1") == same, "%s %s: agree column" % (name, c["criterion"]))
            agree_rows += same
            a, b, lim = num(c["value_rom"]), num(c["value_ref"]), num(c["limit"])
            if not math.isnan(a) and not math.isnan(b):
                check(abs(num(c["difference"]) - (b - a)) <= 1e-5 * max(1.0, abs(b - a)), "%s %s: difference" % (
                    name, c["criterion"]))
                check((c["beyond_fifth_of_limit"] == "1") == (abs(b - a) > 0.2 * abs(lim) * (1 + 1e-9)),
                      "%s %s: beyond a fifth of the bound" % (name, c["criterion"]))
        check(int(s["criteria_agreeing"]) == agree_rows and int(s["criteria"]) == len(rows), "%s: counts" % name)
        check((s["verdicts_agree"] == "1") == (agree_rows == len(rows)), "%s: verdicts_agree" % name)
        check(abs(float(s["sim_s"]) - T_END) < 1e-6, "%s: the reference ran %s s" % (name, s["sim_s"]))
        check(float(s["ref_step_cpu_s"]) > 0, "%s: the reference's CPU is measured" % name)
        # The overlay against each run's own trace.
        ov = read_csv(os.path.join(out, "compare-%s.csv" % name))
        n = int(round(T_END / 0.01))
        check(len(ov) == n, "%s: %d overlay rows, want %d" % (name, len(ov), n))
        for side, d in (("rom", "rom"), ("ref", "reference")):
            own = read_csv(os.path.join(out, d, "sil-%s.csv" % name))
            check(len(own) == len(ov), "%s: %s trace rows" % (name, side))
            for o, w in zip(ov, own):
                for col, wcol, tol in (("slip", "slip", 6e-5), ("ratio", "geometric_ratio", 6e-5),
                                       ("omega1", "omega1_rad_s", 6e-3), ("axial", "axial_force_N", 0.6)):
                    if abs(num(o["%s_%s" % (col, side)]) - num(w[wcol])) > tol:
                        check(False, "%s t=%s: %s_%s %s, the run's trace %s" % (
                            name, o["t_s"], col, side, o["%s_%s" % (col, side)], w[wcol]))
                        break
        for t in (t for t in traces if t["scenario"] == name):
            a = [num(o[t["trace"] + "_rom"]) for o in ov]
            b = [num(o[t["trace"] + "_ref"]) for o in ov]
            rms = math.sqrt(sum((y - x) ** 2 for x, y in zip(a, b)) / len(a))
            scale = max(1e-9, abs(rms), max(abs(x) for x in a + b) * 1e-5)
            check(abs(rms - num(t["rms_difference"])) <= 1e-3 * scale + 1e-5 * max(abs(x) for x in a + b),
                  "%s: RMS difference of %s %s, from the overlay %s" % (name, t["trace"], t["rms_difference"], rms))
    page = open(os.path.join(out, "compare-report.html")).read()
    imgs = re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)", page)
    check(len(imgs) == len(SCENARIOS), "one figure per scenario in the HTML report, found %d" % len(imgs))
    for i in imgs:
        check(png_size(base64.b64decode(i)) == (1100, 1250), "a 1100 x 1250 PNG")
    for s in SCENARIOS:
        check("id='%s'" % s in page, "the report's section of " + s)
    releases = [f for f in os.listdir(os.path.join(out, "reference-cache")) if f.endswith(".release")]
    check(len(releases) == 2, "two release states kept (tip-in, ratio-control), found %d" % len(releases))
    print("check_compare: %d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
