#include "cvtplant/sil/harness/example_controller.hpp"

#include <cmath>

#include "cvtplant/can/bits.hpp"

namespace cvt::sil::harness {

void ExampleController::begin_run(const Scenario&) {
  node_.poll(100000000);
  // Every run starts its E2E counters at 0, as the bridge's Reset expects
  // (docs/sil.md#lock-step): a scenario's counter sequence does not depend
  // on the scenarios before it.
  node_.reboot();
}

void ExampleController::control_period(const Scenario& sc, int k, double t) {
  const Faults& fx = sc.faults;
  const bool silent = t >= sc.link_loss_start_s && t < sc.link_loss_end_s;
  faults_.freeze(in_window(t, fx.freeze_start_s, fx.freeze_end_s));
  if (fx.reboot_s >= 0 && std::fabs(t - fx.reboot_s) < 1e-9) node_.reboot();
  for (const int lost : fx.lost_cmd_periods)
    if (lost == k) faults_.lose_next_sent(cvt::can::CtrlCmd::kId);
  if (!silent && sc.ratio_target) {
    node_.control_step_ratio(sc.demand_Nm(t), sc.ratio_target(t));
  } else if (!silent) {
    node_.control_step(sc.demand_Nm(t));
    if (in_window(t, fx.flood_start_s, fx.flood_end_s))
      for (int i = 1; i < fx.flood_frames; ++i) node_.send_command();
  }
}

void ExampleController::after_step() {
  // The controller's socket got the same group; wait until it has it
  // complete (a group the bridge sent again is not new to it).
  for (int i = 0; i < 1000 && !(node_.poll(10000000), node_.fresh_group()); ++i) {
  }
}

void ExampleController::end_run() { faults_.freeze(false); }

// The commands as they go on the wire, at the DBC's 1 N resolution and its
// rounding (an external controller's are decoded from its frames): a law's
// 18052.5 N is 18053 N in both traces.
Commands ExampleController::commands() const {
  const auto wire = [](float n) { return static_cast<float>(cvt::can::bits::round_to_i32(n)); };
  return {wire(node_.last_output().clamp_force_cmd_N), wire(node_.last_ratio_output().driven_clamp_cmd_N)};
}

void ExampleController::rt_begin(const Scenario&) {
  node_.poll(100000000);
  node_.reboot();
  sched_ = cvtctl::ControlSchedule{};
  steps_ = fresh_steps_ = 0;
}

// On every fresh group (ControlSchedule, as cvtplant-controller does).
RealtimeStep ExampleController::rt_step(const Scenario& sc, std::int64_t now, double t) {
  RealtimeStep r;
  if (!sched_.due(now, node_.fresh_group())) return r;
  node_.poll(0);  // whatever else is queued: the newest group wins
  r.ran = true;
  r.fresh = node_.fresh_group();
  node_.control_step_ratio(sc.demand_Nm(t), sc.ratio_target(t));
  sched_.ran(now);
  ++steps_;
  if (r.fresh) ++fresh_steps_;
  return r;
}

void ExampleController::add_realtime_checks(double periods, std::vector<Check>& c) {
  c.push_back({"control_on_fresh_groups", fresh_steps_ >= 0.95 * periods,
               fmt("%.0f control steps on a fresh group of %.0f steps (at least 95 %% of %.0f periods)",
                   static_cast<double>(fresh_steps_), static_cast<double>(steps_), periods)});
}

}  // namespace cvt::sil::harness
