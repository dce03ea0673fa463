#!/usr/bin/env python3
"""The ratio scenarios in real time on the loopback bus and a virtual clock
(docs/sil.md#ratio-realtime):

1. `cvtplant-sil run --loopback --mode realtime`: every ratio scenario
   passes, judged in full (the plant kept time), with its criteria in the
   JUnit report; a second run writes byte-identical traces (the virtual
   clock makes real time deterministic).
2. A plant slower than its frame (`--loopback-frame-cost-us 1500`): every
   frame overruns, the run says the plant did not keep time, the motion
   criteria are reported as skipped, never as passed or failed, and the
   functional ones (no fault, no rejected frame) are still judged.

usage: check_sil_realtime.py CVTPLANT_SIL OUT_DIR
"""
import filecmp
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

SCENARIOS = ["ratio-sweep", "kick-down", "slip-recovery"]
ALWAYS = ["trace_written", "realtime_paced", "frames_valid", "no_watchdog_fault"]
FULL = ["control_on_fresh_groups", "slip_bounded", "ratio_tracked", "no_gross_slip", "no_cmd_timeout"]
OWN = {"ratio-sweep": ["end_stops_reached"], "kick-down": [],
       "slip-recovery": ["slip_seen_in_drop", "slip_bounded_in_drop", "slip_recovered"]}


def run(sil, out, *extra):
    os.makedirs(out, exist_ok=True)
    junit = os.path.join(out, "sil-junit.xml")
    p = subprocess.run([sil, "run", "--loopback", "--mode", "realtime", "--out", out, "--junit", junit, *extra],
                       capture_output=True, text=True)
    return p, ET.parse(junit).getroot() if os.path.exists(junit) else None


def cases(root, name):
    for s in root.iter("testsuite"):
        if s.get("name") == "sil." + name + ".realtime":
            return {c.get("name"): c for c in s.iter("testcase")}
    return None


def main():
    sil, out = sys.argv[1], sys.argv[2]
    fails = []
    p, root = run(sil, os.path.join(out, "rt1"))
    if p.returncode != 0 or root is None:
        fails.append("real-time run: exit %d\n%s%s" % (p.returncode, p.stdout, p.stderr))
    else:
        for n in SCENARIOS:
            c = cases(root, n)
            if c is None:
                fails.append("%s.realtime: no JUnit suite" % n)
                continue
            for k in ALWAYS + FULL + OWN[n]:
                if k not in c:
                    fails.append("%s.realtime: no %s" % (n, k))
                elif c[k].find("failure") is not None or c[k].find("skipped") is not None:
                    fails.append("%s.realtime: %s not passed: %s" % (n, k, c[k].findtext("system-out")))
            if "realtime_paced" in c and "kept time" not in c["realtime_paced"].findtext("system-out"):
                fails.append("%s.realtime: no kept-time statement" % n)
        print(p.stdout, end="")
        p2, _ = run(sil, os.path.join(out, "rt2"))
        for n in SCENARIOS:
            a = os.path.join(out, "rt1", "sil-%s-realtime.csv" % n)
            b = os.path.join(out, "rt2", "sil-%s-realtime.csv" % n)
            if p2.returncode != 0 or not filecmp.cmp(a, b, shallow=False):
                fails.append("%s.realtime: the second run's trace differs" % n)
            elif sum(1 for _ in open(a)) < 300:
                fails.append("%s.realtime: trace too short" % n)

    p, root = run(sil, os.path.join(out, "slow"), "--scenario", "slip-recovery", "--loopback-frame-cost-us", "1500")
    c = cases(root, "slip-recovery") if root is not None else None
    if p.returncode != 0 or c is None:
        fails.append("slow plant: exit %d\n%s%s" % (p.returncode, p.stdout, p.stderr))
    else:
        paced = c["realtime_paced"].findtext("system-out")
        if "did not keep time" not in paced:
            fails.append("slow plant: realtime_paced says %r" % paced)
        for k in ALWAYS:
            if c[k].find("skipped") is not None or c[k].find("failure") is not None:
                fails.append("slow plant: %s not judged and passed" % k)
        for k in FULL + OWN["slip-recovery"]:
            if c[k].find("skipped") is None:
                fails.append("slow plant: %s judged though the plant did not keep time" % k)
        print("slow plant:", paced)
    for f in fails:
        print("FAIL", f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
