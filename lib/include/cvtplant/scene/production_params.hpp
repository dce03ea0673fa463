#pragma once
// The production-like chain CVT's lumps for the real-time plant
// (docs/rom.md#production-lumps): the multibody reference's production set
// (docs/mbd-production.md: a stiff, light chain, stiff bolts, pin-sheave
// friction in CVT fluid, 12.5-30 kN of clamping) through the lumping of
// docs/rom.md#lumped-parameters, on the seed's geometry and inertias, which
// the set keeps. The controller scenes start from these values; the values
// fitted to the reference on top of them are calibrated_production.hpp.
#include "cvtplant/plant/rom_params.hpp"

namespace cvt::production {

// docs/mbd-production.md#parameters (the reference's cvt::mbd::production_set()).
inline constexpr double kLinkLength_m = 0.0302;         // 53 links on the 1.6014 m pitch line
inline constexpr double kLinkMass_kg = 0.04;            // 1.325 kg/m
inline constexpr double kJointStiffness_N_m = 5.0e7;    // k: 0.32 % strain at the largest strand tension
inline constexpr double kJointDamping_Ns_m = 2.7e3;     // p: the seed's
inline constexpr double kBoltStiffness_N_m = 2.0e7;     // K_b
inline constexpr double kMu0 = 0.09;                    // pin-sheave friction in CVT fluid
inline constexpr double kFrictionB_m_s = 0.03;          // case-1 law, a = 0
// docs/mbd-production.md#envelope
inline constexpr double kClampMin_N = 12500.0;          // each pulley's clamping floor
inline constexpr double kClampMax_N = 30000.0;
inline constexpr double kRatedTorque_Nm = 150.0;
inline constexpr double kClampSafety = 1.3;

// Pin-sheave friction: the seed's case-1 law with a = 0, mu0 = 0.09, b = 0.03 m/s.
constexpr FrictionParams<double> friction() {
  FrictionParams<double> f = friction_presets::table2_case1<double>();
  f.mu0 = kMu0;
  f.a = 0.0;
  f.b_m_s = kFrictionB_m_s;
  return f;
}

// The driven clamping of a controller at input torque T on the set-up driver
// radius: max(floor, S T cos(beta0) / (2 mu0 r1)) (docs/mbd-production.md#envelope).
constexpr double driven_clamp_for_N(double torque_Nm) {
  const double cos_beta0 = 0.96592582628906831;  // cos(15 deg), the seed's half sheave angle
  const double c = kClampSafety * torque_Nm * cos_beta0 / (2.0 * kMu0 * seed::kDriverPitchRadius_m);
  return c > kClampMin_N ? c : kClampMin_N;
}

// The production lumps (docs/rom.md#production-lumps; lib/tests/test_rom_scenes.cpp
// derives each from the constants above): n_w = r1 theta1 / L = 7.5419 links in
// the driver wrap, n_s = s / L = 16.508 in a free strand, n_w2 = 12.468 in the
// driven wrap.
constexpr void apply(RomParams& p) {
  p.lump_mass_kg = 0.15083788906540505;        // (n_w/2) m
  p.k1_N_m = 1514403.0460219155;               // k / (2 n_s)
  p.c1_Ns_m = 81.777764485183430;              // p / (2 n_s)
  p.k2_N_m = 13259268.028689906;               // k / (n_w/2)
  p.c2_Ns_m = 716.00047354925490;              // p / (n_w/2)
  p.K_ax_N_m = 150837889.06540504;             // n_w K_b
  p.sheave_damping_Ns_m = 10421.289753532987;  // zeta = 0.3 with K_ax and the 2 kg sheave
  p.friction = friction();
  p.pitch_m = kLinkLength_m;
  p.driven_clamp_N = kClampMin_N;
  p.radial_mass_kg = 0.71227659168007340;      // (n_w + kappa(0)^2 n_w2) m
  p.radial_damping_Ns_m = 555.47178890074840;  // zeta = 0.05 of the chain-on-bolt mode (1241 Hz)
  // The tension state (docs/rom.md#tension-radial): the chain's mass per
  // metre and axial stiffness kL; the centrifugal tension by its law, m' v^2.
  p.chain_mass_kg_m = kLinkMass_kg / kLinkLength_m;
  p.chain_stiffness_N = kJointStiffness_N_m * kLinkLength_m;
  p.centrifugal_gain = 1.0;
}

}  // namespace cvt::production
