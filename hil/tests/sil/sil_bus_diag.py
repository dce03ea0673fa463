#!/usr/bin/python3
"""Asks cvtplant-bridge for its diagnostics (SimCtrl None) with python3-can and
canmatrix, and prints PlantBusDiag, PlantDiag and the PlantStatus fault flags
as one JSON line (docs/sil.md#robustness). sil_vcan.sh uses it around a
receive-queue overflow it provokes on purpose.

usage: sil_bus_diag.py IFNAME DBC
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sil_peer import Peer  # noqa: E402


def main():
    p = Peer(sys.argv[1], sys.argv[2])
    for _ in range(5):
        _, ack = p.request("None")
        g = p.read_group(ack, timeout=2.0, must=False)
        if g is not None:
            break
    p.bus.shutdown()
    if g is None or "PlantBusDiag" not in g:
        print("sil_bus_diag: FAIL: no answer with PlantBusDiag", file=sys.stderr)
        return 1
    out = {k: (str(v) if k == "bus_state" else int(v)) for k, v in g["PlantBusDiag"].items()
           if not k.startswith("E2E")}
    out["rejected_frames"] = int(g["PlantDiag"]["rejected_frames"])
    out.update({k: bool(v) for k, v in g["PlantStatus"].items() if k.startswith("fault_")})
    print(json.dumps(out))
    return 1 if p.fails else 0


if __name__ == "__main__":
    sys.exit(main())
