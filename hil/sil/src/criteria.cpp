#include "cvtplant/sil/harness/criteria.hpp"

#include <cmath>
#include <cstdio>

namespace cvt::sil::harness {

std::string fmt(const char* f, double a, double b, double c) {
  char buf[240];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

Check measured(std::string name, bool pass, std::string detail, double value, double limit) {
  Check c{std::move(name), pass, std::move(detail)};
  c.value = value;
  c.limit = limit;
  return c;
}

std::string plant_fault_reason(const cvt::can::PlantDiag& diag, const std::string& message) {
  std::string r = std::string(cvt::can::to_string(diag.plant_fault)) + " (PlantDiag.plant_fault)";
  return message.empty() ? r : r + ": " + message;
}

bool in_window(double t, double start, double end) { return start >= 0 && t >= start - 1e-9 && t < end - 1e-9; }

double grew(std::uint16_t now, std::uint16_t then) { return static_cast<std::uint16_t>(now - then); }

Sample sample_of(const Scenario& sc, const Capacity& capacity, double t_s, double t_cmd,
                 const cvt::can::PlantStatus& st, const GroupView& g, const Commands& cmd) {
  Sample s;
  s.t_s = t_s;
  s.demand_Nm = sc.demand_Nm(t_cmd);
  s.clamp_cmd_N = cmd.clamp_cmd_N;
  s.axial_N = g.forces.driver_axial_force_N;
  s.torque_Nm = g.speeds.torque_transmitted_Nm;
  s.slip = g.ratio.slip;
  s.omega1 = g.speeds.omega_driver_rad_s;
  s.omega2 = g.speeds.omega_driven_rad_s;
  const float tau = std::fabs(s.torque_Nm) < 1.0f ? 1.0f : std::fabs(s.torque_Nm);
  s.safety = capacity.at_Nm(s.axial_N, capacity.radius_m) / tau;
  s.cmd_timeout = st.fault_cmd_timeout;
  s.watchdog = st.fault_watchdog;
  s.ratio_target = sc.ratio_target ? sc.ratio_target(t_cmd) : 0.0f;
  s.geometric_ratio = g.ratio.geometric_ratio;
  s.driven_cmd_N = cmd.driven_cmd_N;
  s.driven_axial_N = g.forces.driven_axial_force_N;
  // A fixed-ratio plant sends no PlantShift: its running radius is the set-up one.
  s.radius1_m = sc.ratio_target ? g.shift.radius_driver_m : capacity.radius_m;
  s.stop_under = g.shift.end_stop_underdrive;
  s.stop_over = g.shift.end_stop_overdrive;
  if (sc.ratio_target) {
    // The capacity at the driver's running radius (docs/sil.md#ratio-control).
    const float r1 = s.radius1_m > 0.01f ? s.radius1_m : capacity.radius_m;
    s.safety = capacity.at_Nm(s.axial_N, r1) / tau;
  }
  return s;
}

bool any_watchdog(const std::vector<Sample>& trace) {
  for (const Sample& s : trace)
    if (s.watchdog) return true;
  return false;
}

void ratio_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c) {
  double max_err = 0, max_err_t = 0, since = 0, sum_sq = 0;
  float held = -1.0f;
  int judged = 0;
  bool under = false, over = false;
  // Over the whole run (steps and ramps of the set-point included): the
  // lag of the bounded shift speed, reported beside the settled figures.
  double run_max = 0, run_sum_sq = 0;
  int run_n = 0;
  for (const Sample& s : trace) {
    if (s.ratio_target != held) {
      held = s.ratio_target;
      since = s.t_s;
    }
    under = under || s.stop_under;
    over = over || s.stop_over;
    // Set-points beyond the stops cannot be reached: not tracking targets.
    if (s.ratio_target > 2.65f || s.ratio_target < 0.89f) continue;
    const double e = std::fabs(s.geometric_ratio - s.ratio_target);
    run_max = std::fmax(run_max, e);
    run_sum_sq += e * e;
    ++run_n;
    if (s.t_s - since < sc.settle_s - 1e-9) continue;
    if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s)) continue;
    ++judged;
    sum_sq += e * e;
    if (e > max_err) {
      max_err = e;
      max_err_t = s.t_s;
    }
  }
  const double rms = judged > 0 ? std::sqrt(sum_sq / judged) : 0.0;
  const double run_rms = run_n > 0 ? std::sqrt(run_sum_sq / run_n) : 0.0;
  c.push_back(measured("ratio_tracked", judged > 0 && max_err <= sc.track_bound,
                       fmt("max |ratio - set-point| %.4f at t = %.2f s, ", max_err, max_err_t) +
                           fmt("RMS %.4f over %.0f settled samples (limit ", rms, judged) +
                           fmt("%.3f, set-point held >= %.1f s); ", sc.track_bound, sc.settle_s) +
                           fmt("whole run max %.4f RMS %.4f", run_max, run_rms),
                       judged > 0 ? max_err : NAN, sc.track_bound));
  if (sc.expect_end_stop && sc.t_end_s < sc.end_stops_by_s) {
    c.push_back({"end_stops_reached", true,
                 fmt("not judged: the run was cut at %.1f s, before the set-points beyond the stops (up to %.1f s)",
                     sc.t_end_s, sc.end_stops_by_s),
                 false});
  } else if (sc.expect_end_stop) {
    c.push_back({"end_stops_reached", under && over,
                 fmt("PlantShift end_stop_underdrive seen %.0f, end_stop_overdrive seen %.0f", under, over)});
  }
  if (sc.clamp_drop_start_s >= 0) {
    double peak = 0, recovered = -1;
    for (const Sample& s : trace) {
      if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s))
        peak = std::fmax(peak, std::fabs(s.slip));
      if (s.t_s >= sc.clamp_drop_end_s && recovered < 0 && std::fabs(s.slip) <= 0.02) recovered = s.t_s;
    }
    c.push_back(measured("slip_seen_in_drop", peak > 0.02,
                         fmt("max |slip| %.4f in the drop and the %.1f s after it (the drop must be felt: > 0.02)",
                             peak, kRecovery_s),
                         peak, 0.02));
    c.push_back(measured("slip_bounded_in_drop", peak <= 0.30, fmt("max |slip| %.4f (limit 0.30)", peak), peak, 0.30));
    c.push_back(measured("slip_recovered", recovered >= 0 && recovered <= sc.clamp_drop_end_s + kRecovery_s,
                         fmt("|slip| <= 0.02 again at %.2f s (supply back at %.2f s, limit + ", recovered,
                             sc.clamp_drop_end_s) + fmt("%.1f s)", kRecovery_s),
                         recovered >= 0 ? recovered - sc.clamp_drop_end_s : NAN, kRecovery_s));
  }
}

