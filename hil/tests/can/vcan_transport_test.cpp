// SocketCAN transport against real peers on a (virtual) CAN bus; run through
// hil/vcan-run by hil/tests/can/vcan_peers.sh (docs/can.md#vcan-tests).
//
//   vcan_transport_test peer IF N     controller role against hil/tests/can/vcan_peer.py:
//                                     N CtrlCmd -> PlantSpeeds exchanges, then the
//                                     peer's bad frames must be rejected in order
//   vcan_transport_test echo IF N     answer N frames 0x201 with 0x202 (C++ peer)
//   vcan_transport_test ping IF N     N round trips against `echo`; prints RTT stats
//   vcan_transport_test blast IF N    send N frames back to back; prints counters
//   vcan_transport_test fd IF         a CAN FD-sized frame is refused locally
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/port/socketcan_transport.hpp"

using namespace cvt;
using port::CanIoStatus;

namespace {

constexpr int64_t kSecond = 1000000000;
int g_failures = 0;

#define EXPECT(cond, ...)                               \
  do {                                                  \
    if (!(cond)) {                                      \
      ++g_failures;                                     \
      std::printf("FAIL %s:%d: ", __FILE__, __LINE__);  \
      std::printf(__VA_ARGS__);                         \
      std::printf("\n");                                \
    }                                                   \
  } while (0)

void print_counters(const char* who, const port::CanTransportCounters& c) {
  std::printf("%s counters: tx=%" PRIu64 " rx=%" PRIu64 " enobufs_retries=%" PRIu64 " tx_dropped=%" PRIu64
              " tx_invalid=%" PRIu64 " rx_error_frames=%" PRIu64 " rx_invalid=%" PRIu64 " rx_kernel_drops=%" PRIu64
              " bus_off_events=%" PRIu64 "\n",
              who, c.tx_frames, c.rx_frames, c.tx_enobufs_retries, c.tx_dropped, c.tx_invalid, c.rx_error_frames,
              c.rx_invalid, c.rx_kernel_drops, c.bus_off_events);
}

void print_rtt(const char* what, std::vector<int64_t>& rtt_ns, int64_t wall_ns) {
  if (rtt_ns.empty()) return;
  std::sort(rtt_ns.begin(), rtt_ns.end());
  auto q = [&](double p) { return rtt_ns[static_cast<size_t>(p * static_cast<double>(rtt_ns.size() - 1))] / 1000.0; };
  std::printf("%s: n=%zu round trips, RTT us p50=%.1f p99=%.1f p99.9=%.1f max=%.1f, %.0f round trips/s\n", what,
              rtt_ns.size(), q(0.5), q(0.99), q(0.999), rtt_ns.back() / 1000.0,
              static_cast<double>(rtt_ns.size()) * kSecond / static_cast<double>(wall_ns));
}

bool open_or_fail(port::SocketCanTransport& t, const char* ifname) {
  if (t.open(ifname) != 0) {
    std::printf("FAIL: cannot open %s: %s\n", ifname, t.error_text());
    return false;
  }
  return true;
}

// Receive the next frame that is not one of our own echoes, with a deadline.
CanIoStatus next(port::SocketCanTransport& t, can::CanFrame& f, int64_t timeout_ns = 5 * kSecond) {
  return t.receive(f, timeout_ns);
}

int run_peer(const char* ifname, int n) {
  port::SocketCanTransport t;
  if (!open_or_fail(t, ifname)) return 1;
  port::PosixMonotonicClock clk;
  can::TxChannel<can::CtrlCmd> tx;
  can::RxBank rx;
  can::AnyMessage any;
  std::vector<int64_t> rtt;
  const int64_t t_start = clk.now_ns();
  for (int i = 0; i < n; ++i) {
    can::CtrlCmd c;
    c.clamp_force_cmd_N = 1000.0f + 7.0f * static_cast<float>(i);
    c.driver_torque_req_Nm = -50.0f + 0.26f * static_cast<float>(i);
    can::CanFrame f;
    EXPECT(tx.encode(c, f) == can::CodecStatus::Ok, "encode %d", i);
    const int64_t t0 = clk.now_ns();
    EXPECT(t.send(f) == CanIoStatus::Ok, "send %d", i);
    can::CanFrame r;
    const CanIoStatus st = next(t, r);
    if (st != CanIoStatus::Ok) {
      EXPECT(false, "no reply to CtrlCmd %d: %s", i, port::to_string(st));
      break;
    }
    rtt.push_back(clk.now_ns() - t0);
    const can::RxResult res = rx.receive(r, any);
    EXPECT(res.accepted() && any.which == can::MessageId::PlantSpeeds, "reply %d id 0x%03X: codec %s e2e %s", i,
           static_cast<unsigned>(r.id), can::to_string(res.codec), can::to_string(res.e2e));
    // The peer answers with values derived from what canmatrix decoded.
    const can::PlantSpeeds& s = any.plant_speeds;
    EXPECT(std::abs(s.omega_driver_rad_s - 0.7f * static_cast<float>(i)) < 1e-4f,
           "reply %d omega_driver %g", i, static_cast<double>(s.omega_driver_rad_s));
    EXPECT(std::abs(s.omega_driven_rad_s + s.omega_driver_rad_s) < 1e-4f, "reply %d omega_driven %g", i,
           static_cast<double>(s.omega_driven_rad_s));
    EXPECT(std::abs(s.torque_transmitted_Nm - c.driver_torque_req_Nm) <= 0.01f + 1e-4f, "reply %d torque %g vs %g",
           i, static_cast<double>(s.torque_transmitted_Nm), static_cast<double>(c.driver_torque_req_Nm));
    EXPECT(s.sample_tag == (i & 0xF), "reply %d sample_tag %d", i, s.sample_tag);
  }
  const int64_t wall = clk.now_ns() - t_start;
  print_rtt("C++ <-> python-can", rtt, wall);

  // Send the end marker, then the peer's deliberate bad frames, in order.
  can::TxChannel<can::SimCtrl> sim;
  can::SimCtrl pause;
  pause.sim_request = can::SimRequest::Pause;
  can::CanFrame f;
  EXPECT(sim.encode(pause, f) == can::CodecStatus::Ok, "encode SimCtrl");
  EXPECT(t.send(f) == CanIoStatus::Ok, "send SimCtrl");

  can::CanFrame r;
  CanIoStatus st = next(t, r);
  EXPECT(st == CanIoStatus::ErrorFrame, "expected bus-off error frame, got %s", port::to_string(st));
  EXPECT(t.bus_state() == port::CanBusState::BusOff, "bus state after bus-off frame");
  EXPECT(can::decode_any(r, any) == can::CodecStatus::NotDataFrame, "error frame must not decode");
  EXPECT(t.send(f) == CanIoStatus::BusOff, "send while bus-off must be refused");
  st = next(t, r);
  EXPECT(st == CanIoStatus::ErrorFrame, "expected restarted error frame, got %s", port::to_string(st));
  EXPECT(t.bus_state() == port::CanBusState::ErrorActive, "bus state after restart");

  struct Want {
    const char* what;
    can::CodecStatus codec;
    can::E2eStatus e2e;
  };
  const Want wants[] = {
      {"wrong DLC", can::CodecStatus::WrongDlc, can::E2eStatus::NoNewData},
      {"unknown ID", can::CodecStatus::UnknownId, can::E2eStatus::NoNewData},
      {"bad CRC", can::CodecStatus::Ok, can::E2eStatus::WrongCrc},
      {"replayed frame", can::CodecStatus::Ok, can::E2eStatus::Repeated},
      {"out-of-range value", can::CodecStatus::OutOfRange, can::E2eStatus::Ok},
      {"remote frame", can::CodecStatus::NotDataFrame, can::E2eStatus::NoNewData},
      {"extended ID", can::CodecStatus::NotDataFrame, can::E2eStatus::NoNewData},
  };
  for (const Want& w : wants) {
    st = next(t, r);
    if (st != CanIoStatus::Ok) {
      EXPECT(false, "%s: no frame (%s)", w.what, port::to_string(st));
      continue;
    }
    const can::RxResult res = rx.receive(r, any);
    EXPECT(res.codec == w.codec && res.e2e == w.e2e, "%s: codec %s e2e %s", w.what, can::to_string(res.codec),
           can::to_string(res.e2e));
  }
  // Last, a valid frame: the checker was not disturbed by any of the above.
  st = next(t, r);
  const can::RxResult res = st == CanIoStatus::Ok ? rx.receive(r, any) : can::RxResult{};
  EXPECT(st == CanIoStatus::Ok && res.accepted(), "final valid frame: %s codec %s e2e %s", port::to_string(st),
         can::to_string(res.codec), can::to_string(res.e2e));
  print_counters("peer", t.counters());
  EXPECT(t.counters().rx_error_frames == 2 && t.counters().bus_off_events == 1, "error counters");
  std::printf("%s: %d failures\n", g_failures ? "FAILED" : "PASSED", g_failures);
  return g_failures ? 1 : 0;
}

int run_echo(const char* ifname, int n) {
  port::SocketCanTransport t;
  if (!open_or_fail(t, ifname)) return 1;
  for (int i = 0; i < n; ++i) {
    can::CanFrame r;
    const CanIoStatus st = t.receive(r, 10 * kSecond);
    if (st != CanIoStatus::Ok) {
      std::printf("echo: %s after %d frames\n", port::to_string(st), i);
      return 1;
    }
    r.id = 0x202;
    if (t.send(r) != CanIoStatus::Ok) return 1;
  }
  return 0;
}

int run_ping(const char* ifname, int n) {
  port::SocketCanTransport t;
  if (!open_or_fail(t, ifname)) return 1;
  port::PosixMonotonicClock clk;
  std::vector<int64_t> rtt;
  rtt.reserve(static_cast<size_t>(n));
  can::CanFrame f;
  f.id = 0x201;
  f.dlc = 8;
  const int64_t t_start = clk.now_ns();
  for (int i = 0; i < n; ++i) {
    std::memcpy(f.data, &i, sizeof i);
    const int64_t t0 = clk.now_ns();
    if (t.send(f) != CanIoStatus::Ok) return 1;
    can::CanFrame r;
    do {
      if (t.receive(r, 10 * kSecond) != CanIoStatus::Ok) {
        std::printf("ping: no echo for %d\n", i);
        return 1;
      }
    } while (r.id != 0x202);
    EXPECT(std::memcmp(r.data, f.data, 8) == 0, "echo payload %d", i);
    rtt.push_back(clk.now_ns() - t0);
  }
  print_rtt("C++ <-> C++ (SocketCanTransport)", rtt, clk.now_ns() - t_start);
  return g_failures ? 1 : 0;
}

int run_blast(const char* ifname, int n) {
  port::SocketCanTransport t;
  if (!open_or_fail(t, ifname)) return 1;
  can::CanFrame f;
  f.id = 0x7F0;
  f.dlc = 8;
  int ok = 0, dropped = 0;
  for (int i = 0; i < n; ++i) {
    std::memcpy(f.data, &i, sizeof i);
    const CanIoStatus st = t.send(f);
    ok += st == CanIoStatus::Ok;
    dropped += st == CanIoStatus::Dropped;
  }
  const port::CanTransportCounters c = t.counters();
  print_counters("blast", c);
  std::printf("blast: %d sent, %d dropped of %d\n", ok, dropped, n);
  EXPECT(static_cast<uint64_t>(ok) == c.tx_frames && static_cast<uint64_t>(dropped) == c.tx_dropped &&
             ok + dropped == n,
         "every frame is either sent or counted as dropped");
  return g_failures ? 1 : 0;
}

int run_fd(const char* ifname) {
  port::SocketCanTransport t;
  if (!open_or_fail(t, ifname)) return 1;
  can::CanFrame f;
  f.id = 0x100;
  f.dlc = 12;  // an FD length
  EXPECT(t.send(f) == CanIoStatus::InvalidFrame, "FD-length frame must be refused");
  EXPECT(t.counters().tx_invalid == 1, "tx_invalid counted");
  std::printf("fd: %s\n", g_failures ? "FAILED" : "PASSED");
  return g_failures ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3) {
    const char* mode = argv[1];
    const char* ifname = argv[2];
    const int n = argc >= 4 ? std::atoi(argv[3]) : 100;
    if (!std::strcmp(mode, "peer")) return run_peer(ifname, n);
    if (!std::strcmp(mode, "echo")) return run_echo(ifname, n);
    if (!std::strcmp(mode, "ping")) return run_ping(ifname, n);
    if (!std::strcmp(mode, "blast")) return run_blast(ifname, n);
    if (!std::strcmp(mode, "fd")) return run_fd(ifname);
  }
  std::fprintf(stderr, "usage: %s peer|echo|ping|blast|fd IFNAME [N]\n", argv[0]);
  return 2;
}
