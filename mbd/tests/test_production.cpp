// The production-like parameter set (docs/mbd-production.md): the
// plausibility checks a physically consistent chain CVT must pass, measured
// on the reference at corners of the controller's envelope. Cost: about 15 s
// of CPU (four starts at speed and about 0.8 s of simulated manoeuvres).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cvtplant/mbd/stepper.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;

namespace {

// A corner of the envelope: primary speed, the driver radius the chain starts
// at, the input torque, the clamping forces.
struct Corner {
  double omega1_rad_s, r1_start_m, tau_in_Nm, clamp1_N, clamp2_N;
};

StepperOptions test_options() {
  StepperOptions o;
  o.settle_rtol = 1e-6;  // the start's tolerance: 2x cheaper than the default, same checks
  return o;
}

MbdParams corner_params(const Corner& c) {
  MbdParams p = production_set();
  p.start_r1_m = c.r1_start_m;
  const double r2 = driven_radius_for(c.r1_start_m, DriveGeometry(p.r1_m, p.r2_m, p.center_distance_m).pitch_line_m,
                                      p.center_distance_m);
  p.start.active = true;
  p.start.omega1_rad_s = c.omega1_rad_s;
  p.start.omega2_rad_s = c.omega1_rad_s * c.r1_start_m / r2;
  p.clamp1_N = TimeProfile::constant(c.clamp1_N);
  p.clamp2_N = TimeProfile::constant(c.clamp2_N);
  p.tau_in_Nm = TimeProfile::constant(c.tau_in_Nm);
  // The driven pulley loaded with what the input torque gives at that ratio.
  p.tau_load_Nm = TimeProfile::constant(c.tau_in_Nm * r2 / c.r1_start_m);
  return p;
}

// The clamping design of the set (docs/mbd-production.md#envelope): enough
// for the torque with the safety factor, never below the floor.
double design_clamp_N(double tau_in_Nm, double r1_m) {
  const ProductionEnvelope e = production_envelope();
  const MbdParams p = production_set();
  const double need = tau_in_Nm * std::cos(p.beta0_rad) / (2.0 * p.friction.mu0 * r1_m);
  return std::max(e.clamp_min_N, e.clamp_safety * need);  // the driven clamping; the driver's holds the ratio
}

struct Trace {
  std::vector<StepOutputs> out;
  double min_margin_m = 1e9;  // smallest distance of either sheave from its stops
};

Trace run(Stepper& s, const StepInputs& in, int frames) {
  Trace t;
  const double stop = s.model().params().sheave_stop_m;
  for (int k = 0; k < frames; ++k) {
    const StepOutputs& o = s.step(in);
    REQUIRE_MESSAGE(!s.faulted(), s.fault_message());
    t.out.push_back(o);
    t.min_margin_m = std::min({t.min_margin_m, stop - std::fabs(o.sheave1_m), stop - std::fabs(o.sheave2_m)});
  }
  return t;
}

// Least-squares slope of the geometric ratio over the trace's samples from
// `skip` on [1/s].
double ratio_rate(const Trace& t, int skip) {
  double st = 0, sg = 0, stt = 0, stg = 0;
  int n = 0;
  for (std::size_t k = static_cast<std::size_t>(skip); k < t.out.size(); ++k) {
    const double x = t.out[k].t_s, g = t.out[k].geometric_ratio;
    st += x;
    sg += g;
    stt += x * x;
    stg += x * g;
    ++n;
  }
  return (n * stg - st * sg) / (n * stt - st * st);
}

// From a corner's released state: held at the force ratio the start's lock
// measured, and steps of the driver clamping by +-step in ln(F1/F2).
struct Shift {
  double rate_up, rate_down, rate_hold, x_hold;
  double margin_m;
  double g0;
};

Shift shift_checks(const Corner& c, double step) {
  Stepper s(corner_params(c), test_options());
  REQUIRE_MESSAGE(!s.faulted(), s.fault_message());
  const Stepper::Snapshot start = s.save();
  const int frames = 50, skip = 10;
  const StepInputs in = s.inputs();  // the driver clamping is the force that held the start's ratio
  Shift r{};
  r.g0 = s.outputs().geometric_ratio;
  auto with_ratio = [&](double x) {  // x = ln(F1/F2), F2 kept
    StepInputs i = in;
    i.clamp1_N = in.clamp2_N * std::exp(x);
    return i;
  };
  r.x_hold = std::log(in.clamp1_N / in.clamp2_N);
  const Trace hold = run(s, in, frames);
  s.restore(start);
  const Trace up = run(s, with_ratio(r.x_hold + step), frames);
  s.restore(start);
  const Trace down = run(s, with_ratio(r.x_hold - step), frames);
  r.rate_up = ratio_rate(up, skip);
  r.rate_down = ratio_rate(down, skip);
  r.rate_hold = ratio_rate(hold, skip);
  r.margin_m = std::min({up.min_margin_m, down.min_margin_m, hold.min_margin_m});
  return r;
}

}  // namespace

