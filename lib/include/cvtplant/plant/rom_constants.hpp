#pragma once
// The constants of the reduced-order plant, converted once from the SI set-up
// data (RomParams) to the plant's scalar type and internal units (RomUnits):
// set-up arithmetic in double (soft-float on a Cortex-M4F, so never per
// step). docs/rom.md#parameters derives each value.
#include <cstdint>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/plant/rom_tension.hpp"
#include "cvtplant/plant/rom_units.hpp"

namespace cvt {

// The link-passing ripple's set-up constants (feature polygon,
// docs/rom.md#link-ripple): its relative amplitude A, pi / alpha and the
// phase phi0 of theta = pi psi / alpha + phi0, and 2 alpha / L, the phase
// per metre of chain (the phase rate with the tension feature). An empty
// base without the feature, so the other plants keep their constants' layout.
template <class T, bool kPolygon>
struct RomRippleConstants {};
template <class T>
struct RomRippleConstants<T, true> {
  T rip_A{}, rip_k{}, rip_phase{}, psi_per_m{};
};

template <class T, std::uint32_t F>
struct RomConstants : RomTensionConstants<T, RomLayout<F>::kTension>, RomRippleConstants<T, RomLayout<F>::kPolygon> {
  using L = RomLayout<F>;
  using U = RomUnits<T>;
  using A = RomAcc<T>;

  T r1{}, r2{}, inv_J1{}, inv_J2{}, inv_m{}, k1{}, c1{}, k2{}, c2{};
  FrictionParams<T> friction{};
  T inv_cos1{}, inv_cos2{}, stick_speed{};
  T load1{}, load2{};  // normal force per axial force of each lump (normal_force)
  T tu{};  // one time unit [s] (RomUnits)
  bool hold1 = false, hold2 = false;
  T inv_tau_h{}, clamp_max{}, inv_ms{}, cs{}, K_ax{};
  T T0{}, cv{}, ca{}, inv_w_eps{};
  T alpha{};
  T a1{}, a2{}, a3{}, two_tan_b0{}, tan1{}, tan2{}, inv_mr{}, cr{}, driven_force{}, travel{}, k_stop{}, q0{};
  T wrap_g{};  // eta theta1: the strands' stretch per radial position (docs/rom.md#wrap-tension)
  T floor_speed{}, slope_floor{};  // docs/rom.md#slope-floor
  struct Accounting {
    A J1{}, J2{}, m{}, k1{}, k2{}, c1{}, c2{}, r2{}, ms{}, cs{}, K_ax{};
    A mr{}, cr{}, a1{}, a2{}, a3{}, two_tan_b0{}, driven_force{}, k_stop{}, wrap_g{};
  };
  Accounting acc;  // the energy ledger's copies, in the accounting type
  double two_tan_b0_si = 0.0;  // 2 tan(beta0), set-up copy for set_driven_clamp
  double driven_clamp_si_N = 0.0;  // the driven clamping F_ax2 in N, as reported (RomOutputs)

  // The driven (secondary) clamping F_ax2 [N] the radial row and the ledger
  // use (docs/rom.md#driven-clamping); the same products as the set-up, so
  // the set-up value gives the same bits.
  void set_driven_clamp(double f_N) {
    driven_clamp_si_N = f_N;
    driven_force = T(two_tan_b0_si * f_N);
    acc.driven_force = A(two_tan_b0_si * f_N);
  }

