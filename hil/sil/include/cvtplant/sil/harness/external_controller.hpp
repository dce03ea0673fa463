// A controller under test that is not the harness's own: a process (or an
// ECU) on the bus, driven through the protocol of docs/sil.md#external-lockstep.
// Each period the harness sends HarnessDemand (driver demand, ratio set-point,
// a 4-bit demand_tag) and waits, up to a wall-clock timeout, for the
// controller's CtrlCmd (and CtrlShiftCmd when it controls the ratio) echoing
// that tag; only then does it step the plant. Every command frame passes the
// harness's own E2E and range checks, so a silent, late or malformed
// controller is a failed criterion with the first period it happened, never a
// hang. In real time the harness sends HarnessDemand every 10 ms and measures
// the controller's command intervals. Host only.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/can_transport.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/sil/harness/controller.hpp"

namespace cvt::sil::harness {

struct ExternalOptions {
  // How long the harness waits for the controller's commands of a period
  // (the one wall-clock element of lock-step; docs/sil.md#external-lockstep).
  std::int64_t answer_timeout_ns = 1000000000;
  // After a period the controller left unanswered, the following periods wait
  // only this long until it answers again: a dead controller costs one
  // timeout, not one per period.
  std::int64_t silent_wait_ns = 10000000;
  // How long wait_ready() waits for a controller to come on the bus.
  std::int64_t start_timeout_ns = 10000000000;
};

// The first period a kind of misbehaviour was seen, how often, and what.
struct Misbehaviour {
  int first_period = -1;
  long count = 0;
  std::string first_what;
  void note(int period, const std::string& what) {
    if (first_period < 0 || period < first_period) {
      first_period = period;
      first_what = what;
    }
    ++count;
  }
};

class ExternalController final : public ControllerUnderTest {
 public:
  // `bus`: a transport of the harness's own for this protocol. `idle`
  // services nodes in this process (an in-process plant and controller on
  // the loopback bus) while the harness waits in lock-step; `rt_idle` the
  // in-process controller in real time (the plant is paced by the runner).
  ExternalController(cvt::port::CanTransport& bus, const ExternalOptions& o, std::function<void()> idle = {},
                     std::function<void()> rt_idle = {})
      : bus_(bus), opt_(o), idle_(std::move(idle)), rt_idle_(std::move(rt_idle)) {}

  bool can_run(const Scenario& sc, std::string& why) const override { return accepts(sc, why); }

  // Before the first run: a controller started with the runs
  // (--controller-cmd) opens its socket some time after it was started, and
  // would miss the first Reset's answer with the plant's parameters. A
  // HarnessDemand (no ratio control, demand 0) every 200 ms until a CtrlCmd
  // echoes it, up to start_timeout_ns: then it is on the bus. False when it
  // never answered.
  bool wait_ready();
  // Scenarios whose faults are injected into the controller's own link or
  // software need the example controller.
  static bool accepts(const Scenario& sc, std::string& why);

  void begin_run(const Scenario& sc) override;
  void control_period(const Scenario& sc, int k, double t) override;
  void after_step() override;
  void end_run() override {}
  Commands commands() const override { return commands_; }

  std::uint32_t rejected() const override { return 0; }
  std::uint32_t lost_on_purpose() const override { return 0; }
  bool observes_rejections() const override { return false; }
  void add_checks(const Scenario& sc, std::vector<Check>& c) override;

  void rt_begin(const Scenario& sc) override;
  void rt_receive(std::int64_t now, std::int64_t wait_ns) override;
  RealtimeStep rt_step(const Scenario& sc, std::int64_t now, double t) override;
  GroupView group() const override { return {speeds_, ratio_, forces_, shift_}; }
  void rt_end() override {}
  void add_realtime_checks(double periods, std::vector<Check>& c) override;

  // For tests: what the last run saw.
  const Misbehaviour& silent() const { return silent_; }
  const Misbehaviour& late() const { return late_; }
  const Misbehaviour& invalid_e2e() const { return e2e_; }
  const Misbehaviour& out_of_range() const { return range_; }
  // Periods whose wait ended at the full answer timeout, and at the short
  // wait for a controller that stayed silent.
  long full_timeouts() const { return full_timeouts_; }
  long short_timeouts() const { return short_timeouts_; }

 private:
  enum Kind : int { kCmd = 0, kShift = 1 };
  struct PeriodAnswers {
    bool on_time[2] = {false, false};
    bool late[2] = {false, false};
  };

  void reset_run();
  bool send_demand(std::uint8_t tag, float demand_Nm, float ratio_target, bool ratio_control);
  // One received frame; `period` is the period the harness is in, `waiting`
  // whether that period's deadline has not passed yet.
  void take(const cvt::can::CanFrame& f, int period, bool waiting);
  template <class Msg>
  void take_command(const cvt::can::CanFrame& f, Kind kind, cvt::can::E2eChecker& ck, int period, bool waiting);
  void take_plant(const cvt::can::CanFrame& f);
  bool answered(int k) const;
  double period_s(int k) const { return k * kPeriod_s; }

  cvt::port::CanTransport& bus_;
  ExternalOptions opt_;
  std::function<void()> idle_, rt_idle_;
  cvt::port::PosixMonotonicClock wall_;
  cvt::can::TxChannel<cvt::can::HarnessDemand> tx_demand_;
  cvt::can::E2eChecker cmd_check_{cvt::can::CtrlCmd::kE2eDataId,
                                  {cvt::can::CtrlCmd::kE2eMaxDeltaCounter, cvt::can::CtrlCmd::kE2eSyncCounterInit}};
  cvt::can::E2eChecker shift_check_{
      cvt::can::CtrlShiftCmd::kE2eDataId,
      {cvt::can::CtrlShiftCmd::kE2eMaxDeltaCounter, cvt::can::CtrlShiftCmd::kE2eSyncCounterInit}};
  cvt::can::RxBank plant_rx_;

  // One run.
  bool ratio_control_ = false, realtime_ = false, quiet_ = false;
  int period_ = 0;
  std::uint8_t tag_ = 0;
  std::vector<PeriodAnswers> answers_;
  Misbehaviour silent_, late_, e2e_, range_;
  long frames_checked_[2] = {0, 0};
  std::uint32_t lost_by_counter_ = 0;
  long full_timeouts_ = 0, short_timeouts_ = 0;
  Commands commands_{};

  // Real time: the plant's groups as this node sees them, and the command
  // intervals on the pacing clock.
  cvt::can::PlantSpeeds speeds_{};
  cvt::can::PlantRatio ratio_{};
  cvt::can::PlantForces forces_{};
  cvt::can::PlantShift shift_{};
  bool have_[4] = {false, false, false, false};
  int last_used_tag_ = -1;
  std::int64_t t0_ = -1, next_demand_ = 0, last_cmd_ns_ = -1, last_group_ns_ = -1, last_now_ = 0;
  bool group_waiting_ = false;
  std::vector<std::int64_t> intervals_, responses_;
};

}  // namespace cvt::sil::harness