TEST_SUITE("production") {

TEST_CASE("production set: the envelope's clamping carries the rated torque with the safety factor") {
  const ProductionEnvelope e = production_envelope();
  const MbdParams p = production_set();
  // The smallest driver radius: the driver's opening stop.
  const double r1_min = p.r1_m - p.sheave_stop_m / (2.0 * std::tan(p.beta0_rad));
  const double need = e.clamp_safety * e.rated_torque_Nm * std::cos(p.beta0_rad) / (2.0 * p.friction.mu0 * r1_min);
  MESSAGE("S = " << e.clamp_safety << " at " << e.rated_torque_Nm << " N m on r1 = " << r1_min << " m: " << need
                 << " N of clamping, range " << e.clamp_min_N << "-" << e.clamp_max_N << " N");
  CHECK(need <= e.clamp_max_N);
  CHECK(need >= e.clamp_min_N);
}

TEST_CASE("production set at rated torque in underdrive: strain, capacity at S = 1.3, gross slip below it") {
  const ProductionEnvelope e = production_envelope();
  const double r1 = 0.056, tau = e.rated_torque_Nm, w1 = e.omega1_min_rad_s;
  const double F = design_clamp_N(tau, r1);
  // Driver clamping: the thrust ratio that roughly holds underdrive.
  const Corner c{w1, r1, tau, F, F};
  Stepper s(corner_params(c), test_options());
  REQUIRE_MESSAGE(!s.faulted(), s.fault_message());
  const Stepper::Snapshot start = s.save();
  const MbdParams& p = s.model().params();
  const Trace held = run(s, s.inputs(), 30);
  double t_max = 0, slip_mean = 0;
  for (const StepOutputs& o : held.out) {
    t_max = std::max({t_max, o.tension_tight_N, o.tension_slack_N});
    slip_mean += o.slip / static_cast<double>(held.out.size());
  }
  // The largest joint force anywhere in the chain, from the links at the end.
  double joint_max = 0;
  for (const LinkState& l : s.model().link_states(s.state())) joint_max = std::max(joint_max, l.tension_N);
  const double strain = std::max(t_max, joint_max) / (p.joint_stiffness_N_m * p.link_length_m);
  MESSAGE("rated " << tau << " N m at r1 = " << r1 << " m, clamping " << F << " N: largest strand tension " << t_max
                   << " N, largest joint force " << joint_max << " N, strain " << 100 * strain << " %, mean slip "
                   << slip_mean << ", sheave margin " << held.min_margin_m * 1e3 << " mm");
  CHECK(strain <= 0.005);
  // At S = 1.3 the wrap grips: the driver's mean slip over the frames (the
  // link passing modulates it by about +-1.5 %) stays below 3 % of its speed,
  // the ratio holds and the input torque reaches the driven pulley.
  CHECK(slip_mean < 0.03);
  CHECK(held.out.back().geometric_ratio == doctest::Approx(held.out.front().geometric_ratio).epsilon(0.003));
  CHECK(held.out.back().torque_driven_Nm ==
        doctest::Approx(tau * held.out.back().r2_m / held.out.back().r1_m).epsilon(0.1));
  CHECK(held.min_margin_m > 0);
  // At 0.6 of what the torque needs (S = 0.6) the driver wrap slides: the
  // check above is not passed by a clamping that carries anything.
  s.restore(start);
  StepInputs weak = s.inputs();
  weak.clamp1_N = weak.clamp2_N = 0.6 / e.clamp_safety * F;
  const Trace slid = run(s, weak, 40);
  double slid_mean = 0;
  for (std::size_t k = 20; k < slid.out.size(); ++k) slid_mean += slid.out[k].slip / 20.0;
  MESSAGE("at S = 0.6: mean slip over 20-40 ms " << slid_mean);
  CHECK(slid_mean > 0.05);
}

TEST_CASE("production set at top speed in overdrive: the centrifugal tension is at most 25 % of the strand tensions") {
  const ProductionEnvelope e = production_envelope();
  const double r1 = 0.097, tau = 40.0, w1 = e.omega1_max_rad_s;
  const double F = design_clamp_N(tau, r1);
  const Corner c{w1, r1, tau, F, F};
  Stepper s(corner_params(c), test_options());
  REQUIRE_MESSAGE(!s.faulted(), s.fault_message());
  const MbdParams& p = s.model().params();
  const Trace t = run(s, s.inputs(), 20);
  double t_min = 1e30, tc_max = 0;
  const double m_per_m = p.link_mass_kg / p.link_length_m;
  for (const StepOutputs& o : t.out) {
    t_min = std::min({t_min, o.tension_tight_N, o.tension_slack_N});
    const double v = o.omega1_rad_s * o.r1_m - o.slip1_m_s;  // the chain's speed in the driver wrap
    tc_max = std::max(tc_max, m_per_m * v * v);
  }
  MESSAGE("top speed " << w1 << " rad/s, r1 " << t.out.back().r1_m << " m, clamping " << F << " N: m' v^2 " << tc_max
                       << " N, smallest strand tension " << t_min << " N (" << 100 * tc_max / t_min << " %)");
  CHECK(tc_max <= 0.25 * t_min);
  CHECK(t.min_margin_m > 0);
}

TEST_CASE("production set: the reference shifts by the clamping-force ratio alone, its sheaves floating") {
  const ProductionEnvelope e = production_envelope();
  struct Point {
    std::string what;
    Corner c;
  };
  const double r1_mid = production_set().r1_m;
  const std::vector<Point> points = {
      {"100 rad/s, ratio 1.5, 40 N m", {e.omega1_min_rad_s, r1_mid, 40.0, 0, 0}},
      {"100 rad/s, underdrive 2.2, rated torque", {e.omega1_min_rad_s, 0.058, e.rated_torque_Nm, 0, 0}},
      {"top speed, overdrive, 40 N m", {e.omega1_max_rad_s, 0.097, 40.0, 0, 0}},
  };
  for (const Point& pt : points) {
    Corner c = pt.c;
    c.clamp2_N = design_clamp_N(c.tau_in_Nm, c.r1_start_m);
    c.clamp1_N = c.clamp2_N;  // not applied before the release: the lock holds the driver sheave
    const Shift r = shift_checks(c, 0.1);
    MESSAGE(pt.what << ": geometric ratio " << r.g0 << ", held at ln(F1/F2) = " << r.x_hold << ": d(r2/r1)/dt "
                    << r.rate_hold << " /s; at +0.1: " << r.rate_up << " /s, at -0.1: " << r.rate_down
                    << " /s; sheaves at least " << r.margin_m * 1e3 << " mm from their stops");
    // More driver clamping relative to the driven closes the driver groove:
    // the chain climbs the driver, r2/r1 falls (upshift); less, it rises.
    CHECK(r.rate_up < 0);
    CHECK(r.rate_down > 0);
    // The force ratio that held the ratio at the start holds it free.
    CHECK(std::fabs(r.rate_hold) < 0.25 * std::min(-r.rate_up, r.rate_down));
    CHECK(r.margin_m > 1e-3);
  }
}

}  // TEST_SUITE