void motion_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c) {
  double max_slip = 0, min_sf = 1e9, min_sf_t = 0;
  for (const Sample& s : trace) {
    if (s.t_s < 0.05) continue;
    if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s)) continue;  // ratio_checks
    max_slip = std::fmax(max_slip, std::fabs(s.slip));
    if (s.safety < min_sf) {
      min_sf = s.safety;
      min_sf_t = s.t_s;
    }
  }
  c.push_back(measured("slip_bounded", max_slip <= sc.slip_bound,
                       fmt("max |slip| %.4f (limit %.2f)", max_slip, sc.slip_bound), max_slip, sc.slip_bound));
  if (sc.ratio_target) ratio_checks(sc, trace, c);
  c.push_back(measured("no_gross_slip", min_sf >= 1.05,
                       fmt("min torque-capacity safety factor %.3f at t = %.2f s (limit 1.05)", min_sf, min_sf_t),
                       min_sf < 1e9 ? min_sf : NAN, 1.05));
}

namespace {

// clamp-loss and frozen-controller: a controller silent (or repeating
// itself) from `start`: its last fresh command went out at start - 10 ms,
// the deadline is 50 ms later, seen by the status closing that period
// (docs/sil.md#timeouts).
void outage_checks(const Scenario& sc, const std::vector<Sample>& trace, const LockstepCounts& n,
                   std::vector<Check>& c) {
  const Faults& fx = sc.faults;
  const double outage_start = sc.link_loss_start_s >= 0 ? sc.link_loss_start_s : fx.freeze_start_s;
  const double outage_end = sc.link_loss_start_s >= 0 ? sc.link_loss_end_s : fx.freeze_end_s;
  double first_flag = -1, cleared = -1, axial_at_100ms = 0, axial_before = 0, max_rise = 0, max_drop = 0;
  float prev_axial = 0;
  for (const Sample& s : trace) {
    if (s.cmd_timeout && first_flag < 0) first_flag = s.t_s;
    if (first_flag < 0) axial_before = s.axial_N;
    if (first_flag >= 0 && cleared < 0 && !s.cmd_timeout && s.t_s > outage_end) cleared = s.t_s;
    if (first_flag >= 0 && s.t_s <= first_flag + 0.1 + 1e-9) axial_at_100ms = s.axial_N;
    if (first_flag >= 0 && s.t_s < outage_end) {
      max_rise = std::fmax(max_rise, s.axial_N - prev_axial);
      max_drop = std::fmax(max_drop, prev_axial - s.axial_N);
    }
    prev_axial = s.axial_N;
  }
  // The DBC's ramp rate of the clamp [N per 10 ms period], read from the
  // generated reaction itself (docs/sil.md#timeouts).
  cvt::can::CtrlCmd zero;
  zero.clamp_force_cmd_N = 0.0f;
  const double ramp_N = cvt::can::rx_timeout_ramp(zero, static_cast<float>(kPeriod_s)).clamp_force_cmd_N;
  const double expect = outage_start - kPeriod_s + 0.05;
  c.push_back({"timeout_flag_on_outage", first_flag >= expect - 1e-9 && first_flag <= expect + kPeriod_s + 1e-9,
               fmt("fault_cmd_timeout first at %.3f s (expected within 10 ms after %.3f s)", first_flag, expect)});
  c.push_back(measured("no_force_step_on_timeout", max_rise <= 1.2 * ramp_N,
                       fmt("largest rise of the axial force per 10 ms while timed out %.0f N (ramp %.0f N per 10 ms)",
                           max_rise, ramp_N),
                       max_rise, 1.2 * ramp_N));
  c.push_back(measured("timeout_reaction_raises_clamp", axial_at_100ms >= axial_before + 0.5 * ramp_N * 10.0,
                       fmt("axial force %.0f N 100 ms after the timeout, %.0f N before it", axial_at_100ms,
                           axial_before),
                       axial_at_100ms - axial_before, 0.5 * ramp_N * 10.0));
  c.push_back({"flag_clears_on_recovery", cleared > 0 && cleared <= outage_end + 0.02 + 1e-9,
               fmt("cleared at %.3f s (controller back at %.3f s)", cleared, outage_end)});
  c.push_back({"timeout_counted_once", n.cmd_timeouts == 1, fmt("PlantDiag.cmd_timeouts grew by %.0f", n.cmd_timeouts)});
  if (fx.freeze_start_s >= 0) {
    // The hung controller's repeated frame is never used again: the
    // clamp only rises while the ramp runs (a re-applied stale command
    // would pull it back down every 50 ms).
    const double frozen_frames = std::round((fx.freeze_end_s - fx.freeze_start_s) / kPeriod_s);
    c.push_back(measured("stale_command_never_reapplied", max_drop <= 1.0,
                         fmt("largest drop of the axial force per 10 ms while timed out %.0f N", max_drop), max_drop,
                         1.0));
    c.push_back({"repeated_frames_rejected", n.rejected_frames == frozen_frames,
                 fmt("PlantDiag.rejected_frames grew by %.0f (%.0f repeated frames sent)", n.rejected_frames,
                     frozen_frames)});
  }
}

}  // namespace

