#!/usr/bin/python3
"""python3-can + python3-canmatrix peer driving cvtplant-bridge in lock-step
(docs/sil.md#peer-test). Everything on the wire is encoded and decoded by
canmatrix from the DBC; the E2E CRC by the Profile 1 closed form of
hil/tests/can/e2e_profile1.py, not by the project's codec.

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
3. The faults a real bus has (docs/sil.md#fault-scenarios), each with the
   behaviour the docs define, seen only through canmatrix-decoded frames:
   a. a Step sent again with the same step_seq (its reply was lost) is
      answered with the same group (sample_tag, sim_time_us) and not executed;
   b. a frozen controller (its last CtrlCmd repeated byte for byte for 300 ms):
      fault_cmd_timeout first in the status 60 ms after the last fresh frame
      (deadline 50 ms, then the period that saw it), the clamp ramps up
      (never a step, never back down: the repeated frame is not used again),
      every repeat rejected, one timeout; back: one Sync frame, then used;
   c. two CtrlCmd lost: the counter jump and the Sync frame after it are not
      used (their 30 kN never reach the clamp), the third frame is;
      PlantCmdDiag counts 2 lost and 1 re-synchronisation, no timeout;
   d. a controller restarting with counter 0: the same, one rejected frame;
   e. a flood of 20 CtrlCmd in one period: the last is used, 19 superseded.

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
# The published parameters follow them when due (docs/sil.md#published-parameters);
# the two maps only from a variable-ratio plant.
PARAMS = ("PlantParams", "PlantRatioMap", "PlantThrustMap")


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

    def request(self, req, steps=0, scene="Keep", seq=None):
        """A SimCtrl request with the next step_seq, or with `seq` (a resend)."""
        resend = seq is not None
        seq = self.seq if seq is None else seq
        values = {"sim_request": self.enum("SimCtrl", "sim_request", req),
                  "scene_id": self.enum("SimCtrl", "scene_id", scene),
                  "step_count": steps, "step_seq": seq}
        msg = self.send("SimCtrl", values)
        if not resend:
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
        order = [n for n in g["_order"] if n not in DIAG + PARAMS][-4:]
        if order != ["PlantSpeeds", "PlantRatio", "PlantForces", "PlantStatus"]:
            self.fail("group order %s" % g["_order"])
        # Between PlantForces and PlantStatus: [the diagnostics] [PlantParams].
        tail = g["_order"][g["_order"].index("PlantForces") + 1:-1]
        if tail not in ([], list(DIAG), ["PlantParams"], list(DIAG) + ["PlantParams"]):
            self.fail("%s before PlantStatus, expected [%s] [PlantParams]" % (tail, ", ".join(DIAG)))
        tags = {int(g[n]["sample_tag"]) for n in ("PlantSpeeds", "PlantRatio", "PlantForces", "PlantStatus")}
        if len(tags) != 1:
            self.fail("sample tags differ: %s" % tags)
        if int(st["sim_time_us"]) != sim_us:
            self.fail("sim_time_us %s, expected %d" % (st["sim_time_us"], sim_us))
        if str(st["plant_mode"]) != mode:
            self.fail("plant_mode %s, expected %s" % (st["plant_mode"], mode))


def diff16(now, then):
    return (int(now) - int(then)) % 65536


def faults(p, t_us):
    """Section 3 of the docstring. t_us: the bridge's simulated time now."""
    cmd_name = "CtrlCmd"
    cmd_id = p.f[cmd_name].arbitration_id.id
    groups = 0

    def period(clamp_N, msg=None, counter=None):
        """One lock-step period: a CtrlCmd (or `msg` as it is), Step 10."""
        nonlocal t_us, groups
        if msg is None:
            data = p.payload(cmd_name, {"clamp_force_cmd_N": clamp_N, "driver_torque_req_Nm": 50}, counter=counter)
            msg = can.Message(arbitration_id=cmd_id, data=data, is_extended_id=False)
        p.bus.send(msg)
        _, ack = p.request("Step", steps=10)
        g = p.read_group(ack)
        t_us += 10000
        groups += 1
        p.check_group(g, t_us, "LockStep")
        return g, msg

    def query():
        """SimCtrl None: the current group with the three diagnostics."""
        nonlocal groups
        _, ack = p.request("None")
        g = p.read_group(ack)
        groups += 1
        p.check_group(g, t_us, "LockStep")
        if g is None or any(n not in g for n in DIAG):
            p.fail("SimCtrl None at %d us: no diagnostics" % t_us)
            return None
        return g

    def force(g):
        return float(g["PlantForces"]["driver_axial_force_N"]) if g else float("nan")

    def flag(g):
        return bool(g and g["PlantStatus"]["fault_cmd_timeout"])

    def settle():
        for _ in range(12):  # 6000 N, settled (actuator lag 20 ms)
            period(6000)

    settle()

    # a. A lost reply: the same step_seq again.
    _, ack = p.request("Step", steps=10)
    g1 = p.read_group(ack)
    t_us += 10000
    p.check_group(g1, t_us, "LockStep")
    p.request("Step", steps=10, seq=ack)
    g2 = p.read_group(ack)
    p.check_group(g2, t_us, "LockStep")  # not executed: time unchanged
    groups += 2
    if g1 and g2 and g1["PlantStatus"]["sample_tag"] != g2["PlantStatus"]["sample_tag"]:
        p.fail("resent Step: sample_tag %s, the original's %s" % (g2["PlantStatus"]["sample_tag"],
                                                                  g1["PlantStatus"]["sample_tag"]))
    g, _ = period(6000)  # the next step_seq is executed

    # b. A frozen controller.
    base = query()
    _, last = period(6000)
    t_last = t_us - 10000  # the bridge received the last fresh frame at this time
    f_before = force(base)
    first_flag, max_rise, max_drop, prev, f_100 = None, 0.0, 0.0, force(base), None
    for k in range(30):
        g, _ = period(0, msg=last)
        f = force(g)
        if flag(g) and first_flag is None:
            first_flag = t_us
        if first_flag is not None:
            max_rise, max_drop = max(max_rise, f - prev), max(max_drop, prev - f)
            if t_us == first_flag + 100000:
                f_100 = f
        prev = f
    if first_flag != t_last + 60000:
        p.fail("frozen controller: fault_cmd_timeout first at %s us, expected %d" % (first_flag, t_last + 60000))
    # The DBC ramp: 50 kN/s toward 20 kN, 500 N per 10 ms period.
    if max_rise > 600 or max_drop > 1.0:
        p.fail("frozen controller: the clamp moved by +%.0f/-%.0f N per period while timed out" % (max_rise, max_drop))
    if f_100 is None or f_100 < f_before + 2500:
        p.fail("frozen controller: clamp %s N 100 ms after the timeout, %.0f N before" % (f_100, f_before))
    g_sync, _ = period(6000)
    g_used, _ = period(6000)
    if not flag(g_sync) or flag(g_used):
        p.fail("frozen controller back: fault_cmd_timeout %s after the first fresh frame (Sync), %s after the "
               "second (used); expected set, then clear" % (flag(g_sync), flag(g_used)))
    after = query()
    if base and after:
        grew = (diff16(after["PlantDiag"]["rejected_frames"], base["PlantDiag"]["rejected_frames"]),
                diff16(after["PlantDiag"]["cmd_timeouts"], base["PlantDiag"]["cmd_timeouts"]),
                diff16(after["PlantCmdDiag"]["cmd_resyncs"], base["PlantCmdDiag"]["cmd_resyncs"]))
        if grew != (30, 1, 1):
            p.fail("frozen controller: rejected_frames, cmd_timeouts, cmd_resyncs grew by %s, expected (30, 1, 1)"
                   % (grew,))
    print("sil_peer: frozen controller: timeout flag at +%s ms, clamp %.0f -> %s N in 100 ms, largest rise %.0f N "
          "per period, largest drop %.1f N" % ((first_flag - t_last) // 1000 if first_flag else None, f_before,
                                                "%.0f" % f_100 if f_100 else None, max_rise, max_drop))

    # c, d. A counter jump (two frames lost; a restart from 0): the jump and
    # the Sync frame after it are not used, the next frame is.
    def jump(what, counter, lost):
        base = query()
        f0 = force(base)
        g_jump, _ = period(30000, counter=counter)
        p.tx_counter[cmd_name] = (counter + 1) % 15
        g_sync, _ = period(30000)
        g_used, _ = period(30000)
        if not (force(g_jump) < f0 + 100 and force(g_sync) < f0 + 100):
            p.fail("%s: a frame was used before re-synchronisation: clamp %.0f, %.0f N (%.0f N before)"
                   % (what, force(g_jump), force(g_sync), f0))
        if not force(g_used) > f0 + 2000:
            p.fail("%s: the frame after re-synchronisation was not used: clamp %.0f N" % (what, force(g_used)))
        if any(flag(g) for g in (g_jump, g_sync, g_used)):
            p.fail("%s: command timeout" % what)
        after = query()
        if base and after:
            grew = (diff16(after["PlantCmdDiag"]["cmd_lost_frames"], base["PlantCmdDiag"]["cmd_lost_frames"]),
                    diff16(after["PlantCmdDiag"]["cmd_resyncs"], base["PlantCmdDiag"]["cmd_resyncs"]),
                    diff16(after["PlantDiag"]["rejected_frames"], base["PlantDiag"]["rejected_frames"]),
                    diff16(after["PlantDiag"]["cmd_timeouts"], base["PlantDiag"]["cmd_timeouts"]))
            if grew != (lost, 1, 1, 0):
                p.fail("%s: cmd_lost_frames, cmd_resyncs, rejected_frames, cmd_timeouts grew by %s, expected %s"
                       % (what, grew, (lost, 1, 1, 0)))
        print("sil_peer: %s: clamp %.0f, %.0f, %.0f N after the jump, Sync and next frame (%.0f N before)"
              % (what, force(g_jump), force(g_sync), force(g_used), f0))

    settle()
    jump("two lost commands", (p.tx_counter[cmd_name] + 2) % 15, 2)
    # A restart: counter 0 after a counter far enough from it to be a jump
    # (more than CvtE2EMaxDeltaCounter 2 behind 0).
    settle()
    while p.tx_counter[cmd_name] not in range(5, 12):
        period(6000)
    last = (p.tx_counter[cmd_name] + 14) % 15
    jump("controller restart", 0, (0 - last) % 15 - 1)

    # e. A flood: 20 commands in one period, counters advancing; the last wins.
    settle()
    base = query()
    for _ in range(19):
        p.send(cmd_name, {"clamp_force_cmd_N": 30000, "driver_torque_req_Nm": 50})
    g, _ = period(9000)
    after = query()
    # 9000 N for one period through the 20 ms lag: about 7200 N; 30 kN would
    # have given about 15 kN.
    if not 6200 < force(g) < 9000:
        p.fail("flood: clamp %.0f N, expected between 6200 and 9000 N (the last command, 9000 N)" % force(g))
    if base and after:
        sup = diff16(after["PlantCmdDiag"]["cmd_superseded"], base["PlantCmdDiag"]["cmd_superseded"])
        rej = diff16(after["PlantDiag"]["rejected_frames"], base["PlantDiag"]["rejected_frames"])
        if (sup, rej) != (19, 0):
            p.fail("flood: cmd_superseded grew by %d, rejected_frames by %d, expected 19 and 0" % (sup, rej))
        print("sil_peer: flood: clamp %.0f N after 19 x 30 kN and one 9000 N command in a period; "
              "cmd_superseded +%d, rejected_frames +%d" % (force(g), sup, rej))
    return groups


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
    n = 61 + faults(p, 600000)
    p.bus.shutdown()
    print("sil_peer: %d lock-step groups checked, 6 bad frames sent, %d failures" % (n, len(p.fails)))
    return 1 if p.fails else 0


if __name__ == "__main__":
    sys.exit(main())
