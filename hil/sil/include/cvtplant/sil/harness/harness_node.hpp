// The Harness node of the SIL bus (docs/sil.md#lock-step): SimCtrl requests
// with their resend on a lost frame, HarnessLoad, and the plant's output
// groups read through the E2E receive pipeline. Host only.
#pragma once

#include <cstdint>
#include <functional>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/can_transport.hpp"
#include "cvtplant/port/posix_clock.hpp"

namespace cvt::sil::harness {

// A hang guard, not a criterion: the starved TCG micro-VM has shown single
// round trips of 1.6 s (docs/sil.md#figures).
inline constexpr std::int64_t kReplyTimeout_ns = 10000000000;

class HarnessNode {
 public:
  // on_idle runs whenever the bus has nothing for the harness: with the
  // bridge in-process on the loopback bus (--loopback) it services the bridge.
  HarnessNode(cvt::port::CanTransport& bus, std::int64_t reply_timeout_ns, std::function<void()> on_idle = {})
      : bus_(bus), reply_timeout_ns_(reply_timeout_ns), on_idle_(std::move(on_idle)) {}

  // One request and its complete answer (docs/sil.md#lost-frames): when no
  // PlantStatus acknowledging it arrives within the reply timeout, or the
  // group around it is incomplete, the same request (same step_seq, next
  // E2E counter) is sent again, up to kMaxResends times. The bridge
  // executes a step_seq once and answers a repeat with the same group.
  bool request(cvt::can::SimRequest r, std::uint16_t steps, cvt::can::SceneId scene);

  // The bridge may still hold another harness's last SimCtrl counter and
  // step_seq, which ours could repeat: a None request that is answered
  // (executing nothing either way) proves the next counter and step_seq
  // are taken as new (docs/can.md#e2e-checker, docs/sil.md#lost-frames).
  bool sync(int attempts = 5);

  // Real time (docs/sil.md#ratio-realtime): SimCtrl RunRealTime, which the
  // bridge does not answer; it paces its frames from then on.
  bool start_realtime();

  // Back to Ready with the closing diagnostics. A real-time PlantStatus
  // acknowledges step_seq 0, so the Pause never uses 0: the answer cannot
  // be mistaken for a cyclic status still on its way (skipping a value is
  // not a repeat for the bridge).
  bool pause();

  // Reads every frame already queued (a real-time run's cyclic frames).
  void drain();
  std::uint32_t realtime_statuses() const { return realtime_statuses_; }

  // HarnessLoad: the load override, and the clamping supply's fraction.
  bool send_load(bool active, float torque_Nm, float clamp_supply = 1.0f);

  // The plant's published parameters (docs/sil.md#published-parameters),
  // from the last group that carried them (every answer to Reset).
  bool has_params() const { return has_params_; }
  const cvt::can::PlantParams& params() const { return params_; }

  const cvt::can::PlantStatus& status() const { return status_; }
  const cvt::can::PlantForces& forces() const { return forces_; }
  const cvt::can::PlantShift& shift() const { return shift_; }
  // A variable-ratio scene's groups also carry PlantShift (docs/can.md#layout).
  // A fixed-ratio scene sends none: the last one of another scene is forgotten.
  void expect_shift(bool on) {
    expect_shift_ = on;
    if (!on) shift_ = cvt::can::PlantShift{};
  }
  const cvt::can::PlantSpeeds& speeds() const { return speeds_; }
  const cvt::can::PlantRatio& ratio() const { return ratio_; }
  const cvt::can::PlantDiag& diag() const { return diag_; }
  const cvt::can::PlantCmdDiag& cmd_diag() const { return cmd_diag_; }
  const cvt::can::PlantBusDiag& bus_diag() const { return bus_diag_; }
  std::uint32_t rejected() const { return rejected_; }
  std::uint32_t mixed_groups() const { return mixed_groups_; }
  std::uint32_t resends() const { return resends_; }
  std::uint32_t no_reply() const { return no_reply_; }
  std::uint32_t partial_groups() const { return partial_groups_; }
  std::int64_t max_recovery_ns() const { return max_recovery_ns_; }
  void clear_recovery() { max_recovery_ns_ = 0; }

 private:
  static constexpr int kMaxResends = 3;
  enum class Reply { None, Partial, Complete };

  // Reads the bus until the PlantStatus acknowledging `seq` (the end of the
  // group), checking every plant frame through the E2E receive pipeline.
  // Complete: the three state frames before it carry its sample_tag.
  Reply wait_status(std::uint8_t seq, std::int64_t timeout_ns);

  // One received frame through the E2E receive pipeline into the latest
  // plant state; true when it was an accepted PlantStatus.
  bool take(const cvt::can::CanFrame& f);

  cvt::port::CanTransport& bus_;
  std::int64_t reply_timeout_ns_;
  std::function<void()> on_idle_;
  cvt::port::PosixMonotonicClock clock_;
  std::int64_t max_recovery_ns_ = 0;
  cvt::can::TxChannel<cvt::can::SimCtrl> sim_;
  cvt::can::TxChannel<cvt::can::HarnessLoad> load_;
  cvt::can::RxBank rx_;
  std::uint8_t seq_ = 0;
  cvt::can::PlantStatus status_{};
  cvt::can::PlantSpeeds speeds_{};
  cvt::can::PlantRatio ratio_{};
  cvt::can::PlantForces forces_{};
  cvt::can::PlantShift shift_{};
  bool expect_shift_ = false;
  cvt::can::PlantDiag diag_{};
  cvt::can::PlantBusDiag bus_diag_{};
  cvt::can::PlantCmdDiag cmd_diag_{};
  cvt::can::PlantParams params_{};
  bool has_params_ = false;
  std::uint32_t rejected_ = 0, mixed_groups_ = 0, resends_ = 0, no_reply_ = 0, partial_groups_ = 0;
  std::uint32_t realtime_statuses_ = 0;
};

}  // namespace cvt::sil::harness
