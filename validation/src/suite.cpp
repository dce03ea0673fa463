// The manoeuvre suites (docs/validation.md#suite).
#include "cvtplant/validation/suite.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "cvtplant/validation/errors.hpp"

namespace cvt::validation {

namespace {

using cvt::mbd::TimeProfile;

std::string label(const char* what, double a, double b, double c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s-%g-%g-%g", what, a, b, c);
  return buf;
}

// A factor that steps from 1 to exp(delta) over 1 ms at t.
TimeProfile log_step(double delta, double t) { return TimeProfile{{{t, 1.0}, {t + 1e-3, std::exp(delta)}}}; }

OperatingPoint point(double omega1, double ratio, double torque) { return controller_point(omega1, ratio, torque); }

// A manoeuvre's name, kind, start and length; the builders add its profiles.
Manoeuvre manoeuvre(std::string name, const char* kind, const OperatingPoint& start, double t_end_s) {
  Manoeuvre m;
  m.name = std::move(name);
  m.kind = kind;
  m.start = start;
  m.t_end_s = t_end_s;
  return m;
}

// docs/validation.md#suite: a ratio sweep as the SIL's ratio-sweep drives
// it, by the clamping-force ratio alone: up towards overdrive, back down and
// held.
Manoeuvre sweep(const char* name, double omega1, double ratio, double delta, double up_s, double down_s) {
  Manoeuvre m = manoeuvre(name, "sweep", point(omega1, ratio, 60.0), 0.3 + up_s + down_s);
  const double e = std::exp(delta), d = std::exp(-delta);
  m.clamp1_factor = TimeProfile{{{0.05, 1.0}, {0.1, e}, {0.05 + up_s, e}, {0.1 + up_s, d},
                                 {0.05 + up_s + down_s, d}, {0.1 + up_s + down_s, 1.0}}};
  return m;
}

// A kick-down: the driver's torque steps up, the driven clamping rises to
// carry it and the driver's falls below it, so the ratio goes to underdrive.
Manoeuvre kick_down(const char* name, double omega1, double ratio, double from_Nm, double to_Nm, double delta) {
  Manoeuvre m = manoeuvre(name, "kick-down", point(omega1, ratio, from_Nm), 1.2);
  const double f2 = controller_clamp2_N(to_Nm, 2.0) / m.start.clamp2_N;
  m.tau_in_Nm = TimeProfile{{{0.1, from_Nm}, {0.15, to_Nm}}};
  m.clamp2_factor = TimeProfile{{{0.05, 1.0}, {0.1, f2}}};
  m.clamp1_factor = TimeProfile{{{0.05, 1.0}, {0.1, f2 * std::exp(delta)}}};
  return m;
}

// Both clampings reduced together below what the torque needs (gross slip)
// and raised again: the SIL's clamping reduction.
Manoeuvre clamp_reduction(const char* name, double omega1, double ratio, double torque, double low) {
  Manoeuvre m = manoeuvre(name, "slip", point(omega1, ratio, torque), 0.6);
  m.clamp1_factor = TimeProfile{{{0.05, 1.0}, {0.15, low}, {0.3, low}, {0.4, 1.0}}};
  m.clamp2_factor = m.clamp1_factor;
  return m;
}

Manoeuvre tip_in(const char* name, double omega1, double ratio, double from_Nm, double to_Nm) {
  Manoeuvre m = manoeuvre(name, "tip-in", point(omega1, ratio, from_Nm), 0.8);
  m.start.clamp2_N = controller_clamp2_N(to_Nm, ratio);
  m.tau_in_Nm = TimeProfile{{{0.05, from_Nm}, {0.35, to_Nm}}};
  return m;
}

}  // namespace

double controller_clamp2_N(double torque_Nm, double ratio) {
  static const cvt::mbd::MbdParams p = cvt::mbd::production_set();
  static const cvt::mbd::ProductionEnvelope e = cvt::mbd::production_envelope();
  const double r1 = driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, ratio);
  return std::max(e.clamp_min_N, capacity_clamp_N(torque_Nm, r1, p.friction.mu0, p.beta0_rad, e.clamp_safety));
}

OperatingPoint controller_point(double omega1_rad_s, double ratio, double torque_Nm) {
  OperatingPoint op;
  op.omega1_rad_s = omega1_rad_s;
  op.ratio = ratio;
  op.tau_in_Nm = torque_Nm;
  op.clamp2_N = controller_clamp2_N(torque_Nm, ratio);
  return op;
}

Manoeuvre hold_manoeuvre(double omega1_rad_s, double ratio, double torque_Nm, double t_end_s) {
  return manoeuvre(label("hold", omega1_rad_s, ratio, torque_Nm), "hold", point(omega1_rad_s, ratio, torque_Nm), t_end_s);
}

Manoeuvre clamp_step_manoeuvre(const OperatingPoint& op, double delta, double at_s, double t_end_s) {
  Manoeuvre m =
      manoeuvre(label(delta > 0 ? "step-up" : "step-down", op.omega1_rad_s, op.ratio, std::fabs(delta)), "clamp-step", op,
                t_end_s);
  m.clamp1_factor = log_step(delta, at_s);
  return m;
}

std::vector<std::string> suite_names() { return {"controller", "ci"}; }

Suite suite_by_name(const std::string& name) {
  Suite s;
  s.name = name;
  if (name == "controller") {
    s.summary = "the production set's envelope: holds at 5 ratios x 3 torques, clamping-ratio steps up and down at "
                "100 and 200 rad/s, a ratio sweep, a kick-down, a clamping reduction into gross slip and back";
    for (const double ratio : {0.95, 1.2, 1.5, 2.0, 2.5})
      for (const double torque : {40.0, 90.0, 150.0}) s.fit.push_back(hold_manoeuvre(150.0, ratio, torque, 0.3));
    for (const double omega1 : {100.0, 200.0})
      for (const double delta : {0.1, -0.1}) s.fit.push_back(clamp_step_manoeuvre(point(omega1, 1.5, 60.0), delta, 0.05, 0.5));
    s.fit.push_back(sweep("sweep-150", 150.0, 2.0, 0.25, 1.2, 1.2));
    s.fit.push_back(kick_down("kick-down-150", 150.0, 1.2, 40.0, 150.0, -0.2));
    s.fit.push_back(clamp_reduction("slip-150", 150.0, 1.5, 100.0, 0.45));
    // Held out: other speeds, ratios and torques than any run of the fit.
    s.held_out.push_back(hold_manoeuvre(175.0, 1.75, 120.0, 0.3));
    s.held_out.push_back(clamp_step_manoeuvre(point(150.0, 1.3, 100.0), 0.07, 0.05, 0.5));
    s.held_out.push_back(sweep("sweep-120", 120.0, 1.1, -0.2, 1.0, 0.6));
    s.held_out.push_back(tip_in("tip-in-150", 150.0, 1.8, 30.0, 120.0));
    s.uncertainty_runs = {"hold-150-1.5-90", "step-up-100-1.5-0.1", "sweep-150", "kick-down-150", "slip-150"};
    return s;
  }
  if (name == "ci") {
    s.summary = "one steady hold and one clamping step from one start (150 rad/s, ratio 1.5, 60 N m)";
    s.fit.push_back(hold_manoeuvre(150.0, 1.5, 60.0, 0.06));
    s.fit.push_back(clamp_step_manoeuvre(point(150.0, 1.5, 60.0), 0.1, 0.01, 0.06));
    s.uncertainty_runs = {s.fit[0].name, s.fit[1].name};
    return s;
  }
  throw InputError("unknown suite '" + name + "' (controller, ci)");
}

}  // namespace cvt::validation
