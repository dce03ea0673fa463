#pragma once
// What the reduced-order plant reports each frame (docs/rom.md#outputs).
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/rom_formulas.hpp"

namespace cvt {

// Everything a frame reports (docs/rom.md#outputs). Forces in N, torques in N m.
template <class T>
struct RomOutputs {
  T omega1_rad_s{}, omega2_rad_s{};
  T speed_ratio{};        // w1 / w2 (0 while |w2| < 1e-3 rad/s)
  T geometric_ratio{};    // r2 / r1 (varies with wedging)
  T radius1_m{}, radius2_m{};  // pitch radii (constant unless wedging)
  T slip{};               // (v1 - v_c) / v1 (0 while |v1| < 1e-3 m/s)
  T clamp_force_N{};      // F_ax acting on the lumps (with the link-passing ripple under chordal action)
  T torque_transmitted_Nm{};  // r1e (F1 + F2): friction torque on the driver
  T tau_in_Nm{}, tau_load_Nm{};  // as applied (held pulleys report the holding torque)
  T friction1_N{}, friction2_N{};            // tangential friction on the lumps
  T radial_friction1_N{}, radial_friction2_N{};  // along the flank, radial direction (wedging; seed Eq. 7 F_r)
  T v_rel1_m_s{}, v_rel2_m_s{};
  // The chain's tension state (feature tension, docs/rom.md#tension; else 0).
  T tension_tight_N{}, tension_slack_N{};  // T_t, T_s
  T centrifugal_tension_N{};               // m' v_c^2
  T creep_strain{};                        // dT / (kL + T_s)
  bool stick1 = false, stick2 = false;
  bool sheave_on_stop = false;             // tension: the driver sheave on its stop (or fixed), T_1 = T_stop
  // Wedging (docs/rom.md#driven-clamping, #end-stop; else 0 and false): the
  // driven clamping force F_ax2, and the chain pressed into a ratio end stop,
  // at the driver's smallest radius (underdrive) or its largest (overdrive).
  T driven_clamp_force_N{};
  bool stop_underdrive = false, stop_overdrive = false;
};

}  // namespace cvt
