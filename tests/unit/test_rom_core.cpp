// Reduced-order CVT plant: reduction to seed Eq. 9, analytic Jacobian,
// lumped-parameter derivation (docs/rom.md).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/cvt_rom.hpp"
#include "cvtplant/plant/oscillator.hpp"

namespace {

// The seed oscillator written as a plant scene (docs/rom.md#holds): r1 = 1 m
// so v1 = w1 exactly, beta = 0 and F_ax = m g so N_i = m g exactly.
cvt::RomParams oscillator_as_rom(const cvt::FrictionParams<double>& f) {
  cvt::RomParams p;
  p.r1_m = 1.0;
  p.r2_m = 1.0;
  p.beta0_rad = 0.0;
  p.lump_mass_kg = 1.0;
  p.k1_N_m = 25.0;
  p.k2_N_m = 25.0;
  p.c1_Ns_m = 1.0;
  p.c2_Ns_m = 1.0;
  p.friction = f;
  p.hold_driver_speed = true;
  p.hold_driven_speed = true;
  return p;
}

template <std::uint32_t F>
void check_jacobian_against_duals(const cvt::RomParams& p, const cvt::RomInitial& x0, double clamp_N) {
  using Rom = cvt::CvtRom<double, F>;
  Rom rom(p);
  rom.inputs.tau_in_Nm = 80.0;
  rom.inputs.tau_load_Nm = 40.0;
  rom.inputs.clamp_N = clamp_N;
  typename Rom::State x = rom.initial_state(x0);
  // Move every state off its symmetric value so each partial is exercised.
  for (int i = 0; i < Rom::kStates; ++i) x(i) += 1e-3 * (i + 1);
  typename Rom::Jacobian Ja, Jd;
  rom.jacobian(x, Ja);
  cvt::jacobian_by_duals(rom, x, Jd);
  for (int i = 0; i < Rom::kStates; ++i)
    for (int j = 0; j < Rom::kStates; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      // A held pulley's column is zero by design (docs/rom.md#jacobian): it
      // multiplies an increment that is always zero.
      const bool held_column = (j == 0 && p.hold_driver_speed) || (j == 1 && p.hold_driven_speed);
      // Both are exact derivatives of the same expression: only rounding differs.
      CHECK(Ja(i, j) == doctest::Approx(held_column ? 0.0 : Jd(i, j)).epsilon(1e-10).scale(1.0));
    }
}

}  // namespace

TEST_CASE("ROM with held pulleys is seed Eq. 9: same trajectory as StickSlipOscillator") {
  for (const bool stribeck : {false, true}) {
    const auto f = stribeck ? cvt::friction_presets::oscillator_stribeck<double>()
                            : cvt::friction_presets::oscillator_coulomb<double>();
    CAPTURE(stribeck);
    const cvt::StickSlipOscillator<double> osc(cvt::OscillatorParams<double>::seed_section3(f));
    cvt::CvtRom<double> rom(oscillator_as_rom(f));
    rom.inputs.clamp_N = 1.0 * 9.81;  // m g
    cvt::RomInitial x0;
    x0.omega1_rad_s = 3.5;  // belt speed / r1
    x0.xd1_m_s = 3.0;
    x0.xd2_m_s = 6.0;
    for (const cvt::Method m : {cvt::Method::rk4, cvt::Method::ros2, cvt::Method::linear_implicit_euler}) {
      CAPTURE(cvt::method_name(m));
      Eigen::Vector4d xo(0, 3, 0, 6);
      auto xr = rom.initial_state(x0);
      const double h = m == cvt::Method::rk4 ? 1e-4 : 1e-3;
      const long n = std::lround(20.0 / h);
      double worst = 0;
      for (long i = 0; i < n; ++i) {
        cvt::step(m, osc, xo, h);
        cvt::step(m, rom, xr, h);
        for (int k = 0; k < 4; ++k) worst = std::max(worst, std::fabs(xo(k) - xr(2 + k)));
      }
      // Same operations in the same order: the 20 s trajectories agree bit for
      // bit (the Rosenbrock LU sees identity rows/columns for the held pulleys).
      CHECK(worst == 0.0);
      CHECK(xr(0) == 3.5);
      CHECK(xr(1) == 0.0);
    }
  }
}

TEST_CASE("ROM analytic Jacobian equals the dual-number Jacobian for every feature") {
  cvt::RomParams p;
  p.road_T0_Nm = 10.0;
  p.road_cv_Nms_rad = 0.05;
  p.road_ca_Nms2_rad2 = 0.002;
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.omega2_rad_s = 99.9;
  x0.x1_m = 0.02;
  x0.x2_m = 0.03;
  x0.phase_rad = 0.05;
  namespace f = cvt::rom_feature;
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    check_jacobian_against_duals<0>(p, x0, 3000.0);
    check_jacobian_against_duals<f::axial>(p, x0, 3000.0);
    check_jacobian_against_duals<f::road_load>(p, x0, 3000.0);
    check_jacobian_against_duals<f::deformation>(p, x0, 3000.0);
    check_jacobian_against_duals<f::polygon>(p, x0, 3000.0);
    check_jacobian_against_duals<f::all>(p, x0, 3000.0);
    p.friction = fr;
  }
  // Near stick, where the atan slope dominates.
  x0.omega2_rad_s = 100.0;
  check_jacobian_against_duals<f::all>(p, x0, 3000.0);
  p.hold_driver_speed = true;
  check_jacobian_against_duals<f::axial | f::road_load>(p, x0, 3000.0);
}
