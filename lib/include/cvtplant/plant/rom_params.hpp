#pragma once
// Parameters of the reduced-order CVT plant (docs/rom.md#parameters).
// Set-up data in SI units; the plant converts them to its scalar type once,
// in its constructor (double is soft-float on a Cortex-M4F, so never per step).
#include <cstdint>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_features.hpp"

namespace cvt {

struct RomParams {
  // Geometry (seed Table 1 / section 4; physics/seed.hpp).
  double r1_m = seed::kDriverPitchRadius_m;
  double r2_m = seed::kDrivenPitchRadius_m;
  double beta0_rad = seed::kHalfSheaveAngle_rad;  // 15 deg half sheave angle
  double center_distance_m = seed::kCenterDistance_m;
  // Pulley inertias (seed Table 1).
  double J1_kgm2 = seed::kDriverInertia_kgm2;
  double J2_kgm2 = seed::kDrivenInertia_kgm2;
  // Link lumps (docs/rom.md#lumped-parameters: derived from Table 1).
  double lump_mass_kg = 0.42705977341642810;   // (n_w/2) * 0.1125 kg
  double k1_N_m = 2707.8729961981267;          // k / (2 n_s): two lumps in parallel = the free strand
  double c1_Ns_m = 81.236189885943800;         // p / (2 n_s)
  double k2_N_m = 23708.624951962083;          // k / (n_w/2)
  double c2_Ns_m = 711.25874855886240;         // p / (n_w/2)
  // docs/rom.md#lump-load-split: the wrap's normal load 2 f F_ax / cos(beta)
  // split between the entry lump (1, from the tight strand) and the exit
  // lump (2, into the slack strand). 0.5 and 1: the seed's even wrap.
  double entry_load_share = 0.5;    // s in (0, 1): lump 1 carries s, lump 2 1 - s
  double normal_load_factor = 1.0;  // f: effective normal load over F_ax / cos(beta)
  FrictionParams<double> friction = friction_presets::table2_case1<double>();
  // Kinematic holds (docs/rom.md#holds): the pulley runs at its initial speed
  // whatever the torques; the held torque is reported as the input/load torque.
  bool hold_driver_speed = false;
  bool hold_driven_speed = false;
  // Below this |v_rel| a lump is reported as sticking [m/s] (output only).
  double stick_speed_m_s = 0.01;
  // Pulley speeds beyond this are outside the model (no centrifugal chain
  // load, chain speeds of 150 m/s and more): the watchdog faults
  // (speed-out-of-range, docs/rom.md#watchdog) [rad/s]. 2000 rad/s = 19,100 rpm.
  double speed_limit_rad_s = 2000.0;

  // feature: axial (docs/rom.md#axial)
  double actuator_tau_s = 0.02;       // hydraulic clamping lag
  double clamp_max_N = 40000.0;       // actuator saturation F_max
  double sheave_mass_kg = 2.0;        // movable sheave
  double sheave_damping_Ns_m = 1045.0;  // zeta = 0.3 with K_ax and m_s
  double K_ax_N_m = 1518434.7499250777; // n_w * K_b

  // feature: road_load (docs/rom.md#road-load), at the driven shaft
  double road_T0_Nm = 0.0;
  double road_cv_Nms_rad = 0.0;
  double road_ca_Nms2_rad2 = 0.0;
  double road_w_eps_rad_s = 1.0;     // tanh smoothing of the rolling-resistance sign

  // feature: deformation (docs/rom.md#deformation): lump wrap angles
  double zeta1_rad = 0.74726119582927043;  // theta1/4: centre of the leading half wrap
  double zeta2_rad = 2.2417835874878113;   // 3 theta1/4

  // feature: polygon (docs/rom.md#polygon)
  double pitch_m = seed::kLinkLength_m;  // link length L
  // docs/rom.md#link-ripple: the lumps' normal load and the reported F_ax
  // carry F_ax (1 + A cos(pi psi / alpha + phi0)), A = gain (2/pi)
  // sin(pi d) / n_w, the fundamental of the loaded-bolt count (n_w = r1
  // theta1 / L links in the driver wrap, d its fractional part). 0 (the
  // default) leaves F_ax smooth, bit for bit; 1 is rigid bolts.
  double ripple_gain = 0.0;

  // feature: wedging (docs/rom.md#wedging). Needs axial: the bolt force then
  // also depends on the chain's radial position.
  double driven_clamp_N = 3636.8353493461495;  // constant driven clamping F_ax2 (holds the ratio at 3.3 kN)
  double radial_mass_kg = 2.0166389766945220;  // (n_w1 + kappa^2 n_w2) x 0.1125 kg
  double radial_damping_Ns_m = 93.8;           // zeta = 0.05 of the chain-on-bolt mode (74 Hz)
  double radial_travel_m = 0.025;              // |r1 - r1_m| at the ratio end stops (pulley hub / rim)
  double radial_stop_N_m = 1.0e7;              // end-stop contact stiffness; 2x the travel is a fault
  // docs/rom.md#wrap-tension: the driver wrap's mean tension exceeds the
  // driven wrap's by eta times the strands' tension difference; 0 is the
  // no-load thrust ratio (the ratio holds under torque).
  double wrap_tension_share = 0.0;             // eta in [0, 1)

