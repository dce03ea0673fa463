#!/usr/bin/python3
"""The DBC generator refuses DBC content it cannot honour (docs/can.md#codegen):
each mutation of hil/cvtplant.dbc below must make dbc2cpp.py exit 2 with one
line naming the message and signal on stderr, and write nothing.

usage: check_codegen_refusals.py DBC2CPP DBC OUT_DIR
"""

import os
import subprocess
import sys

# (what, text to replace, replacement, expected words in the error)
MUTATIONS = [
    ("Ramp on an unscaled signal", 'BA_ "CvtPhysType" SG_ 769 rt_overruns 1;',
     'BA_ "CvtPhysType" SG_ 769 rt_overruns 1;\nBA_ "CvtTimeoutAction" SG_ 769 rt_overruns 3;\n'
     'BA_ "CvtSubstituteRate" SG_ 769 rt_overruns 10;', "PlantDiag.rt_overruns: Ramp"),
    ("Ramp without a rate", 'BA_ "CvtSubstituteRate" SG_ 256 clamp_force_cmd_N 50000;',
     'BA_ "CvtSubstituteRate" SG_ 256 clamp_force_cmd_N 0;', "CtrlCmd.clamp_force_cmd_N: Ramp"),
    ("Ramp target outside [min|max]", 'BA_ "CvtSubstituteValue" SG_ 256 clamp_force_cmd_N 20000;',
     'BA_ "CvtSubstituteValue" SG_ 256 clamp_force_cmd_N 70000;', "CtrlCmd.clamp_force_cmd_N: CvtSubstituteValue"),
    ("E2E sync counter out of range", 'BA_ "CvtE2EMaxDeltaCounter" BO_ 128 14;',
     'BA_ "CvtE2EMaxDeltaCounter" BO_ 128 14;\nBA_ "CvtE2ESyncCounterInit" BO_ 256 15;', "CtrlCmd: CvtE2ESyncCounterInit"),
]


def main():
    gen, dbc, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    text = open(dbc).read()
    fails = 0
    for what, old, new, expect in MUTATIONS:
        if old not in text:
            print("check_codegen_refusals: FAIL: %s: the DBC no longer contains %r" % (what, old))
            fails += 1
            continue
        path = os.path.join(out, "mutated.dbc")
        hdr = os.path.join(out, "mutated.hpp")
        open(path, "w").write(text.replace(old, new))
        if os.path.exists(hdr):
            os.remove(hdr)
        r = subprocess.run([sys.executable, gen, "--dbc", path, "--out", hdr], capture_output=True, text=True)
        lines = r.stderr.strip().splitlines()
        ok = r.returncode == 2 and len(lines) == 1 and expect in lines[0] and not os.path.exists(hdr)
        print("%s %s: exit %d, %s" % ("ok  " if ok else "FAIL", what, r.returncode, r.stderr.strip()))
        fails += 0 if ok else 1
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
