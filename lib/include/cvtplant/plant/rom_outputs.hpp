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

// The outputs of `plant` (a CvtRom) at state x with its current inputs.
template <class Plant>
inline RomOutputs<typename Plant::Scalar> rom_outputs(const Plant& plant,
                                                     const typename Plant::State& x) {
  using T = typename Plant::Scalar;
  using L = typename Plant::Layout;
  const auto& c = plant.constants();
  RomOutputs<T> o;
  const T w1 = x(L::kW1), w2 = x(L::kW2);
  const T r1e = plant.driver_radius(x);
  const T r2 = plant.pitch_radius2(x);
  const T v1 = r1e * w1;
  const T vc = r2 * w2;
  T fax, vc1 = vc;
  if constexpr (L::kTension) {
    // docs/rom.md#tension: the chain's axial force, and the entry lump meets
    // the chain at the tight strand's speed.
    const auto t = plant.chain_tension(x, vc);
    fax = t.F_ax;
    vc1 = vc + t.creep;
    o.tension_slack_N = t.T_s;
    o.tension_tight_N = t.T_s + t.dT;
    o.centrifugal_tension_N = t.T_c;
    o.creep_strain = t.eps;
    o.sheave_on_stop = t.on_stop;
  } else {
    fax = plant.clamp_force(x);
  }
  // docs/rom.md#link-ripple: the lumps' axial force, rippled under chordal action.
  fax = plant.lumps_axial_force(fax, plant.ripple_cos(x));
  o.omega1_rad_s = w1;
  o.omega2_rad_s = w2;
  o.radius1_m = plant.pitch_radius1(x);
  o.radius2_m = r2;
  o.geometric_ratio = r2 / o.radius1_m;
  const T w_tiny = T(1e-3);
  o.speed_ratio = abs(w2) < w_tiny ? T(0) : w1 / w2;
  o.slip = abs(v1) < w_tiny ? T(0) : (v1 - vc) / v1;
  o.clamp_force_N = fax;
  o.v_rel1_m_s = slip_velocity<T>(vc1, x(L::kV1), v1);
  o.v_rel2_m_s = slip_velocity<T>(vc, x(L::kV2), v1);
  if constexpr (L::kWedge) {
    const auto w = plant.wedge_contact(o.v_rel1_m_s, o.v_rel2_m_s, x(L::kRhoDot), fax);
    o.friction1_N = w.F1;
    o.friction2_N = w.F2;
    o.radial_friction1_N = w.Fr1;
    o.radial_friction2_N = w.Fr2;
    o.driven_clamp_force_N = T(c.driven_clamp_si_N);
    const T pen = plant.stop_penetration(x(L::kRho));
    o.stop_overdrive = pen > T(0);
    o.stop_underdrive = pen < T(0);
  } else {
    o.friction1_N = lump_friction(friction_characteristic(c.friction, o.v_rel1_m_s), normal_force(fax, c.load1));
    o.friction2_N = lump_friction(friction_characteristic(c.friction, o.v_rel2_m_s), normal_force(fax, c.load2));
  }
  o.torque_transmitted_Nm = friction_torque(r1e, o.friction1_N, o.friction2_N);
  o.tau_in_Nm = c.hold1 ? o.torque_transmitted_Nm : plant.inputs.tau_in_Nm;
  if (c.hold2) {
    const auto st = plant.strands(x);
    o.tau_load_Nm = strand_torque(r2, st.s1, st.s2);
  } else {
    o.tau_load_Nm = plant.load_torque(w2);
  }
  o.stick1 = abs(o.v_rel1_m_s) < c.stick_speed;
  o.stick2 = abs(o.v_rel2_m_s) < c.stick_speed;
  return o;
}

}  // namespace cvt
