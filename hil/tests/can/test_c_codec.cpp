// The C99 codec against the C++ codec (docs/can.md#c-codec): both generated
// from hil/cvtplant.dbc, they must give the same frames and the same values,
// bit for bit, for every message: packing (rounding, ranges, NaN, enums),
// E2E protection, the receive pipeline with its checker state across frame
// sequences (repeats, jumps, counter 15, bad CRCs, wrong DLCs, other frame
// kinds), and the timeout reactions. A fixed-seed generator, so a failure
// repeats. The C++ side is itself checked against canmatrix
// (can_canmatrix_agreement).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "cvtplant/can/messages.hpp"
#include "cvtplant_c/can_messages.h"

namespace can = cvt::can;

namespace {

// splitmix64: a fixed sequence on every platform.
struct Rng {
  std::uint64_t s = 0x2545F4914F6CDD1Dull;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(next() >> 11) * 0x1.0p-53); }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

// One value for a signal of kind `kind` with DBC range [lo, hi] and LSB `f`:
// range ends, half-LSB ties and just beyond, anything in between, beyond the
// range, and for floats NaN and the infinities. Integers stay inside their
// C type (`tlo`, `thi`).
double draw(Rng& r, can::SignalKind kind, double lo, double hi, double f, double tlo, double thi) {
  if (kind == can::SignalKind::Bool) return r.below(2);
  if (kind == can::SignalKind::Enum) return r.below(static_cast<int>(hi) + 3);
  if (kind == can::SignalKind::Integer) {
    const double a = std::fmax(tlo, lo - 3), b = std::fmin(thi, hi + 3);
    switch (r.below(4)) {
      case 0: return lo;
      case 1: return hi;
      default: return std::floor(r.uniform(a, b + 1));
    }
  }
  const double k = std::floor(r.uniform(lo / f, hi / f));
  switch (r.below(12)) {
    case 0: return lo;
    case 1: return hi;
    case 2: return lo - f / 2;
    case 3: return hi + f / 2;
    case 4: return (k + 0.5) * f;  // a tie in decimal
    case 5: return static_cast<double>(static_cast<float>((k + 0.5) * f));
    case 6: return r.uniform(lo - 3 * f, lo + 3 * f);
    case 7: return r.uniform(hi - 3 * f, hi + 3 * f);
    case 8: return std::numeric_limits<double>::quiet_NaN();
    case 9: return r.below(2) ? HUGE_VAL : -HUGE_VAL;
    case 10: return r.uniform(lo - (hi - lo), hi + (hi - lo));
    default: return r.uniform(lo, hi);
  }
}

template <class T>
constexpr double type_lo() {
  if constexpr (std::is_integral_v<T>) return static_cast<double>(std::numeric_limits<T>::min());
  return 0;
}
template <class T>
constexpr double type_hi() {
  if constexpr (std::is_integral_v<T>) return static_cast<double>(std::numeric_limits<T>::max());
  return 0;
}

// The C++ message's signals from / to doubles, in DBC order, as the C
// cvt_can_any_set/get do.
template <class Msg>
void set_cpp(Msg& m, const double* in) {
  int i = 0;
  m.visit([&](const can::SignalInfo&, auto& v) {
    using T = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<T, bool>) v = in[i] != 0.0;
    else if constexpr (std::is_enum_v<T>) v = static_cast<T>(static_cast<int>(in[i]));
    else v = static_cast<T>(in[i]);
    ++i;
  });
}
template <class Msg>
void get_cpp(const Msg& m, double* out) {
  int i = 0;
  m.visit([&](const can::SignalInfo&, const auto& v) { out[i++] = static_cast<double>(v); });
}

bool same_bits(const double* a, const double* b, int n) {
  const bool same = std::memcmp(a, b, sizeof(double) * n) == 0;
  static int shown = 0;
  if (!same && shown++ < 5)
    for (int i = 0; i < n; ++i) std::printf("  signal %d: %.17g / %.17g\n", i, a[i], b[i]);
  return same;
}

