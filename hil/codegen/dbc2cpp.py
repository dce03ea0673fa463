#!/usr/bin/env python3
"""Generate the heap-free C++ codec (hil/codegen/include/cvtplant/can/messages.hpp)
from the DBC (hil/cvtplant.dbc), which stays the single source of truth.

The DBC is parsed with python3-canmatrix (Debian), an independent parser, so a
DBC that canmatrix reads differently from what we intended shows up here and
in the agreement test (hil/tests/can/agree_canmatrix.py).

It also writes the C99 codec (docs/can.md#c-codec) from the same parse.

Usage:
  dbc2cpp.py --dbc hil/cvtplant.dbc --out hil/codegen/include/cvtplant/can/messages.hpp \
      [--c-header hil/codegen/c/include/cvtplant_c/can_messages.h --c-source hil/codegen/c/src/can_messages.c]
  dbc2cpp.py --dbc hil/cvtplant.dbc --check hil/codegen/include/cvtplant/can/messages.hpp [--c-header ... --c-source ...]

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
    # The field's type and a value's literal, in dialect d (CPP or C99).
    def type_name(self, d):
        if self.kind == "enum":
            return d.enum_type(self.enum_name)
        return {"bool": "bool", "float": "float", "int": getattr(self, "ctype", "")}[self.kind]

    def value(self, d, raw=None, phys=None):
        if self.kind == "float":
            if phys is None:
                phys = Decimal(raw) * self.factor + self.offset
            return flit(phys)
        if phys is not None:
            raw = int(phys)
        if self.kind == "bool":
            return "true" if raw else "false"
        if self.kind == "enum":
            return d.enum_const(self.enum_name, self.values[raw])
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

    def pack_lines(self, d):
        """Encoding of this signal into `w`, in dialect `d` (C++ or C)."""
        f = d.field(self.name)
        out = []
        if self.kind == "float":
            scaled = f if self.offset == 0 else "(%s - %s)" % (f, flit(self.offset))
            inv = self.exact_inverse()
            quotient = ("%s * %s" % (scaled, flit(inv))) if inv is not None else (
                "%s / %s" % (scaled, flit(self.factor)))
            out += [
                "  if (!%s(%s)) return %s;" % (d.fn("is_finite"), f, d.status("NotFinite")),
                "  if (!(%s >= %s && %s <= %s)) return %s;" % (f, flit(self.min), f, flit(self.max),
                                                               d.status("OutOfRange")),
                "  {",
                "    int32_t raw = %s(%s);" % (d.fn("round_to_i32"), quotient),
                "    // Only a value within half an LSB of a range end can round outside",
                "    // the raw interval; the nearest in-range code is the right answer.",
                "    if (raw < %s) raw = %s;" % (cint(self.raw_min), cint(self.raw_min)),
                "    if (raw > %s) raw = %s;" % (cint(self.raw_max), cint(self.raw_max)),
                "    w = %s(w, %d, %d, %s);" % (d.fn("put"), self.start, self.len,
                                              d.cast("uint64_t", d.cast("int64_t", "raw"))),
                "  }",
            ]
        elif self.kind == "int":
            lo, hi = self.ctype_limits()
            conds = self.range_conds(f, lo, hi)
            if conds:
                out.append("  if (%s) return %s;" % (" || ".join(conds), d.status("OutOfRange")))
            out.append("  w = %s(w, %d, %d, %s);" % (d.fn("put"), self.start, self.len,
                                                      d.cast("uint64_t", d.cast("int64_t", f))))
        elif self.kind == "enum":
            out += [
                "  if (!%s(%s)) return %s;" % (d.enum_valid(self.enum_name), f, d.status("InvalidEnum")),
                "  w = %s(w, %d, %d, %s);" % (d.fn("put"), self.start, self.len, d.cast("uint64_t", f)),
            ]
        else:  # bool
            out.append("  w = %s(w, %d, 1, %s ? 1u : 0u);" % (d.fn("put"), self.start, f))
        return out

    def unpack_lines(self, d):
        """Decoding of this signal from `w` into the local `m`, in dialect `d`."""
        t = "m.%s" % self.name
        g = "%s(w, %d, %d)" % (d.fn("get_signed" if self.signed else "get_unsigned"), self.start, self.len)
        if self.kind == "bool":
            return ["  %s = %s != 0;" % (t, g)]
        out = ["  {", "    const int64_t raw = %s;" % d.cast("int64_t", g)]
        conds = self.range_conds("raw", self.bit_lo, self.bit_hi)
        if self.kind == "enum":
            et = d.enum_type(self.enum_name)
            out.append("    const %s v = %s;" % (et, d.cast(et, "raw")))
            out.append("    if (!%s(v)) return %s;" % (d.enum_valid(self.enum_name), d.status("InvalidEnum")))
            out.append("    %s = v;" % t)
        else:
            if conds:
                out.append("    if (%s) return %s;" % (" || ".join(conds), d.status("OutOfRange")))
            if self.kind == "int":
                out.append("    %s = %s;" % (t, d.cast(self.ctype, "raw")))
            else:
                inv = self.exact_inverse()
                as_float = d.cast("float", d.cast("int32_t", "raw"))
                expr = ("%s / %s" % (as_float, flit(inv))) if inv is not None else (
                    "%s * %s" % (as_float, flit(self.factor)))
                if self.offset != 0:
                    expr += " + %s" % flit(self.offset)
                out.append("    %s = %s;" % (t, expr))
        out.append("  }")
        return out


# The two languages the codec is written in: the same statements, their
# spellings. pack_lines/unpack_lines write one rule for both.
class CppDialect:
    def field(self, name):
        return "m.%s" % name

    def fn(self, name):
        return "bits::" + name

    def status(self, name):
        return "CodecStatus::" + name

    def cast(self, t, e):
        return "static_cast<%s>(%s)" % (t, e)

    def enum_type(self, enum_name):
        return enum_name

    def enum_valid(self, enum_name):
        return "is_valid"

    def enum_const(self, enum_name, value):
        return "%s::%s" % (enum_name, value)


class CDialect:
    def field(self, name):
        return "m->%s" % name

    def fn(self, name):
        return "cvt_can_" + name

    def status(self, name):
        return "CVT_CODEC_" + c_upper(name)

    def cast(self, t, e):
        return "(%s)%s" % (t, e)

    def enum_type(self, enum_name):
        return c_enum_type(enum_name)

    def enum_valid(self, enum_name):
        return c_enum_type(enum_name) + "_is_valid"

    def enum_const(self, enum_name, value):
        return c_enum_const(enum_name, value)


# C99 pieces (docs/can.md#c-codec): the same arithmetic as the C++ methods
# above, so both codecs give identical frames and values.
def c_upper(name):
    return snake(name).upper()


def c_enum_type(enum_name):
    return "cvt_" + snake(enum_name)


def c_enum_const(enum_name, value):
    return "CVT_%s_%s" % (c_upper(enum_name), c_upper(value))


CPP, C99 = CppDialect(), CDialect()


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
            w("  %s %s = %s;%s" % (s.type_name(CPP), s.name, s.value(CPP, raw=s.init_raw),
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
            L.extend(s.pack_lines(CPP))
        w("  bits::store_le64(w, payload);")
        w("  return CodecStatus::Ok;")
        w("}")
        w("")
        w("// Writes `out` only when every signal is valid.")
        w("inline CodecStatus unpack(const uint8_t (&payload)[8], %s& out) noexcept {" % m.name)
        w("  const uint64_t w = bits::load_le64(payload);")
        w("  %s m;" % m.name)
        for s in m.signals:
            L.extend(s.unpack_lines(CPP))
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
                w("  m.%s = %s;  // Replace: init value" % (s.name, s.value(CPP, raw=s.init_raw)))
            elif s.timeout_action == "Substitute":
                w("  m.%s = %s;  // Substitute" % (s.name, s.value(CPP, phys=s.substitute)))
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
                s.name, s.name, s.value(CPP, phys=s.substitute), flit(s.rate), format(s.rate.normalize(), "f"), s.unit or "1"))
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


def generate_c(path):
    """The C99 codec (docs/can.md#c-codec): header and source text."""
    with open(path, "rb") as fh:
        digest = hashlib.sha256(fh.read()).hexdigest()
    msgs, enums = load(path)
    H, C = [], []
    h, c = H.append, C.append
    for w in (h, c):
        w("/* GENERATED by hil/codegen/dbc2cpp.py from hil/cvtplant.dbc -- do not edit.")
        w(" * Regenerate: cmake --build <build> --target can_codegen")
        w(" * (ctest hil.codegen_fresh fails when this file and the DBC disagree).")
        w(" * DBC sha256: %s" % digest)
        w(" *")
        w(" * The C99 codec of the bus: the same frames and values as the C++ codec")
        w(" * (cvtplant/can/messages.hpp), checked by ctest hil.c_codec_agreement. No heap,")
        w(" * no libm. Physical values in SI units; pack() rounds to the nearest raw")
        w(" * code and range-checks the physical value, unpack() checks the raw code")
        w(" * against the exact raw image of [min|max]. docs/can.md#c-codec */")
    h("#ifndef CVTPLANT_C_CAN_MESSAGES_H")
    h("#define CVTPLANT_C_CAN_MESSAGES_H")
    h("")
    h("#include <stdbool.h>")
    h("#include <stddef.h>")
    h("#include <stdint.h>")
    h("")
    h('#include "cvtplant_c/can.h"')
    h("")
    h("#ifdef __cplusplus")
    h('extern "C" {')
    h("#endif")
    h("")
    h('#define CVT_CAN_DBC_SHA256 "%s"' % digest)
    h("")
    c('#include "cvtplant_c/can_messages.h"')
    c("")
    for name in sorted(enums):
        e = enums[name]
        et = c_enum_type(name)
        h("typedef enum {")
        for k, v in e.values.items():
            h("  %s = %d," % (c_enum_const(name, v), k))
        h("} %s;" % et)
        h("bool %s_is_valid(%s v);" % (et, et))
        h("const char* %s_name(%s v);" % (et, et))
        h("")
        c("bool %s_is_valid(%s v) {" % (et, et))
        c("  switch (v) {")
        for k, v in e.values.items():
            c("    case %s:" % c_enum_const(name, v))
        c("      return true;")
        c("  }")
        c("  return false;")
        c("}")
        c("")
        c("const char* %s_name(%s v) {" % (et, et))
        c("  switch (v) {")
        for k, v in e.values.items():
            c('    case %s: return "%s";' % (c_enum_const(name, v), v))
        c("  }")
        c('  return "?";')
        c("}")
        c("")
    for m in msgs:
        t = "cvt_" + m.member
        U = "CVT_" + m.member.upper()
        h("/* 0x%03X %s: cycle %d ms, receive timeout %d ms, E2E data ID 0x%04X. */" % (
            m.id, m.name, m.cycle_ms, m.timeout_ms, m.data_id))
        h("#define %s_ID 0x%03Xu" % (U, m.id))
        h("#define %s_DLC %du" % (U, m.dlc))
        h("#define %s_E2E_DATA_ID 0x%04Xu" % (U, m.data_id))
        h("#define %s_E2E_MAX_DELTA_COUNTER %du" % (U, m.max_delta))
        h("#define %s_E2E_SYNC_COUNTER_INIT %du" % (U, m.sync_init))
        h("#define %s_CYCLE_TIME_MS %du" % (U, m.cycle_ms))
        h("#define %s_RX_TIMEOUT_MS %du" % (U, m.timeout_ms))
        h("#define %s_SIGNAL_COUNT %du" % (U, len(m.signals)))
        h("typedef struct {")
        for sg in m.signals:
            cm = sg.comment()
            h("  %s %s;%s" % (sg.type_name(C99), sg.name, ("  /* " + cm + " */") if cm else ""))
        h("} %s;" % t)
        h("extern const char* const %s_signal_names[%d];" % (t, len(m.signals)))
        h("/* Every signal at its initial value (GenSigStartValue). */")
        h("void %s_init(%s* m);" % (t, t))
        h("/* Signals only: byte 0 and the low nibble of byte 1 are left 0 for E2E;")
        h(" * nothing is written on an error. */")
        h("cvt_codec_status %s_pack(const %s* m, uint8_t payload[8]);" % (t, t))
        h("/* Writes *out only when every signal is valid. */")
        h("cvt_codec_status %s_unpack(const uint8_t payload[8], %s* out);" % (t, t))
        h("/* Pack and protect (next E2E counter); on a pack error nothing is written")
        h(" * and the counter does not advance. */")
        h("cvt_codec_status %s_encode(const %s* m, cvt_e2e_protector* p, cvt_can_frame* out);" % (t, t))
        h("/* The receive pipeline of docs/can.md#rejection; *out written only when")
        h(" * accepted. */")
        h("cvt_rx_result %s_receive(const cvt_can_frame* f, cvt_e2e_checker* c, %s* out);" % (t, t))
        h("void %s_protector_init(cvt_e2e_protector* p);" % t)
        h("void %s_checker_init(cvt_e2e_checker* c);" % t)
        h("/* From a receive timeout on (docs/can.md#timeouts): Replace and")
        h(" * Substitute applied; Ramp signals move with _rx_timeout_ramp(). */")
        h("void %s_on_rx_timeout(%s* m);" % (t, t))
        h("void %s_rx_timeout_ramp(%s* m, float dt_s);" % (t, t))
        h("")
        c("const char* const %s_signal_names[%d] = {%s};" % (t, len(m.signals), ", ".join('"%s"' % sg.name for sg in m.signals)))
        c("")
        c("void %s_init(%s* m) {" % (t, t))
        for sg in m.signals:
            c("  m->%s = %s;" % (sg.name, sg.value(C99, raw=sg.init_raw)))
        c("}")
        c("")
        c("cvt_codec_status %s_pack(const %s* m, uint8_t payload[8]) {" % (t, t))
        c("  uint64_t w = 0;")
        for sg in m.signals:
            C.extend(sg.pack_lines(C99))
        c("  cvt_can_store_le64(w, payload);")
        c("  return CVT_CODEC_OK;")
        c("}")
        c("")
        c("cvt_codec_status %s_unpack(const uint8_t payload[8], %s* out) {" % (t, t))
        c("  const uint64_t w = cvt_can_load_le64(payload);")
        c("  %s m;" % t)
        for sg in m.signals:
            C.extend(sg.unpack_lines(C99))
        c("  *out = m;")
        c("  return CVT_CODEC_OK;")
        c("}")
        c("")
        c("cvt_codec_status %s_encode(const %s* m, cvt_e2e_protector* p, cvt_can_frame* out) {" % (t, t))
        c("  cvt_can_frame f = {%s_ID, %s_DLC, 0, {0}};" % (U, U))
        c("  const cvt_codec_status st = %s_pack(m, f.data);" % t)
        c("  if (st != CVT_CODEC_OK) return st;")
        c("  cvt_e2e_protect(p, f.data);")
        c("  *out = f;")
        c("  return CVT_CODEC_OK;")
        c("}")
        c("")
        c("cvt_rx_result %s_receive(const cvt_can_frame* f, cvt_e2e_checker* c, %s* out) {" % (t, t))
        c("  cvt_rx_result r = {CVT_CODEC_OK, CVT_E2E_NO_NEW_DATA};")
        c("  if (!cvt_can_is_standard_data_frame(f)) r.codec = CVT_CODEC_NOT_DATA_FRAME;")
        c("  else if (f->id != %s_ID) r.codec = CVT_CODEC_UNKNOWN_ID;" % U)
        c("  else if (f->dlc != %s_DLC) r.codec = CVT_CODEC_WRONG_DLC;" % U)
        c("  if (r.codec != CVT_CODEC_OK) return r;")
        c("  const cvt_e2e_verdict v = cvt_e2e_evaluate(c, f->data);")
        c("  r.e2e = v.status;")
        c("  if (v.status != CVT_E2E_OK && v.status != CVT_E2E_SYNC && v.status != CVT_E2E_WRONG_SEQUENCE) return r;")
        c("  %s tmp;" % t)
        c("  r.codec = %s_unpack(f->data, &tmp);" % t)
        c("  if (r.codec != CVT_CODEC_OK) return r;")
        c("  cvt_e2e_commit(c, v);")
        c("  if (v.status == CVT_E2E_OK) *out = tmp;")
        c("  return r;")
        c("}")
        c("")
        c("void %s_protector_init(cvt_e2e_protector* p) { cvt_e2e_protector_init(p, %s_E2E_DATA_ID); }" % (t, U))
        c("")
        c("void %s_checker_init(cvt_e2e_checker* c) {" % t)
        c("  cvt_e2e_checker_init(c, %s_E2E_DATA_ID, %s_E2E_MAX_DELTA_COUNTER, %s_E2E_SYNC_COUNTER_INIT);" % (U, U, U))
        c("}")
        c("")
        c("void %s_on_rx_timeout(%s* m) {" % (t, t))
        acted = False
        for sg in m.signals:
            if sg.timeout_action == "Replace":
                c("  m->%s = %s; /* Replace: init value */" % (sg.name, sg.value(C99, raw=sg.init_raw)))
                acted = True
            elif sg.timeout_action == "Substitute":
                c("  m->%s = %s; /* Substitute */" % (sg.name, sg.value(C99, phys=sg.substitute)))
                acted = True
        if not acted:
            c("  (void)m;")
        c("}")
        c("")
        ramps = [sg for sg in m.signals if sg.timeout_action == "Ramp"]
        c("void %s_rx_timeout_ramp(%s* m, float dt_s) {" % (t, t))
        if not ramps:
            c("  (void)m;")
            c("  (void)dt_s;")
        for sg in ramps:
            c("  m->%s = cvt_can_ramp_toward(m->%s, %s, %s * dt_s); /* Ramp, %s %s/s */" % (
                sg.name, sg.name, sg.value(C99, phys=sg.substitute), flit(sg.rate),
                format(sg.rate.normalize(), "f"), sg.unit or "1"))
        c("}")
        c("")
    # Message table, generic access, dispatch and the bank of receivers.
    h("typedef enum {")
    for m in msgs:
        h("  CVT_MSG_%s," % m.member.upper())
    h("} cvt_can_message_id;")
    h("#define CVT_CAN_MESSAGE_COUNT %du" % len(msgs))
    h("")
    h("typedef struct {")
    h("  uint32_t can_id;")
    h("  uint8_t dlc;")
    h("  uint16_t e2e_data_id;")
    h("  uint8_t e2e_max_delta_counter;")
    h("  uint8_t e2e_sync_counter_init;")
    h("  uint16_t cycle_time_ms;")
    h("  uint16_t rx_timeout_ms;")
    h("  uint8_t signal_count;")
    h("  const char* name;")
    h("  const char* const* signal_names;")
    h("} cvt_can_message_info;")
    h("extern const cvt_can_message_info cvt_can_messages[CVT_CAN_MESSAGE_COUNT];")
    h("/* Index into cvt_can_messages, or -1 for an ID this bus does not define. */")
    h("int cvt_can_find_message(uint32_t can_id);")
    h("")
    h("typedef struct {")
    h("  cvt_can_message_id which;")
    h("  union {")
    for m in msgs:
        h("    cvt_%s %s;" % (m.member, m.member))
    h("  } u;")
    h("} cvt_can_any;")
    h("/* Shape checks and unpack, no E2E (for logs and tools); *out written")
    h(" * only on success. */")
    h("cvt_codec_status cvt_can_decode_any(const cvt_can_frame* f, cvt_can_any* out);")
    h("/* Pack the selected message (signals only, no E2E). */")
    h("cvt_codec_status cvt_can_any_pack(const cvt_can_any* a, uint8_t payload[8]);")
    h("/* The selected message's signals as doubles, in DBC order (exact: every")
    h(" * signal is a float, an integer of at most 32 bits, a bool or an enum). */")
    h("void cvt_can_any_get(const cvt_can_any* a, double* out);")
    h("/* Sets the selected message's signals from doubles, in DBC order: floats")
    h(" * rounded to float, integers and enum codes converted, bools != 0. */")
    h("void cvt_can_any_set(cvt_can_any* a, const double* in);")
    h("/* The selected message's _init, _on_rx_timeout and _rx_timeout_ramp. */")
    h("void cvt_can_any_init(cvt_can_any* a);")
    h("void cvt_can_any_on_rx_timeout(cvt_can_any* a);")
    h("void cvt_can_any_rx_timeout_ramp(cvt_can_any* a, float dt_s);")
    h("")
    h("/* One E2E receiver per message: the receive pipeline dispatched on the ID. */")
    h("typedef struct {")
    h("  cvt_e2e_checker checkers[CVT_CAN_MESSAGE_COUNT];")
    h("} cvt_can_rx_bank;")
    h("void cvt_can_rx_bank_init(cvt_can_rx_bank* b);")
    h("cvt_rx_result cvt_can_rx_bank_receive(cvt_can_rx_bank* b, const cvt_can_frame* f, cvt_can_any* out);")
    h("/* The deadline of `id` expired (docs/can.md#timeouts). */")
    h("void cvt_can_rx_bank_require_resync(cvt_can_rx_bank* b, cvt_can_message_id id);")
    h("/* A new run: forget the sender of `id`. */")
    h("void cvt_can_rx_bank_reset(cvt_can_rx_bank* b, cvt_can_message_id id);")
    h("")
    c("const cvt_can_message_info cvt_can_messages[CVT_CAN_MESSAGE_COUNT] = {")
    for m in msgs:
        U = "CVT_" + m.member.upper()
        c('    {%s_ID, %s_DLC, %s_E2E_DATA_ID, %s_E2E_MAX_DELTA_COUNTER, %s_E2E_SYNC_COUNTER_INIT, %s_CYCLE_TIME_MS,' % ((U,) * 6))
        c('     %s_RX_TIMEOUT_MS, %s_SIGNAL_COUNT, "%s", cvt_%s_signal_names},' % (U, U, m.name, m.member))
    c("};")
    c("")
    c("int cvt_can_find_message(uint32_t can_id) {")
    c("  switch (can_id) {")
    for i, m in enumerate(msgs):
        c("    case CVT_%s_ID: return %d;" % (m.member.upper(), i))
    c("  }")
    c("  return -1;")
    c("}")
    c("")
    c("cvt_codec_status cvt_can_decode_any(const cvt_can_frame* f, cvt_can_any* out) {")
    c("  if (!cvt_can_is_standard_data_frame(f)) return CVT_CODEC_NOT_DATA_FRAME;")
    c("  switch (f->id) {")
    for m in msgs:
        U = "CVT_" + m.member.upper()
        c("    case %s_ID: {" % U)
        c("      if (f->dlc != %s_DLC) return CVT_CODEC_WRONG_DLC;" % U)
        c("      cvt_%s v;" % m.member)
        c("      const cvt_codec_status st = cvt_%s_unpack(f->data, &v);" % m.member)
        c("      if (st != CVT_CODEC_OK) return st;")
        c("      out->which = CVT_MSG_%s;" % m.member.upper())
        c("      out->u.%s = v;" % m.member)
        c("      return st;")
        c("    }")
    c("  }")
    c("  return CVT_CODEC_UNKNOWN_ID;")
    c("}")
    c("")
    c("cvt_codec_status cvt_can_any_pack(const cvt_can_any* a, uint8_t payload[8]) {")
    c("  switch (a->which) {")
    for m in msgs:
        c("    case CVT_MSG_%s: return cvt_%s_pack(&a->u.%s, payload);" % (m.member.upper(), m.member, m.member))
    c("  }")
    c("  return CVT_CODEC_UNKNOWN_ID;")
    c("}")
    c("")
    c("void cvt_can_any_get(const cvt_can_any* a, double* out) {")
    c("  switch (a->which) {")
    for m in msgs:
        c("    case CVT_MSG_%s:" % m.member.upper())
        for i, sg in enumerate(m.signals):
            c("      out[%d] = (double)a->u.%s.%s;" % (i, m.member, sg.name))
        c("      break;")
    c("  }")
    c("}")
    c("")
    c("void cvt_can_any_set(cvt_can_any* a, const double* in) {")
    c("  switch (a->which) {")
    for m in msgs:
        c("    case CVT_MSG_%s:" % m.member.upper())
        for i, sg in enumerate(m.signals):
            ty = sg.type_name(C99)
            if sg.kind == "bool":
                c("      a->u.%s.%s = in[%d] != 0.0;" % (m.member, sg.name, i))
            elif sg.kind == "enum":
                c("      a->u.%s.%s = (%s)(int)in[%d];" % (m.member, sg.name, ty, i))
            else:
                c("      a->u.%s.%s = (%s)in[%d];" % (m.member, sg.name, ty, i))
        c("      break;")
    c("  }")
    c("}")
    c("")
    for fn, args, call in (("init", "", ""), ("on_rx_timeout", "", ""), ("rx_timeout_ramp", ", float dt_s", ", dt_s")):
        c("void cvt_can_any_%s(cvt_can_any* a%s) {" % (fn, args))
        c("  switch (a->which) {")
        for m in msgs:
            c("    case CVT_MSG_%s: cvt_%s_%s(&a->u.%s%s); break;" % (m.member.upper(), m.member, fn, m.member, call))
        c("  }")
        c("}")
        c("")
    c("void cvt_can_rx_bank_init(cvt_can_rx_bank* b) {")
    for i, m in enumerate(msgs):
        c("  cvt_%s_checker_init(&b->checkers[%d]);" % (m.member, i))
    c("}")
    c("")
    c("cvt_rx_result cvt_can_rx_bank_receive(cvt_can_rx_bank* b, const cvt_can_frame* f, cvt_can_any* out) {")
    c("  cvt_rx_result r = {CVT_CODEC_NOT_DATA_FRAME, CVT_E2E_NO_NEW_DATA};")
    c("  if (!cvt_can_is_standard_data_frame(f)) return r;")
    c("  r.codec = CVT_CODEC_UNKNOWN_ID;")
    c("  switch (f->id) {")
    for i, m in enumerate(msgs):
        c("    case CVT_%s_ID:" % m.member.upper())
        c("      r = cvt_%s_receive(f, &b->checkers[%d], &out->u.%s);" % (m.member, i, m.member))
        c("      if (cvt_rx_accepted(r)) out->which = CVT_MSG_%s;" % m.member.upper())
        c("      break;")
    c("  }")
    c("  return r;")
    c("}")
    c("")
    c("void cvt_can_rx_bank_require_resync(cvt_can_rx_bank* b, cvt_can_message_id id) {")
    c("  cvt_e2e_require_resync(&b->checkers[id]);")
    c("}")
    c("")
    c("void cvt_can_rx_bank_reset(cvt_can_rx_bank* b, cvt_can_message_id id) { cvt_e2e_reset(&b->checkers[id]); }")
    h("#ifdef __cplusplus")
    h("}")
    h("#endif")
    h("")
    h("#endif /* CVTPLANT_C_CAN_MESSAGES_H */")
    return "\n".join(H) + "\n", "\n".join(C) + "\n"


def check_or_write(text, out, check):
    """Writes `text` to `out`, or compares it with `check`: 0 same, 1 stale."""
    if out:
        with open(out, "w", newline="\n") as fh:
            fh.write(text)
        return 0
    try:
        with open(check) as fh:
            have = fh.read()
    except OSError as e:
        print("dbc2cpp: cannot read %s: %s" % (check, e), file=sys.stderr)
        return 1
    if have == text:
        print("dbc2cpp: %s is up to date" % check)
        return 0
    sys.stdout.writelines(difflib.unified_diff(have.splitlines(True), text.splitlines(True), check, "generated"))
    print("dbc2cpp: %s is stale; regenerate with --out" % check, file=sys.stderr)
    return 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dbc", required=True)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--out", help="write the C++ header here")
    g.add_argument("--check", help="compare with this committed C++ header; exit 1 on difference")
    ap.add_argument("--c-header", help="also the C99 codec's header (written with --out, compared with --check)")
    ap.add_argument("--c-source", help="also the C99 codec's source (with --c-header)")
    a = ap.parse_args(argv)
    if bool(a.c_header) != bool(a.c_source):
        print("dbc2cpp: --c-header and --c-source go together", file=sys.stderr)
        return 2
    try:
        text = generate(a.dbc)
        c_text = generate_c(a.dbc) if a.c_header else None
    except DbcError as e:
        print("dbc2cpp: %s: %s" % (a.dbc, e), file=sys.stderr)
        return 2
    rc = check_or_write(text, a.out, a.check)
    if c_text is not None:
        write = a.out is not None
        rc |= check_or_write(c_text[0], a.c_header if write else None, None if write else a.c_header)
        rc |= check_or_write(c_text[1], a.c_source if write else None, None if write else a.c_source)
    return rc


if __name__ == "__main__":
    sys.exit(main())
