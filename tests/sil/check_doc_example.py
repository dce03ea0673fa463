#!/usr/bin/python3
"""Checks the candump example of docs/sil.md#log against implementations that
are not the project's: the E2E CRC is recomputed with python3-crcmod
(CRC-8 SAE J1850, chained as AUTOSAR Profile 1 chains Crc_CalculateCRC8),
the payload is decoded with python3-canmatrix from the DBC, and the decoded
sim_time_us must equal the timestamp (the example is logged with
--log-clock sim).

usage: check_doc_example.py DOCS_SIL_MD DBC
"""

import logging
import re
import sys

logging.disable(logging.CRITICAL)
import canmatrix.formats  # noqa: E402
import crcmod  # noqa: E402

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
    data_id = int(frame.attributes["CvtE2EDataID"])
    # crcmod's J1850 with Profile 1's chaining: each call continues from the
    # previous result (crcmod undoes the final XOR, as Crc_CalculateCRC8 does
    # with IsFirstCall = FALSE); the first call starts from 0xFF; the result
    # is XORed with 0xFF.
    j1850 = crcmod.mkCrcFun(0x11D, initCrc=0x00, rev=False, xorOut=0xFF)
    assert j1850(b"123456789") == 0x4B
    crc = j1850(bytes([data_id & 0xFF]), 0xFF)
    crc = j1850(bytes([data_id >> 8]), crc)
    crc = j1850(data[1:8], crc) ^ 0xFF
    fails = []
    if crc != data[0]:
        fails.append("CRC in the example 0x%02X, crcmod gives 0x%02X" % (data[0], crc))
    d = frame.decode(bytearray(data))
    sim_us = int(d["sim_time_us"].raw_value) if "sim_time_us" in d else None
    if sim_us is not None and sim_us != sec * 1000000 + usec:
        fails.append("sim_time_us %d, timestamp %d.%06d" % (sim_us, sec, usec))
    for f in fails:
        print("check_doc_example: FAIL:", f)
    print("check_doc_example: %s 0x%03X#%s: CRC 0x%02X (crcmod 0x%02X), %s; %d failures" % (
        frame.name, ident, m.group(4), data[0], crc,
        ", ".join("%s %s" % (k, v.named_value if v.named_value is not None and not str(v.named_value).isdigit()
                             else v.raw_value) for k, v in d.items() if not k.startswith("E2E_CRC")), len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
