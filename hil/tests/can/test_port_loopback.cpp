// Port layer: loopback transport, virtual and POSIX clocks, SocketCAN error
// reporting when the kernel lacks SocketCAN (docs/can.md#port).
#include <doctest/doctest.h>

#include <cstring>
#include <initializer_list>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/port/socketcan_transport.hpp"

using namespace cvt;
using port::CanBusState;
using port::CanIoStatus;

namespace {
can::CanFrame data_frame(uint32_t id, uint8_t fill) {
  can::CanFrame f;
  f.id = id;
  f.dlc = 8;
  for (uint8_t& b : f.data) b = fill++;
  return f;
}
}  // namespace

TEST_CASE("loopback delivers to every other node, not to the sender") {
  port::LoopbackBus<3, 4> bus;
  const can::CanFrame f = data_frame(0x123, 1);
  REQUIRE(bus.node(0).send(f) == CanIoStatus::Ok);
  can::CanFrame r;
  CHECK(bus.node(0).receive(r, 0) == CanIoStatus::Timeout);
  for (size_t i : {size_t{1}, size_t{2}}) {
    REQUIRE(bus.node(i).receive(r, 0) == CanIoStatus::Ok);
    CHECK(r.id == 0x123);
    CHECK(std::memcmp(r.data, f.data, 8) == 0);
    CHECK(bus.node(i).counters().rx_frames == 1);
  }
  CHECK(bus.node(0).counters().tx_frames == 1);
}

TEST_CASE("loopback ring overflow drops the newest frames and counts them") {
  port::LoopbackBus<2, 3> bus;
  for (uint8_t i = 0; i < 5; ++i) REQUIRE(bus.node(0).send(data_frame(0x100 + i, i)) == CanIoStatus::Ok);
  CHECK(bus.node(1).counters().rx_kernel_drops == 2);
  can::CanFrame r;
  for (uint32_t i = 0; i < 3; ++i) {
    REQUIRE(bus.node(1).receive(r, 0) == CanIoStatus::Ok);
    CHECK(r.id == 0x100 + i);  // FIFO, oldest kept
  }
  CHECK(bus.node(1).receive(r, 0) == CanIoStatus::Timeout);
}

TEST_CASE("loopback drop filter: a frame lost on the wire reaches no node, the sender sees Ok") {
  port::LoopbackBus<3, 8> bus;
  // Drop every second frame with ID 0x200 that node 0 sends.
  struct Ctx {
    int seen = 0;
  } ctx;
  bus.set_drop_filter(
      [](void* c, size_t from, const can::CanFrame& f) {
        return from == 0 && f.id == 0x200 && (static_cast<Ctx*>(c)->seen++ % 2) == 1;
      },
      &ctx);
  for (uint8_t i = 0; i < 4; ++i) CHECK(bus.node(0).send(data_frame(0x200, i)) == CanIoStatus::Ok);
  CHECK(bus.node(1).send(data_frame(0x200, 9)) == CanIoStatus::Ok);  // another sender: kept
  CHECK(bus.frames_dropped() == 2);
  for (size_t n : {size_t{1}, size_t{2}}) CHECK(bus.node(n).pending() == (n == 1 ? 2u : 3u));
  can::CanFrame r;
  REQUIRE(bus.node(2).receive(r, 0) == CanIoStatus::Ok);
  CHECK(r.data[0] == 0);
  REQUIRE(bus.node(2).receive(r, 0) == CanIoStatus::Ok);
  CHECK(r.data[0] == 2);
  bus.set_drop_filter(nullptr);
  CHECK(bus.node(0).send(data_frame(0x200, 7)) == CanIoStatus::Ok);
  CHECK(bus.frames_dropped() == 2);
  CHECK(bus.node(0).counters().tx_frames == 5);  // the sender cannot tell
}

TEST_CASE("transmit buffer exhaustion: bounded retries, then counted drop") {
  using Bus = port::LoopbackBus<2, 8>;
  Bus bus;
  bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound);
  CHECK(bus.node(0).send(data_frame(0x10, 0)) == CanIoStatus::Ok);
  CHECK(bus.node(0).counters().tx_enobufs_retries == Bus::kTxRetryBound);
  CHECK(bus.node(0).counters().tx_dropped == 0);
  bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound + 1);
  CHECK(bus.node(0).send(data_frame(0x11, 0)) == CanIoStatus::Dropped);
  CHECK(bus.node(0).counters().tx_enobufs_retries == 2 * Bus::kTxRetryBound);
  CHECK(bus.node(0).counters().tx_dropped == 1);
  CHECK(bus.node(1).pending() == 1);  // only the frame that made it
}

TEST_CASE("invalid frames are refused on send") {
  port::LoopbackBus<2, 4> bus;
  can::CanFrame f = data_frame(0x800, 0);  // not an 11-bit ID
  CHECK(bus.node(0).send(f) == CanIoStatus::InvalidFrame);
  f = data_frame(0x100, 0);
  f.dlc = 9;  // CAN FD length on a classic bus
  CHECK(bus.node(0).send(f) == CanIoStatus::InvalidFrame);
  f.dlc = 8;
  f.flags = can::kFrameError;
  CHECK(bus.node(0).send(f) == CanIoStatus::InvalidFrame);
  CHECK(bus.node(0).counters().tx_invalid == 3);
  CHECK(bus.node(1).pending() == 0);
}

