#!/usr/bin/python3
"""Checks the bridge's candump-format log against candump's own capture
(docs/sil.md#log).

- every line of both files parses as candump -L: "(sec.usec) IFACE ID#HEX";
- the plant frames candump captured (the DBC's Plant messages) are, in order
  and byte for byte, exactly the frames in the bridge's log;
- each of them has a valid Profile 1 CRC and a counter sequence 0..14 without
  gaps per message; the first 400 and every 20th decode with canmatrix, and
  so does at least one frame of every Plant message of the DBC, with every
  signal the DBC gives it;
- the harness's SimCtrl and the controller's CtrlCmd frames are on the bus.

usage: check_sil_log.py CANDUMP_LOG BRIDGE_LOG DBC
"""

import os
import re
import sys

import canmatrix.formats

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "can"))
from e2e_profile1 import p01_crc  # noqa: E402

LINE = re.compile(r"^\((\d+)\.(\d{6})\) (\S+) ([0-9A-F]{3}|[0-9A-F]{8})#(R\d?|[0-9A-F]*)$")


def parse(path, fails):
    out = []
    for ln in open(path).read().splitlines():
        m = LINE.match(ln)
        if not m:
            fails.append("%s: unparsable line %r" % (os.path.basename(path), ln))
            continue
        out.append((m.group(4), m.group(5)))
    return out


def main():
    dump_path, bridge_path, dbc = sys.argv[1:4]
    db = canmatrix.formats.loadp_flat(dbc)
    byid = {f.arbitration_id.id: f for f in db.frames}
    fails = []
    dump = parse(dump_path, fails)
    bridge = parse(bridge_path, fails)
    plant_ids = {f.arbitration_id.id for f in db.frames if f.name.startswith("Plant")}
    plant = [(i, d) for i, d in dump if len(i) == 3 and int(i, 16) in plant_ids]
    if not bridge:
        fails.append("bridge log is empty")
    if plant != bridge:
        n = min(len(plant), len(bridge))
        first = next((k for k in range(n) if plant[k] != bridge[k]), n)
        fails.append("candump captured %d plant frames, bridge logged %d; first difference at #%d"
                     % (len(plant), len(bridge), first))
    last = {}
    decoded = set()
    # canmatrix decoding is slow under the VM's TCG: every frame gets the CRC
    # and counter check, a sample of them the canmatrix decode.
    for k, (ident, data) in enumerate(bridge):
        fr = byid.get(int(ident, 16))
        p = bytearray.fromhex(data)
        if fr is None or len(p) != 8:
            fails.append("bridge sent %s#%s" % (ident, data))
            continue
        if p[0] != p01_crc(int(fr.attributes["CvtE2EDataID"]), p):
            fails.append("%s: CRC" % fr.name)
        ctr = p[1] & 0x0F
        if fr.name in last and ctr != (last[fr.name] + 1) % 15:
            fails.append("%s: counter %d after %d" % (fr.name, ctr, last[fr.name]))
        last[fr.name] = ctr
        if k < 400 or k % 20 == 0 or fr.name not in decoded:
            d = fr.decode(p)
            missing = {s.name for s in fr.signals} - set(d)
            if missing:
                fails.append("%s: canmatrix decoded no %s" % (fr.name, sorted(missing)))
            decoded.add(fr.name)
    for fr in db.frames:
        if fr.arbitration_id.id in plant_ids and fr.name not in decoded:
            fails.append("no %s frame in the bridge log" % fr.name)
    ids = [int(i, 16) for i, _ in dump if len(i) == 3]
    n_sim, n_cmd = ids.count(0x080), ids.count(0x100)
    if n_sim == 0 or n_cmd == 0:
        fails.append("SimCtrl %d / CtrlCmd %d frames on the bus" % (n_sim, n_cmd))
    for f in fails[:20]:
        print("check_sil_log: FAIL:", f)
    print("check_sil_log: %d candump lines, %d plant frames match the bridge log, %d SimCtrl, %d CtrlCmd, %d failures"
          % (len(dump), len(bridge), n_sim, n_cmd, len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
