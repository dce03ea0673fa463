#!/usr/bin/python3
"""python3-can + python3-canmatrix peer driving cvtplant-bridge in lock-step
(docs/sil.md#peer-test). Everything on the wire is encoded and decoded by
canmatrix from the DBC; the E2E CRC by the Profile 1 closed form of
tests/can/e2e_profile1.py, not by the project's codec.

1. Reset to scene TipIn, then 50 periods of CtrlCmd (5000 N, 50 N m) + Step 10:
   each group must be Speeds, Ratio, Forces[, Diag], Status with one
   sample_tag, CRC and counter sequence valid, step_seq_ack = the request's,
   sim_time_us = 10000 k, mode LockStep; the axial force settles at 5000 N.
2. Malformed frames (bad CRC, wrong DLC, unknown ID, out-of-range with a valid
   CRC, an exact replay of the last Step, a protocol error frame): none is
   applied (sim time and command unchanged), the next status flags
   fault_rx_rejected and fault_bus_error, and PlantDiag.rejected_frames grows
   by exactly 5; PlantBusDiag and PlantCmdDiag decode and report nothing
   lost.

usage: sil_peer.py IFNAME DBC
"""

import logging
import os
import sys
from decimal import Decimal

logging.disable(logging.CRITICAL)
import can  # noqa: E402
import canmatrix.formats  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "can"))
from e2e_profile1 import p01_crc  # noqa: E402


# Sent together, in this order, just before PlantStatus (docs/can.md#layout).
DIAG = ("PlantDiag", "PlantBusDiag", "PlantCmdDiag")


class Peer:
    def __init__(self, ifname, dbc):
        db = canmatrix.formats.loadp_flat(dbc)
        self.f = {f.name: f for f in db.frames}
        self.byid = {f.arbitration_id.id: f for f in db.frames}
        self.bus = can.Bus(interface="socketcan", channel=ifname, receive_own_messages=False)
        self.tx_counter = {}
        self.rx_counter = {}
        self.fails = []
        self.seq = 0

    def fail(self, what):
        self.fails.append(what)
        print("sil_peer: FAIL:", what)

    def payload(self, name, values, counter=None):
        fr = self.f[name]
        full = {s.name: Decimal(0) for s in fr.signals}
        full.update({k: Decimal(v) for k, v in values.items()})
        raws = {s.name: s.phys2raw(full[s.name]) for s in fr.signals}
        if counter is None:
            counter = self.tx_counter.get(name, 0)
            self.tx_counter[name] = (counter + 1) % 15
        raws["E2E_Counter"] = counter
        raws["E2E_CRC"] = 0
        p = bytearray(fr.encode(raws))
        p[0] = p01_crc(int(fr.attributes["CvtE2EDataID"]), p)
        return p

    def send(self, name, values):
        data = self.payload(name, values)
        msg = can.Message(arbitration_id=self.f[name].arbitration_id.id, data=data, is_extended_id=False)
        self.bus.send(msg)
        return msg

    def request(self, req, steps=0, scene="Keep"):
        values = {"sim_request": self.enum("SimCtrl", "sim_request", req),
                  "scene_id": self.enum("SimCtrl", "scene_id", scene),
                  "step_count": steps, "step_seq": self.seq}
        msg = self.send("SimCtrl", values)
        seq = self.seq
        self.seq = (self.seq + 1) % 16
        return msg, seq

    def enum(self, frame, sig, name):
        s = self.f[frame].signal_by_name(sig)
        for k, v in s.values.items():
            if v == name:
                return int(k)
        raise KeyError(name)

    def sync(self):
        """The bridge may hold another harness's last SimCtrl counter; ours
        could repeat it and be rejected as REPEATED (docs/can.md#e2e-checker).
        A None request answered proves the next counter is accepted."""
        for _ in range(5):
            _, ack = self.request("None")
            if self.read_group(ack, timeout=2.0, must=False) is not None:
                return True
        self.fail("bridge never answered a SimCtrl None")
        return False

    def read_group(self, ack, timeout=10.0, must=True):
        """Frames up to the PlantStatus acknowledging `ack`; checks each."""
        group = {}
        while True:
            msg = self.bus.recv(timeout=timeout)
            if msg is None:
                if must:
                    self.fail("no PlantStatus for step_seq %d" % ack)
                return None
            if msg.is_error_frame or msg.arbitration_id not in self.byid:
                continue
            fr = self.byid[msg.arbitration_id]
            if not fr.name.startswith("Plant"):
                continue
            data = bytearray(msg.data)
            if len(data) != 8 or data[0] != p01_crc(int(fr.attributes["CvtE2EDataID"]), data):
                self.fail("%s: DLC/CRC" % fr.name)
            d = fr.decode(data)
            ctr = d["E2E_Counter"].raw_value
            last = self.rx_counter.get(fr.name)
            if last is not None and ctr != (last + 1) % 15:
                self.fail("%s: counter %d after %d" % (fr.name, ctr, last))
            self.rx_counter[fr.name] = ctr
            group[fr.name] = {k: (v.named_value if k in ("plant_mode", "bus_state") else v.phys_value)
                              for k, v in d.items()}
            group.setdefault("_order", []).append(fr.name)
            if fr.name == "PlantStatus" and int(d["step_seq_ack"].raw_value) == ack:
                return group

    def check_group(self, g, sim_us, mode):
        if g is None:
            return
        st = g["PlantStatus"]
        order = [n for n in g["_order"] if n not in DIAG][-4:]
        if order != ["PlantSpeeds", "PlantRatio", "PlantForces", "PlantStatus"]:
            self.fail("group order %s" % g["_order"])
        diag = [n for n in g["_order"][-4:] if n in DIAG]
        if diag and diag != list(DIAG):
            self.fail("diagnostics %s, expected %s before PlantStatus" % (diag, list(DIAG)))
        tags = {int(g[n]["sample_tag"]) for n in ("PlantSpeeds", "PlantRatio", "PlantForces", "PlantStatus")}
        if len(tags) != 1:
            self.fail("sample tags differ: %s" % tags)
        if int(st["sim_time_us"]) != sim_us:
            self.fail("sim_time_us %s, expected %d" % (st["sim_time_us"], sim_us))
        if str(st["plant_mode"]) != mode:
            self.fail("plant_mode %s, expected %s" % (st["plant_mode"], mode))


