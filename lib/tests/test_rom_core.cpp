// Reduced-order CVT plant: reduction to seed Eq. 9, analytic Jacobian,
// lumped-parameter derivation (docs/rom.md).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/cvt_rom.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "rom_jacobian_check.hpp"

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

using rom_test::road_load_params;

// Driver at 150 rad/s, driven at omega2 (100 rad/s: no slip), strands
// stretched, polygon phase off zero: every Jacobian entry is exercised.
cvt::RomInitial driving_state(double omega2_rad_s) {
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.omega2_rad_s = omega2_rad_s;
  x0.x1_m = 0.02;
  x0.x2_m = 0.03;
  x0.phase_rad = 0.05;
  return x0;
}

template <std::uint32_t F>
void check_jacobian_against_duals(const cvt::RomParams& p, const cvt::RomInitial& x0, double clamp_N) {
  const auto rom = rom_test::loaded_plant<F>(p, clamp_N);
  rom_test::check_jacobian_at(rom, rom_test::offset_state(rom, x0), false);
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
  cvt::RomParams p = road_load_params();
  cvt::RomInitial x0 = driving_state(99.9);
  namespace f = cvt::rom_feature;
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    p.friction = fr;  // each law in turn: case 1's exponential ramp, case 2's Stribeck hump
    CAPTURE(static_cast<int>(fr.law));
    check_jacobian_against_duals<0>(p, x0, 3000.0);
    check_jacobian_against_duals<f::axial>(p, x0, 3000.0);
    check_jacobian_against_duals<f::road_load>(p, x0, 3000.0);
    check_jacobian_against_duals<f::deformation>(p, x0, 3000.0);
    check_jacobian_against_duals<f::polygon>(p, x0, 3000.0);
    check_jacobian_against_duals<f::basic>(p, x0, 3000.0);
    // The chain's tension state (docs/rom.md#tension; its regimes in test_rom_tension.cpp).
    check_jacobian_against_duals<f::tension>(p, x0, 3000.0);
    check_jacobian_against_duals<f::tension | f::basic>(p, x0, 3000.0);
    // Every feature at once: tension on the radial DOF (docs/rom.md#tension-radial;
    // its regimes in test_rom_composition.cpp).
    check_jacobian_against_duals<f::known>(p, x0, 3000.0);
  }
  // Near stick, where the atan slope dominates (case 2, the last law above).
  x0.omega2_rad_s = 100.0;
  check_jacobian_against_duals<f::basic>(p, x0, 3000.0);
  p.hold_driver_speed = true;
  check_jacobian_against_duals<f::axial | f::road_load>(p, x0, 3000.0);
}

