// A start at speed (docs/mbd.md#start-at-speed): the spin-up and the hold
// bring the chain to a steady running state before the release, a release
// with balanced torques stays there, and the ledger closes from the release.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

namespace {

// The built-in drive-train scenes' start (150 / 100 rad/s, tip-in's road
// load and 4 kN clamping), at a lower speed to keep the test short.
MbdParams at_speed(double omega1) {
  MbdParams p = seed_case(1);
  p.sheaves = SheaveMode::clamped;
  p.clamp1_N = TimeProfile::constant(4000.0);
  p.road.T0_Nm = 10.0;
  p.road.cv_Nms_rad = 0.05;
  p.road.ca_Nms2_rad2 = 0.002;
  p.tau_load_Nm = TimeProfile::constant(0.0);
  p.start.active = true;
  p.start.omega1_rad_s = omega1;
  p.start.omega2_rad_s = omega1 * kR1 / kR2;
  return p;
}

constexpr double kOmega1 = 100.0;

}  // namespace

TEST_CASE("start at speed: the hold is steady, and a release with balanced torques stays at its speeds") {
  MbdParams p = at_speed(kOmega1);
  RunOptions o;
  o.t_end_s = 0.001;
  const Recorded held = record(p, o);
  REQUIRE(!held.stats.hold_samples.empty());
  // Criterion (docs/mbd.md#start-at-speed), over the hold's last 0.2 s: the
  // driven speed within a range of 0.2 % of its mean, the means of the
  // driver's holding torque and of both axial forces over the window's two
  // halves (each about a lap of the chain) within 5 % of each other.
  const HoldSteadiness h = hold_steadiness(held.stats.hold_samples, 0.2);
  CHECK(h.omega2_range_rel < 2e-3);
  CHECK(h.holding_torque_change_rel < 0.05);
  CHECK(h.F_ax_change_rel[0] < 0.05);
  CHECK(h.F_ax_change_rel[1] < 0.05);
  // The centrifugal tension of the chain at 10 m/s pushes it out to the
  // ratio stops on both pulleys (docs/mbd.md#start-at-speed): the sheaves
  // sit on their closing stops, which carry part of the clamping.
  const Sample& rel = held.stats.hold_samples.back();
  for (int j = 0; j < 2; ++j) {
    CHECK(rel.sheave_opening_m[j] < -p.sheave_stop_m);
    CHECK(h.F_ax_mean_N[j] < rel.clamp_N[j]);
  }
  CHECK(rel.omega_rad_s[0] == kOmega1);
  // Driven by the chain under the road load: near the geometric r1/r2.
  CHECK(rel.omega_rad_s[1] == doctest::Approx(kOmega1 * kR1 / kR2).epsilon(0.15));
  MESSAGE("hold at " << kOmega1 << " rad/s: omega2 " << rel.omega_rad_s[1] << " rad/s (range " << h.omega2_range_rel
                     << " of it over 0.2 s), holding torque " << h.holding_torque_mean_Nm << " N m (change "
                     << h.holding_torque_change_rel << "), F_ax " << h.F_ax_mean_N[0] << " / " << h.F_ax_mean_N[1]
                     << " N (change " << h.F_ax_change_rel[0] << " / " << h.F_ax_change_rel[1] << ")");

  // Released with the driver torque that held it (its mean over the last
  // 0.2 s: the lap modulates it): the same hold (it does not depend on the
  // input torque), then the speeds stay.
  p.tau_in_Nm = TimeProfile::constant(h.holding_torque_mean_Nm);
  o.t_end_s = 0.1;
  const Recorded run = record(p, o);
  const Sample& s0 = run.samples.front();
  CHECK(s0.omega_rad_s[0] == rel.omega_rad_s[0]);
  CHECK(s0.omega_rad_s[1] == rel.omega_rad_s[1]);
  double drift[2] = {0, 0};
  for (const Sample& s : run.samples)
    for (int j = 0; j < 2; ++j)
      drift[j] = std::max(drift[j], std::fabs(s.omega_rad_s[j] / s0.omega_rad_s[j] - 1.0));
  CHECK(drift[0] < 2e-3);
  CHECK(drift[1] < 2e-3);
  // The ledger starts at the release and closes over the run; the stored
  // energy at the release includes the pulleys' and the chain's motion.
  CHECK(s0.W_in_J == 0.0);
  CHECK(s0.W_load_J == 0.0);
  const double pulleys_J = 0.5 * p.J1_kgm2 * kOmega1 * kOmega1 +
                           0.5 * p.J2_kgm2 * s0.omega_rad_s[1] * s0.omega_rad_s[1];
  // The chain (44 links of 0.1125 kg) runs at least at the pitch-line speed.
  CHECK(s0.E_kin_J - pulleys_J > 0.5 * 44 * 0.1125 * (kOmega1 * kR1) * (kOmega1 * kR1));
  CHECK(run.stats.ledger_residual_max_rel <= 1e-6);
  const Sample& e = run.samples.back();
  CHECK(e.W_in_J == doctest::Approx(h.holding_torque_mean_Nm * kOmega1 * 0.1).epsilon(2e-3));
  MESSAGE("released with " << h.holding_torque_mean_Nm << " N m: speeds within " << drift[0] << " / " << drift[1]
                           << " over 0.1 s; ledger residual " << run.stats.ledger_residual_max_rel);
}
