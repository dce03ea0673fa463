// Faults a SIL scenario injects into a node's link (docs/sil.md#fault-scenarios).
// Host only (the harness).
#pragma once

#include <cstdint>
#include <cstring>

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
  // Scales both clamping commands on the wire (CtrlCmd, CtrlShiftCmd) by
  // `s`, counter kept and CRC recomputed: the actuators' supply pressure
  // dropping to a fraction, which the controller sees only as slip.
  void scale_clamp(float s) { clamp_scale_ = s; }
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
    if (clamp_scale_ != 1.0f && f.dlc == 8 && (f.id == cvt::can::CtrlCmd::kId || f.id == cvt::can::CtrlShiftCmd::kId)) {
      cvt::can::CanFrame g = f;
      if (f.id == cvt::can::CtrlCmd::kId) rescale<cvt::can::CtrlCmd>(g, [this](cvt::can::CtrlCmd& m) {
          m.clamp_force_cmd_N *= clamp_scale_;
        });
      else rescale<cvt::can::CtrlShiftCmd>(g, [this](cvt::can::CtrlShiftCmd& m) {
          m.driven_clamp_force_cmd_N *= clamp_scale_;
        });
      return inner_.send(g);
    }
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
  template <class Msg, class Edit>
  static void rescale(cvt::can::CanFrame& g, Edit edit) {
    Msg m;
    if (cvt::can::unpack(g.data, m) != cvt::can::CodecStatus::Ok) return;
    edit(m);
    std::uint8_t q[8];
    if (cvt::can::pack(m, q) != cvt::can::CodecStatus::Ok) return;
    q[1] = static_cast<std::uint8_t>((q[1] & 0xF0u) | (g.data[1] & 0x0Fu));
    q[0] = cvt::can::e2e_crc(Msg::kE2eDataId, q);
    std::memcpy(g.data, q, 8);
  }

  cvt::port::CanTransport& inner_;
  float clamp_scale_ = 1.0f;
  std::int64_t lose_tx_ = -1, lose_rx_ = -1;
  bool frozen_ = false, have_last_ = false;
  cvt::can::CanFrame last_{};
  std::uint32_t lost_ = 0;
};

}  // namespace cvt::sil::harness