namespace {

// The fixed-point plant runs in its own units (cvt::RomUnits,
// docs/rom.md#fixed-point): time in 2^-10 s, displacements in 2^-10 m. Its
// right-hand side and Jacobian must be the SI ones transformed,
//   f_u(i) = t_u f(i) / s_i,   J_u(i, j) = t_u J(i, j) s_j / s_i,
// with s_i the unit of state i, evaluated at the same physical state.
template <std::uint32_t F>
void check_fixed_units(const cvt::RomParams& p, const cvt::RomInitial& x0, double clamp_N, double f_rel_tol = 1e-3) {
  using Q = cvt::CvtRom<cvt::q16_16, F>;
  using D = cvt::CvtRom<double, F>;
  using L = typename Q::Layout;
  Q q(p);
  D d(p);
  q.inputs.tau_in_Nm = cvt::q16_16(80.0);
  q.inputs.tau_load_Nm = cvt::q16_16(40.0);
  q.inputs.clamp_N = cvt::q16_16(clamp_N);
  d.inputs.tau_in_Nm = 80.0;
  d.inputs.tau_load_Nm = 40.0;
  d.inputs.clamp_N = clamp_N;
  typename Q::State xq = q.initial_state(x0);
  for (int i = 0; i < Q::kStates; ++i) xq(i) += cvt::q16_16(1e-3 * (i + 1));
  const Eigen::Matrix<double, Q::kStates, 1> xs = q.to_si(xq);  // the same physical state, exactly
  const double tu = cvt::RomUnits<cvt::q16_16>::time_s, lu = cvt::RomUnits<cvt::q16_16>::length_m;
  double unit[Q::kStates];
  for (int i = 0; i < Q::kStates; ++i) unit[i] = 1.0;
  unit[L::kX1] = unit[L::kX2] = lu;
  if constexpr (L::kAxial) unit[L::kDelta] = lu;

  typename Q::State fq;
  typename D::State fd;
  q.derivative(xq, fq);
  d.derivative(typename D::State(xs), fd);
  typename Q::Jacobian Jq;
  typename D::Jacobian Jd;
  q.jacobian(xq, Jq);
  d.jacobian(typename D::State(xs), Jd);
  const double lsb = 1.0 / 65536;
  double worst_f = 0, worst_J = 0;  // in units of the tolerance
  int wf = -1, wi = -1, wj = -1;
  for (int i = 0; i < Q::kStates; ++i) {
    const double ref = tu * fd(i) / unit[i];
    const double ef = std::fabs(cvt::to_double(fq(i)) - ref) / (f_rel_tol * std::fabs(ref) + 16 * lsb);
    if (ef > worst_f) {
      worst_f = ef;
      wf = i;
    }
    for (int j = 0; j < Q::kStates; ++j) {
      const double rj = tu * Jd(i, j) * unit[j] / unit[i];
      // The friction slope here changes by 1 % per LSB (1.5e-5 m/s) of v_rel,
      // whose fixed-point value carries that rounding; a W-method does not
      // need J exactly. A wrong unit would be off by 2^10.
      const double e = std::fabs(cvt::to_double(Jq(i, j)) - rj) / (2e-2 * std::fabs(rj) + 16 * lsb);
      if (e > worst_J) {
        worst_J = e;
        wi = i;
        wj = j;
      }
    }
  }
  MESSAGE("features " << F << ": fixed-point f and J vs scaled SI, worst error / tolerance " << worst_f << " (f "
                      << wf << "), " << worst_J << " (J " << wi << "," << wj << ")");
  CHECK(worst_f <= 1.0);
  CHECK(worst_J <= 1.0);
  // Every entry in range: nothing saturated (the reason for the units).
  for (int i = 0; i < Q::kStates; ++i) {
    CHECK(fq(i) != cvt::q16_16::max());
    CHECK(fq(i) != cvt::q16_16::lowest());
    for (int j = 0; j < Q::kStates; ++j) CHECK(cvt::abs(Jq(i, j)) < cvt::q16_16(16384.0));
  }
}

}  // namespace

TEST_CASE("fixed-point ROM: derivative and Jacobian in its units equal the SI ones scaled") {
  cvt::RomParams p = road_load_params();
  // v_rel = 4 and 6 mm/s after the offsets: lambda v = 40, 60, the steep part.
  const cvt::RomInitial x0 = driving_state(100.0);
  namespace f = cvt::rom_feature;
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    p.friction = fr;
    // 4 kN: the largest clamping force of the built-in scenes (tip-in).
    check_fixed_units<0>(p, x0, 4000.0);
    check_fixed_units<f::axial>(p, x0, 4000.0);
    check_fixed_units<f::axial | f::road_load>(p, x0, 4000.0);
    check_fixed_units<f::axial | f::road_load | f::deformation>(p, x0, 4000.0);
    // Chordal action: r1 cos(psi) has 1.5e-5 m resolution, so v1 = r1e w1
    // carries ~2e-4 m/s at 150 rad/s, and the steep friction force follows
    // (docs/rom.md#fixed-point): no built-in scene uses it in fixed point.
    check_fixed_units<f::basic>(p, x0, 4000.0, 1e-2);
    // The chain's tension state (docs/rom.md#tension): on the stop at 11.4 m/s
    // and 4 kN, clamped at 1.5 kN, and on fixed sheaves.
    check_fixed_units<f::tension>(p, x0, 4000.0);
    check_fixed_units<f::tension | f::axial | f::road_load | f::deformation>(p, x0, 1500.0);
    cvt::RomParams pf = p;
    pf.fixed_sheaves = true;
    check_fixed_units<f::tension | f::road_load>(pf, x0, 0.0);
    // Chordal action with the tension feature: the ripple on the chain's
    // axial force and the phase row of the link passing (docs/rom.md#link-ripple).
    cvt::RomParams pr = p;
    pr.ripple_gain = 1.0;
    pf.ripple_gain = 1.0;
    check_fixed_units<f::tension | f::polygon>(pf, x0, 0.0, 1e-2);
    check_fixed_units<f::tension | f::polygon | f::axial>(pr, x0, 1500.0, 1e-2);
  }
}

