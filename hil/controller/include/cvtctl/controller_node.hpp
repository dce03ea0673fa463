// The example controller's CAN application (docs/sil.md#controller), written
// the way an ECU project uses cvtplant: only the core codec (cvt::can) and the
// port layer's transport interface. Heap-free, no exceptions.
//
// It collects the plant's output groups (PlantSpeeds, PlantRatio,
// PlantForces with one sample_tag), runs ClampLaw once per control period and
// sends CtrlCmd. A period without a fresh group (incomplete, mixed tags,
// E2E-rejected, or the sample it already used, e.g. a group the plant sent
// again) runs the law with plant_data_valid = false. Driven by a harness on
// the bus (docs/sil.md#external-lockstep), it takes the driver demand and the
// set-point from HarnessDemand and echoes its demand_tag in its commands.
#pragma once

#include <cstdint>

#include "cvtctl/clamp_law.hpp"
#include "cvtctl/ratio_law.hpp"
#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/can_transport.hpp"

namespace cvtctl {

struct ControllerCounters {
  std::uint32_t accepted = 0;
  std::uint32_t rejected = 0;        // any receive-pipeline rejection
  std::uint32_t resync_withheld = 0; // valid frames withheld while E2E re-synchronises (docs/can.md#e2e-checker)
  std::uint32_t error_frames = 0;
  std::uint32_t invalid_periods = 0; // control periods without a fresh group (stale inputs)
  std::uint32_t fresh_periods = 0;   // control periods with a fresh group
  std::uint32_t tx_failed = 0;
};

class ControllerNode {
 public:
  ControllerNode(cvt::port::CanTransport& bus, const ClampLawParams& p = {}, const RatioLawParams& rp = {})
      : bus_(bus), law_(p), ratio_law_(rp) {}

  // Start of a new run (the plant was reset): forget everything received.
  void restart() {
    rx_.reset_all();
    law_.reset();
    ratio_law_.reset();
    have_speeds_ = have_ratio_ = have_forces_ = have_status_ = have_shift_ = false;
    last_used_tag_ = -1;
    demand_pending_ = false;
  }

  // The harness reset the plant (a PlantStatus in Ready at sim time 0, the
  // answer to SimCtrl Reset, docs/sil.md#external-lockstep): a new run, so
  // the laws start again from rest. Cleared by the call.
  bool take_new_run() {
    const bool r = new_run_;
    new_run_ = false;
    if (r) {
      law_.reset();
      ratio_law_.reset();
      // A new harness may start its HarnessDemand counter anywhere.
      rx_.reset(cvt::can::MessageId::HarnessDemand);
    }
    return r;
  }

  // The ECU itself restarts: as restart(), and its CtrlCmd counter starts
  // again at 0 (docs/sil.md#fault-scenarios).
  void reboot() {
    tx_.reset();
    tx_shift_.reset();
    restart();
  }

  // Handles every queued frame, waiting up to wait_ns for the first.
  // Returns true once a PlantStatus arrived since the last control_step().
  bool poll(std::int64_t wait_ns) {
    cvt::can::CanFrame f;
    cvt::port::CanIoStatus st = bus_.receive(f, wait_ns);
    while (st != cvt::port::CanIoStatus::Timeout) {
      handle(st, f);
      st = bus_.receive(f, 0);
    }
    return have_status_;
  }

  // One control period: law on the latest group, then CtrlCmd.
  cvt::port::CanIoStatus control_step(float torque_demand_Nm) {
    ClampLawInputs in;
    in.torque_demand_Nm = torque_demand_Nm;
    in.plant_data_valid = fresh_group();
    if (in.plant_data_valid) {
      in.torque_transmitted_Nm = speeds_.torque_transmitted_Nm;
      in.slip = ratio_.slip;
      last_used_tag_ = speeds_.sample_tag;
      ++counters_.fresh_periods;
    } else {
      ++counters_.invalid_periods;
    }
    last_out_ = law_.step(in);
    have_speeds_ = have_ratio_ = have_forces_ = have_status_ = false;
    return send_command();
  }

