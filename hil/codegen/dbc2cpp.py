#!/usr/bin/env python3
"""Generate the heap-free C++ codec (hil/codegen/include/cvtplant/can/messages.hpp)
from the DBC (hil/cvtplant.dbc), which stays the single source of truth.

The DBC is parsed with python3-canmatrix (Debian), an independent parser, so a
DBC that canmatrix reads differently from what we intended shows up here and
in the agreement test (hil/tests/can/agree_canmatrix.py).

Usage:
  dbc2cpp.py --dbc hil/cvtplant.dbc --out hil/codegen/include/cvtplant/can/messages.hpp
  dbc2cpp.py --dbc hil/cvtplant.dbc --check hil/codegen/include/cvtplant/can/messages.hpp

--check exits 1 (printing a diff) when the committed header is not what the
DBC generates. Conventions enforced here are documented in docs/can.md#codegen.
"""

import argparse
import difflib
import hashlib
import logging
import re
import sys
from decimal import Decimal, ROUND_CEILING, ROUND_FLOOR

logging.disable(logging.CRITICAL)  # canmatrix logs format plugins it lacks

try:
    import canmatrix.formats  # noqa: E402
except ImportError:  # pragma: no cover - reported to the user
    sys.exit("dbc2cpp: python3-canmatrix is required (apt-get install python3-canmatrix)")


class DbcError(Exception):
    pass


IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def camel(name):
    return "".join(p[:1].upper() + p[1:] for p in name.split("_"))


def snake(name):
    s = re.sub(r"(?<=[a-z0-9])([A-Z])", r"_\1", name)
    return s.lower()


def flit(d):
    """Float literal for a Decimal; the compiler rounds it to nearest float."""
    s = format(Decimal(d).normalize(), "f")
    if "." not in s:
        s += ".0"
    return s + "f"


def dlit(d):
    """Double literal for a Decimal."""
    s = format(Decimal(d).normalize(), "f")
    if "." not in s:
        s += ".0"
    return s


def cint(v):
    v = int(v)
    if v < 0:
        # Written as an expression so INT32_MIN-like values stay well-formed.
        return "(%d)" % v
    return str(v)


