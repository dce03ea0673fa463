// The multibody reference behind the bridge (docs/sil.md#reference-plant):
// what it publishes against closed forms of the geometry, its actuators
// against the first-order lag's closed form, the lock-step protocol and the
// determinism of a run, real time refused when it cannot keep time.
// Cost: the start-up of tip-in once (about 3.5 s of CPU; every test after
// the first starts from the release state kept in this process).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "cosim_rig.hpp"
#include "cvtplant/cosim/reference_plant.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

using namespace cosim_test;
using cvt::cosim::ReferencePlant;

namespace {

// Open-belt geometry in closed form (seed section 2, the pitch line):
// wrap angles pi -+ 2 asin((r2 - r1) / C) and the length they give.
double wrap1(double r1, double r2, double c) { return M_PI - 2.0 * std::asin((r2 - r1) / c); }
double wrap2(double r1, double r2, double c) { return M_PI + 2.0 * std::asin((r2 - r1) / c); }
double belt_length(double r1, double r2, double c) {
  return r1 * wrap1(r1, r2, c) + r2 * wrap2(r1, r2, c) + 2.0 * std::sqrt(c * c - (r2 - r1) * (r2 - r1));
}
// The driven radius of the same chain at driver radius r1, by bisection.
double driven_for(double r1, double length, double c) {
  double lo = 0.01, hi = 0.3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (belt_length(r1, mid, c) < length ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("reference plant: the published parameters are the reference's geometry and friction") {
  ReferencePlant p;
  REQUIRE(p.load(*cvt::find_builtin_scene("ratio-control")));
  const cvt::sil::PublishedParams q = p.published();
  // The scene's friction (the production CVT's mu0 = 0.09), Table 1's sheave angle.
  const double mu0 = cvt::find_builtin_scene("ratio-control")->params.friction.mu0, beta0 = 15.0 * M_PI / 180.0;
  const double r1 = 0.0762, r2 = 0.1143, c = 0.5, travel = 0.025;
  CHECK(q.variable_ratio);
  // Seed Eq. 7 at rest: each bolt presses both flanks with F_b / cos(beta0).
  CHECK(q.capacity_coeff == doctest::Approx(2.0 * mu0 / std::cos(beta0)).epsilon(1e-12));
  CHECK(q.radius_driver_m == doctest::Approx(r1).epsilon(1e-15));
  CHECK(q.clamp_max_N == 40000.0);
  const double len = belt_length(r1, r2, c);
  const double rho[3] = {travel, 0.0, -travel};
  for (int i = 0; i < 3; ++i) {
    const double a = r1 + rho[i], b = driven_for(a, len, c);
    CHECK(q.ratio[i] == doctest::Approx(b / a).epsilon(1e-9));
    CHECK(q.thrust_ratio[i] == doctest::Approx(wrap1(a, b, c) / wrap2(a, b, c)).epsilon(1e-9));
  }
  MESSAGE("reference ratio map " << q.ratio[0] << " " << q.ratio[1] << " " << q.ratio[2] << ", thrust ratios "
                                 << q.thrust_ratio[0] << " " << q.thrust_ratio[1] << " " << q.thrust_ratio[2]);
  REQUIRE(p.load(*cvt::find_builtin_scene("tip-in")));
  CHECK(!p.published().variable_ratio);
  // A scene the reference cannot run is refused with the mapping's reason.
  ReferencePlant o;
  CHECK(!o.load(*cvt::find_builtin_scene("oscillator-coulomb")));
  CHECK(std::string(o.load_refusal()).find("held pulleys") != std::string::npos);
}

TEST_CASE("reference plant: the clamping reaches the sheaves through the real-time plant's actuators") {
  ReferencePlant p;
  const cvt::Scene& s = *cvt::find_builtin_scene("tip-in");
  REQUIRE(p.load(s));
  p.reset();
  REQUIRE(!p.faulted());
  const double f0 = s.clamp.at(0.0), tau = s.params.actuator_tau_s, dt = s.frame_s;
  CHECK(p.driver_clamp_N() == f0);
  // Without a driven command the driven clamping is the driver's times the
  // static thrust ratio theta2 / theta1 (the mapping's default).
  const double thrust = wrap2(0.0762, 0.1143, 0.5) / wrap1(0.0762, 0.1143, 0.5);
  cvt::RomInputs<double> u;
  u.tau_in_Nm = 20.0;
  u.clamp_N = 8000.0;
  double worst = 0;
  for (int k = 1; k <= 40; ++k) {
    p.step(u);
    REQUIRE(!p.faulted());
    const double expect = 8000.0 + (f0 - 8000.0) * std::exp(-k * dt / tau);
    worst = std::max(worst, std::fabs(p.driver_clamp_N() - expect) / 8000.0);
    CHECK(p.driven_clamp_N() == doctest::Approx(p.driver_clamp_N() * thrust).epsilon(1e-12));
  }
  CHECK(worst < 1e-12);
  // Saturated at the actuator's limit.
  u.clamp_N = 60000.0;
  for (int k = 0; k < 5; ++k) p.step(u);
  CHECK(p.driver_clamp_N() < s.params.clamp_max_N);
  CHECK(p.driver_clamp_N() > 8000.0);
  CHECK(p.frames() == 45);
  CHECK(p.reference_outputs().t_s == doctest::Approx(0.045).epsilon(1e-12));
}

TEST_CASE("the reference behind the bridge: lock-step on the bus, every criterion present, the same run twice") {
  Rig rig;
  const cvt::sil::harness::Scenario sc = short_scenario("tip-in", 0.2);
  const auto a = rig.run(sc);
  // Against the bus: every Step answered in time and in mode, frames valid,
  // the torque capacity from what the reference published.
  for (const char* name : {"bridge_answered_every_step", "lockstep_time_exact", "frames_valid", "no_watchdog_fault",
                           "no_cmd_timeout", "trace_written"}) {
    const auto* c = find(a, name);
    REQUIRE(c != nullptr);
    CHECK_MESSAGE(c->pass, name << ": " << c->detail);
  }
  CHECK(a.trace.size() == 20);
  CHECK(rig.node.params().capacity_coeff == doctest::Approx(0.51764).epsilon(1e-4));
  CHECK(rig.node.status().sim_time_us == 200000);
  CHECK(rig.node.diag().plant_fault == cvt::can::PlantFault::None);
  // The same inputs give the same bits: a second run of the scenario on the
  // same bridge (Reset restores the release state).
  const auto b = rig.run(sc);
  REQUIRE(b.trace.size() == a.trace.size());
  for (std::size_t i = 0; i < a.trace.size(); ++i) {
    CHECK(std::memcmp(&a.trace[i].slip, &b.trace[i].slip, sizeof(float)) == 0);
    CHECK(std::memcmp(&a.trace[i].axial_N, &b.trace[i].axial_N, sizeof(float)) == 0);
    CHECK(std::memcmp(&a.trace[i].omega1, &b.trace[i].omega1, sizeof(float)) == 0);
    CHECK(std::memcmp(&a.trace[i].torque_Nm, &b.trace[i].torque_Nm, sizeof(float)) == 0);
  }
  // The torque the driver passes to the chain is positive while it drives.
  CHECK(a.trace.back().torque_Nm > 0.0f);
}

TEST_CASE("the reference behind the bridge: real time only when it keeps time") {
  Rig rig;
  rig.run(short_scenario("tip-in", 0.05));
  ReferencePlant& p = rig.reference();
  const bool keeps = p.keeps_time();
  const std::string said = std::string("the reference ") + (keeps ? "keeps time" : "does not keep time") +
                           " on this host: " + p.realtime_refusal();
  MESSAGE(said);
  // A verdict of this host's speed: whichever it is, the bridge follows it.
  CHECK(rig.bridge().start_realtime() == keeps);
  if (!keeps) {
    CHECK(std::string(p.realtime_refusal()).find("does not keep time") != std::string::npos);
    CHECK(rig.bridge().realtime_refused() == 1);
    CHECK(rig.bridge().mode() != cvt::can::PlantMode::RealTime);
    // SimCtrl RunRealTime from the bus is refused the same way.
    REQUIRE(rig.node.start_realtime());
    CHECK(rig.bridge().realtime_refused() == 2);
    CHECK(rig.bridge().mode() != cvt::can::PlantMode::RealTime);
  }
}
