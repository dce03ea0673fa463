// The real-time step of the reduced-order plant (docs/rom.md#cost,
// #slope-floor): the friction evaluated once per state and shared, and the
// friction slope floor in W that lets one ROS2 step per 1 ms frame start
// seed case 2 from rest.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

// rom_sim.hpp first: it brings the dual-number overloads of dm:: that the
// friction law templates must see for the wedging plants' Jacobian.
#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/scalar/fixed.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

namespace f = cvt::rom_feature;

template <class T>
bool same_bits(const T& a, const T& b) {
  if constexpr (std::is_floating_point_v<T>) return std::memcmp(&a, &b, sizeof(T)) == 0;
  else return a.raw() == b.raw();
}

template <class T>
void check_fused_friction(const cvt::FrictionParams<double>& pd) {
  const cvt::FrictionParams<T> p = pd.template cast<T>();
  for (const double v : {0.0, 1e-6, -1e-6, 5e-5, -1e-4, 3e-4, -0.02, 0.1, -0.7, 2.5, -9.0}) {
    CAPTURE(v);
    const T vt(v);
    const cvt::FrictionEval<T> e = cvt::friction_characteristic_and_slope(p, vt);
    // The same operations in the same order as the separate functions:
    // sharing them changes no result bit.
    CHECK(same_bits(e.phi, cvt::friction_characteristic(p, vt)));
    CHECK(same_bits(e.slope, cvt::friction_characteristic_slope(p, vt)));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("fused friction value and slope are bit for bit the separate ones", T, double, float,
                   cvt::q16_16) {
  namespace fp = cvt::friction_presets;
  for (cvt::FrictionParams<double> p : {fp::oscillator_coulomb<double>(), fp::oscillator_stribeck<double>(),
                                        fp::table2_case1<double>(), fp::table2_case2<double>()}) {
    for (const cvt::SignFunction s : {cvt::SignFunction::atan, cvt::SignFunction::tanh, cvt::SignFunction::exact}) {
      p.sign = s;
      CAPTURE(static_cast<int>(p.law));
      CAPTURE(static_cast<int>(s));
      check_fused_friction<T>(p);
    }
  }
}

namespace {

// The simulator shares one friction evaluation per state between the step,
// the Jacobian and the ledger; without the slope floor its states must be
// those of plain rom_step calls, bit for bit, also after the state is written
// from outside (the cache must not outlive the state it belongs to). Fixed
// point carries its rounding remainders from step to step
// (integrate/increment.hpp); the plain calls carry theirs too.
template <class T, std::uint32_t F>
void check_cache_is_transparent(const cvt::Scene& s) {
  cvt::RomSimConfig cfg = cvt::sim_config_of(s);
  cfg.w_slope_floor = false;
  cfg.substeps = 2;
  cvt::RomSimulator<T, F> sim(s.params, cfg);
  cvt::CvtRom<T, F> plant(s.params);
  cvt::RomInputs<T> u = cvt::scene_inputs_at<T>(s, 0.0);
  sim.reset(s.initial, u);
  plant.inputs = u;
  typename cvt::CvtRom<T, F>::State x = plant.initial_state(s.initial);
  cvt::CarryOf<cvt::CvtRom<T, F>> carry;
  bool all_same = true;
  for (int i = 0; i < 600; ++i) {
    if (i == 300) {
      // A harness nudges the driver speed between frames.
      sim.mutable_state()(0) += T(0.5);
      x(0) += T(0.5);
    }
    u = cvt::scene_inputs_at<T>(s, i * 1e-3);
    REQUIRE(sim.step_frame(u) == cvt::RomFault::none);
    plant.inputs = u;
    for (int k = 0; k < 2; ++k) {
      cvt::rom_step(cvt::Method::ros2, plant, x, sim.substep(), false, &carry);
      plant.wrap(x);
    }
    for (int k = 0; k < x.size(); ++k) all_same = all_same && same_bits(sim.state()(k), x(k));
  }
  CHECK(all_same);
}
template <class T, std::uint32_t F>
void check_cache_is_transparent(const char* scene) {
  check_cache_is_transparent<T, F>(*cvt::find_builtin_scene(scene));
}

}  // namespace

TEST_CASE("the shared friction evaluation does not change the trajectory") {
  check_cache_is_transparent<double, f::axial>("seed-case2");
  check_cache_is_transparent<float, f::axial | f::road_load>("tip-in");
  check_cache_is_transparent<cvt::q16_16, f::axial>("seed-case1");
  check_cache_is_transparent<cvt::q16_16, f::tension>("seed-case1");
  check_cache_is_transparent<double, 0>("gross-slip");
  // Wedging shares its contact with the partials of each lump (docs/rom.md#cost).
  check_cache_is_transparent<float, f::axial | f::road_load | f::wedging>("ratio-control");
  // With the chain's tension and no actuator the clamping input sets the
  // chain's axial force, which the contact carries (docs/rom.md#tension): a
  // command that changes every frame must reach the frame's first stage.
  cvt::Scene tension = *cvt::find_builtin_scene("seed-case1");
  tension.features = f::tension;
  tension.clamp = cvt::ramp_profile(3300.0, 1500.0, 0.1, 0.5);
  check_cache_is_transparent<double, f::tension>(tension);
}

TEST_CASE("slope floor: W sees the stick stiffness only inside the regularisation layer") {
  const cvt::Scene& s = *cvt::find_builtin_scene("seed-case2");
  using Rom = cvt::CvtRom<double, f::axial>;
  Rom rom(s.params);
  rom.inputs = cvt::scene_inputs_at<double>(s, 0.0);
  Rom::State x = rom.initial_state(s.initial);
  Rom::Jacobian J, W;
  // Exact rest: case 2 has mu(0) = 0, so the true slope, and with it the
  // lump's friction entry, is zero; the floored W has the layer-edge slope.
  rom.jacobian(x, rom.contact(x), J, false);
  rom.jacobian(x, rom.contact(x), W, true);
  CHECK(rom.contact(x).lump1.slope == 0.0);
  const double floor = cvt::friction_characteristic_slope(s.params.friction, 1.0 / s.params.friction.lambda_s_m);
  // The entry lump's normal load (docs/rom.md#lump-load-split).
  const double N = 3300.0 * cvt::lump_load_per_axial(s.params.entry_load_share, s.params.normal_load_factor,
                                                     std::cos(s.params.beta0_rad));
  CHECK(W(3, 3) - J(3, 3) == doctest::Approx(-floor * N / s.params.lump_mass_kg).epsilon(1e-9));
  // Outside the layer (slipping at 0.76 m/s) the floor changes nothing.
  x(0) = 10.0;
  rom.jacobian(x, rom.contact(x), J, false);
  rom.jacobian(x, rom.contact(x), W, true);
  CHECK(W == J);
  // Without the exact Jacobian's blindness (case 1: mu(0) = a > 0) neither.
  const cvt::Scene& s1 = *cvt::find_builtin_scene("seed-case1");
  Rom rom1(s1.params);
  rom1.inputs = cvt::scene_inputs_at<double>(s1, 0.0);
  const Rom::State x1 = rom1.initial_state(s1.initial);
  rom1.jacobian(x1, rom1.contact(x1), J, false);
  rom1.jacobian(x1, rom1.contact(x1), W, true);
  CHECK(W == J);
}

namespace {

// seed-case2 from rest at one ROS2 step per 1 ms frame for `t_end` s; the
// fault and w1 at the end.
template <class T, std::uint32_t F>
std::pair<cvt::RomFault, double> case2_from_rest(bool floor, int substeps, double t_end) {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case2");
  s.features = F;
  s.t_end_s = t_end;
  // The seed's even wrap at the full lumped normal load: there the first
  // steps without the floor blow up (the calibrated wrap of the built-in
  // scene happens to pass; docs/rom.md#slope-floor).
  s.params.entry_load_share = 0.5;
  s.params.normal_load_factor = 1.0;
  cvt::RomSimConfig cfg = cvt::sim_config_of(s);
  cfg.substeps = substeps;
  cfg.w_slope_floor = floor;
  double w1 = 0;
  const cvt::RomFault fault = cvt::run_scene<T, F>(s, cfg, [&](long, double, const cvt::RomSimulator<T, F>& sim) {
    w1 = cvt::to_double(sim.state()(0));
    return true;
  });
  return {fault, w1};
}

}  // namespace

TEST_CASE_TEMPLATE("slope floor: one step per frame starts seed case 2 from rest", T, double, float) {
  // Without the floor the first steps do not see the stick stiffness and
  // the watchdog stops the run within a few frames (docs/rom.md#slope-floor).
  CHECK(case2_from_rest<T, f::axial>(false, 1, 1.0).first == cvt::RomFault::energy_growth);
  CHECK(case2_from_rest<T, f::axial | f::wedging>(false, 1, 1.0).first == cvt::RomFault::energy_growth);
  // With it the run completes and agrees with 20 substeps per frame.
  const double ref = case2_from_rest<double, f::axial>(true, 20, 2.0).second;
  const auto r = case2_from_rest<T, f::axial>(true, 1, 2.0);
  CHECK(r.first == cvt::RomFault::none);
  CHECK(r.second == doctest::Approx(ref).epsilon(1e-4));
  const double ref_w = case2_from_rest<double, f::axial | f::wedging>(true, 20, 2.0).second;
  const auto rw = case2_from_rest<T, f::axial | f::wedging>(true, 1, 2.0);
  CHECK(rw.first == cvt::RomFault::none);
  // The seed case's wrap-tension coupling (docs/rom.md#wrap-tension) adds
  // a strand stiffness to the radial mode, so one step per frame is
  // 1.1e-4 from 20 substeps here (within 1e-4 without it): inside the
  // plant's 1e-3 accuracy goal.
  CHECK(rw.second == doctest::Approx(ref_w).epsilon(2e-4));
}

TEST_CASE("slope floor: fixed point starts seed case 2 from rest at one step per frame") {
  CHECK(case2_from_rest<cvt::q16_16, f::axial>(false, 1, 1.0).first != cvt::RomFault::none);
  const auto r = case2_from_rest<cvt::q16_16, f::axial>(true, 1, 2.0);
  CHECK(r.first == cvt::RomFault::none);
  CHECK(r.second == doctest::Approx(case2_from_rest<double, f::axial>(true, 20, 2.0).second).epsilon(1e-3));
}

namespace {

// Without the energy ledger (RomSimConfig::energy_ledger, docs/rom.md#cost)
// a frame integrates the same trajectory bit for bit, the ledger stays at its
// reset value, and the essential watchdog checks still latch their faults.
template <class T, std::uint32_t F>
void check_ledger_off(const char* scene) {
  const cvt::Scene& s = *cvt::find_builtin_scene(scene);
  cvt::RomSimConfig on = cvt::sim_config_of(s);
  cvt::RomSimConfig off = on;
  off.energy_ledger = false;
  cvt::RomSimulator<T, F> a(s.params, on), b(s.params, off);
  a.reset(s.initial, cvt::scene_inputs_at<T>(s, 0.0));
  b.reset(s.initial, cvt::scene_inputs_at<T>(s, 0.0));
  bool all_same = true;
  for (int i = 0; i < 1500; ++i) {
    const cvt::RomInputs<T> u = cvt::scene_inputs_at<T>(s, i * s.frame_s);
    REQUIRE(a.step_frame(u) == cvt::RomFault::none);
    REQUIRE(b.step_frame(u) == cvt::RomFault::none);
    for (int k = 0; k < a.state().size(); ++k) all_same = all_same && same_bits(a.state()(k), b.state()(k));
  }
  CHECK(all_same);
  // The ledger with it booked work; without it nothing was booked.
  CHECK(a.energy().input_J != decltype(a.energy().input_J)(0));
  CHECK(b.energy().input_J == decltype(b.energy().input_J)(0));
  CHECK(b.energy().stored_J == decltype(b.energy().stored_J)(0));
  // Essential checks: a non-finite input, and a pulley pushed past the speed limit.
  if constexpr (std::is_floating_point_v<T>) {
    cvt::RomSimulator<T, F> c = b;
    cvt::RomInputs<T> bad = cvt::scene_inputs_at<T>(s, 0.0);
    bad.tau_in_Nm = T(NAN);
    CHECK(c.step_frame(bad) == cvt::RomFault::input_non_finite);
  }
  cvt::RomSimulator<T, F> d = b;
  d.mutable_state()(0) = T(s.params.speed_limit_rad_s * 1.01);
  CHECK(d.step_frame(cvt::scene_inputs_at<T>(s, 1.5)) == cvt::RomFault::speed_out_of_range);
}

}  // namespace

TEST_CASE("energy ledger off: same trajectory, no booking, essential checks kept") {
  check_ledger_off<double, f::axial>("seed-case1");
  check_ledger_off<float, f::axial>("seed-case1");
  check_ledger_off<cvt::q16_16, f::axial>("seed-case1");
  check_ledger_off<double, f::tension>("seed-case1");
  check_ledger_off<cvt::q16_16, f::tension>("seed-case1");
  check_ledger_off<double, f::axial | f::road_load | f::wedging>("ratio-control");
}
