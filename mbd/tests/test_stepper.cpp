// The stepping interface (docs/mbd.md#stepping): the same run as simulate(),
// bit-identical repeats, save and restore, failures as a fault state.
// Cost: about 3 s of CPU (seed case 1 from rest, short spans).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "cvtplant/mbd/stepper.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

namespace {

// Inputs that change every frame: a clamped seed case, torques and clamping
// moving (so a replay that took the wrong input would show).
StepInputs inputs_at(int k) {
  StepInputs in;
  in.clamp1_N = 3300.0 + 10.0 * (k % 7);
  in.clamp2_N = 3637.0 - 5.0 * (k % 5);
  in.tau_in_Nm = 100.0 + 0.5 * k;
  in.tau_load_Nm = 50.0;
  return in;
}

MbdParams clamped_seed() {
  MbdParams p = seed_case(1);
  p.sheaves = SheaveMode::clamped;
  p.clamp1_N = TimeProfile::constant(3300.0);
  p.clamp2_N = TimeProfile::constant(3637.0);
  return p;
}

bool same_bits(const StepOutputs& a, const StepOutputs& b) {
  const double va[] = {a.t_s, a.omega1_rad_s, a.omega2_rad_s, a.geometric_ratio, a.F_ax1_N, a.F_ax2_N, a.slip,
                       a.torque_transmitted_Nm, a.sheave1_m, a.sheave2_m, a.E_residual_J, a.W_in_J};
  const double vb[] = {b.t_s, b.omega1_rad_s, b.omega2_rad_s, b.geometric_ratio, b.F_ax1_N, b.F_ax2_N, b.slip,
                       b.torque_transmitted_Nm, b.sheave1_m, b.sheave2_m, b.E_residual_J, b.W_in_J};
  return std::memcmp(va, vb, sizeof va) == 0 && a.fault == b.fault;
}

}  // namespace

