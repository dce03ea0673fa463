#include "cvtplant/sil/harness/runner.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "cvtplant/sil/harness/report.hpp"
#include "cvtplant/sil/latency_stats.hpp"

namespace cvt::sil::harness {

namespace {

// The plant's torque capacity as it published it in the answer to Reset
// (docs/sil.md#published-parameters); a plant that published nothing cannot
// have its safety factor judged, which a failing check says.
Capacity plant_capacity(const HarnessNode& h, std::vector<Check>& missing) {
  if (!h.has_params()) {
    missing.push_back({"plant_parameters_published", false,
                       "no PlantParams in the answer to Reset: the torque-capacity safety factor cannot be judged"});
    return {};
  }
  return {h.params().capacity_coeff, h.params().radius_driver_m};
}

// HarnessLoad carries the load override and the clamping supply; a scenario
// that uses neither sends none.
bool sends_load(const Scenario& sc) { return sc.load_override || sc.clamp_drop_start_s >= 0; }

bool plant_stopped(const cvt::can::PlantStatus& st) {
  return st.fault_watchdog || st.plant_mode == cvt::can::PlantMode::Fault;
}

std::string fault_message(const RunConfig& cfg) { return cfg.plant != nullptr ? cfg.plant->fault_message() : ""; }

}  // namespace

ScenarioResult run_lockstep(const Scenario& sc, HarnessNode& h, FaultInjector& hf, ControllerUnderTest& ctl,
                            const RunConfig& cfg) {
  cvt::port::PosixMonotonicClock clock;
  const std::int64_t t0 = clock.now_ns();
  ScenarioResult res;
  res.name = sc.name;
  res.what = sc.what;
  std::vector<Sample> trace;
  LockstepCounts n;
  const Faults& fx = sc.faults;
  h.expect_shift(sc.scene == cvt::can::SceneId::RatioControl);
  if (!h.request(cvt::can::SimRequest::Reset, 0, sc.scene)) ++n.no_reply;
  // Baselines: the bridge's counters run over its lifetime.
  const cvt::can::PlantDiag diag0 = h.diag();
  const cvt::can::PlantCmdDiag cmd0 = h.cmd_diag();
  const std::uint32_t resends0 = h.resends(), lost_harness0 = hf.lost(), lost_ctl0 = ctl.lost_on_purpose();
  const std::uint32_t ctl_rejected0 = ctl.rejected();
  std::vector<Check> missing;
  const Capacity capacity = plant_capacity(h, missing);
  h.clear_recovery();
  ctl.begin_run(sc);
  n.periods = static_cast<int>(sc.t_end_s / kPeriod_s + 0.5);
  std::uint32_t expect_us = 0;
  for (int k = 0; k < n.periods && n.no_reply == 0; ++k) {
    const double t = k * kPeriod_s;
    ctl.control_period(sc, k, t);
    if (sends_load(sc)) h.send_load(sc.load_override, sc.load_Nm(t), clamp_supply(sc, t));
    if (k == fx.lost_step_period) hf.lose_next_sent(cvt::can::SimCtrl::kId);
    if (k == fx.lost_status_period) hf.lose_next_received(cvt::can::PlantStatus::kId);
    if (k == fx.lost_speeds_period) hf.lose_next_received(cvt::can::PlantSpeeds::kId);
    if (!h.request(cvt::can::SimRequest::Step, kFramesPerPeriod, cvt::can::SceneId::Keep)) {
      ++n.no_reply;
      break;
    }
    ctl.after_step();
    if (cfg.on_period) cfg.on_period(t + kPeriod_s);
    expect_us += kFramesPerPeriod * 1000;
    const cvt::can::PlantStatus& st = h.status();
    trace.push_back(sample_of(sc, capacity, st.sim_time_us * 1e-6, t, st,
                              GroupView{h.speeds(), h.ratio(), h.forces(), h.shift()}, ctl.commands()));
    // A plant that stopped (docs/sil.md#plant-faults) ends the run: it would
    // answer every further Step without moving. Its reason came with this
    // group (PlantDiag is in the group that first shows the fault).
    if (plant_stopped(st)) {
      n.plant_fault_s = st.sim_time_us * 1e-6;
      n.plant_fault = plant_fault_reason(h.diag(), fault_message(cfg));
      break;
    }
    if (st.sim_time_us != expect_us) ++n.bad_time;
    if (st.plant_mode != cvt::can::PlantMode::LockStep) ++n.bad_mode;
  }
  ctl.end_run();
  // The closing diagnostics (SimCtrl None answers with them).
  if (n.no_reply == 0 && !h.request(cvt::can::SimRequest::None, 0, cvt::can::SceneId::Keep)) ++n.no_reply;
  res.wall_s = static_cast<double>(clock.now_ns() - t0) * 1e-9;

  const std::string csv = cfg.out_dir + "/sil-" + sc.name + ".csv";
  const bool trace_written = write_trace(csv, trace);

  n.resends = h.resends() - resends0;
  n.harness_rejected = h.rejected();
  n.controller_rejected = ctl.observes_rejections() ? ctl.rejected() - ctl_rejected0 : -1.0;
  n.cmd_timeouts = grew(h.diag().cmd_timeouts, diag0.cmd_timeouts);
  n.rejected_frames = grew(h.diag().rejected_frames, diag0.rejected_frames);
  const cvt::can::PlantCmdDiag& cmd1 = h.cmd_diag();
  n.cmd_lost = grew(cmd1.cmd_lost_frames, cmd0.cmd_lost_frames);
  n.resyncs = grew(cmd1.cmd_resyncs, cmd0.cmd_resyncs);
  n.superseded = grew(cmd1.cmd_superseded, cmd0.cmd_superseded);
  n.harness_lost = hf.lost() - lost_harness0;
  n.controller_lost = ctl.lost_on_purpose() - lost_ctl0;
  n.max_recovery_ms = static_cast<double>(h.max_recovery_ns()) * 1e-6;
  res.checks.push_back({"trace_written", trace_written, csv});
  res.checks.insert(res.checks.end(), missing.begin(), missing.end());
  lockstep_checks(sc, trace, n, res.checks);
  ctl.add_checks(sc, res.checks);
  partial_not_judged(sc, res.checks);
  res.trace = std::move(trace);
  return res;
}

ScenarioResult run_realtime(const Scenario& sc, HarnessNode& h, ControllerUnderTest& ctl, const RunConfig& cfg,
                            const RealTimeBus& bus) {
  cvt::port::PosixMonotonicClock wall;
  const std::int64_t w0 = wall.now_ns();
  ScenarioResult res;
  res.name = std::string(sc.name) + ".realtime";
  res.what = std::string(sc.what) + " (real time)";
  std::vector<Sample> trace;
  h.expect_shift(true);
  bool answered = h.request(cvt::can::SimRequest::Reset, 0, sc.scene);
  const cvt::can::PlantDiag diag0 = h.diag();
  const std::uint32_t ctl_rejected0 = ctl.rejected(), h_rejected0 = h.rejected();
  const std::uint32_t rt_status0 = h.realtime_statuses();
  std::vector<Check> missing;
  const Capacity capacity = plant_capacity(h, missing);
  ctl.rt_begin(sc);
  bool timeout_seen = false;
  answered = answered && h.start_realtime();
  if (bus.start) bus.start();
  const std::int64_t t0 = bus.clock.now_ns();
  const std::int64_t end = t0 + static_cast<std::int64_t>(sc.t_end_s * 1e9 + 0.5);
  constexpr std::int64_t kLoadCycle_ns = std::int64_t{cvt::can::HarnessLoad::kCycleTime_ms} * 1000000;
  std::int64_t next_load = t0;
  while (answered) {
    if (bus.frame) bus.frame();
    const std::int64_t now = bus.clock.now_ns();
    if (now >= end) break;
    const double t = static_cast<double>(now - t0) * 1e-9;
    if (sends_load(sc) && now >= next_load) {
      h.send_load(sc.load_override, sc.load_Nm(t), clamp_supply(sc, t));
      next_load += kLoadCycle_ns;
    }
    ctl.rt_receive(now, bus.poll_ns);
    h.drain();
    timeout_seen = timeout_seen || h.status().fault_cmd_timeout;
    const RealtimeStep step = ctl.rt_step(sc, now, t);
    if (!step.ran || !step.fresh) continue;
    trace.push_back(sample_of(sc, capacity, t, t, h.status(), ctl.group(), ctl.commands()));
  }
  ctl.rt_end();
  answered = answered && h.pause();
  res.wall_s = static_cast<double>(wall.now_ns() - w0) * 1e-9;

  const std::string csv = cfg.out_dir + "/sil-" + sc.name + "-realtime.csv";
  auto& c = res.checks;
  c.push_back({"trace_written", write_trace(csv, trace), csv});
  c.insert(c.end(), missing.begin(), missing.end());
  // Functional criteria: judged in every run.
  const double frames = h.status().sim_time_us / 1000.0;
  const double overruns = grew(h.diag().rt_overruns, diag0.rt_overruns);
  const double rt_statuses = h.realtime_statuses() - rt_status0;
  const bool kept_time = frames > 0 && overruns <= kMaxOverrunFraction * frames;
  c.push_back({"realtime_paced", answered && rt_statuses > 0 && frames > 0,
               fmt("%.0f plant frames in %.0f ms of the ", frames, sc.t_end_s * 1e3) + bus.clock_name +
                   fmt(", %.0f overran; %.0f PlantStatus in RealTime; ", overruns, rt_statuses) +
                   (kept_time ? "kept time: every criterion judged"
                              : "did not keep time (more than 1 % of the frames overran): only realtime_paced, "
                                "frames_valid and no_watchdog_fault are judged")});
  // The plant rejects nothing but the counter jump that may follow a
  // command timeout, one per command message (CtrlCmd, CtrlShiftCmd): the
  // frames queued during the outage are drained, the next fresh one skips
  // their counters (docs/sil.md#timeouts). With no timeout, nothing.
  const double plant_rejected = grew(h.diag().rejected_frames, diag0.rejected_frames);
  const double timeouts = grew(h.diag().cmd_timeouts, diag0.cmd_timeouts);
  const double h_rej = h.rejected() - h_rejected0;
  const double ctl_rej = ctl.observes_rejections() ? ctl.rejected() - ctl_rejected0 : 0.0;
  c.push_back({"frames_valid", h_rej == 0 && ctl_rej == 0 && plant_rejected <= 2 * timeouts,
               (ctl.observes_rejections() ? fmt("harness rejected %.0f, controller rejected %.0f, ", h_rej, ctl_rej)
                                          : fmt("harness rejected %.0f, ", h_rej)) +
                   fmt("PlantDiag.rejected_frames grew by %.0f (at most 2 counter jumps per command timeout: %.0f "
                       "timeouts)",
                       plant_rejected, timeouts)});
  const bool watchdog = any_watchdog(trace) || plant_stopped(h.status());
  c.push_back({"no_watchdog_fault", !watchdog,
               watchdog ? "plant fault: " + plant_fault_reason(h.diag(), fault_message(cfg)) : "none"});
  ctl.add_checks(sc, c);
  // Judged when the plant kept time.
  const std::size_t full_from = c.size();
  ctl.add_realtime_checks(std::floor(sc.t_end_s / kPeriod_s) - 1, c);
  motion_checks(sc, trace, c);
  c.push_back({"no_cmd_timeout", !timeout_seen && timeouts == 0,
               timeout_seen ? fmt("fault_cmd_timeout raised, PlantDiag.cmd_timeouts grew by %.0f", timeouts) : "none"});
  if (!kept_time) not_judged_from(c, full_from);
  partial_not_judged(sc, c);
  res.trace = std::move(trace);
  return res;
}

int bench(HarnessNode& h, cvtctl::ControllerNode* ctl, long steps) {
  if (!h.request(cvt::can::SimRequest::Reset, 0, cvt::can::SceneId::TipIn)) {
    std::fprintf(stderr, "cvtplant-sil: bridge did not answer the Reset\n");
    return 1;
  }
  if (ctl != nullptr) ctl->restart();
  cvt::port::PosixMonotonicClock clock;
  std::vector<std::int64_t> rtt;
  rtt.reserve(static_cast<size_t>(steps));
  const std::int64_t t0 = clock.now_ns();
  for (long i = 0; i < steps; ++i) {
    const std::int64_t a = clock.now_ns();
    if (ctl != nullptr) {
      ctl->poll(0);
      ctl->control_step(50.0f);
    }
    if (!h.request(cvt::can::SimRequest::Step, 1, cvt::can::SceneId::Keep)) {
      std::fprintf(stderr, "cvtplant-sil: no answer to step %ld\n", i);
      return 1;
    }
    rtt.push_back(clock.now_ns() - a);
  }
  const double secs = static_cast<double>(clock.now_ns() - t0) * 1e-9;
  const cvt::sil::LatencySummary s = cvt::sil::summarize_latencies(rtt);
  std::printf(
      "{\"round_trips\": %ld, \"with_controller\": %s, \"seconds\": %.3f, \"round_trips_per_s\": %.0f, "
      "\"rtt_us\": {\"p50\": %.1f, \"p99\": %.1f, \"p99_9\": %.1f, \"max\": %.1f}, \"sim_time_us\": %u}\n",
      steps, ctl != nullptr ? "true" : "false", secs, static_cast<double>(steps) / secs, s.p50_ns * 1e-3,
      s.p99_ns * 1e-3, s.p999_ns * 1e-3, s.max_ns * 1e-3, h.status().sim_time_us);
  return h.status().sim_time_us == static_cast<std::uint32_t>(steps * 1000) ? 0 : 1;
}

}  // namespace cvt::sil::harness
