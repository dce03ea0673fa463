#!/usr/bin/python3
"""Codec vs python3-canmatrix agreement test (docs/can.md#agreement).

canmatrix (Debian's python3-canmatrix) is an independent DBC implementation.
This test checks, against hil/cvtplant.dbc:

1. codec -> canmatrix: frames packed by the C++ codec (can_agree_tool pack)
   decode with canmatrix to the physical values the codec was given, to
   within half an LSB, and the raw code is the exactly-rounded nearest one
   (not a truncated one) except within float precision of a tie. The E2E CRC
   in byte 0 matches an independent Python implementation of the Profile 1
   (DataIDMode BOTH) closed form, the counter is 0..14.
2. canmatrix -> codec: frames encoded by canmatrix from on-grid physical
   values (canmatrix truncates, so off-grid values would test canmatrix, not
   us), with the E2E header computed here, decode with the codec
   (can_agree_tool decode) to the float nearest the exact value, and the
   codec's E2E check accepts the Python CRC.
3. Raw codes outside [min|max], which canmatrix decodes without complaint,
   are rejected by the codec with OUT_OF_RANGE.

usage: agree_canmatrix.py <can_agree_tool> <cvtplant.dbc>
"""

import logging
import math
import random
import struct
import subprocess
import sys
from decimal import Decimal, ROUND_CEILING, ROUND_FLOOR

logging.disable(logging.CRITICAL)
import canmatrix  # noqa: E402
import canmatrix.formats  # noqa: E402
from e2e_profile1 import p01_crc  # noqa: E402

E2E_SIGNALS = ("E2E_CRC", "E2E_Counter")



def f32(text):
    """The float32 a printed value denotes (the tool prints round-trip exact)."""
    return struct.unpack("<f", struct.pack("<f", float(text)))[0]


def ulp32(x):
    x = abs(x)
    if x == 0:
        return 2.0 ** -149
    return 2.0 ** (math.floor(math.log2(x)) - 23)


def raw_limits(sig):
    lo = (Decimal(sig.min) - Decimal(sig.offset)) / Decimal(sig.factor)
    hi = (Decimal(sig.max) - Decimal(sig.offset)) / Decimal(sig.factor)
    return int(lo.to_integral_value(ROUND_CEILING)), int(hi.to_integral_value(ROUND_FLOOR))


def bit_limits(sig):
    if sig.is_signed:
        return -(1 << (sig.size - 1)), (1 << (sig.size - 1)) - 1
    return 0, (1 << sig.size) - 1


def is_float_signal(sig):
    """Mirror of dbc2cpp's rule: scaled signals are float, unless 1 bit,
    enumerated, or marked CvtPhysType integer."""
    return not (sig.size == 1 or sig.values or sig.attributes.get("CvtPhysType") == "integer")


def round_half_away(d):
    return int(d.to_integral_value("ROUND_HALF_UP"))  # HALF_UP in decimal = away from zero


def parse_kv(tokens):
    out = {}
    for t in tokens:
        k, v = t.split("=", 1)
        out[k] = v
    return out


class Checker:
    def __init__(self):
        self.failures = 0
        self.checks = 0

    def ok(self, cond, msg):
        self.checks += 1
        if not cond:
            self.failures += 1
            if self.failures <= 30:
                print("FAIL:", msg)