  // One period of ratio control (docs/sil.md#ratio-control): RatioLaw on
  // the latest group (PlantShift included), then CtrlCmd (driver clamping,
  // torque request) and CtrlShiftCmd (driven clamping, the set-point).
  cvt::port::CanIoStatus control_step_ratio(float torque_demand_Nm, float ratio_target) {
    RatioLawInputs in;
    in.torque_demand_Nm = torque_demand_Nm;
    in.ratio_target = ratio_target;
    in.plant_data_valid = fresh_group() && have_shift_ && shift_.sample_tag == speeds_.sample_tag;
    if (in.plant_data_valid) {
      in.torque_transmitted_Nm = speeds_.torque_transmitted_Nm;
      in.slip = ratio_.slip;
      in.geometric_ratio = ratio_.geometric_ratio;
      in.radius_driver_m = shift_.radius_driver_m;
      in.on_end_stop = shift_.end_stop_underdrive || shift_.end_stop_overdrive;
      last_used_tag_ = speeds_.sample_tag;
      ++counters_.fresh_periods;
    } else {
      ++counters_.invalid_periods;
    }
    last_ratio_out_ = ratio_law_.step(in);
    last_out_.clamp_force_cmd_N = last_ratio_out_.driver_clamp_cmd_N;
    last_out_.driver_torque_req_Nm = last_ratio_out_.driver_torque_req_Nm;
    last_ratio_target_ = ratio_target;
    have_speeds_ = have_ratio_ = have_forces_ = have_status_ = have_shift_ = false;
    const cvt::port::CanIoStatus st = send_command();
    const cvt::port::CanIoStatus st2 = send_shift_command();
    return st != cvt::port::CanIoStatus::Ok ? st : st2;
  }

  // A HarnessDemand arrived since the last control step: the harness's
  // period has started (docs/sil.md#external-lockstep).
  bool demand_pending() const { return demand_pending_; }
  // A harness has sent HarnessDemand: the demand and set-point are its.
  bool has_demand() const { return have_demand_; }
  const cvt::can::HarnessDemand& demand() const { return demand_; }
  // One period on the harness's demand: the ratio law when it asks for ratio
  // control, else the clamping law.
  cvt::port::CanIoStatus control_step_demand() {
    demand_pending_ = false;
    if (demand_.ratio_control) return control_step_ratio(demand_.driver_demand_Nm, demand_.ratio_target);
    return control_step(demand_.driver_demand_Nm);
  }

  cvt::port::CanIoStatus send_shift_command() {
    cvt::can::CtrlShiftCmd cmd;
    cmd.demand_tag = demand_.demand_tag;
    cmd.driven_clamp_force_cmd_N = clamp_f(last_ratio_out_.driven_clamp_cmd_N, 0.0f, 60000.0f);
    cmd.ratio_target = clamp_f(last_ratio_target_, 0.0f, 6.5f);
    return send_message(cmd, tx_shift_);
  }

  // The last command once more, with the next E2E counter (a controller that
  // sends faster than its cycle; the SIL flood scenario uses it).
  cvt::port::CanIoStatus send_command() {
    cvt::can::CtrlCmd cmd;
    cmd.demand_tag = demand_.demand_tag;
    cmd.clamp_force_cmd_N = last_out_.clamp_force_cmd_N;
    cmd.driver_torque_req_Nm = clamp_f(last_out_.driver_torque_req_Nm, -600.0f, 600.0f);
    return send_message(cmd, tx_);
  }

  // Encodes (next E2E counter) and sends one command; failures are counted.
  template <class Msg>
  cvt::port::CanIoStatus send_message(const Msg& m, cvt::can::TxChannel<Msg>& ch) {
    cvt::can::CanFrame f;
    if (ch.encode(m, f) != cvt::can::CodecStatus::Ok) {
      ++counters_.tx_failed;
      return cvt::port::CanIoStatus::InvalidFrame;
    }
    const cvt::port::CanIoStatus st = bus_.send(f);
    if (st != cvt::port::CanIoStatus::Ok) ++counters_.tx_failed;
    return st;
  }

