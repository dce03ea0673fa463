// cvtplant-controller: the example controller as a free-running ECU
// (docs/sil.md#controller-schedule): one control step per plant output group
// (ControlSchedule: as soon as a fresh group is complete, at most one per
// 5 ms, and at least one per 15 ms), or with --schedule fixed every 10 ms on
// its own clock. For the bridge's real-time mode. With --lockstep it is the
// external controller of a lock-step harness (cvtplant-sil run --controller
// external, docs/sil.md#external-lockstep): one control step per HarnessDemand.
// Whenever a harness sends HarnessDemand, the demand and set-point are its.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cvtctl/control_schedule.hpp"
#include "cvtctl/controller_node.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "stop_flag.hpp"
#include "cvtplant/port/socketcan_transport.hpp"

namespace {

const char kUsage[] =
    "usage: cvtplant-controller [--iface NAME] [--demand-Nm T] [--duration-s S] [--schedule group|fixed]\n"
    "                           [--ratio-steps T:R[,T:R...]] [--lockstep]\n"
    "The example clamping-force controller on SocketCAN until S seconds passed\n"
    "(0 = until SIGINT/SIGTERM). --schedule group (default): one control step per\n"
    "fresh plant output group, 5 ms apart at least, 15 ms at most; fixed: every\n"
    "10 ms of host time, whatever arrived. Prints its counters as JSON at the end,\n"
    "fresh_fraction = control steps with a fresh group / all steps.\n"
    "--ratio-steps: ratio control (docs/sil.md#ratio-control) with the set-point R from\n"
    "T seconds after the start (up to 8 steps, T increasing, R in [0.5, 3]); the JSON\n"
    "then reports the largest |ratio - set-point| once a set-point has held 1 s\n"
    "(set-points beyond the end stops, outside 0.8908..2.6498, are not judged).\n"
    "Once a harness sends HarnessDemand, its driver demand and set-point replace\n"
    "--demand-Nm and --ratio-steps. --lockstep: one control step per HarnessDemand\n"
    "(the external controller of cvtplant-sil run --controller external), until\n"
    "--duration-s of host time, SIGINT/SIGTERM.\n"
    "Exit 0, 1 (interface), 2 (usage).\n";

[[noreturn]] void bad_usage(const char* msg, const char* v) {
  std::fprintf(stderr, "cvtplant-controller: %s%s (see --help)\n", msg, v);
  std::exit(2);
}

double number(const char* flag, const char* v, double lo, double hi) {
  char* end = nullptr;
  const double d = std::strtod(v, &end);
  if (end == v || *end != '\0' || !(d >= lo && d <= hi)) {
    std::fprintf(stderr, "cvtplant-controller: %s: expected a number in [%g, %g], got '%s' (see --help)\n", flag, lo,
                 hi, v);
    std::exit(2);
  }
  return d;
}

// --ratio-steps "T:R,T:R": set-point steps (docs/sil.md#ratio-control).
struct RatioSteps {
  int n = 0;
  double t_s[8] = {}, ratio[8] = {};
  // The set-point at t and the time it has held.
  double at(double t, double& held_s) const {
    int k = 0;
    while (k + 1 < n && t >= t_s[k + 1]) ++k;
    held_s = t - t_s[k];
    return ratio[k];
  }
};

RatioSteps parse_ratio_steps(const char* v) {
  RatioSteps r;
  const char* p = v;
  while (*p != '\0') {
    char* end = nullptr;
    const double t = std::strtod(p, &end);
    if (end == p || *end != ':' || r.n == 8) bad_usage("--ratio-steps: expected up to 8 T:R pairs, got ", v);
    p = end + 1;
    const double x = std::strtod(p, &end);
    if (end == p || (*end != ',' && *end != '\0')) bad_usage("--ratio-steps: expected up to 8 T:R pairs, got ", v);
    if (!(t >= 0 && t <= 1e6) || !(x >= 0.5 && x <= 3.0) || (r.n > 0 && !(t > r.t_s[r.n - 1])) || (r.n == 0 && t != 0))
      bad_usage("--ratio-steps: times from 0, increasing; ratios in [0.5, 3]: ", v);
    r.t_s[r.n] = t;
    r.ratio[r.n] = x;
    ++r.n;
    p = *end == ',' ? end + 1 : end;
  }
  if (r.n == 0) bad_usage("--ratio-steps: expected up to 8 T:R pairs, got ", v);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const char* iface = "vcan0";
  double demand_Nm = 50, duration_s = 0;
  bool fixed = false, lockstep = false;
  RatioSteps ratio_steps;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (!std::strcmp(a, "-h") || !std::strcmp(a, "--help")) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (!std::strcmp(a, "--lockstep")) {
      lockstep = true;
      continue;
    }
    const bool known = !std::strcmp(a, "--iface") || !std::strcmp(a, "--demand-Nm") ||
                       !std::strcmp(a, "--duration-s") || !std::strcmp(a, "--schedule") ||
                       !std::strcmp(a, "--ratio-steps");
    if (!known) bad_usage("unknown option ", a);
    if (i + 1 >= argc) bad_usage("missing value for ", a);
    const char* v = argv[++i];
    if (!std::strcmp(a, "--iface")) iface = v;
    else if (!std::strcmp(a, "--demand-Nm")) demand_Nm = number(a, v, -600, 600);
    else if (!std::strcmp(a, "--ratio-steps")) ratio_steps = parse_ratio_steps(v);
    else if (!std::strcmp(a, "--schedule")) {
      if (!std::strcmp(v, "fixed")) fixed = true;
      else if (std::strcmp(v, "group") != 0) bad_usage("--schedule: expected group or fixed, got ", v);
    } else duration_s = number(a, v, 0, 1e6);
  }
  cvt::hil::install_stop_handlers();
  cvt::port::SocketCanTransport bus;
  if (bus.open(iface) != 0) {
    std::fprintf(stderr, "cvtplant-controller: %s: %s\n", iface, bus.error_text());
    return 1;
  }
  cvt::port::PosixMonotonicClock clock;
  cvtctl::ControllerNode node(bus);
  cvtctl::ControlSchedule sched;
  constexpr std::int64_t kPeriod_ns = std::int64_t{cvt::can::CtrlCmd::kCycleTime_ms} * 1000000;
  const std::int64_t t0 = clock.now_ns();
  const auto end = t0 + static_cast<std::int64_t>(duration_s * 1e9);
  std::int64_t deadline = t0, last = t0, max_gap = 0;
  long periods = 0, settled = 0;
  double max_err = 0, max_slip = 0;
  while (!cvt::hil::stop_requested() && (duration_s == 0 || clock.now_ns() < end)) {
    std::int64_t now = clock.now_ns();
    if (lockstep) {
      // The harness's period: every frame it needs came before its
      // HarnessDemand (docs/sil.md#external-lockstep).
      node.poll(10000000);
      node.take_new_run();
      if (!node.demand_pending()) continue;
      node.control_step_demand();
      ++periods;
      continue;
    }
    if (fixed) {
      node.poll(0);
    } else {
      // Wait for a fresh group, at most until the schedule's deadline.
      while (!cvt::hil::stop_requested() && !sched.due(now, node.fresh_group())) {
        if (node.fresh_group()) clock.sleep_until(sched.earliest_ns());
        else node.poll(sched.wait_until_ns() - now);
        now = clock.now_ns();
      }
      node.poll(0);  // whatever else is queued: the newest group wins
    }
    node.take_new_run();
    if (node.has_demand()) {
      // A harness plays the scenario: its demand and set-point.
      node.control_step_demand();
    } else if (ratio_steps.n > 0) {
      double held = 0;
      const double target = ratio_steps.at(static_cast<double>(now - t0) * 1e-9, held);
      // The group this step uses (fresh) against the set-point it had.
      const bool fresh = node.fresh_group();
      node.control_step_ratio(static_cast<float>(demand_Nm), static_cast<float>(target));
      if (fresh) {
        const double slip = std::fabs(static_cast<double>(node.ratio().slip));
        max_slip = slip > max_slip ? slip : max_slip;
        // Set-points beyond the travel (outside the thrust map) drive the
        // chain onto a stop: not tracking targets.
        const cvtctl::ThrustMap map;
        if (held >= 1.0 && target >= map.ratio[0] && target <= map.ratio[4]) {
          const double e = std::fabs(static_cast<double>(node.ratio().geometric_ratio) - target);
          max_err = e > max_err ? e : max_err;
          ++settled;
        }
      }
    } else {
      node.control_step(static_cast<float>(demand_Nm));
    }
    if (periods > 0 && now - last > max_gap) max_gap = now - last;
    last = now;
    sched.ran(now);
    ++periods;
    if (fixed) {
      deadline += kPeriod_ns;
      clock.sleep_until(deadline);
    }
  }
  const cvtctl::ControllerCounters& c = node.counters();
  std::printf(
      "{\"schedule\": \"%s\", \"periods\": %ld, \"fresh_periods\": %u, \"invalid_periods\": %u, "
      "\"fresh_fraction\": %.4f, \"max_step_gap_ms\": %.3f, \"accepted\": %u, \"rejected\": %u, "
      "\"resync_withheld\": %u, \"error_frames\": %u, \"tx_failed\": %u, \"last_clamp_cmd_N\": %.0f, "
      "\"ratio\": {\"steps\": %d, \"settled_samples\": %ld, \"max_abs_error_settled\": %.4f, "
      "\"max_abs_slip\": %.4f, \"last_driven_clamp_cmd_N\": %.0f}}\n",
      fixed ? "fixed" : "group", periods, c.fresh_periods, c.invalid_periods,
      periods > 0 ? static_cast<double>(c.fresh_periods) / static_cast<double>(periods) : 0.0,
      static_cast<double>(max_gap) * 1e-6, c.accepted, c.rejected, c.resync_withheld, c.error_frames, c.tx_failed,
      static_cast<double>(node.last_output().clamp_force_cmd_N), ratio_steps.n, settled, max_err, max_slip,
      static_cast<double>(node.last_ratio_output().driven_clamp_cmd_N));
  return 0;
}