  explicit RomConstants(const RomParams& p) {
    r1 = T(p.r1_m);
    r2 = T(p.r2_m);
    inv_J1 = T(1.0 / p.J1_kgm2);
    inv_J2 = T(1.0 / p.J2_kgm2);
    inv_m = T(1.0 / p.lump_mass_kg);
    // Springs act on displacements, so they are stored per length unit.
    k1 = T(p.k1_N_m * U::length_m);
    c1 = T(p.c1_Ns_m);
    k2 = T(p.k2_N_m * U::length_m);
    c2 = T(p.c2_Ns_m);
    friction = p.friction.template cast<T>();
    // docs/rom.md#deformation: beta_i = beta0 + Delta/2 sin(zeta_i - theta_c + pi/2),
    // Delta, theta_c from seed Eq. 4. The lumps sit at fixed wrap angles, so
    // 1/cos(beta_i) is a set-up constant and the feature costs nothing per step.
    double b1 = p.beta0_rad, b2 = p.beta0_rad;
    if constexpr (L::kDeform) {
      const double ratio = p.r1_m / p.r2_m;
      const double Delta = seed::deformation_amplitude_rad(ratio);
      const double theta_c = seed::deformation_centre_rad(ratio);
      b1 = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta1_rad);
      b2 = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta2_rad);
    }
    inv_cos1 = T(1.0 / dm::cos(b1));
    inv_cos2 = T(1.0 / dm::cos(b2));
    // docs/rom.md#lump-load-split: the entry lump (1) carries the share s of
    // the wrap's normal load, the exit lump (2) the rest; set-up constants,
    // so the split costs nothing per step.
    load1 = T(lump_load_per_axial(p.entry_load_share, p.normal_load_factor, dm::cos(b1)));
    load2 = T(lump_load_per_axial(1.0 - p.entry_load_share, p.normal_load_factor, dm::cos(b2)));
    hold1 = p.hold_driver_speed;
    hold2 = p.hold_driven_speed;
    stick_speed = T(p.stick_speed_m_s);
    // docs/rom.md#slope-floor: the edge of the sign's regularisation layer
    // (none for the exact sign) and the friction slope there.
    if (p.friction.sign != SignFunction::exact) {
      floor_speed = T(1.0 / p.friction.lambda_s_m);
      slope_floor = friction_characteristic_slope(friction, floor_speed);
    }
    tu = T(U::time_s);
    if constexpr (L::kAxial) {
      // Per time unit in the constant (0.049 in fixed point, 3200 LSB): one
      // rounding of (F_cmd - F_h) x constant, not a rounded rate times 50.
      inv_tau_h = T(U::time_s / p.actuator_tau_s);
      clamp_max = T(p.clamp_max_N);
      inv_ms = T(1.0 / p.sheave_mass_kg);
      cs = T(p.sheave_damping_Ns_m);
      K_ax = T(p.K_ax_N_m * U::length_m);
    }
    if constexpr (L::kRoad) {
      T0 = T(p.road_T0_Nm);
      cv = T(p.road_cv_Nms_rad);
      ca = T(p.road_ca_Nms2_rad2);
      inv_w_eps = T(1.0 / p.road_w_eps_rad_s);
    }
    if constexpr (L::kPolygon) {
      // docs/rom.md#polygon: half the angle one link subtends on the driver.
      const double alpha_rad = dm::asin_setup(p.pitch_m / (2.0 * p.r1_m));
      alpha = T(alpha_rad);
      // docs/rom.md#link-ripple: the loaded-bolt count's fundamental
      // (2/pi) sin(pi d) cos(theta), theta = pi psi / alpha + pi (1 - d),
      // d the fractional part of the links in the driver wrap.
      this->rip_A = T(rom_ripple_amplitude(p));
      this->rip_k = T(kPi / alpha_rad);
      this->rip_phase = T(kPi * (1.0 - rom_wrap_links_fraction(p)));
      this->psi_per_m = T(2.0 * alpha_rad / p.pitch_m);
    }
    if constexpr (L::kWedge) {
      // docs/rom.md#wedging: r2(rho) from chain length conservation, as the
      // cubic through the exact solutions at rho = 0, +-e, +-2e (e = travel/2).
      const double e = 0.5 * p.radial_travel_m;
      auto r2_at = [&p](double rho) { return seed::driven_pitch_radius_m(p.r1_m, p.r2_m, p.center_distance_m, rho); };
      const double fp1 = r2_at(e), fm1 = r2_at(-e);
      const double fp2 = r2_at(2 * e), fm2 = r2_at(-2 * e);
      const double f0 = p.r2_m;
      const double a1_m = (8.0 * (fp1 - fm1) - (fp2 - fm2)) / (12.0 * e);
      const double a2_1_m = (16.0 * (fp1 + fm1) - (fp2 + fm2) - 30.0 * f0) / (24.0 * e * e);
      const double a3_1_m2 = ((fp2 - fm2) - 2.0 * (fp1 - fm1)) / (12.0 * e * e * e);
      const double tb = dm::sin(p.beta0_rad) / dm::cos(p.beta0_rad);
      a1 = T(a1_m);
      a2 = T(a2_1_m);
      a3 = T(a3_1_m2);
      two_tan_b0 = T(2.0 * tb);
      tan1 = T(dm::sin(b1) / dm::cos(b1));
      tan2 = T(dm::sin(b2) / dm::cos(b2));
      inv_mr = T(1.0 / p.radial_mass_kg);
      cr = T(p.radial_damping_Ns_m);
      two_tan_b0_si = 2.0 * tb;
      driven_force = T(2.0 * tb * p.driven_clamp_N);
      driven_clamp_si_N = p.driven_clamp_N;
      travel = T(p.radial_travel_m);
      k_stop = T(p.radial_stop_N_m);
      acc.k_stop = A(p.radial_stop_N_m);
      q0 = friction_characteristic_slope(friction, T(0));
      acc.mr = A(p.radial_mass_kg);
      acc.cr = A(p.radial_damping_Ns_m);
      acc.a1 = A(a1_m);
      acc.a2 = A(a2_1_m);
      acc.a3 = A(a3_1_m2);
      acc.two_tan_b0 = A(2.0 * tb);
      acc.driven_force = A(2.0 * tb * p.driven_clamp_N);
      // docs/rom.md#wrap-tension: the set-up driver wrap angle theta1.
      const double g = p.wrap_tension_share * seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, p.center_distance_m);
      wrap_g = T(g);
      acc.wrap_g = A(g);
    }
    if constexpr (L::kTension) {
      // docs/rom.md#tension: the driver wrap's axial force per N of wrap
      // tension, theta1 / (2 tan beta0), at the set-up radii.
      const double theta1 = seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, p.center_distance_m);
      const double cF = theta1 / (2.0 * dm::sin(p.beta0_rad) / dm::cos(p.beta0_rad));
      const double m = p.centrifugal_gain * p.chain_mass_kg_m;
      this->ten_m = T(m);
      this->ten_two_m_r2 = T(2.0 * m * p.r2_m);
      this->ten_cF = T(cF);
      this->ten_inv_cF = T(1.0 / cF);
      this->ten_Tmax = T(p.stop_tension_N);
      this->ten_eta_s = T(p.stop_tension_share);
      this->ten_cF_eta_s = T(cF * p.stop_tension_share);
      this->ten_k_ws = T(p.wrap_excess_share + 0.5);
      this->ten_kL = T(p.chain_stiffness_N / U::tension_N);
      this->ten_unit = T(1.0 / U::tension_N);
      this->ten_g = T(p.creep_gain);
      this->ten_fixed = p.fixed_sheaves;
      // Fixed point: m v_c^2 saturates above sqrt(Q max / m); the simulator faults there.
      if constexpr (U::kScaled) this->ten_w2_max = m > 0.0 ? T(dm::sqrt(T::max().to_double() / m) / p.r2_m) : T::max();
    }
    // Accounting copies (docs/rom.md#energy-balance).
    acc.J1 = A(p.J1_kgm2);
    acc.J2 = A(p.J2_kgm2);
    acc.m = A(p.lump_mass_kg);
    acc.k1 = A(p.k1_N_m);
    acc.k2 = A(p.k2_N_m);
    acc.c1 = A(p.c1_Ns_m);
    acc.c2 = A(p.c2_Ns_m);
    acc.r2 = A(p.r2_m);
    acc.ms = A(p.sheave_mass_kg);
    acc.cs = A(p.sheave_damping_Ns_m);
    acc.K_ax = A(p.K_ax_N_m);
  }
};

}  // namespace cvt