TEST_CASE("error frames are reported with bus state, never as data") {
  port::LoopbackBus<2, 8> bus;
  auto& n = bus.node(1);
  bus.inject_error(1, port::can_err::kController, port::can_err::kCtrlRxWarning);
  bus.inject_error(1, port::can_err::kController, port::can_err::kCtrlTxPassive);
  bus.inject_error(1, port::can_err::kBusOff);
  bus.inject_error(1, port::can_err::kRestarted);
  can::CanFrame r;
  CHECK(n.receive(r, 0) == CanIoStatus::ErrorFrame);
  CHECK(n.bus_state() == CanBusState::ErrorWarning);
  // The codec refuses an error frame even if a caller tried to decode it.
  can::AnyMessage any;
  CHECK(can::decode_any(r, any) == can::CodecStatus::NotDataFrame);
  CHECK(n.receive(r, 0) == CanIoStatus::ErrorFrame);
  CHECK(n.bus_state() == CanBusState::ErrorPassive);
  CHECK(n.receive(r, 0) == CanIoStatus::ErrorFrame);
  CHECK(n.bus_state() == CanBusState::BusOff);
  CHECK(n.send(data_frame(0x100, 0)) == CanIoStatus::BusOff);
  CHECK(n.receive(r, 0) == CanIoStatus::ErrorFrame);
  CHECK(n.bus_state() == CanBusState::ErrorActive);
  CHECK(n.send(data_frame(0x100, 0)) == CanIoStatus::Ok);
  const port::CanTransportCounters c = n.counters();
  CHECK(c.rx_error_frames == 4);
  CHECK(c.bus_off_events == 1);
  CHECK(c.rx_frames == 0);
}

TEST_CASE("virtual clock: a receive timeout advances simulated time, no wall time") {
  port::VirtualClock clk(1000);
  port::LoopbackBus<2, 4> bus(&clk);
  can::CanFrame r;
  CHECK(bus.node(1).receive(r, 5000000) == CanIoStatus::Timeout);
  CHECK(clk.now_ns() == 1000 + 5000000);
  clk.sleep_until(10);  // in the past: no effect
  CHECK(clk.now_ns() == 5001000);
  clk.advance(-5);  // time never runs backwards
  CHECK(clk.now_ns() == 5001000);
}

TEST_CASE("CAN link over loopback: E2E, codec and the timeout reaction") {
  port::VirtualClock clk;
  port::LoopbackBus<2, 16> bus(&clk);
  can::TxChannel<can::CtrlCmd> tx;
  can::RxChannel<can::CtrlCmd> rx;
  can::CtrlCmd cmd, applied;
  can::CanFrame f;
  int64_t last_rx_ns = 0;
  for (int i = 0; i < 20; ++i) {
    cmd.clamp_force_cmd_N = 1000.0f + 10.0f * static_cast<float>(i);
    REQUIRE(tx.encode(cmd, f) == can::CodecStatus::Ok);
    REQUIRE(bus.node(0).send(f) == CanIoStatus::Ok);
    REQUIRE(bus.node(1).receive(f, 0) == CanIoStatus::Ok);
    REQUIRE(rx.receive(f, applied).accepted());
    last_rx_ns = clk.now_ns();
    clk.advance(can::CtrlCmd::kCycleTime_ms * 1000000LL);
  }
  CHECK(applied.clamp_force_cmd_N == 1190.0f);
  // Link silent: the receiver waits; after kRxTimeout_ms it applies the
  // DBC's reaction and requires its E2E state to re-synchronise
  // (docs/can.md#timeouts).
  while (bus.node(1).receive(f, 1000000) == CanIoStatus::Timeout &&
         clk.now_ns() - last_rx_ns < can::CtrlCmd::kRxTimeout_ms * 1000000LL) {
  }
  CHECK(clk.now_ns() - last_rx_ns >= can::CtrlCmd::kRxTimeout_ms * 1000000LL);
  applied = can::on_rx_timeout(applied);
  rx.require_resync();
  CHECK(applied.clamp_force_cmd_N == 1190.0f);  // the DBC's Ramp starts from the last value
  applied = can::rx_timeout_ramp(applied, 0.5f);
  CHECK(applied.clamp_force_cmd_N == 20000.0f);  // 1190 + 25000 capped at the substitute
  CHECK(rx.checker().resynchronising());
}

TEST_CASE("POSIX monotonic clock: non-decreasing, sleep_until reaches the deadline") {
  port::PosixMonotonicClock c;
  const int64_t t0 = c.now_ns();
  const int64_t t1 = c.now_ns();
  CHECK(t1 >= t0);
  const int64_t deadline = t1 + 2000000;
  c.sleep_until(deadline);
  CHECK(c.now_ns() >= deadline);
  c.sleep_until(t0);  // past: returns at once
}

TEST_CASE("SocketCAN: a failing open names the step and the reason") {
  port::SocketCanTransport t;
  const int err = t.open("cvtnonexist0");
  CHECK(err != 0);
  CHECK_FALSE(t.is_open());
  CHECK(std::strlen(t.error_text()) > 0);
  MESSAGE("open(cvtnonexist0): " << t.error_text());
  can::CanFrame f;
  CHECK(t.send(data_frame(0x100, 0)) == CanIoStatus::IoError);
  CHECK(t.receive(f, 0) == CanIoStatus::IoError);
  port::SocketCanTransport u;
  CHECK(u.open("an-interface-name-far-too-long") != 0);
}