TEST_SUITE("stepper") {

TEST_CASE("stepper: constant inputs give the run simulate() gives, within the tolerance") {
  MbdParams p = seed_case(1);
  RunOptions o;
  o.t_end_s = 0.1;
  const Recorded ref = record(p, o);
  Stepper s(p);
  REQUIRE(!s.faulted());
  StepInputs in{0, 0, 100.0, 50.0};
  double worst = 0;
  for (int k = 1; k <= 100; ++k) {
    const StepOutputs& out = s.step(in);
    REQUIRE(!s.faulted());
    const Sample& r = ref.samples[static_cast<std::size_t>(k)];
    CHECK(out.t_s == doctest::Approx(r.t_s).epsilon(1e-12));
    worst = std::max({worst, std::fabs(out.omega1_rad_s - r.omega_rad_s[0]) / (1.0 + std::fabs(r.omega_rad_s[0])),
                      std::fabs(out.omega2_rad_s - r.omega_rad_s[1]) / (1.0 + std::fabs(r.omega_rad_s[1])),
                      std::fabs(out.F_ax1_N - r.F_ax_N[0]) / r.F_ax_N[0]});
  }
  MESSAGE("stepper against simulate over 0.1 s: largest difference " << worst);
  // Both are BDF at rtol 5e-7; the stepper stops at every frame, simulate steps past.
  CHECK(worst < 1e-5);
  // The torques applied are the inputs; a fixed-sheave run sits on its "stops".
  CHECK(s.outputs().tau_in_Nm == 100.0);
  CHECK(s.outputs().sheave1_on_stop);
  CHECK(s.outputs().ledger_residual_rel < 1e-6);
}

TEST_CASE("stepper: the same inputs give the same bits; a restored state replays bit for bit") {
  Stepper a(clamped_seed()), b(clamped_seed());
  for (int k = 0; k < 30; ++k) {
    a.step(inputs_at(k));
    b.step(inputs_at(k));
    REQUIRE(same_bits(a.outputs(), b.outputs()));
  }
  const Stepper::Snapshot snap = a.save();
  std::vector<StepOutputs> first, second;
  for (int k = 30; k < 60; ++k) first.push_back(a.step(inputs_at(k)));
  a.restore(snap);
  CHECK(a.t_s() == snap.t_s);
  CHECK(same_bits(a.outputs(), snap.outputs));
  for (int k = 30; k < 60; ++k) second.push_back(a.step(inputs_at(k)));
  // Into another stepper of the same model: the same again.
  b.restore(snap);
  for (int k = 30; k < 60; ++k) {
    const StepOutputs& o = b.step(inputs_at(k));
    CHECK(same_bits(o, second[static_cast<std::size_t>(k - 30)]));
  }
  for (std::size_t k = 0; k < first.size(); ++k) CHECK(same_bits(first[k], second[k]));
  // Several frames per step land on the same frame times.
  a.restore(snap);
  a.step(inputs_at(30), 5);
  CHECK(a.t_s() == doctest::Approx(snap.t_s + 0.005).epsilon(1e-12));
}

TEST_CASE("stepper: a stepper built from a release snapshot runs as the one that saved it") {
  Stepper a(clamped_seed());
  const Stepper::Snapshot release = a.save();
  Stepper b(clamped_seed(), StepperOptions{}, release);
  CHECK(b.t_s() == 0.0);
  CHECK(same_bits(a.outputs(), b.outputs()));
  CHECK(b.inputs().clamp1_N == a.inputs().clamp1_N);
  for (int k = 0; k < 30; ++k) {
    a.step(inputs_at(k));
    b.step(inputs_at(k));
    REQUIRE(same_bits(a.outputs(), b.outputs()));
  }
  // Only a release: a later state lacks the release energy its ledger needs.
  CHECK_THROWS_AS(Stepper(clamped_seed(), StepperOptions{}, a.save()), std::invalid_argument);
  MbdParams fixed = seed_case(1);
  CHECK_THROWS_AS(Stepper(fixed, StepperOptions{}, release), std::invalid_argument);
}

TEST_CASE("stepper: a failure mid-run is a fault state, and a faulted stepper stays put") {
  SUBCASE("ledger") {
    StepperOptions o;
    o.ledger_tol = 1e-13;
    Stepper s(seed_case(1), o);
    const StepInputs in{0, 0, 100.0, 50.0};
    int k = 0;
    while (!s.faulted() && k < 200) s.step(in), ++k;
    CHECK(s.outputs().fault == StepFault::ledger);
    CHECK(s.fault_message().find("energy ledger residual") != std::string::npos);
    const double t = s.t_s();
    s.step(in);
    CHECK(s.t_s() == t);
  }
  SUBCASE("step cap") {
    StepperOptions o;
    o.max_steps_per_frame = 3;
    Stepper s(seed_case(1), o);
    s.step({0, 0, 100.0, 50.0}, 10);
    CHECK(s.outputs().fault == StepFault::step_cap);
    CHECK(s.fault_message().find("step cap") != std::string::npos);
  }
  SUBCASE("runaway") {
    Stepper s(seed_case(1));
    for (int k = 0; k < 400 && !s.faulted(); ++k) s.step({0, 0, 1000.0, -1000.0}, 10);
    // 1000 N m on both pulleys spins them up without bound.
    CHECK(s.faulted());
    MESSAGE("fault after " << s.t_s() << " s: " << s.fault_message());
  }
  SUBCASE("bad inputs") {
    Stepper s(clamped_seed());
    s.step({std::numeric_limits<double>::quiet_NaN(), 3637.0, 100.0, 50.0});
    CHECK(s.outputs().fault == StepFault::input);
    Stepper z(clamped_seed());
    z.step({0.0, 3637.0, 100.0, 50.0});
    CHECK(z.outputs().fault == StepFault::input);
    Stepper f(clamped_seed());
    f.step(inputs_at(0), 0);
    CHECK(f.outputs().fault == StepFault::input);
  }
}

}  // TEST_SUITE