class Sig:
    def __init__(self, frame, s):
        self.name = s.name
        self.start = int(s.start_bit)
        self.len = int(s.size)
        self.signed = bool(s.is_signed)
        self.factor = Decimal(str(s.factor))
        self.offset = Decimal(str(s.offset))
        self.min = Decimal(str(s.min))
        self.max = Decimal(str(s.max))
        self.unit = s.unit or ""
        self.values = dict(sorted((int(k), v) for k, v in s.values.items()))
        self.attrs = dict(s.attributes)
        where = "%s.%s" % (frame.name, s.name)
        if not IDENT.match(self.name):
            raise DbcError("%s: signal name is not a C identifier" % where)
        if not s.is_little_endian:
            raise DbcError("%s: Motorola byte order is not supported (docs/can.md#layout)" % where)
        if s.is_float:
            raise DbcError("%s: float signals (SIG_VALTYPE_) are not used on this bus" % where)
        if getattr(s, "multiplex", None) is not None:
            raise DbcError("%s: multiplexing is not supported" % where)
        if self.start + self.len > 64 or self.len < 1:
            raise DbcError("%s: bits %d..%d outside the 8-byte payload" % (where, self.start, self.start + self.len - 1))
        if self.factor == 0:
            raise DbcError("%s: factor 0" % where)
        if self.signed:
            self.bit_lo, self.bit_hi = -(1 << (self.len - 1)), (1 << (self.len - 1)) - 1
        else:
            self.bit_lo, self.bit_hi = 0, (1 << self.len) - 1
        # Exact raw interval of the physical range (Decimal arithmetic), so a
        # decoder can range-check the raw value without float rounding at the
        # boundaries and still mean exactly phys in [min, max].
        lo = (self.min - self.offset) / self.factor
        hi = (self.max - self.offset) / self.factor
        if self.factor < 0:
            lo, hi = hi, lo
        self.raw_min = int(lo.to_integral_value(rounding=ROUND_CEILING))
        self.raw_max = int(hi.to_integral_value(rounding=ROUND_FLOOR))
        if self.raw_min > self.raw_max:
            raise DbcError("%s: [min|max] contains no raw value" % where)
        if self.raw_min < self.bit_lo or self.raw_max > self.bit_hi:
            raise DbcError("%s: [min|max] needs raw %d..%d, %d bits give %d..%d"
                           % (where, self.raw_min, self.raw_max, self.len, self.bit_lo, self.bit_hi))
        phys_type = self.attrs.get("CvtPhysType", "float32")
        identity = self.factor == 1 and self.offset == 0
        if self.len == 1 and not self.signed:
            self.kind = "bool"
        elif self.values:
            self.kind = "enum"
        elif phys_type == "integer":
            self.kind = "int"
        else:
            self.kind = "float"
        if self.kind in ("bool", "enum", "int") and not identity:
            raise DbcError("%s: %s signals must have factor 1, offset 0" % (where, self.kind))
        if self.kind == "enum":
            if self.len > 8 or self.signed:
                raise DbcError("%s: enum signals are unsigned and at most 8 bits" % where)
            for k, v in self.values.items():
                if not IDENT.match(v):
                    raise DbcError("%s: VAL_ name %r is not a C identifier" % (where, v))
                if not (self.raw_min <= k <= self.raw_max):
                    raise DbcError("%s: VAL_ %d outside [min|max]" % (where, k))
        if self.kind == "float" and self.len > 24:
            # float has a 24-bit significand: wider raw values would not
            # survive the raw -> float conversion exactly.
            raise DbcError("%s: scaled signals are limited to 24 bits (float32)" % where)
        if self.kind == "int":
            self.ctype = ("int" if self.signed else "uint") + str(
                8 if self.len <= 8 else 16 if self.len <= 16 else 32 if self.len <= 32 else 64) + "_t"
        init_raw = int(Decimal(str(self.attrs.get("GenSigStartValue", "0"))))
        if not (self.raw_min <= init_raw <= self.raw_max):
            raise DbcError("%s: GenSigStartValue %d outside [min|max]" % (where, init_raw))
        if self.kind == "enum" and init_raw not in self.values:
            raise DbcError("%s: GenSigStartValue %d is not in the VAL_ table" % (where, init_raw))
        self.init_raw = init_raw
        self.timeout_action = self.attrs.get("CvtTimeoutAction", "None")
        if self.timeout_action not in ("None", "Replace", "Substitute", "Ramp"):
            raise DbcError("%s: unknown CvtTimeoutAction %r" % (where, self.timeout_action))
        self.substitute = Decimal(str(self.attrs.get("CvtSubstituteValue", "0")))
        self.rate = Decimal(str(self.attrs.get("CvtSubstituteRate", "0")))
        if self.timeout_action in ("Substitute", "Ramp") and not (self.min <= self.substitute <= self.max):
            raise DbcError("%s: CvtSubstituteValue outside [min|max]" % where)
        if self.timeout_action == "Ramp" and (self.kind != "float" or not self.rate > 0):
            raise DbcError("%s: Ramp needs a scaled (float) signal and CvtSubstituteRate > 0" % where)
        if self.kind == "enum":
            self.enum_name = camel(self.name)

    # C++ pieces ---------------------------------------------------------
    def cpp_type(self):
        return {"bool": "bool", "float": "float", "enum": getattr(self, "enum_name", ""),
                "int": getattr(self, "ctype", "")}[self.kind]

    def cpp_value(self, raw=None, phys=None):
        if self.kind == "float":
            if phys is None:
                phys = Decimal(raw) * self.factor + self.offset
            return flit(phys)
        if phys is not None:
            raw = int(phys)
        if self.kind == "bool":
            return "true" if raw else "false"
        if self.kind == "enum":
            return "%s::%s" % (self.enum_name, self.values[raw])
        return cint(raw)

    def comment(self):
        if self.kind == "float":
            return "[%s, %s] %s, LSB %s" % (self.min, self.max, self.unit or "1", self.factor)
        if self.kind == "int":
            return ("[%d, %d] %s" % (self.raw_min, self.raw_max, self.unit)).rstrip()
        return ""

    def exact_inverse(self):
        """1/factor when it is an integer a float holds exactly (0.02 -> 50).
        Scaling by that exact inverse rounds once, against the true DBC
        factor; using the float nearest 0.02 would add its representation
        error to every value (docs/can.md#rounding)."""
        inv = Decimal(1) / self.factor
        if inv == inv.to_integral_value() and 0 < inv <= (1 << 24):
            return inv
        return None

    def raw_getter(self):
        fn = "get_signed" if self.signed else "get_unsigned"
        return "bits::%s(w, %d, %d)" % (fn, self.start, self.len)

    def range_conds(self, var, lo_type, hi_type):
        """Comparisons of `var` against [raw_min, raw_max] that are not
        tautological for a variable whose type spans [lo_type, hi_type]."""
        conds = []
        if self.raw_min > lo_type:
            conds.append("%s < %s" % (var, cint(self.raw_min)))
        if self.raw_max < hi_type:
            conds.append("%s > %s" % (var, cint(self.raw_max)))
        return conds

    def ctype_limits(self):
        bits = int(re.sub(r"\D", "", self.ctype))
        if self.ctype.startswith("u"):
            return 0, (1 << bits) - 1
        return -(1 << (bits - 1)), (1 << (bits - 1)) - 1

    def pack_lines(self):
        f = "m.%s" % self.name
        out = []
        if self.kind == "float":
            scaled = f if self.offset == 0 else "(%s - %s)" % (f, flit(self.offset))
            inv = self.exact_inverse()
            quotient = ("%s * %s" % (scaled, flit(inv))) if inv is not None else (
                "%s / %s" % (scaled, flit(self.factor)))
            out += [
                "  if (!bits::is_finite(%s)) return CodecStatus::NotFinite;" % f,
                "  if (!(%s >= %s && %s <= %s)) return CodecStatus::OutOfRange;" % (f, flit(self.min), f, flit(self.max)),
                "  {",
                "    int32_t raw = bits::round_to_i32(%s);" % quotient,
                "    // Only a value within half an LSB of a range end can round outside",
                "    // the raw interval; the nearest in-range code is the right answer.",
                "    if (raw < %s) raw = %s;" % (cint(self.raw_min), cint(self.raw_min)),
                "    if (raw > %s) raw = %s;" % (cint(self.raw_max), cint(self.raw_max)),
                "    w = bits::put(w, %d, %d, static_cast<uint64_t>(static_cast<int64_t>(raw)));" % (self.start, self.len),
                "  }",
            ]
        elif self.kind == "int":
            lo, hi = self.ctype_limits()
            conds = self.range_conds(f, lo, hi)
            if conds:
                out.append("  if (%s) return CodecStatus::OutOfRange;" % " || ".join(conds))
            out.append("  w = bits::put(w, %d, %d, static_cast<uint64_t>(static_cast<int64_t>(%s)));"
                       % (self.start, self.len, f))
        elif self.kind == "enum":
            out += [
                "  if (!is_valid(%s)) return CodecStatus::InvalidEnum;" % f,
                "  w = bits::put(w, %d, %d, static_cast<uint64_t>(%s));" % (self.start, self.len, f),
            ]
        else:  # bool
            out.append("  w = bits::put(w, %d, 1, %s ? 1u : 0u);" % (self.start, f))
        return out

    def unpack_lines(self):
        t = "m.%s" % self.name
        g = self.raw_getter()
        out = ["  {", "    const int64_t raw = static_cast<int64_t>(%s);" % g]
        if self.kind == "bool":
            out = ["  %s = %s != 0;" % (t, g)]
            return out
        conds = self.range_conds("raw", self.bit_lo, self.bit_hi)
        if self.kind == "enum":
            out.append("    const %s v = static_cast<%s>(raw);" % (self.enum_name, self.enum_name))
            out.append("    if (!is_valid(v)) return CodecStatus::InvalidEnum;")
            out.append("    %s = v;" % t)
        else:
            if conds:
                out.append("    if (%s) return CodecStatus::OutOfRange;" % " || ".join(conds))
            if self.kind == "int":
                out.append("    %s = static_cast<%s>(raw);" % (t, self.ctype))
            else:
                inv = self.exact_inverse()
                expr = ("static_cast<float>(static_cast<int32_t>(raw)) / %s" % flit(inv)) if inv is not None else (
                    "static_cast<float>(static_cast<int32_t>(raw)) * %s" % flit(self.factor))
                if self.offset != 0:
                    expr += " + %s" % flit(self.offset)
                out.append("    %s = %s;" % (t, expr))
        out.append("  }")
        return out


