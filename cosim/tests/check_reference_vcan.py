#!/usr/bin/env python3
"""The reference on vcan0 against the same run on the loopback bus
(ctest cosim.reference_vcan, docs/sil.md#tests):

- the vcan run answered every step in time (its bus criteria pass) and its
  criteria have the loopback run's verdicts, one by one;
- the bridge started from the host's release state (no start-up in the VM),
  ran every frame and saw no fault, nothing rejected, nothing dropped;
- its candump log holds one output group per Step, each with its PlantStatus;
- the two traces agree closely: the same program on another CPU (the
  micro-VM's emulated one) takes other libm paths in the integrator's step
  control, so the bits may differ, the physics may not.

usage: check_reference_vcan.py OUT_DIR SCENARIO T_END
"""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

failures = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def verdicts(path):
    out = {}
    for c in ET.parse(path).getroot().iter("testcase"):
        out[c.get("name")] = ("FAIL" if c.find("failure") is not None
                              else "skipped" if c.find("skipped") is not None else "pass")
    return out


def main():
    out, scenario, t_end = sys.argv[1], sys.argv[2], float(sys.argv[3])
    host, vcan = os.path.join(out, "host"), os.path.join(out, "vcan")
    for f in (os.path.join(host, "sil-junit.xml"), os.path.join(vcan, "sil-junit.xml"), os.path.join(vcan, "bridge.json")):
        if not os.path.isfile(f):
            check(False, f + " written")
            return 1
    h, v = verdicts(os.path.join(host, "sil-junit.xml")), verdicts(os.path.join(vcan, "sil-junit.xml"))
    for name in ("bridge_answered_every_step", "lockstep_time_exact", "frames_valid", "no_watchdog_fault"):
        check(v.get(name) == "pass", "vcan: %s passes (%s)" % (name, v.get(name)))
    check(set(h) == set(v), "the same criteria on both buses")
    for name in sorted(h):
        check(h[name] == v.get(name), "%s: %s on the loopback bus, %s on vcan0" % (name, h[name], v.get(name)))
    b = json.load(open(os.path.join(vcan, "bridge.json")))
    frames = int(round(t_end * 1000))
    check(b["reference"]["release_from_cache"], "the bridge started from the host's release state")
    check(b["plant_fault"] == "none" and b["frames"] == frames,
          "the bridge ran %d frames without a fault (%s, %s)" % (frames, b["frames"], b["plant_fault"]))
    check(b["rx"]["rejected"] == 0 and b["tx"]["failed"] == 0, "nothing rejected or lost by the bridge")
    print("vcan: the reference's CPU in the VM %.1f s for %.2f s simulated" % (b["reference"]["step_cpu_s"], t_end))
    statuses = 0
    with open(os.path.join(vcan, "bridge.log")) as f:
        for line in f:
            if " 300#" in line:
                statuses += 1
    periods = int(round(t_end / 0.01))
    check(statuses >= periods + 2, "a PlantStatus for each of the %d Steps and the Reset and None (%d)" % (
        periods, statuses))
    rows = {}
    for side, d in (("host", host), ("vcan", vcan)):
        with open(os.path.join(d, "sil-%s.csv" % scenario), newline="") as f:
            rows[side] = list(csv.DictReader(f))
    check(len(rows["host"]) == len(rows["vcan"]) == periods, "%d samples on both" % periods)
    worst = {}
    for a, c in zip(rows["host"], rows["vcan"]):
        check(a["t_s"] == c["t_s"], "same sample times") if a["t_s"] != c["t_s"] else None
        for col in ("slip", "omega1_rad_s", "omega2_rad_s", "axial_force_N", "torque_transmitted_Nm"):
            worst[col] = max(worst.get(col, 0.0), abs(float(a[col]) - float(c[col])))
    bounds = {"slip": 0.002, "omega1_rad_s": 0.1, "omega2_rad_s": 0.1, "axial_force_N": 20.0,
              "torque_transmitted_Nm": 2.0}
    for col, w in sorted(worst.items()):
        check(w <= bounds[col], "largest difference of %s between the buses %g (bound %g)" % (col, w, bounds[col]))
    print("check_reference_vcan: %d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
