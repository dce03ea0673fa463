#pragma once
// Parameters of the planar multibody chain CVT (docs/mbd.md#parameters):
// seed Table 1 (chain, pulleys, bolts), Table 2 (friction, through the core's
// presets), the seed's section-4 load case, and the choices the seed leaves
// open (link count, link inertia, start-up, sheave mode), each with the
// reason given in docs/mbd.md.
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/physics/seed.hpp"

namespace cvt::mbd {

// The model's version: raised whenever a change to the equations, the
// start-up or the numerics changes what a run with the same inputs produces,
// so stored reference runs (`cvtplant validate`, `cvtplant calibrate`) are
// recomputed rather than reused.
inline constexpr int kReferenceVersion = 2;

// Fixed sheaves: the groove is rigid and fixed on the shaft (the seed's
// pulleys). Clamped: one sheave of each pulley is free to move axially and is
// pushed closed by a given force (docs/mbd.md#clamped-sheaves).
enum class SheaveMode { fixed, clamped };

// A quantity as a function of time: piecewise linear through (t_s, value)
// points, held constant before the first and after the last. The clamping
// forces [N] and the input and load torques [N m] are such profiles.
struct TimeProfile {
  std::vector<std::pair<double, double>> points;  // strictly increasing t_s
  double at(double t_s) const;
  bool empty() const { return points.empty(); }
  static TimeProfile constant(double value) { return TimeProfile{{{0.0, value}}}; }
};

// Road load on the driven shaft, the real-time plant's law
// (docs/rom.md#road-load, cvt::road_load_torque): the load torque is
// tau_load(t) + T0 tanh(w2 / w_eps) + c_v w2 + c_a w2 |w2|. All zero: none.
struct RoadLoad {
  double T0_Nm = 0.0;
  double cv_Nms_rad = 0.0;
  double ca_Nms2_rad2 = 0.0;
  double w_eps_rad_s = 1.0;  // tanh smoothing of the rolling-resistance sign
  bool active() const { return T0_Nm != 0.0 || cv_Nms_rad != 0.0 || ca_Nms2_rad2 != 0.0; }
};

// A start at speed (docs/mbd.md#start-at-speed): after the settle at rest the
// pulleys are run up to omega1, omega2 with the friction on (spin-up, both
// speeds imposed, a smooth ramp), then the driver is held at omega1 while the
// driven pulley runs free under the load at t = 0 and finds its own speed
// (hold); released at t = 0. Inactive: the release is from rest.
struct StartAtSpeed {
  bool active = false;
  double omega1_rad_s = 0.0, omega2_rad_s = 0.0;
  double spinup_s = 0.2;
  double hold_s = 1.0;
  double duration_s() const { return active ? spinup_s + hold_s : 0.0; }
};

// A pulley speed imposed kinematically (a test rig's motor): from the release
// on the pulley runs at omega_rad_s whatever the chain does (a speed step at
// t = 0), and the torque that holds it is booked as input (driver) or load
// (driven) work in the energy ledger.
struct SpeedHold {
  bool active = false;
  double omega_rad_s = 0.0;
};

struct MbdParams {
  // --- seed Table 1 and section 4 (docs/mbd.md#parameters)
  double beta0_rad = seed::kHalfSheaveAngle_rad;  // non-deformed half sheave angle
  double center_distance_m = seed::kCenterDistance_m;
  double link_mass_kg = seed::kLinkMass_kg;
  double J1_kgm2 = seed::kDriverInertia_kgm2;
  double J2_kgm2 = seed::kDrivenInertia_kgm2;
  double link_length_m = seed::kLinkLength_m;             // L: distance between a link's two pins
  double bolt_stiffness_N_m = seed::kBlockStiffness_N_m;  // K_b (Eq. 5)
  double bolt_length_m = seed::kBlockLength_m;            // l_b (Eq. 5)
  double joint_stiffness_N_m = seed::kChainStiffness_N_m;  // k, force element between links
  double joint_damping_Ns_m = seed::kChainDamping_Ns_m;    // p, force element between links
  double joint_rot_damping_Nms_rad = 0;  // articulation damper on the links' relative rotation (0: none, the seed's)
  double r1_m = seed::kDriverPitchRadius_m;  // driver pitch radius (bolt unloaded touches both flanks here)
  double r2_m = seed::kDrivenPitchRadius_m;  // driven pitch radius
  // --- choices the seed leaves open (docs/mbd.md#open-choices)
  int links = 44;                  // N: fills the pitch line with about 520 N of pretension
  double link_inertia_kgm2 = -1;   // <= 0: slender bar, m L^2 / 12
  bool sheave_deformation = true;  // seed Eq. 3-4 on both pulleys
  // --- friction (seed Eq. 6, Table 2), the core's laws and sign smoothing
  FrictionParams<double> friction = friction_presets::table2_case1<double>();
  // --- loads (seed section 4: constant torques) from the release on
  TimeProfile tau_in_Nm = TimeProfile::constant(seed::kInputTorque_Nm);
  TimeProfile tau_load_Nm = TimeProfile::constant(seed::kLoadTorque_Nm);
  RoadLoad road;  // added to tau_load on the driven pulley
  SpeedHold hold1, hold2;
  // --- sheaves
  SheaveMode sheaves = SheaveMode::fixed;
  TimeProfile clamp1_N;  // driver; required in clamped mode
  TimeProfile clamp2_N;  // driven; empty: clamp1 times the static thrust ratio theta2/theta1
  double sheave_mass_kg = 2.0;         // movable sheave (the real-time plant's value)
  double sheave_damping_Ns_m = 1045.0;  // zeta ~ 0.3 against the wrap's axial stiffness
  // Ratio end stops: the movable sheave travels +-2 tan(beta0) x 25 mm, the
  // real-time plant's +-25 mm of chain travel in the groove (hub and rim),
  // against a stiff stop (its 1e7 N/m radial stop seen axially).
  double sheave_stop_m = 0.013397459621556135;
  double sheave_stop_N_m = 3.5e7;
  // --- start-up (docs/mbd.md#start-up): chain wrapped on the pitch line,
  // pulleys held, a light drag on the links while it settles; released at t = 0.
  double settle_s = 0.1;
  double settle_drag_Ns_m = 20.0;
  StartAtSpeed start;  // after the settle; inactive: released from rest
  // Clamped sheaves: the chain wrapped at this driver radius (and the driven
  // radius that keeps the pitch line's length), the movable sheaves opened to
  // seat it there (docs/mbd.md#start-up); 0: on the pitch radii.
  double start_r1_m = 0;
  // Clamped sheaves: the driver's movable sheave held at its start opening
  // through the settle, the spin-up and the hold (a ratio lock, as a test
  // rig's position-controlled primary), the driven one clamped; the force that
  // holds it is the driver clamping that holds the ratio (docs/mbd.md#start-up).
  bool start_ratio_lock = false;
  // --- numerics: the error-weight scale of the links' rotation rates
  // (docs/mbd.md#tolerances).
  double tolerance_link_rate_rad_s = 10.0;

