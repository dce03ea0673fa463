#pragma once
// Physical constants, the seed paper's parameters and its closed-form
// formulas, in one place (docs/physics.md#seed-parameters). Everything that
// needs a value from the seed takes it from here: the real-time plant's
// parameters (plant/rom_params.hpp), the built-in scenes, the seed
// oscillator, the friction presets, the analysis toolkit and the multibody
// reference. SI units; the seed's degrees are converted once, here.
//
// Set-up arithmetic only: double, deterministic (cvt::dm), never per step.
#include "cvtplant/math/detmath.hpp"

namespace cvt {

// ---------------------------------------------------------------- constants
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kHalfPi = 1.57079632679489661923;
inline constexpr double kTwoPi = 6.28318530717958647692;
inline constexpr double kTwoOverPi = 0.63661977236758134308;  // the atan sign's 2/pi (seed Eq. 9)
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kGravity_m_s2 = 9.81;  // as the seed's section 3 uses it

namespace seed {

// ---------------------------------------------------------------- Table 1, section 4
inline constexpr double kDriverPitchRadius_m = 0.0762;
inline constexpr double kDrivenPitchRadius_m = 0.1143;
inline constexpr double kDriverInertia_kgm2 = 1.4516;  // J1
inline constexpr double kDrivenInertia_kgm2 = 3.2661;  // J2
inline constexpr double kHalfSheaveAngle_deg = 15.0;   // beta0
inline constexpr double kHalfSheaveAngle_rad = 0.26179938779914943;
inline constexpr double kLinkMass_kg = 0.1125;
inline constexpr double kLinkLength_m = 0.03;      // pitch L
inline constexpr double kBlockStiffness_N_m = 200e3;  // K_b
inline constexpr double kBlockLength_m = 0.02;        // l_b
inline constexpr double kChainStiffness_N_m = 90e3;   // k
inline constexpr double kChainDamping_Ns_m = 2.7e3;   // p
inline constexpr double kCenterDistance_m = 0.5;
// Section 4's load case.
inline constexpr double kInputTorque_Nm = 100.0;
inline constexpr double kLoadTorque_Nm = 50.0;

// ---------------------------------------------------------------- section 3, the oscillator (Eq. 8/9)
inline constexpr double kOscMass_kg = 1.0;          // m1 = m2
inline constexpr double kOscStiffness_N_m = 25.0;   // k1 = k2
inline constexpr double kOscDamping_Ns_m = 1.0;     // c1 = c2
inline constexpr double kOscBeltSpeed_m_s = 3.5;    // v
inline constexpr double kOscSignSlope_s_m = 1e4;    // lambda of the atan sign

// ---------------------------------------------------------------- friction (section 3, Table 2, Eq. 6)
inline constexpr double kMu0 = 0.25;
// Section 3, Stribeck (case 2 form).
inline constexpr double kOscStribeckSigma = 6.5;
inline constexpr double kOscStribeckKappa_s_m = 5.0;
inline constexpr double kOscStribeckChi_s_m = 1.0;
// Table 2, case 1.
inline constexpr double kCase1A = 0.003;
inline constexpr double kCase1B_m_s = 0.1;
// Table 2, case 2.
inline constexpr double kCase2Sigma = 3.5;
inline constexpr double kCase2Kappa_s_m = 10.0;
inline constexpr double kCase2Chi_s_m = 3.0;

// ---------------------------------------------------------------- formulas
// Seed Eq. 4: amplitude of the flank-angle variation along the wrap [rad]
// for the speed ratio r1/r2 (docs/rom.md#deformation).
inline double deformation_amplitude_rad(double radius_ratio) {
  return 0.00045 / dm::exp(0.55 * dm::log_setup(radius_ratio));
}
// Seed Eq. 4: wrap angle of the largest flank opening [rad].
inline double deformation_centre_rad(double radius_ratio) {
  return kPi * radius_ratio / 3.0 + 23.0 * kPi / 180.0;
}
// Seed Eq. 3: flank angle at wrap angle zeta, beta0 + Delta/2 sin(zeta - theta_c + pi/2).
inline double flank_angle_rad(double beta0_rad, double amplitude_rad, double centre_rad, double zeta_rad) {
  return beta0_rad + 0.5 * amplitude_rad * dm::sin(zeta_rad - centre_rad + kHalfPi);
}

// Open-chain geometry of two pulleys at centre distance C: the wrap angle on
// the smaller pulley is pi - 2 asin((r2 - r1)/C) on the driver and
// pi + 2 asin(...) on the driven one, and the chain length is
// r1 theta1 + r2 theta2 + 2 sqrt(C^2 - (r2 - r1)^2) (docs/rom.md#wedging).
inline double wrap_angle_driver_rad(double r1_m, double r2_m, double C_m) {
  return kPi - 2.0 * dm::asin_setup((r2_m - r1_m) / C_m);
}
inline double wrap_angle_driven_rad(double r1_m, double r2_m, double C_m) {
  return kPi + 2.0 * dm::asin_setup((r2_m - r1_m) / C_m);
}
inline double chain_length_m(double r1_m, double r2_m, double C_m) {
  const double s = dm::asin_setup((r2_m - r1_m) / C_m);
  return r1_m * (kPi - 2.0 * s) + r2_m * (kPi + 2.0 * s) + 2.0 * dm::sqrt(C_m * C_m - (r2_m - r1_m) * (r2_m - r1_m));
}

// Driven pitch radius that keeps the chain length of radii (r1, r2) when the
// driver radius becomes r1 + rho: Newton on the chain length, dL/dr2 = the
// driven wrap angle (docs/rom.md#wedging).
inline double driven_pitch_radius_m(double r1_m, double r2_m, double C_m, double rho_m) {
  const double L0 = chain_length_m(r1_m, r2_m, C_m), a = r1_m + rho_m;
  double b = r2_m;
  for (int i = 0; i < 30; ++i) b -= (chain_length_m(a, b, C_m) - L0) / wrap_angle_driven_rad(a, b, C_m);
  return b;
}

}  // namespace seed
}  // namespace cvt