class Msg:
    def __init__(self, f):
        self.name = f.name
        if not IDENT.match(self.name):
            raise DbcError("%s: message name is not a C identifier" % self.name)
        if f.arbitration_id.extended:
            raise DbcError("%s: extended IDs are not used on this bus (11-bit only)" % self.name)
        self.id = int(f.arbitration_id.id)
        if self.id > 0x7FF:
            raise DbcError("%s: ID 0x%X is not an 11-bit ID" % (self.name, self.id))
        self.dlc = int(f.size)
        if self.dlc != 8:
            raise DbcError("%s: every E2E-protected message has DLC 8" % self.name)
        a = f.attributes
        self.cycle_ms = int(a.get("GenMsgCycleTime", 0))
        self.timeout_ms = int(a.get("CvtRxTimeout", 0))
        self.data_id = int(a.get("CvtE2EDataID", 0))
        self.max_delta = int(a.get("CvtE2EMaxDeltaCounter", 2))
        self.sync_init = int(a.get("CvtE2ESyncCounterInit", 1))
        if self.data_id == 0:
            raise DbcError("%s: no CvtE2EDataID; every message on this bus is E2E protected" % self.name)
        if not (1 <= self.max_delta <= 14):
            raise DbcError("%s: CvtE2EMaxDeltaCounter must be 1..14" % self.name)
        if not (0 <= self.sync_init <= 14):
            raise DbcError("%s: CvtE2ESyncCounterInit must be 0..14" % self.name)
        sigs = {s.name: s for s in f.signals}
        crc, ctr = sigs.get("E2E_CRC"), sigs.get("E2E_Counter")
        if crc is None or ctr is None:
            raise DbcError("%s: E2E_CRC and E2E_Counter signals are required" % self.name)
        if (int(crc.start_bit), int(crc.size)) != (0, 8) or (int(ctr.start_bit), int(ctr.size)) != (8, 4):
            raise DbcError("%s: E2E_CRC must be bits 0..7 and E2E_Counter bits 8..11" % self.name)
        self.signals = [Sig(f, s) for s in f.signals if s.name not in ("E2E_CRC", "E2E_Counter")]
        used = 0x0FFF  # CRC byte and counter nibble
        for s in self.signals:
            m = ((1 << s.len) - 1) << s.start
            if used & m:
                raise DbcError("%s.%s overlaps another signal or the E2E header" % (self.name, s.name))
            used |= m
        self.member = snake(self.name)