void lockstep_checks(const Scenario& sc, const std::vector<Sample>& trace, const LockstepCounts& n,
                     std::vector<Check>& c) {
  const Faults& fx = sc.faults;
  // A plant that stopped ends the run there (docs/sil.md#plant-faults):
  // the bridge answered every step until then; no_watchdog_fault fails.
  const bool stopped = n.plant_fault_s >= 0;
  c.push_back({"bridge_answered_every_step",
               n.no_reply == 0 && (stopped || trace.size() == static_cast<size_t>(n.periods)),
               fmt("%.0f of %.0f periods answered, %.0f requests sent again", static_cast<double>(trace.size()),
                   n.periods, n.resends) +
                   (stopped ? fmt("; the run stopped at the plant fault at t = %.3f s", n.plant_fault_s) : "")});
  c.push_back({"lockstep_time_exact", n.bad_time == 0 && n.bad_mode == 0,
               fmt("%.0f groups with sim_time_us != 10000 k, %.0f not in LockStep", n.bad_time, n.bad_mode)});
  c.push_back({"frames_valid", n.harness_rejected == 0 && n.controller_rejected <= 0,
               n.controller_rejected < 0
                   ? fmt("harness rejected %.0f (what the controller rejected is not observable on the bus)",
                         n.harness_rejected)
                   : fmt("harness rejected %.0f, controller rejected %.0f", n.harness_rejected,
                         n.controller_rejected)});
  motion_checks(sc, trace, c);
  c.push_back({"no_watchdog_fault", !any_watchdog(trace) && !stopped,
               stopped ? fmt("plant fault at t = %.3f s: ", n.plant_fault_s) + n.plant_fault
                       : (any_watchdog(trace) ? "plant watchdog fault" : "none")});
  if (sc.link_loss_start_s >= 0 || fx.freeze_start_s >= 0) {
    outage_checks(sc, trace, n, c);
  } else {
    bool any_timeout = false;
    for (const Sample& s : trace) any_timeout = any_timeout || s.cmd_timeout;
    c.push_back({"no_cmd_timeout", !any_timeout && n.cmd_timeouts == 0,
                 any_timeout ? "fault_cmd_timeout raised" : "none"});
  }
  if (fx.lost_requests() > 0) {
    // One resend per loss at least (more if an answer was merely slow);
    // lockstep_time_exact above shows no request ran twice or not at all.
    c.push_back({"lost_requests_recovered", n.resends >= fx.lost_requests() && n.harness_lost == fx.lost_requests(),
                 fmt("%.0f frames lost on purpose, %.0f requests sent again; slowest recovery %.1f ms wall "
                     "(the reply timeout, then the answer to the resent request)",
                     n.harness_lost, n.resends, n.max_recovery_ms)});
  }
  if (!fx.lost_cmd_periods.empty()) {
    const double lost = static_cast<double>(fx.lost_cmd_periods.size());
    c.push_back({"lost_commands_resynchronised", n.cmd_lost == lost && n.resyncs == 1 && n.controller_lost == lost,
                 fmt("PlantCmdDiag: %.0f commands lost, %.0f re-synchronisations", n.cmd_lost, n.resyncs)});
  }
  if (fx.reboot_s >= 0) {
    // The restarted counter is a jump: adopted, one Sync frame, then used.
    c.push_back({"restart_resynchronised", n.resyncs == 1 && n.rejected_frames == 1,
                 fmt("PlantCmdDiag.cmd_resyncs grew by %.0f, PlantDiag.rejected_frames by %.0f", n.resyncs,
                     n.rejected_frames)});
  }
  if (fx.flood_frames > 0) {
    const double expect = std::round((fx.flood_end_s - fx.flood_start_s) / kPeriod_s) * (fx.flood_frames - 1);
    c.push_back({"flood_superseded_counted", n.superseded == expect,
                 fmt("PlantCmdDiag.cmd_superseded grew by %.0f (expected %.0f: all but the last of each period)",
                     n.superseded, expect)});
  }
}

void partial_not_judged(const Scenario& sc, std::vector<Check>& checks) {
  if (!(sc.t_end_s < sc.min_t_end_s - 1e-9)) return;
  for (Check& c : checks)
    if (c.judged && !partial_criterion(c.name)) {
      c.judged = false;
      c.detail = fmt("not judged, the run was cut at %.2f s (the scenario needs %.1f s): ", sc.t_end_s,
                     sc.min_t_end_s) +
                 c.detail;
    }
}

void not_judged_from(std::vector<Check>& c, std::size_t from) {
  for (std::size_t i = from; i < c.size(); ++i) {
    c[i].judged = false;
    c[i].detail = "not judged, the plant did not keep time: " + c[i].detail;
  }
}

}  // namespace cvt::sil::harness
