#!/usr/bin/python3
"""Checks the candump example of docs/can.md#candump-example: the decoded
lines in the docs are what hil/candump-decode (canmatrix, from the DBC)
prints for the raw lines above them, every frame's E2E CRC agrees with the
tests' own Profile 1 closed form (hil/tests/can/e2e_profile1.py), and the
decoder refuses bad input with exit 2.

usage: check_candump_example.py DOCS_CAN_MD DECODER DBC
"""

import logging
import os
import re
import subprocess
import sys

logging.disable(logging.CRITICAL)
import canmatrix.formats  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from e2e_profile1 import p01_crc  # noqa: E402

RAW = re.compile(r"^    (\(\d+\.\d{6}\) vcan0 [0-9A-F]{3}#[0-9A-F]{16})$")
DECODED = re.compile(r"^    (\d+\.\d{6} 0x[0-9A-F]{3} \w+ .*)$")


def main():
    doc, decoder, dbc = sys.argv[1:4]
    text = open(doc).read()
    start = text.index("{#candump-example}")
    end = text.find("\n## ", start)
    section = text[start:end if end > 0 else len(text)]
    raw = [m.group(1) for m in map(RAW.match, section.splitlines()) if m]
    want = [m.group(1) for m in map(DECODED.match, section.splitlines()) if m]
    fails = []
    if len(raw) < 8 or len(want) != len(raw):
        fails.append("%d raw and %d decoded lines in the example" % (len(raw), len(want)))
    got = subprocess.run([decoder, "--dbc", dbc], input="\n".join(raw) + "\n", capture_output=True, text=True)
    if got.returncode != 0:
        fails.append("decoder exit %d: %s" % (got.returncode, got.stderr.strip()))
    lines = got.stdout.splitlines()
    for i, (a, b) in enumerate(zip(lines, want)):
        if a != b:
            fails.append("line %d: decoder prints\n  %s\ndocs say\n  %s" % (i + 1, a, b))
    if len(lines) != len(want):
        fails.append("decoder printed %d lines, the docs show %d" % (len(lines), len(want)))
    frames = {f.arbitration_id.id: f for f in canmatrix.formats.loadp_flat(dbc).frames}
    names = set()
    for r in raw:
        ident, data = r.split(") vcan0 ")[1].split("#")
        frame = frames[int(ident, 16)]
        names.add(frame.name)
        data = bytes.fromhex(data)
        crc = p01_crc(int(frame.attributes["CvtE2EDataID"]), data)
        if crc != data[0]:
            fails.append("%s: CRC 0x%02X, Profile 1 gives 0x%02X" % (r, data[0], crc))
    for need in ("CtrlCmd", "CtrlShiftCmd", "PlantRatio", "PlantShift"):
        if need not in names:
            fails.append("the example has no %s frame" % need)
    # Bad input: one line on stderr, exit 2, nothing decoded.
    for args, stdin, what in (
        (["--dbc", dbc], "(1.0) vcan0 nonsense\n", "a line that is not a candump -L frame"),
        (["--dbc", dbc, "--frobnicate"], "", "an unknown option"),
        (["--dbc", dbc + ".missing"], "", "a missing DBC"),
        (["--dbc", dbc, "--ids", "xyz"], "", "IDs that are not hex"),
        (["--dbc", dbc, "/nonexistent/candump.log"], "", "a missing log"),
    ):
        r = subprocess.run([decoder] + args, input=stdin, capture_output=True, text=True)
        if r.returncode != 2 or not r.stderr.startswith("candump-decode: ") or r.stdout:
            fails.append("%s: exit %d, stderr %r" % (what, r.returncode, r.stderr))
    for f in fails:
        print("check_candump_example: FAIL:", f)
    print("check_candump_example: %d frames (%s), %d failures" % (len(raw), ", ".join(sorted(names)), len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