def main():
    ifname, dbc = sys.argv[1], sys.argv[2]
    p = Peer(ifname, dbc)
    if not p.sync():
        return 1
    p.rx_counter.clear()
    _, ack = p.request("Reset", scene="TipIn")
    p.check_group(p.read_group(ack), 0, "Ready")
    last_step = None
    g = None
    for k in range(50):
        p.send("CtrlCmd", {"clamp_force_cmd_N": 5000, "driver_torque_req_Nm": 50})
        last_step, ack = p.request("Step", steps=10)
        g = p.read_group(ack)
        p.check_group(g, 10000 * (k + 1), "LockStep")
    if g is not None:
        fax = float(g["PlantForces"]["driver_axial_force_N"])
        w1 = float(g["PlantSpeeds"]["omega_driver_rad_s"])
        if abs(fax - 5000) > 50:
            p.fail("axial force %.0f N after 0.5 s of a 5000 N command" % fax)
        if not 100 < w1 < 300:
            p.fail("driver speed %.1f rad/s" % w1)
        if g["PlantStatus"]["fault_rx_rejected"] or g["PlantStatus"]["fault_cmd_timeout"]:
            p.fail("unexpected fault flags: %s" % g["PlantStatus"])
    diag0 = int(g["PlantDiag"]["rejected_frames"]) if g and "PlantDiag" in g else None
    if diag0 is None:
        p.fail("no PlantDiag at 500 ms")
        diag0 = 0
    # The bridge's counters run over its lifetime: compare differences.
    cmd0 = g.get("PlantCmdDiag", {}) if g else {}

    cmd_id = p.f["CtrlCmd"].arbitration_id.id
    nxt = p.tx_counter["CtrlCmd"]
    bad_crc = p.payload("CtrlCmd", {"clamp_force_cmd_N": 59000}, counter=nxt)
    bad_crc[0] ^= 0x5A
    oor = p.payload("CtrlCmd", {"clamp_force_cmd_N": 0}, counter=nxt)
    oor[2:4] = (60001).to_bytes(2, "little")  # 60001 N > 60000
    oor[0] = p01_crc(int(p.f["CtrlCmd"].attributes["CvtE2EDataID"]), oor)
    for m in (can.Message(arbitration_id=cmd_id, data=bad_crc, is_extended_id=False),
              can.Message(arbitration_id=cmd_id, data=bytes(7), dlc=7, is_extended_id=False),
              can.Message(arbitration_id=0x555, data=bytes(8), is_extended_id=False),
              can.Message(arbitration_id=cmd_id, data=oor, is_extended_id=False),
              last_step,
              can.Message(arbitration_id=0x008, is_error_frame=True, data=bytes(8), is_extended_id=False)):
        p.bus.send(m)
    _, ack = p.request("None")
    g = p.read_group(ack)
    p.check_group(g, 500000, "LockStep")  # the replayed Step advanced nothing
    if g is not None:
        st = g["PlantStatus"]
        if not st["fault_rx_rejected"]:
            p.fail("fault_rx_rejected not set after malformed frames")
        if not st["fault_bus_error"]:
            p.fail("fault_bus_error not set after an error frame")
    # Valid commands again, the first with the counter the rejected frames
    # used; ten periods reach the 600 ms boundary, which brings PlantDiag.
    for k in range(10):
        p.send("CtrlCmd", {"clamp_force_cmd_N": 6000, "driver_torque_req_Nm": 50})
        _, ack = p.request("Step", steps=10)
        g = p.read_group(ack)
        p.check_group(g, 510000 + 10000 * k, "LockStep")
    if g is not None:
        if "PlantDiag" not in g:
            p.fail("no PlantDiag at 600 ms")
        elif int(g["PlantDiag"]["rejected_frames"]) - diag0 != 5:
            p.fail("rejected_frames grew by %d, expected 5" % (int(g["PlantDiag"]["rejected_frames"]) - diag0))
        fax = float(g["PlantForces"]["driver_axial_force_N"])
        if not 5500 < fax < 6100:
            p.fail("axial force %.0f N: the valid 6000 N command was not applied" % fax)
        # The other diagnostics, decoded by canmatrix: no command lost,
        # re-synchronised or superseded (one per period); the bus error was
        # a protocol error frame, which leaves the controller error-active.
        bus, cmd = g.get("PlantBusDiag"), g.get("PlantCmdDiag")
        if bus is None or cmd is None:
            p.fail("PlantBusDiag/PlantCmdDiag missing at 600 ms")
        else:
            if str(bus["bus_state"]) != "ErrorActive" or int(bus["tx_dropped"]) != 0:
                p.fail("PlantBusDiag %s" % bus)
            grew = {k: (int(cmd[k]) - int(cmd0.get(k, 0))) % 65536
                    for k in ("cmd_superseded", "cmd_lost_frames", "cmd_resyncs")}
            if any(grew.values()):
                p.fail("PlantCmdDiag grew by %s" % grew)
    p.bus.shutdown()
    print("sil_peer: 61 lock-step groups checked, 6 bad frames sent, %d failures" % len(p.fails))
    return 1 if p.fails else 0


if __name__ == "__main__":
    sys.exit(main())
