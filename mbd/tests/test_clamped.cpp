// Clamped sheaves with a clamping force given as a time profile
// (docs/mbd.md#clamped-sheaves): the profile itself, and the axial force the
// chain puts on each movable sheave following it.
#include <doctest/doctest.h>

#include <cmath>

#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

TEST_CASE("clamping profile: piecewise linear through its points, held before the first and after the last") {
  TimeProfile f;
  f.points = {{0.1, 3300.0}, {0.3, 4300.0}, {0.5, 3800.0}};
  CHECK(f.at(0.0) == 3300.0);
  CHECK(f.at(0.1) == 3300.0);
  CHECK(f.at(0.2) == doctest::Approx(3800.0).epsilon(1e-14));
  CHECK(f.at(0.3) == 4300.0);
  CHECK(f.at(0.45) == doctest::Approx(4300.0 - 0.75 * 500.0).epsilon(1e-14));
  CHECK(f.at(2.0) == 3800.0);
}

TEST_CASE("clamped sheaves: the chain's axial force follows a clamping ramp on both pulleys") {
  // Seed case 1 loads, driver clamping held at 3.3 kN for 0.1 s, then ramped
  // to 4.3 kN over 0.2 s; the driven clamping is the default, the driver's
  // times the static thrust ratio theta2/theta1. The movable sheave is
  // quasi-static: F_ax - F_clamp = m_s s'' + c_s s', where c_s s' is about
  // 10 N while the ramp closes the groove at 1 cm/s and m_s s'' rings at the
  // link-passing rate; 1 % covers both.
  MbdParams p = seed_case(1);
  p.sheaves = SheaveMode::clamped;
  p.clamp1_N.points = {{0.1, 3300.0}, {0.3, 4300.0}};
  RunOptions o;
  o.t_end_s = 0.35;
  o.sample_s = 1e-3;
  const Recorded r = record(p, o);
  const double thrust_ratio = wrap_driven_rad() / wrap_driver_rad();
  double worst[2] = {0, 0};
  for (const Sample& s : r.samples) {
    const double clamp[2] = {p.clamp1_N.at(s.t_s), thrust_ratio * p.clamp1_N.at(s.t_s)};
    for (int j = 0; j < 2; ++j) {
      CHECK(s.clamp_N[j] == doctest::Approx(clamp[j]).epsilon(1e-12));
      // The first 20 ms: the release's torque steps shake the sheaves.
      if (s.t_s >= 0.02) worst[j] = std::max(worst[j], std::fabs(s.F_ax_N[j] / clamp[j] - 1.0));
    }
  }
  CHECK(worst[0] < 0.01);
  CHECK(worst[1] < 0.01);
  // The clamping did work on the chain while it closed the grooves, and the
  // ledger books it.
  const Sample& e = r.samples.back();
  CHECK(e.F_ax_N[0] > 4200.0);
  CHECK(e.W_clamp_J > 1.0);
  CHECK(r.stats.ledger_residual_max_rel <= 1e-6);
  MESSAGE("clamping ramp 3.3 -> 4.3 kN: axial force within " << worst[0] << " (driver), " << worst[1]
                                                             << " (driven) of the clamping force; W_clamp "
                                                             << e.W_clamp_J << " J, ledger residual "
                                                             << r.stats.ledger_residual_max_rel);
}