def main():
    tool, dbc_path = sys.argv[1], sys.argv[2]
    db = canmatrix.formats.loadp_flat(dbc_path)
    frames = {int(f.arbitration_id.id): f for f in db.frames}
    chk = Checker()

    # 1. codec -> canmatrix --------------------------------------------------
    out = subprocess.run([tool, "pack", "400"], check=True, capture_output=True, text=True).stdout
    n_frames = 0
    n_ties = 0
    n_trunc_differs = 0
    for line in out.splitlines():
        tok = line.split()
        if not tok or tok[0] != "FRAME":
            continue
        n_frames += 1
        can_id, dlc, payload, name = int(tok[1], 16), int(tok[2]), bytes.fromhex(tok[3]), tok[4]
        inputs = parse_kv(tok[5:])
        fr = frames.get(can_id)
        chk.ok(fr is not None and fr.name == name, "%s: ID 0x%X not in DBC" % (name, can_id))
        if fr is None:
            continue
        chk.ok(dlc == fr.size == len(payload), "%s: DLC %d vs DBC %d" % (name, dlc, fr.size))
        dec = fr.decode(bytearray(payload))
        data_id = int(fr.attributes["CvtE2EDataID"])
        chk.ok(dec["E2E_CRC"].raw_value == p01_crc(data_id, payload),
               "%s: CRC 0x%02X, independent 0x%02X" % (name, dec["E2E_CRC"].raw_value, p01_crc(data_id, payload)))
        chk.ok(0 <= dec["E2E_Counter"].raw_value <= 14, "%s: counter out of 0..14" % name)
        expected_names = {s.name for s in fr.signals if s.name not in E2E_SIGNALS}
        chk.ok(set(inputs) == expected_names, "%s: signal set %s vs DBC %s" % (name, sorted(inputs), sorted(expected_names)))
        for s in fr.signals:
            if s.name in E2E_SIGNALS or s.name not in inputs:
                continue
            raw = dec[s.name].raw_value
            phys = Decimal(dec[s.name].phys_value) if not isinstance(dec[s.name].phys_value, str) else None
            given = inputs[s.name]
            factor, offset = Decimal(s.factor), Decimal(s.offset)
            if is_float_signal(s):
                x = Decimal(f32(given))  # exact value of the float handed to the codec
                q = (x - offset) / factor
                lsb = float(factor)
                # Bound: half an LSB from rounding, plus the float rounding of
                # the scaled quotient q (half an ulp of q, in LSB).
                slack = 0.5 * ulp32(float(q))
                err = abs(float(raw * factor + offset - x))
                chk.ok(err <= lsb * (0.5 + slack) + 1e-12,
                       "%s.%s: input %s decoded %s, error %.3g LSB" % (name, s.name, given, phys, err / lsb))
                frac = abs(q - q.to_integral_value(ROUND_FLOOR)) if q >= 0 else abs(q - q.to_integral_value(ROUND_CEILING))
                near_tie = abs(frac - Decimal("0.5")) <= Decimal(slack)
                n_ties += near_tie
                lo, hi = raw_limits(s)
                nearest = min(max(round_half_away(q), lo), hi)
                if not near_tie:
                    chk.ok(raw == nearest, "%s.%s: input %s gave raw %d, nearest is %d" % (name, s.name, given, raw, nearest))
                if int(q) != nearest:
                    n_trunc_differs += 1
            else:
                chk.ok(raw == int(given), "%s.%s: raw %d, codec was given %s" % (name, s.name, raw, given))

    print("codec -> canmatrix: %d frames; %d near-tie values; %d values where truncation would differ" %
          (n_frames, n_ties, n_trunc_differs))
    chk.ok(n_frames >= 8 * 400, "too few frames from the tool")
    chk.ok(n_trunc_differs > 100, "the sample does not exercise rounding")

    # 2. canmatrix -> codec ---------------------------------------------------
    rng = random.Random(20240607)
    sent = []
    for fr in sorted(db.frames, key=lambda f: f.arbitration_id.id):
        data_id = int(fr.attributes["CvtE2EDataID"])
        for i in range(300):
            values = {}
            expect = {}
            for s in fr.signals:
                if s.name in E2E_SIGNALS:
                    continue
                lo, hi = raw_limits(s)
                if s.values:
                    raw = rng.choice(sorted(int(k) for k in s.values))
                elif i == 0:
                    raw = lo
                elif i == 1:
                    raw = hi
                else:
                    raw = rng.randint(lo, hi)
                phys = Decimal(raw) * Decimal(s.factor) + Decimal(s.offset)
                values[s.name] = phys
                expect[s.name] = (raw, phys)
            # canmatrix 0.9.5 Frame.encode packs raw codes; its own
            # phys2raw does the scaling (exact here: on-grid values).
            raws = {s.name: s.phys2raw(values[s.name]) for s in fr.signals if s.name in values}
            for n, (raw, _) in expect.items():
                chk.ok(int(raws[n]) == raw, "canmatrix phys2raw of %s.%s" % (fr.name, n))
            raws["E2E_Counter"] = i % 15
            raws["E2E_CRC"] = 0
            payload = bytearray(fr.encode(raws))
            payload[0] = p01_crc(data_id, payload)
            sent.append((fr, payload, expect))
    lines = "".join("%03X %d %s\n" % (fr.arbitration_id.id, fr.size, p.hex().upper()) for fr, p, _ in sent)
    res = subprocess.run([tool, "decode"], input=lines, check=True, capture_output=True, text=True).stdout.splitlines()
    chk.ok(len(res) == len(sent), "decode answered %d of %d frames" % (len(res), len(sent)))
    for (fr, payload, expect), line in zip(sent, res):
        tok = line.split()
        chk.ok(tok[0] == "OK" and tok[1] == fr.name, "%s %s: codec said %s" % (fr.name, payload.hex(), line))
        if tok[0] != "OK":
            continue
        got = parse_kv(tok[2:])
        chk.ok(got.get("crc_ok") == "1", "%s %s: codec rejects the Python CRC" % (fr.name, payload.hex()))
        for name, (raw, phys) in expect.items():
            g = got.get(name)
            if g is None:
                chk.ok(False, "%s.%s missing in codec output" % (fr.name, name))
                continue
            if is_float_signal(fr.signal_by_name(name)):
                # Decoded float must be the float nearest the exact value:
                # the codec divides the exact raw by the exact inverse LSB.
                err = abs(float(Decimal(f32(g)) - phys))
                chk.ok(err <= 0.5 * ulp32(float(phys)) * (1 + 1e-9),
                       "%s.%s: raw %d exact %s codec %s (%.3g ulp)" % (fr.name, name, raw, phys, g, err / ulp32(float(phys))))
            else:
                chk.ok(Decimal(g) == phys, "%s.%s: exact %s codec %s" % (fr.name, name, phys, g))
    print("canmatrix -> codec: %d frames" % len(sent))

    # 3. out-of-range raw codes -------------------------------------------------
    bad = []
    for fr in db.frames:
        data_id = int(fr.attributes["CvtE2EDataID"])
        for s in fr.signals:
            if s.name in E2E_SIGNALS:
                continue
            lo, hi = raw_limits(s)
            blo, bhi = bit_limits(s)
            for raw in ([hi + 1] if hi < bhi else []) + ([lo - 1] if lo > blo else []):
                if s.values and raw in s.values:
                    continue
                word = 0
                for t in fr.signals:  # every other signal at its lowest valid raw code
                    if t.name in E2E_SIGNALS:
                        continue
                    r = raw if t is s else (min(int(k) for k in t.values) if t.values else raw_limits(t)[0])
                    word |= (r & ((1 << t.size) - 1)) << t.start_bit
                payload = bytearray(word.to_bytes(8, "little"))
                payload[0] = p01_crc(data_id, payload)
                dec = fr.decode(payload)
                chk.ok(dec[s.name].raw_value == raw, "python packing of %s.%s" % (fr.name, s.name))
                bad.append((fr, s, raw, payload))
    lines = "".join("%03X %d %s\n" % (fr.arbitration_id.id, fr.size, p.hex().upper()) for fr, _, _, p in bad)
    res = subprocess.run([tool, "decode"], input=lines, check=True, capture_output=True, text=True).stdout.splitlines()
    for (fr, s, raw, _), line in zip(bad, res):
        want = "REJECT INVALID_ENUM" if s.values else "REJECT OUT_OF_RANGE"
        chk.ok(line.strip() == want, "%s.%s raw %d: codec said %r, want %r" % (fr.name, s.name, raw, line, want))
    print("out-of-range raw codes rejected: %d cases" % len(bad))
    chk.ok(len(bad) >= 10, "too few out-of-range cases")

    print("%d checks, %d failures" % (chk.checks, chk.failures))
    return 1 if chk.failures else 0


if __name__ == "__main__":
    sys.exit(main())
