#!/usr/bin/python3
"""Check the candump -L log of hil/tests/can/vcan_peers.sh: every line parses,
the CtrlCmd stream decodes with canmatrix to the values the controller sent
(E2E CRC and counter checked independently), the replies and every bad frame
of vcan_peer.py were on the bus, error frames were logged as error frames.

usage: check_candump.py LOG DBC N
"""

import logging
import re
import sys
from decimal import Decimal

logging.disable(logging.CRITICAL)
import canmatrix.formats  # noqa: E402
from e2e_profile1 import p01_crc  # noqa: E402

LINE = re.compile(r"^\((\d+\.\d{6})\) (\w+) ([0-9A-F]{3}|[0-9A-F]{8})#(R\d?|[0-9A-F]*)$")



def main():
    log, dbc, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    db = canmatrix.formats.loadp_flat(dbc)
    cmd = next(f for f in db.frames if f.name == "CtrlCmd")
    data_id = int(cmd.attributes["CvtE2EDataID"])
    fails = []
    counts = {}
    cmds = []
    err = []
    remote = ext = 0
    lines = open(log).read().splitlines()
    for ln in lines:
        m = LINE.match(ln)
        if not m:
            fails.append("unparsable candump line: %r" % ln)
            continue
        ident, data = m.group(3), m.group(4)
        if len(ident) == 8:
            v = int(ident, 16)
            if v & 0x20000000:
                err.append(v & 0x1FFFFFFF)
                continue
            ext += 1
            continue
        cid = int(ident, 16)
        if data.startswith("R"):
            remote += 1
            continue
        counts[cid] = counts.get(cid, 0) + 1
        if cid == cmd.arbitration_id.id:
            cmds.append(bytearray.fromhex(data))
    if len(cmds) != n:
        fails.append("CtrlCmd frames in log: %d, expected %d" % (len(cmds), n))
    for i, p in enumerate(cmds):
        d = cmd.decode(p)
        if p[0] != p01_crc(data_id, p):
            fails.append("CtrlCmd %d: CRC" % i)
        if d["E2E_Counter"].raw_value != i % 15:
            fails.append("CtrlCmd %d: counter %d" % (i, d["E2E_Counter"].raw_value))
        if Decimal(d["clamp_force_cmd_N"].phys_value) != 1000 + 7 * i:
            fails.append("CtrlCmd %d: clamp %s" % (i, d["clamp_force_cmd_N"].phys_value))
    if counts.get(0x200, 0) < n + 5:
        fails.append("PlantSpeeds frames: %d, expected >= %d" % (counts.get(0x200, 0), n + 5))
    if counts.get(0x555, 0) != 1:
        fails.append("unknown-ID frame 0x555 missing")
    if 0x040 not in err or 0x100 not in err:
        fails.append("error frames (bus-off 0x040, restarted 0x100) missing: %s" % err)
    if remote != 1 or ext != 1:
        fails.append("remote %d / extended %d frames, expected 1 / 1" % (remote, ext))
    for f in fails[:20]:
        print("FAIL:", f)
    print("candump log: %d lines, %d CtrlCmd, %d PlantSpeeds, error frames %s, %d failures" %
          (len(lines), len(cmds), counts.get(0x200, 0), ["0x%03X" % e for e in err], len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