cvt_can_frame to_c(const can::CanFrame& f) {
  cvt_can_frame g{};
  g.id = f.id;
  g.dlc = f.dlc;
  g.flags = f.flags;
  std::memcpy(g.data, f.data, 8);
  return g;
}

struct Counts {
  long packed = 0, pack_errors = 0, frames = 0, accepted = 0, rejected = 0, timeouts = 0;
};

// Every check of one message type; `idx` its index in both message tables.
template <class Msg>
void agree(int idx, Rng& r, Counts& n) {
  constexpr int kSig = sizeof(Msg::kSignals) / sizeof(Msg::kSignals[0]);
  static_assert(kSig <= 16, "the value arrays below hold 16 signals");
  const cvt_can_message_info& info = cvt_can_messages[idx];
  REQUIRE(info.can_id == Msg::kId);
  REQUIRE(info.dlc == Msg::kDlc);
  REQUIRE(info.e2e_data_id == Msg::kE2eDataId);
  REQUIRE(info.e2e_max_delta_counter == Msg::kE2eMaxDeltaCounter);
  REQUIRE(info.e2e_sync_counter_init == Msg::kE2eSyncCounterInit);
  REQUIRE(info.cycle_time_ms == Msg::kCycleTime_ms);
  REQUIRE(info.rx_timeout_ms == Msg::kRxTimeout_ms);
  REQUIRE(info.signal_count == kSig);
  REQUIRE(std::strcmp(info.name, Msg::kName) == 0);
  for (int i = 0; i < kSig; ++i) REQUIRE(std::strcmp(info.signal_names[i], Msg::kSignals[i].name) == 0);
  REQUIRE(cvt_can_find_message(Msg::kId) == idx);

  // Initial values (GenSigStartValue).
  {
    cvt_can_any c{};
    c.which = static_cast<cvt_can_message_id>(idx);
    cvt_can_any_init(&c);
    double a[16], b[16];
    get_cpp(Msg{}, a);
    cvt_can_any_get(&c, b);
    CHECK(same_bits(a, b, kSig));
  }

  // Packing and E2E protection of random values: same status, same bytes.
  can::TxChannel<Msg> tx;
  cvt_e2e_protector ptx;
  cvt_e2e_protector_init(&ptx, Msg::kE2eDataId);
  double lo_t[16], hi_t[16];
  {
    int i = 0;
    Msg probe;
    probe.visit([&](const can::SignalInfo&, const auto& v) {
      using T = std::decay_t<decltype(v)>;
      lo_t[i] = type_lo<T>();
      hi_t[i] = type_hi<T>();
      ++i;
    });
  }
  std::vector<can::CanFrame> valid;  // frames to feed the receivers below
  for (int rep = 0; rep < 3000; ++rep) {
    double in[16];
    for (int i = 0; i < kSig; ++i) {
      const can::SignalInfo& s = Msg::kSignals[i];
      in[i] = draw(r, s.kind, s.min, s.max, s.lsb, lo_t[i], hi_t[i]);
    }
    // A quarter of the sets in range everywhere: mostly valid frames.
    if (rep % 4 == 0)
      for (int i = 0; i < kSig; ++i) {
        const can::SignalInfo& s = Msg::kSignals[i];
        if (s.kind == can::SignalKind::Float || s.kind == can::SignalKind::Integer)
          in[i] = std::fmin(s.max, std::fmax(s.min, std::isfinite(in[i]) ? in[i] : s.min));
      }
    Msg m;
    set_cpp(m, in);
    cvt_can_any c{};
    c.which = static_cast<cvt_can_message_id>(idx);
    cvt_can_any_set(&c, in);
    uint8_t pc[8] = {0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE}, pcc[8];
    std::memcpy(pcc, pc, 8);
    const can::CodecStatus s1 = can::pack(m, pc);
    const cvt_codec_status s2 = cvt_can_any_pack(&c, pcc);
    REQUIRE_MESSAGE(static_cast<int>(s1) == static_cast<int>(s2), Msg::kName, " rep ", rep);
    CHECK_MESSAGE(std::memcmp(pc, pcc, 8) == 0, Msg::kName, " rep ", rep);
    ++(s1 == can::CodecStatus::Ok ? n.packed : n.pack_errors);
    // The same through the E2E transmit path: counters advance only on Ok.
    can::CanFrame f1;
    const can::CodecStatus e1 = tx.encode(m, f1);
    cvt_can_frame f2{};
    f2.id = Msg::kId;
    f2.dlc = Msg::kDlc;
    const cvt_codec_status e2 = cvt_can_any_pack(&c, f2.data);
    if (e2 == CVT_CODEC_OK) cvt_e2e_protect(&ptx, f2.data);
    REQUIRE(static_cast<int>(e1) == static_cast<int>(e2));
    CHECK(tx.protector().next_counter() == ptx.counter);
    if (e1 == can::CodecStatus::Ok) {
      CHECK(std::memcmp(f1.data, f2.data, 8) == 0);
      valid.push_back(f1);
    }
    // Values back: decode both ways, bit-identical doubles.
    if (s1 == can::CodecStatus::Ok) {
      Msg d1;
      cvt_can_any d2{};
      cvt_can_frame cf = to_c(f1);
      REQUIRE(can::unpack(f1.data, d1) == can::CodecStatus::Ok);
      REQUIRE(cvt_can_decode_any(&cf, &d2) == CVT_CODEC_OK);
      REQUIRE(d2.which == idx);
      double a[16], b[16];
      get_cpp(d1, a);
      cvt_can_any_get(&d2, b);
      CHECK(same_bits(a, b, kSig));
      // The timeout reaction from that state, then ramps of random steps.
      Msg t1 = can::on_rx_timeout(d1);
      cvt_can_any t2 = d2;
      cvt_can_any_on_rx_timeout(&t2);
      for (int k = 0; k < 4; ++k) {
        const float dt = static_cast<float>(r.uniform(0.0, 0.05));
        t1 = can::rx_timeout_ramp(t1, dt);
        cvt_can_any_rx_timeout_ramp(&t2, dt);
      }
      get_cpp(t1, a);
      cvt_can_any_get(&t2, b);
      CHECK(same_bits(a, b, kSig));
      ++n.timeouts;
    }
  }

  // The receive pipeline over frame sequences: in order, repeated, jumping,
  // counter 15, a bad CRC, a wrong DLC, other kinds; both checkers' states
  // after every frame.
  can::RxBank bank;
  cvt_can_rx_bank cbank;
  cvt_can_rx_bank_init(&cbank);
  std::uint8_t ctr = 0;
  for (int rep = 0; rep < 3000 && !valid.empty(); ++rep) {
    can::CanFrame f = valid[static_cast<std::size_t>(r.below(static_cast<int>(valid.size())))];
    // The counter the sequence takes.
    switch (r.below(10)) {
      case 0: break;                                                        // repeated
      case 1: ctr = static_cast<std::uint8_t>((ctr + 2 + r.below(13)) % 15); break;  // a jump
      case 2: ctr = 15; break;                                              // invalid counter
      default: ctr = static_cast<std::uint8_t>((ctr + 1) % 15); break;      // in sequence
    }
    f.data[1] = static_cast<std::uint8_t>((f.data[1] & 0xF0u) | ctr);
    f.data[0] = can::e2e_crc(Msg::kE2eDataId, f.data);
    if (ctr == 15) ctr = 0;
    switch (r.below(16)) {
      case 0: f.data[0] ^= static_cast<std::uint8_t>(1u << r.below(8)); break;  // bad CRC
      case 1: f.dlc = static_cast<std::uint8_t>(r.below(8)); break;              // wrong DLC
      case 2: f.flags = static_cast<std::uint8_t>(1u << r.below(3)); break;      // not a data frame
      case 3:                                                                     // raw codes anywhere, valid CRC
        for (int b = 2; b < 8; ++b) f.data[b] = static_cast<std::uint8_t>(r.next());
        f.data[1] = static_cast<std::uint8_t>((r.next() & 0xF0u) | (f.data[1] & 0x0Fu));
        f.data[0] = can::e2e_crc(Msg::kE2eDataId, f.data);
        break;
      case 4: bank.require_resync(static_cast<can::MessageId>(idx));
              cvt_can_rx_bank_require_resync(&cbank, static_cast<cvt_can_message_id>(idx)); break;
      case 5: if (r.below(8) == 0) {
                bank.reset(static_cast<can::MessageId>(idx));
                cvt_can_rx_bank_reset(&cbank, static_cast<cvt_can_message_id>(idx));
              } break;
      default: break;
    }
    can::AnyMessage a1;
    cvt_can_any a2{};
    const cvt_can_frame cf = to_c(f);
    const can::RxResult r1 = bank.receive(f, a1);
    const cvt_rx_result r2 = cvt_can_rx_bank_receive(&cbank, &cf, &a2);
    REQUIRE_MESSAGE(static_cast<int>(r1.codec) == static_cast<int>(r2.codec), Msg::kName, " frame ", rep);
    REQUIRE_MESSAGE(static_cast<int>(r1.e2e) == static_cast<int>(r2.e2e), Msg::kName, " frame ", rep);
    REQUIRE(r1.accepted() == cvt_rx_accepted(r2));
    ++n.frames;
    ++(r1.accepted() ? n.accepted : n.rejected);
    if (r1.accepted()) {
      REQUIRE(static_cast<int>(a1.which) == static_cast<int>(a2.which));
      double x[16], y[16];
      can::visit_any(a1, [&](const auto& m) {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, Msg>) get_cpp(m, x);
      });
      cvt_can_any_get(&a2, y);
      CHECK_MESSAGE(same_bits(x, y, kSig), Msg::kName, " ", x[0], "/", y[0], " ", x[1], "/", y[1], " ", x[2], "/", y[2]);
    }
    const can::E2eChecker& k1 = bank.checker(static_cast<can::MessageId>(idx));
    const cvt_e2e_checker& k2 = cbank.checkers[idx];
    REQUIRE(k1.synced() == k2.synced);
    REQUIRE(k1.last_counter() == k2.last);
    REQUIRE(k1.resynchronising() == (k2.sync_left > 0));
    REQUIRE(k1.lost_frames() == k2.lost_frames);
    REQUIRE(k1.resyncs() == k2.resyncs);
  }
}

}  // namespace

TEST_CASE("C and C++ codecs: same frames, values, E2E and receive verdicts for every message") {
  REQUIRE(CVT_CAN_MESSAGE_COUNT == can::kMessageCount);
  REQUIRE(std::strcmp(CVT_CAN_DBC_SHA256, can::kDbcSha256) == 0);
  Rng r;
  Counts n;
  int idx = 0;
  can::for_each_message_type([&](auto m) {
    agree<decltype(m)>(idx, r, n);
    ++idx;
  });
  CHECK(idx == CVT_CAN_MESSAGE_COUNT);
  MESSAGE("C/C++ agreement: ", idx, " messages; ", n.packed, " value sets packed alike, ", n.pack_errors,
          " refused alike; ", n.timeouts, " timeout reactions; ", n.frames, " received frames (", n.accepted, " accepted, ", n.rejected,
          " rejected) with the same verdicts, values and checker states");
  CHECK(n.accepted > 1000);
  CHECK(n.rejected > 1000);
  CHECK(n.pack_errors > 1000);
}