  // feature: tension (docs/rom.md#tension). The chain's tension state: creep
  // of the soft chain under load (the driver's surface runs at the tight
  // strand's speed), its centrifugal tension m' v_c^2, and the driver sheave
  // held by its clamping force or closed on its stop (or fixed).
  double chain_mass_kg_m = 3.0910877470796927;  // m': 44 links of 0.1125 kg on the 1.6014 m pitch line; 0: no centrifugal tension
  double centrifugal_gain = 1.7862;             // kappa: T_c = kappa m' v_c^2 on the driver wrap, v_c the slack strand's speed
  double chain_stiffness_N = 2700.0;            // k L: a link's pitch is L (1 + T / (k L))
  double creep_gain = 1.0;                      // g: 1 = belt-creep theory; 0: no creep
  // docs/rom.md#tension-parameters: measured on the multibody reference,
  // fixed sheaves, seed case 1 (at rest, and over 0.5-1 s).
  double stop_tension_N = 536.86268306837;      // T_max: the driver wrap's mean tension at rest with the sheaves on their stops
  double stop_tension_share = 0.1671;           // eta_s: its rise per N of the strands' difference dT on the stops
  double wrap_excess_share = 0.1343;            // eta_w: the driver wrap's mean over the strands' mean, per N of dT
  bool fixed_sheaves = false;                   // the driver sheave never leaves its stop: the clamp input is unused
};

// The fastest driver whose link passing an integrator step of `step_s`
// resolves with 8 steps per link, |w1| h <= 2 alpha / 8 with alpha =
// asin(L / (2 r1)) (docs/rom.md#polygon) [rad/s]. Up to it ROS2 keeps the
// pulley speeds within 1e-4 of a resolved run; at 2.6 steps per link (one
// step per 1 ms frame at 150 rad/s) they were 7 % off without any fault.
inline double rom_polygon_resolved_speed_rad_s(const RomParams& p, double step_s) {
  return 2.0 * dm::asin_setup(p.pitch_m / (2.0 * p.r1_m)) / 8.0 / step_s;
}

// docs/rom.md#link-ripple: the links in the driver wrap, n_w = r1 theta1 / L,
// and the relative amplitude of the lumps' axial-force ripple, the
// fundamental of the loaded-bolt count that steps between floor(n_w) and
// floor(n_w) + 1 with duty d = n_w - floor(n_w): A = gain (2/pi) sin(pi d) / n_w.
inline double rom_wrap_links(const RomParams& p) {
  return p.r1_m * seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, p.center_distance_m) / p.pitch_m;
}
inline double rom_wrap_links_fraction(const RomParams& p) {
  const double n_w = rom_wrap_links(p);
  return n_w - static_cast<double>(static_cast<long>(n_w));
}
inline double rom_ripple_amplitude(const RomParams& p) {
  return p.ripple_gain * (2.0 / kPi) * dm::sin(kPi * rom_wrap_links_fraction(p)) / rom_wrap_links(p);
}

// The link phase's rate at a starting state, or a bound of it [rad/s]: w1,
// or with the tension feature (2 alpha / L) r2 |w2| kL / (kL + T_s) <= (2
// alpha / L) r2 |w2| (docs/rom.md#link-ripple), r2 the driven radius at the
// chain's starting radial offset (wedging; 0 at a fixed ratio), which scene
// validation holds against rom_polygon_resolved_speed_rad_s.
inline double rom_polygon_phase_rate_bound_rad_s(const RomParams& p, double omega1_rad_s, double omega2_rad_s,
                                                 bool tension, double radius_offset_m = 0.0) {
  const double r2 = radius_offset_m == 0.0
                        ? p.r2_m
                        : seed::driven_pitch_radius_m(p.r1_m, p.r2_m, p.center_distance_m, radius_offset_m);
  const double w =
      tension ? 2.0 * dm::asin_setup(p.pitch_m / (2.0 * p.r1_m)) / p.pitch_m * r2 * omega2_rad_s : omega1_rad_s;
  return w < 0.0 ? -w : w;
}

// Plant inputs, held constant over a frame (zero-order hold).
template <class T>
struct RomInputs {
  T tau_in_Nm = T(0);     // driver torque
  T tau_load_Nm = T(0);   // load torque at the driven shaft (road load adds to it)
  T clamp_N = T(0);       // axial force F_ax (no axial feature) or clamping command F_cmd (axial)
};

// Initial conditions in SI (set-up only).
struct RomInitial {
  double omega1_rad_s = 0, omega2_rad_s = 0;
  double x1_m = 0, xd1_m_s = 0, x2_m = 0, xd2_m_s = 0;
  double phase_rad = 0;  // polygon: link-passing phase psi in [-alpha, alpha)
  double radius_offset_m = 0;  // wedging: r1 - r1_m at the start (r2 follows, docs/rom.md#wedging)
  // axial: actuator force and bolt compression start at the static
  // equilibrium of the first frame's command (F_h = F_cmd, delta = F_cmd/K_ax).
};

}  // namespace cvt
