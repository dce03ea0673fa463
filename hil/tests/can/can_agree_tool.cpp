// Helper for hil/tests/can/agree_canmatrix.py (the codec-vs-canmatrix agreement
// test). Host-only test tool.
//
//   can_agree_tool pack [N]   pack N pseudo-random messages of every type
//                             with the codec (+E2E) and print
//                             "FRAME <id> <dlc> <hex> <Msg> sig=value ..."
//                             where value is the physical INPUT handed to
//                             the codec (float printed round-trip exact).
//   can_agree_tool decode     read "<id> <dlc> <hex>" lines and print
//                             "OK <Msg> crc_ok=<0|1> sig=value ..." with the
//                             codec's decoded values, or "REJECT <status>".
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <type_traits>

#include "cvtplant/can/messages.hpp"

using namespace cvt::can;

namespace {

struct Rng {
  uint64_t s = 0x9E3779B97F4A7C15ull;
  uint32_t next() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return static_cast<uint32_t>(s >> 16);
  }
  double unit() { return next() / 4294967296.0; }
};

template <class T>
void print_value(const T& v) {
  if constexpr (std::is_same_v<T, float>) {
    std::printf("%.9g", static_cast<double>(v));
  } else if constexpr (std::is_same_v<T, bool>) {
    std::printf("%d", v ? 1 : 0);
  } else if constexpr (std::is_enum_v<T>) {
    std::printf("%u", static_cast<unsigned>(v));
  } else if constexpr (std::is_signed_v<T>) {
    std::printf("%" PRId64, static_cast<int64_t>(v));
  } else {
    std::printf("%" PRIu64, static_cast<uint64_t>(v));
  }
}

template <class Msg>
void print_signals(const Msg& m) {
  m.visit([](const SignalInfo& si, const auto& v) {
    std::printf(" %s=", si.name);
    print_value(v);
  });
}

void print_frame(const CanFrame& f) {
  std::printf("FRAME %03" PRIX32 " %u ", f.id, f.dlc);
  for (int i = 0; i < 8; ++i) std::printf("%02X", f.data[i]);
}

// Physical test values: range ends, exact ties (k + 1/2 LSB), and uniform
// values, all inside [min, max].
float sample_float(const SignalInfo& si, Rng& r) {
  const uint32_t pick = r.next() % 10;
  double v;
  if (pick == 0) {
    v = si.min;
  } else if (pick == 1) {
    v = si.max;
  } else if (pick == 2) {
    const double k = static_cast<double>(static_cast<int64_t>(si.min / si.lsb + r.unit() * (si.max - si.min) / si.lsb));
    v = (k + 0.5) * si.lsb;
  } else {
    v = si.min + r.unit() * (si.max - si.min);
  }
  float f = static_cast<float>(v);
  if (f < static_cast<float>(si.min)) f = static_cast<float>(si.min);
  if (f > static_cast<float>(si.max)) f = static_cast<float>(si.max);
  return f;
}

template <class Msg>
void pack_some(int n, Rng& r) {
  TxChannel<Msg> tx;
  for (int i = 0; i < n; ++i) {
    Msg m;
    m.visit([&r](const SignalInfo& si, auto& v) {
      using T = std::decay_t<decltype(v)>;
      if constexpr (std::is_same_v<T, float>) {
        v = sample_float(si, r);
      } else if constexpr (std::is_same_v<T, bool>) {
        v = (r.next() & 1u) != 0;
      } else if constexpr (std::is_enum_v<T>) {
        do {
          v = static_cast<T>(static_cast<uint32_t>(si.min) + r.next() % (static_cast<uint32_t>(si.max - si.min) + 1u));
        } while (!is_valid(v));
      } else {
        const uint64_t span = static_cast<uint64_t>(si.max - si.min) + 1u;
        const uint64_t draw = (static_cast<uint64_t>(r.next()) << 32 | r.next()) % span;
        v = static_cast<T>(static_cast<int64_t>(si.min) + static_cast<int64_t>(draw));
      }
    });
    CanFrame f;
    const CodecStatus st = tx.encode(m, f);
    if (st != CodecStatus::Ok) {
      std::fprintf(stderr, "pack %s failed: %s\n", Msg::kName, to_string(st));
      std::exit(2);
    }
    print_frame(f);
    std::printf(" %s", Msg::kName);
    print_signals(m);
    std::printf("\n");
  }
}

int decode_stdin() {
  char line[256];
  while (std::fgets(line, sizeof line, stdin)) {
    unsigned id = 0, dlc = 0;
    char hex[64] = {};
    if (std::sscanf(line, "%x %u %63s", &id, &dlc, hex) != 3) continue;
    CanFrame f;
    f.id = id;
    f.dlc = static_cast<uint8_t>(dlc);
    for (int i = 0; i < 8 && hex[2 * i] && hex[2 * i + 1]; ++i) {
      char b[3] = {hex[2 * i], hex[2 * i + 1], 0};
      f.data[i] = static_cast<uint8_t>(std::strtoul(b, nullptr, 16));
    }
    AnyMessage any;
    const CodecStatus st = decode_any(f, any);
    if (st != CodecStatus::Ok) {
      std::printf("REJECT %s\n", to_string(st));
      continue;
    }
    const int idx = find_message(f.id);
    const bool crc_ok = f.data[0] == e2e_crc(kMessages[idx].e2e_data_id, f.data) &&
                        (f.data[1] & 0x0F) < kE2eCounterModulo;
    visit_any(any, [crc_ok](const auto& m) {
      std::printf("OK %s crc_ok=%d", m.kName, crc_ok ? 1 : 0);
      print_signals(m);
      std::printf("\n");
    });
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "pack") == 0) {
    const int n = argc >= 3 ? std::atoi(argv[2]) : 200;
    Rng r;
    for_each_message_type([&](auto proto) { pack_some<decltype(proto)>(n, r); });
    return 0;
  }
  if (argc >= 2 && std::strcmp(argv[1], "decode") == 0) return decode_stdin();
  std::fprintf(stderr, "usage: %s pack [N] | decode\n", argv[0]);
  return 2;
}