def load(path):
    db = canmatrix.formats.loadp_flat(path)
    msgs = sorted((Msg(f) for f in db.frames), key=lambda m: m.id)
    seen_ids, seen_data_ids, enums = set(), set(), {}
    for m in msgs:
        if m.id in seen_ids:
            raise DbcError("duplicate CAN ID 0x%X" % m.id)
        if m.data_id in seen_data_ids:
            raise DbcError("duplicate E2E data ID 0x%04X" % m.data_id)
        seen_ids.add(m.id)
        seen_data_ids.add(m.data_id)
        for s in m.signals:
            if s.kind == "enum":
                prev = enums.get(s.enum_name)
                if prev is not None and prev.values != s.values:
                    raise DbcError("enum %s defined twice with different values" % s.enum_name)
                enums[s.enum_name] = s
    return msgs, enums


def generate(path):
    with open(path, "rb") as fh:
        digest = hashlib.sha256(fh.read()).hexdigest()
    msgs, enums = load(path)
    L = []
    w = L.append
    w("// GENERATED by hil/codegen/dbc2cpp.py from hil/cvtplant.dbc -- do not edit.")
    w("// Regenerate: cmake --build <build> --target can_codegen")
    w("// (ctest hil.codegen_fresh fails when this file and the DBC disagree).")
    w("// DBC sha256: %s" % digest)
    w("//")
    w("// Physical values in SI units (names carry the unit). pack() rounds to the")
    w("// nearest raw code and range-checks the physical value; unpack() checks")
    w("// the raw code against the exact raw image of [min|max]. docs/can.md")
    w("#pragma once")
    w("")
    w("#include <cstdint>")
    w("")
    w('#include "cvtplant/can/bits.hpp"')
    w('#include "cvtplant/can/channel.hpp"')
    w('#include "cvtplant/can/codec_status.hpp"')
    w('#include "cvtplant/can/e2e.hpp"')
    w('#include "cvtplant/can/frame.hpp"')
    w('#include "cvtplant/can/signal_info.hpp"')
    w("")
    w("namespace cvt::can {")
    w("")
    w('inline constexpr const char kDbcSha256[] = "%s";' % digest)
    w("")
    for name in sorted(enums):
        s = enums[name]
        w("enum class %s : uint8_t {" % name)
        for k, v in s.values.items():
            w("  %s = %d," % (v, k))
        w("};")
        w("")
        w("constexpr bool is_valid(%s v) noexcept {" % name)
        w("  switch (v) {")
        for k, v in s.values.items():
            w("    case %s::%s:" % (name, v))
        w("      return true;")
        w("  }")
        w("  return false;")
        w("}")
        w("")
        w("constexpr const char* to_string(%s v) noexcept {" % name)
        w("  switch (v) {")
        for k, v in s.values.items():
            w('    case %s::%s: return "%s";' % (name, v, v))
        w("  }")
        w('  return "?";')
        w("}")
        w("")
    for m in msgs:
        w("// 0x%03X %s: cycle %d ms, receive timeout %d ms, E2E data ID 0x%04X." % (
            m.id, m.name, m.cycle_ms, m.timeout_ms, m.data_id))
        w("struct %s {" % m.name)
        w("  static constexpr uint32_t kId = 0x%03Xu;" % m.id)
        w("  static constexpr uint8_t kDlc = %d;" % m.dlc)
        w("  static constexpr uint16_t kE2eDataId = 0x%04Xu;" % m.data_id)
        w("  static constexpr uint8_t kE2eMaxDeltaCounter = %d;" % m.max_delta)
        w("  static constexpr uint8_t kE2eSyncCounterInit = %d;" % m.sync_init)
        w("  static constexpr uint16_t kCycleTime_ms = %d;" % m.cycle_ms)
        w("  static constexpr uint16_t kRxTimeout_ms = %d;" % m.timeout_ms)
        w('  static constexpr const char* kName = "%s";' % m.name)
        mask = 0
        for sg in m.signals:
            mask |= ((1 << sg.len) - 1) << sg.start
        w("  // Payload bits carrying signals (E2E header excluded).")
        w("  static constexpr uint64_t kSignalMask = 0x%016Xull;" % mask)
        w("")
        for s in m.signals:
            c = s.comment()
            w("  %s %s = %s;%s" % (s.cpp_type(), s.name, s.cpp_value(raw=s.init_raw),
                                    ("  // " + c) if c else ""))
        w("")
        w("  static constexpr SignalInfo kSignals[%d] = {" % len(m.signals))
        kinds = {"float": "Float", "int": "Integer", "enum": "Enum", "bool": "Bool"}
        for s in m.signals:
            w('      {"%s", "%s", SignalKind::%s, %s, %s, %s},' % (
                s.name, s.unit, kinds[s.kind], dlit(s.min), dlit(s.max), dlit(s.factor)))
        w("  };")
        for const in ("", " const"):
            w("  template <class F>")
            w("  constexpr void visit(F&& f)%s {" % const)
            for i, s in enumerate(m.signals):
                w("    f(kSignals[%d], %s);" % (i, s.name))
            w("  }")
        w("};")
        w("")
        w("// Signals only: byte 0 and the low nibble of byte 1 are left 0 for E2E.")
        w("inline CodecStatus pack(const %s& m, uint8_t (&payload)[8]) noexcept {" % m.name)
        w("  uint64_t w = 0;")
        for s in m.signals:
            L.extend(s.pack_lines())
        w("  bits::store_le64(w, payload);")
        w("  return CodecStatus::Ok;")
        w("}")
        w("")
        w("// Writes `out` only when every signal is valid.")
        w("inline CodecStatus unpack(const uint8_t (&payload)[8], %s& out) noexcept {" % m.name)
        w("  const uint64_t w = bits::load_le64(payload);")
        w("  %s m;" % m.name)
        for s in m.signals:
            L.extend(s.unpack_lines())
        w("  out = m;")
        w("  return CodecStatus::Ok;")
        w("}")
        w("")
        w("// Value to use from a receive timeout on (docs/can.md#timeouts). Ramp")
        w("// signals start from the last value and move with rx_timeout_ramp().")
        w("constexpr %s on_rx_timeout(const %s& last) noexcept {" % (m.name, m.name))
        w("  %s m = last;" % m.name)
        for s in m.signals:
            if s.timeout_action == "Replace":
                w("  m.%s = %s;  // Replace: init value" % (s.name, s.cpp_value(raw=s.init_raw)))
            elif s.timeout_action == "Substitute":
                w("  m.%s = %s;  // Substitute" % (s.name, s.cpp_value(phys=s.substitute)))
        w("  return m;")
        w("}")
        w("")
        ramps = [s for s in m.signals if s.timeout_action == "Ramp"]
        w("// While timed out, once per dt_s [s]: each Ramp signal moves toward its")
        w("// substitute value by at most CvtSubstituteRate * dt_s.")
        w("constexpr %s rx_timeout_ramp(const %s& current, float dt_s) noexcept {" % (m.name, m.name))
        w("  %s m = current;" % m.name)
        if not ramps:
            w("  (void)dt_s;")
        for s in ramps:
            w("  m.%s = ramp_toward(m.%s, %s, %s * dt_s);  // Ramp, %s %s/s" % (
                s.name, s.name, s.cpp_value(phys=s.substitute), flit(s.rate), format(s.rate.normalize(), "f"), s.unit or "1"))
        w("  return m;")
        w("}")
        w("")
    # Message table, dispatch and a bank of receivers.
    w("enum class MessageId : uint8_t {")
    for m in msgs:
        w("  %s," % m.name)
    w("};")
    w("inline constexpr uint8_t kMessageCount = %d;" % len(msgs))
    w("")
    w("struct MessageInfo {")
    w("  uint32_t can_id;")
    w("  uint8_t dlc;")
    w("  uint16_t e2e_data_id;")
    w("  uint8_t e2e_max_delta_counter;")
    w("  uint8_t e2e_sync_counter_init;")
    w("  uint16_t cycle_time_ms;")
    w("  uint16_t rx_timeout_ms;")
    w("  const char* name;")
    w("};")
    w("")
    w("inline constexpr MessageInfo kMessages[kMessageCount] = {")
    for m in msgs:
        w("    {%s::kId, %s::kDlc, %s::kE2eDataId, %s::kE2eMaxDeltaCounter, %s::kE2eSyncCounterInit, %s::kCycleTime_ms," % ((m.name,) * 6))
        w("     %s::kRxTimeout_ms, %s::kName}," % ((m.name,) * 2))
    w("};")
    w("")
    w("// Index into kMessages, or -1 for an ID this bus does not define.")
    w("constexpr int find_message(uint32_t can_id) noexcept {")
    w("  switch (can_id) {")
    for i, m in enumerate(msgs):
        w("    case %s::kId: return %d;" % (m.name, i))
    w("  }")
    w("  return -1;")
    w("}")
    w("")
    w("struct AnyMessage {")
    w("  MessageId which = MessageId::%s;" % msgs[0].name)
    for m in msgs:
        w("  %s %s;" % (m.name, m.member))
    w("};")
    w("")
    w("// Shape checks and unpack, no E2E (for logs and tools). `out.which` and")
    w("// the selected member are written only on success.")
    w("inline CodecStatus decode_any(const CanFrame& f, AnyMessage& out) noexcept {")
    w("  if (!is_standard_data_frame(f)) return CodecStatus::NotDataFrame;")
    w("  switch (f.id) {")
    for m in msgs:
        w("    case %s::kId: {" % m.name)
        w("      if (f.dlc != %s::kDlc) return CodecStatus::WrongDlc;" % m.name)
        w("      const CodecStatus st = unpack(f.data, out.%s);" % m.member)
        w("      if (st == CodecStatus::Ok) out.which = MessageId::%s;" % m.name)
        w("      return st;")
        w("    }")
    w("  }")
    w("  return CodecStatus::UnknownId;")
    w("}")
    w("")
    w("// Calls f(Msg{}) once per message type, in CAN ID order.")
    w("template <class F>")
    w("void for_each_message_type(F&& f) {")
    for m in msgs:
        w("  f(%s{});" % m.name)
    w("}")
    w("")
    w("// Calls f(const Msg&) with the member selected by `which`.")
    w("template <class F>")
    w("void visit_any(const AnyMessage& a, F&& f) {")
    w("  switch (a.which) {")
    for m in msgs:
        w("    case MessageId::%s: f(a.%s); break;" % (m.name, m.member))
    w("  }")
    w("}")
    w("")
    w("// One E2E receiver per message: the full receive pipeline of channel.hpp")
    w("// dispatched on the CAN ID.")
    w("class RxBank {")
    w(" public:")
    w("  RxResult receive(const CanFrame& f, AnyMessage& out) noexcept {")
    w("    if (!is_standard_data_frame(f)) return RxResult{CodecStatus::NotDataFrame, E2eStatus::NoNewData};")
    w("    RxResult r{CodecStatus::UnknownId, E2eStatus::NoNewData};")
    w("    switch (f.id) {")
    for i, m in enumerate(msgs):
        w("      case %s::kId:" % m.name)
        w("        r = cvt::can::receive(f, checkers_[%d], out.%s);" % (i, m.member))
        w("        if (r.accepted()) out.which = MessageId::%s;" % m.name)
        w("        break;")
    w("    }")
    w("    return r;")
    w("  }")
    w("  // The deadline of `id` expired (docs/can.md#timeouts).")
    w("  void require_resync(MessageId id) noexcept { checkers_[static_cast<uint8_t>(id)].require_resync(); }")
    w("  // A new run: forget the sender of `id`.")
    w("  void reset(MessageId id) noexcept { checkers_[static_cast<uint8_t>(id)].reset(); }")
    w("  void reset_all() noexcept {")
    w("    for (E2eChecker& c : checkers_) c.reset();")
    w("  }")
    w("  const E2eChecker& checker(MessageId id) const noexcept { return checkers_[static_cast<uint8_t>(id)]; }")
    w("")
    w(" private:")
    w("  E2eChecker checkers_[kMessageCount] = {")
    for m in msgs:
        w("      E2eChecker{%s::kE2eDataId, E2eCheckerConfig{%s::kE2eMaxDeltaCounter, %s::kE2eSyncCounterInit}}," % (
            m.name, m.name, m.name))
    w("  };")
    w("};")
    w("")
    w("}  // namespace cvt::can")
    return "\n".join(L) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dbc", required=True)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--out", help="write the header here")
    g.add_argument("--check", help="compare with this committed header; exit 1 on difference")
    a = ap.parse_args(argv)
    try:
        text = generate(a.dbc)
    except DbcError as e:
        print("dbc2cpp: %s: %s" % (a.dbc, e), file=sys.stderr)
        return 2
    if a.out:
        with open(a.out, "w", newline="\n") as fh:
            fh.write(text)
        return 0
    try:
        with open(a.check) as fh:
            have = fh.read()
    except OSError as e:
        print("dbc2cpp: cannot read %s: %s" % (a.check, e), file=sys.stderr)
        return 1
    if have == text:
        print("dbc2cpp: %s is up to date with %s" % (a.check, a.dbc))
        return 0
    sys.stdout.writelines(difflib.unified_diff(
        have.splitlines(True), text.splitlines(True), a.check, "generated from " + a.dbc))
    print("dbc2cpp: %s is stale; regenerate with --out" % a.check, file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
