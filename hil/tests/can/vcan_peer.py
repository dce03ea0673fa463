#!/usr/bin/python3
"""python3-can peer for hil/tests/can/vcan_peers.sh (docs/can.md#vcan-tests).

Plays the plant against vcan_transport_test's controller role: receives
CtrlCmd, decodes it with python3-canmatrix against the DBC and checks the E2E
header with an independent CRC, answers PlantSpeeds encoded by canmatrix.
After the controller's SimCtrl Pause it sends, in order: a bus-off error
frame, a controller-restarted error frame, a wrong-DLC frame, an unknown ID,
a bad CRC, a replay, an out-of-range value with a valid CRC, a remote frame,
an extended-ID frame and finally one valid frame.

usage: vcan_peer.py IFNAME DBC READY_FILE
"""

import logging
import sys
from decimal import Decimal

logging.disable(logging.CRITICAL)
import can  # noqa: E402
import canmatrix  # noqa: E402
import canmatrix.formats  # noqa: E402
from e2e_profile1 import p01_crc  # noqa: E402



def main():
    ifname, dbc, ready = sys.argv[1], sys.argv[2], sys.argv[3]
    db = canmatrix.formats.loadp_flat(dbc)
    byname = {f.name: f for f in db.frames}
    cmd_f, speeds_f, sim_f = byname["CtrlCmd"], byname["PlantSpeeds"], byname["SimCtrl"]
    bus = can.Bus(interface="socketcan", channel=ifname, receive_own_messages=False)
    open(ready, "w").write("ready\n")
    failures = 0
    last_cmd_counter = None
    counter = 0
    n = 0
    last_reply = None

    def speeds_payload(values, ctr, crc_xor=0):
        full = {s.name: Decimal(0) for s in speeds_f.signals}
        full.update(values)
        raws = {s.name: s.phys2raw(full[s.name]) for s in speeds_f.signals}
        raws["E2E_Counter"] = ctr
        raws["E2E_CRC"] = 0
        p = bytearray(speeds_f.encode(raws))
        p[0] = p01_crc(int(speeds_f.attributes["CvtE2EDataID"]), p) ^ crc_xor
        return p

    while True:
        msg = bus.recv(timeout=20.0)
        if msg is None:
            print("vcan_peer: FAIL: timed out waiting for the controller")
            return 1
        if msg.is_error_frame:
            continue
        if msg.arbitration_id == sim_f.arbitration_id.id:
            d = sim_f.decode(bytearray(msg.data))
            if d["sim_request"].named_value == "Pause":
                break
            continue
        if msg.arbitration_id != cmd_f.arbitration_id.id:
            continue
        data = bytearray(msg.data)
        d = cmd_f.decode(data)
        if data[0] != p01_crc(int(cmd_f.attributes["CvtE2EDataID"]), data):
            print("vcan_peer: FAIL: CtrlCmd %d CRC" % n)
            failures += 1
        ctr = d["E2E_Counter"].raw_value
        if last_cmd_counter is not None and ctr != (last_cmd_counter + 1) % 15:
            print("vcan_peer: FAIL: CtrlCmd counter %d after %d" % (ctr, last_cmd_counter))
            failures += 1
        last_cmd_counter = ctr
        clamp = Decimal(d["clamp_force_cmd_N"].phys_value)
        torque = Decimal(d["driver_torque_req_Nm"].phys_value)
        if clamp != 1000 + 7 * n:
            print("vcan_peer: FAIL: CtrlCmd %d clamp %s" % (n, clamp))
            failures += 1
        omega = (clamp - 1000) / 10
        values = {"sample_tag": n & 0xF, "omega_driver_rad_s": omega, "omega_driven_rad_s": -omega,
                  "torque_transmitted_Nm": torque}
        payload = speeds_payload(values, counter)
        counter = (counter + 1) % 15
        last_reply = can.Message(arbitration_id=speeds_f.arbitration_id.id, data=payload, is_extended_id=False)
        bus.send(last_reply)
        n += 1

    nxt = counter  # next counter the controller would accept
    bad = [
        can.Message(arbitration_id=0x040, is_error_frame=True, data=bytes(8), is_extended_id=False),
        can.Message(arbitration_id=0x100, is_error_frame=True, data=bytes(8), is_extended_id=False),
        can.Message(arbitration_id=speeds_f.arbitration_id.id, data=bytes(7), dlc=7, is_extended_id=False),
        can.Message(arbitration_id=0x555, data=bytes(8), is_extended_id=False),
        can.Message(arbitration_id=speeds_f.arbitration_id.id, is_extended_id=False,
                    data=speeds_payload({"omega_driver_rad_s": Decimal(1)}, nxt, crc_xor=0x5A)),
        last_reply,
    ]
    oor = bytearray(8)
    oor[2:4] = (32767).to_bytes(2, "little")  # 655.34 rad/s > 650
    oor[1] = nxt
    oor[0] = p01_crc(int(speeds_f.attributes["CvtE2EDataID"]), oor)
    bad.append(can.Message(arbitration_id=speeds_f.arbitration_id.id, data=oor, is_extended_id=False))
    bad.append(can.Message(arbitration_id=speeds_f.arbitration_id.id, is_remote_frame=True, dlc=8,
                           is_extended_id=False))
    bad.append(can.Message(arbitration_id=speeds_f.arbitration_id.id, data=bytes(8), is_extended_id=True))
    bad.append(can.Message(arbitration_id=speeds_f.arbitration_id.id, is_extended_id=False,
                           data=speeds_payload({"omega_driver_rad_s": Decimal(2)}, nxt)))
    for m in bad:
        bus.send(m)
    bus.shutdown()
    print("vcan_peer: %d CtrlCmd frames answered, %d bad frames sent, %d failures" % (n, len(bad) - 1, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
