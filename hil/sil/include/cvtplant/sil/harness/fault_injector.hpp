// Faults a SIL scenario injects into a node's link (docs/sil.md#fault-scenarios).
// Host only (the harness).
#pragma once

#include <cstdint>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/can_transport.hpp"

namespace cvt::sil::harness {

// Wraps a node's transport to lose frames on purpose (docs/sil.md#lost-frames):
// the next sent frame with an ID (lost on the wire: the sender sees Ok, as
// on CAN), the next received frame with an ID (lost to this receiver, e.g. a
// queue overflow), and a frozen mode in which every send repeats the last
// frame sent before the freeze (a hung ECU whose CAN driver keeps sending
// its mailbox). Works on any transport, so the scenarios run the same on
// vcan and on the loopback bus.
class FaultInjector final : public cvt::port::CanTransport {
 public:
  explicit FaultInjector(cvt::port::CanTransport& inner) : inner_(inner) {}

  void lose_next_sent(std::uint32_t id) { lose_tx_ = static_cast<std::int64_t>(id); }
  void lose_next_received(std::uint32_t id) { lose_rx_ = static_cast<std::int64_t>(id); }
  void freeze(bool on) { frozen_ = on && have_last_; }
  std::uint32_t lost() const { return lost_; }

  cvt::port::CanIoStatus send(const cvt::can::CanFrame& f) noexcept override {
    if (lose_tx_ == static_cast<std::int64_t>(f.id)) {
      lose_tx_ = -1;
      ++lost_;
      return cvt::port::CanIoStatus::Ok;
    }
    if (frozen_) return inner_.send(last_);
    last_ = f;
    have_last_ = true;
    return inner_.send(f);
  }
  cvt::port::CanIoStatus receive(cvt::can::CanFrame& out, std::int64_t timeout_ns) noexcept override {
    cvt::port::CanIoStatus st = inner_.receive(out, timeout_ns);
    if (st == cvt::port::CanIoStatus::Ok && lose_rx_ == static_cast<std::int64_t>(out.id)) {
      lose_rx_ = -1;
      ++lost_;
      st = inner_.receive(out, 0);
    }
    return st;
  }
  cvt::port::CanTransportCounters counters() const noexcept override { return inner_.counters(); }
  cvt::port::CanBusState bus_state() const noexcept override { return inner_.bus_state(); }

 private:
  cvt::port::CanTransport& inner_;
  std::int64_t lose_tx_ = -1, lose_rx_ = -1;
  bool frozen_ = false, have_last_ = false;
  cvt::can::CanFrame last_{};
  std::uint32_t lost_ = 0;
};

}  // namespace cvt::sil::harness