  // A complete group arrived since the last control step (all three frames
  // with one sample_tag).
  bool group_complete() const {
    return have_speeds_ && have_ratio_ && have_forces_ && speeds_.sample_tag == ratio_.sample_tag &&
           speeds_.sample_tag == forces_.sample_tag;
  }
  // ... and it is not the sample the last step already used: a group the
  // plant sent again (docs/sil.md#lost-frames) carries the used sample's
  // tag and comes before any newer sample.
  bool fresh_group() const { return group_complete() && speeds_.sample_tag != last_used_tag_; }
  const cvt::can::PlantSpeeds& speeds() const { return speeds_; }
  const cvt::can::PlantRatio& ratio() const { return ratio_; }
  const cvt::can::PlantForces& forces() const { return forces_; }
  const cvt::can::PlantStatus& status() const { return status_; }
  const ClampLawOutputs& last_output() const { return last_out_; }
  const RatioLawOutputs& last_ratio_output() const { return last_ratio_out_; }
  const cvt::can::PlantShift& shift() const { return shift_; }
  const ClampLaw& law() const { return law_; }
  const ControllerCounters& counters() const { return counters_; }

 private:
  void handle(cvt::port::CanIoStatus st, const cvt::can::CanFrame& f) {
    if (st == cvt::port::CanIoStatus::ErrorFrame) {
      ++counters_.error_frames;
      return;
    }
    if (st != cvt::port::CanIoStatus::Ok) return;
    // Only the plant's outputs are inputs of this ECU; its own CtrlCmd and
    // the harness's frames are not checked here.
    switch (f.id) {
      case cvt::can::PlantSpeeds::kId:
      case cvt::can::PlantRatio::kId:
      case cvt::can::PlantForces::kId:
      case cvt::can::PlantShift::kId:
      case cvt::can::PlantStatus::kId:
      case cvt::can::PlantDiag::kId:
      case cvt::can::HarnessDemand::kId: break;
      default: return;
    }
    const cvt::can::RxResult r = rx_.receive(f, any_);
    if (!r.accepted()) {
      if (r.e2e == cvt::can::E2eStatus::Sync && r.codec == cvt::can::CodecStatus::Ok) ++counters_.resync_withheld;
      else ++counters_.rejected;
      return;
    }
    ++counters_.accepted;
    switch (any_.which) {
      case cvt::can::MessageId::PlantSpeeds:
        speeds_ = any_.plant_speeds;
        have_speeds_ = true;
        // A newer sample is in: the used tag can come round again (4 bits)
        // without meaning a repeat.
        if (speeds_.sample_tag != last_used_tag_) last_used_tag_ = -1;
        break;
      case cvt::can::MessageId::PlantRatio: ratio_ = any_.plant_ratio; have_ratio_ = true; break;
      case cvt::can::MessageId::PlantForces: forces_ = any_.plant_forces; have_forces_ = true; break;
      case cvt::can::MessageId::PlantShift: shift_ = any_.plant_shift; have_shift_ = true; break;
      case cvt::can::MessageId::PlantStatus:
        status_ = any_.plant_status;
        have_status_ = true;
        if (status_.plant_mode == cvt::can::PlantMode::Ready && status_.sim_time_us == 0) new_run_ = true;
        break;
      case cvt::can::MessageId::HarnessDemand:
        demand_ = any_.harness_demand;
        demand_pending_ = have_demand_ = true;
        break;
      default: break;
    }
  }

  cvt::port::CanTransport& bus_;
  ClampLaw law_;
  RatioLaw ratio_law_;
  cvt::can::TxChannel<cvt::can::CtrlShiftCmd> tx_shift_;
  cvt::can::PlantShift shift_{};
  bool have_shift_ = false;
  RatioLawOutputs last_ratio_out_{};
  float last_ratio_target_ = 0.0f;
  cvt::can::RxBank rx_;
  cvt::can::AnyMessage any_;
  cvt::can::TxChannel<cvt::can::CtrlCmd> tx_;
  cvt::can::PlantSpeeds speeds_{};
  cvt::can::PlantRatio ratio_{};
  cvt::can::PlantForces forces_{};
  cvt::can::PlantStatus status_{};
  bool have_speeds_ = false, have_ratio_ = false, have_forces_ = false, have_status_ = false;
  int last_used_tag_ = -1;
  cvt::can::HarnessDemand demand_{};
  bool demand_pending_ = false, have_demand_ = false, new_run_ = false;
  ClampLawOutputs last_out_{};
  ControllerCounters counters_{};
};

}  // namespace cvtctl