  double link_inertia() const {
    return link_inertia_kgm2 > 0 ? link_inertia_kgm2 : link_mass_kg * link_length_m * link_length_m / 12.0;
  }
};

// The seed's section-4 scenario: tau_in = 100 N m, tau_load = 50 N m, Table 1,
// friction case 1 or 2 of Table 2.
MbdParams seed_case(int friction_case);

// The named parameter sets (docs/mbd-production.md): the seed's Table 1 as
// printed, and a production-like chain CVT on the seed's geometry whose chain,
// bolts, friction and clamping come from published data on production chain
// CVTs.
enum class ParameterSet { seed, production };
const char* parameter_set_name(ParameterSet s);                      // "seed", "production"
std::optional<ParameterSet> parameter_set_by_name(std::string_view name);

// The production-like set with clamped sheaves, no loads and no clamping
// profile yet: a run sets the clamping forces, the torques and the start.
MbdParams production_set();

// What the production-like set is rated for (docs/mbd-production.md#envelope):
// the operating envelope a controller drives it in, and the clamping design
// the plausibility checks hold it to.
struct ProductionEnvelope {
  double rated_torque_Nm;         // input torque the variator is designed for
  double omega1_min_rad_s;        // primary speeds of the controller's envelope
  double omega1_max_rad_s;
  double clamp_min_N, clamp_max_N;  // clamping range of each pulley's actuator
  double clamp_safety;            // clamping safety factor against gross slip
  double ratio_underdrive, ratio_overdrive;  // geometric ratio r2/r1 at the driver's stops
};
ProductionEnvelope production_envelope();

}  // namespace cvt::mbd
