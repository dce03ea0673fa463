// Torque profiles and road load on the reference (docs/mbd.md#loads): the
// torques the model applies are the profiles and the real-time plant's
// road-load law, and the energy ledger books their work.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

namespace {

// docs/rom.md#road-load, restated from the docs (not the shared function).
double road_law(double T0, double cv, double ca, double w_eps, double w2) {
  return T0 * std::tanh(w2 / w_eps) + cv * w2 + ca * w2 * std::fabs(w2);
}

// Trapezoid rule over the samples of f(sample).
template <class F>
double trapezoid(const std::vector<Sample>& s, F f) {
  double sum = 0;
  for (std::size_t k = 1; k < s.size(); ++k) sum += 0.5 * (f(s[k]) + f(s[k - 1])) * (s[k].t_s - s[k - 1].t_s);
  return sum;
}

}  // namespace

TEST_CASE("torque ramps and road load: the applied torques are the profiles and the law, and their work is booked") {
  // Input torque ramped 20 -> 120 N m over 20-60 ms, load torque 0 -> 30 N m
  // over 10-50 ms, road load with all three terms (and a w_eps that makes
  // tanh's curvature show). The pulleys start from rest, so the driven
  // pulley turns backwards first and the tanh term changes sign.
  MbdParams p = seed_case(1);
  p.tau_in_Nm.points = {{0.02, 20.0}, {0.06, 120.0}};
  p.tau_load_Nm.points = {{0.01, 0.0}, {0.05, 30.0}};
  p.road.T0_Nm = 10.0;
  p.road.cv_Nms_rad = 0.5;
  p.road.ca_Nms2_rad2 = 0.02;
  p.road.w_eps_rad_s = 0.5;
  RunOptions o;
  o.t_end_s = 0.1;
  o.sample_s = 1e-4;
  const Recorded r = record(p, o);
  double worst_in = 0, worst_load = 0;
  for (const Sample& s : r.samples) {
    const double t = s.t_s;
    const double tau_in = t <= 0.02 ? 20.0 : t >= 0.06 ? 120.0 : 20.0 + 100.0 * (t - 0.02) / 0.04;
    const double tau_load = (t <= 0.01 ? 0.0 : t >= 0.05 ? 30.0 : 30.0 * (t - 0.01) / 0.04) +
                            road_law(10.0, 0.5, 0.02, 0.5, s.omega_rad_s[1]);
    worst_in = std::max(worst_in, std::fabs(s.tau_in_Nm - tau_in));
    worst_load = std::max(worst_load, std::fabs(s.tau_load_Nm - tau_load));
  }
  CHECK(worst_in < 1e-12);
  CHECK(worst_load < 1e-12);
  // The work, by the trapezoid rule over the 0.1 ms samples of the torques
  // restated above times the recorded speeds, against the ledger's integrals.
  const double w_in = trapezoid(r.samples, [](const Sample& s) {
    const double t = s.t_s;
    return (t <= 0.02 ? 20.0 : t >= 0.06 ? 120.0 : 20.0 + 100.0 * (t - 0.02) / 0.04) * s.omega_rad_s[0];
  });
  const double w_load = trapezoid(r.samples, [](const Sample& s) {
    const double t = s.t_s;
    const double tl = (t <= 0.01 ? 0.0 : t >= 0.05 ? 30.0 : 30.0 * (t - 0.01) / 0.04) +
                      road_law(10.0, 0.5, 0.02, 0.5, s.omega_rad_s[1]);
    return tl * s.omega_rad_s[1];
  });
  const Sample& e = r.samples.back();
  bool backwards = false;
  for (const Sample& s : r.samples) backwards = backwards || s.omega_rad_s[1] < -0.05;
  CHECK(backwards);  // the tanh term acted on both signs
  CHECK(e.W_in_J == doctest::Approx(w_in).epsilon(1e-4));
  CHECK(std::fabs(e.W_load_J - w_load) <= 1e-4 * std::max(std::fabs(w_load), 1e-3 * e.W_in_J));
  CHECK(r.stats.ledger_residual_max_rel <= 1e-6);
  MESSAGE("torque ramps with road load, 0.1 s: W_in " << e.W_in_J << " J (trapezoid " << w_in << "), W_load "
                                                      << e.W_load_J << " J (trapezoid " << w_load
                                                      << "), ledger residual " << r.stats.ledger_residual_max_rel);
}

TEST_CASE("road load c_v w2 on a held driver: the driven pulley settles where the chain's torque equals the law") {
  // The driver held at 20 rad/s (a start at speed: spin-up, hold, and the
  // hold kept after the release), the driven pulley free under a pure
  // viscous road load, on fixed sheaves (a fixed geometric ratio). In steady
  // state J2 w2' = M2 - c_v w2 = 0: the chain's mean moment on the driven
  // pulley is c_v times its mean speed. The chain's lap (1.05 s at 1.5 m/s)
  // modulates both by a few percent; the means are over 0.2-1.0 s.
  MbdParams p = seed_case(1);
  p.tau_load_Nm = TimeProfile::constant(0.0);
  p.road.cv_Nms_rad = 2.0;
  p.start.active = true;
  p.start.omega1_rad_s = 20.0;
  p.start.omega2_rad_s = 20.0 * kR1 / kR2;
  p.start.hold_s = 0.5;
  p.hold1.active = true;
  p.hold1.omega_rad_s = 20.0;
  RunOptions o;
  o.t_end_s = 1.0;
  const Recorded r = record(p, o);
  double w2 = 0, m2 = 0, lo = 1e9, hi = -1e9;
  int n = 0;
  for (const Sample& s : r.samples)
    if (s.t_s >= 0.2) {
      w2 += s.omega_rad_s[1];
      m2 += s.chain_torque_Nm[1];
      lo = std::min(lo, s.omega_rad_s[1]);
      hi = std::max(hi, s.omega_rad_s[1]);
      ++n;
    }
  w2 /= n;
  m2 /= n;
  CHECK(hi - lo < 1e-2 * w2);  // steady but for the lap's modulation
  CHECK(m2 == doctest::Approx(2.0 * w2).epsilon(0.02));
  // The chain drives it near the geometric ratio r2/r1 = 1.5, slower by creep and slip.
  CHECK(w2 < 20.0 * kR1 / kR2);
  CHECK(w2 > 0.85 * 20.0 * kR1 / kR2);
  CHECK(r.stats.ledger_residual_max_rel <= 1e-6);
  MESSAGE("held driver 20 rad/s, c_v 2 N m s/rad: omega2 " << w2 << " rad/s (range " << hi - lo
                                                           << "), chain torque on the driven " << m2
                                                           << " N m against c_v omega2 " << 2.0 * w2);
}