namespace {

// rom_step's block elimination (docs/rom.md#structured-solve) solves the
// same W = I - gamma h J as the dense LU of integrate/rosenbrock.hpp.
template <std::uint32_t F>
void check_structured_step(const cvt::RomParams& p, const cvt::RomInitial& x0, cvt::Method m) {
  using Rom = cvt::CvtRom<double, F>;
  Rom rom(p);
  rom.inputs.tau_in_Nm = 80.0;
  rom.inputs.tau_load_Nm = 40.0;
  rom.inputs.clamp_N = 3000.0;
  typename Rom::State x = rom.initial_state(x0);
  for (int i = 0; i < Rom::kStates; ++i) x(i) += 1e-3 * (i + 1);
  typename Rom::State xs = x, xd = x;
  double worst = 0;
  for (int n = 0; n < 50; ++n) {
    cvt::rom_step(m, rom, xs, 5e-4);
    cvt::step(m, rom, xd, 5e-4);
    for (int i = 0; i < Rom::kStates; ++i)
      worst = std::max(worst, std::fabs(xs(i) - xd(i)) / (1e-3 + std::fabs(xd(i))));
    xs = xd;  // compare single steps, not the drift of two roundings
  }
  CAPTURE(F);
  CAPTURE(cvt::method_name(m));
  CHECK(worst < 1e-12);
}

}  // namespace

TEST_CASE("ROM structured linear solve equals the dense LU step for every feature") {
  cvt::RomParams p = road_load_params();
  p.ripple_gain = 1.0;  // the link-passing ripple's entries where polygon is on (docs/rom.md#link-ripple)
  const cvt::RomInitial x0 = driving_state(100.0);
  namespace f = cvt::rom_feature;
  for (const cvt::Method m : {cvt::Method::ros2, cvt::Method::linear_implicit_euler}) {
    check_structured_step<0>(p, x0, m);
    check_structured_step<f::axial>(p, x0, m);
    check_structured_step<f::road_load>(p, x0, m);
    check_structured_step<f::polygon>(p, x0, m);
    check_structured_step<f::basic>(p, x0, m);
    // Wedging: the 6x6 core with the bolt and radial velocities.
    check_structured_step<f::axial | f::wedging>(p, x0, m);
    check_structured_step<f::all>(p, x0, m);
    // The chain's tension state: its partials fill the core rows' columns
    // x_i and delta, which the elimination takes in (docs/rom.md#tension).
    check_structured_step<f::tension>(p, x0, m);
    check_structured_step<f::tension | f::basic>(p, x0, m);
    // With chordal action the phase row follows the chain's link passing:
    // entries in w2, x_i, xd_i and delta, eliminated on its own
    // (docs/rom.md#link-ripple).
    check_structured_step<f::tension | f::polygon>(p, x0, m);
    check_structured_step<f::tension | f::polygon | f::axial>(p, x0, m);
    // Tension on the radial DOF; with chordal action the phase row's radial
    // columns are eliminated with the kinematic rows delta and rho.
    check_structured_step<f::axial | f::wedging | f::tension>(p, x0, m);
    check_structured_step<f::known>(p, x0, m);
    p.fixed_sheaves = true;
    check_structured_step<f::tension | f::road_load>(p, x0, m);
    check_structured_step<f::tension | f::polygon | f::road_load>(p, x0, m);
    p.fixed_sheaves = false;
    p.hold_driver_speed = true;  // a held pulley: identity row and column
    check_structured_step<f::axial | f::road_load>(p, x0, m);
    check_structured_step<f::tension | f::axial>(p, x0, m);
    check_structured_step<f::tension | f::polygon | f::axial>(p, x0, m);
    p.hold_driver_speed = false;
    p.hold_driven_speed = true;
    check_structured_step<f::tension | f::polygon>(p, x0, m);
    check_structured_step<f::known>(p, x0, m);
    p.hold_driven_speed = false;
  }
}
