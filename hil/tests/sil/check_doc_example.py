#!/usr/bin/python3
"""Checks the candump example of docs/sil.md#log against implementations that
are not the project's codec: the E2E CRC is recomputed with the tests'
Profile 1 closed form (hil/tests/can/e2e_profile1.py), the payload is decoded
with python3-canmatrix from the DBC, and the decoded sim_time_us must equal
the timestamp (the example is logged with --log-clock sim).

usage: check_doc_example.py DOCS_SIL_MD DBC
"""

import logging
import os
import re
import sys

logging.disable(logging.CRITICAL)
import canmatrix.formats  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "can"))
from e2e_profile1 import p01_crc  # noqa: E402

LINE = re.compile(r"^\s+\((\d+)\.(\d{6})\) vcan0 ([0-9A-F]{3})#([0-9A-F]{16})$")


def main():
    doc, dbc = sys.argv[1:3]
    text = open(doc).read()
    section = text[text.index("{#log}"):]
    m = next((LINE.match(ln) for ln in section.splitlines() if LINE.match(ln)), None)
    if m is None:
        print("check_doc_example: FAIL: no candump example line in the #log section")
        return 1
    sec, usec, ident, data = int(m.group(1)), int(m.group(2)), int(m.group(3), 16), bytes.fromhex(m.group(4))
    frame = {f.arbitration_id.id: f for f in canmatrix.formats.loadp_flat(dbc).frames}.get(ident)
    if frame is None:
        print("check_doc_example: FAIL: ID 0x%03X is not in the DBC" % ident)
        return 1
    crc = p01_crc(int(frame.attributes["CvtE2EDataID"]), data)
    fails = []
    if crc != data[0]:
        fails.append("CRC in the example 0x%02X, Profile 1 gives 0x%02X" % (data[0], crc))
    d = frame.decode(bytearray(data))
    sim_us = int(d["sim_time_us"].raw_value) if "sim_time_us" in d else None
    if sim_us is not None and sim_us != sec * 1000000 + usec:
        fails.append("sim_time_us %d, timestamp %d.%06d" % (sim_us, sec, usec))
    for f in fails:
        print("check_doc_example: FAIL:", f)
    print("check_doc_example: %s 0x%03X#%s: CRC 0x%02X (Profile 1 0x%02X), %s; %d failures" % (
        frame.name, ident, m.group(4), data[0], crc,
        ", ".join("%s %s" % (k, v.named_value if v.named_value is not None and not str(v.named_value).isdigit()
                             else v.raw_value) for k, v in d.items() if not k.startswith("E2E_CRC")), len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
