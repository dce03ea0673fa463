#pragma once
// The formulas of the reduced-order plant that several of its parts use, one
// function each, written once (docs/rom.md). Each keeps the operation order
// the trace hashes were recorded with: a change here changes the bits of every
// target's trajectory (tests/determinism, tests/cross).
//
// Fixed point (RomUnits): the arguments are in the plant's units; every
// operation saturates (scalar/fixed.hpp), so an out-of-range intermediate
// shows as a state at a rail, which the watchdog reports.
//
// Also used by the multibody reference (mbd/), so that both models load the
// driven shaft by the same law.
#include "cvtplant/math/detmath.hpp"

namespace cvt {

// Slip velocity of a lump against the driver, v_rel = (v_c + xd) - v1, with
// the chain frame at v_c = r2 w2 and the driver surface at v1 = r1e w1
// (docs/rom.md#kinematics).
template <class S>
inline S slip_velocity(const S& v_chain, const S& xd, const S& v_driver) {
  return (v_chain + xd) - v_driver;
}

// Force of a lump's strand spring and damper, k1 x + c1 xd (seed Eq. 8;
// docs/rom.md#equations-of-motion).
template <class S>
inline S strand_force(const S& k1, const S& c1, const S& x, const S& xd) {
  return k1 * x + c1 * xd;
}

// Stretch of a lump's strand with the wrap-tension coupling, x + g rho
// (g = eta theta1; docs/rom.md#wrap-tension): the chain that the driver wrap
// gives up when it sinks by -rho goes into the strands. Applied alike to the
// stretch and its rate.
template <class S>
inline S strand_stretch(const S& x, const S& g, const S& rho) {
  return x + g * rho;
}

// Inward pull of the wrap tension on the chain's radial position, g (F_s1 +
// F_s2): theta1 times the driver wrap's mean tension in excess of the driven
// wrap's, eta (F_s1 + F_s2) (docs/rom.md#wrap-tension) [N]; strands_sum = F_s1 + F_s2.
template <class S>
inline S wrap_tension_pull(const S& g, const S& strands_sum) {
  return g * strands_sum;
}

// Torque of both strands on the driven pulley, r2 (F_s1 + F_s2).
template <class S>
inline S strand_torque(const S& r2, const S& strand1, const S& strand2) {
  return r2 * (strand1 + strand2);
}

// Normal load of a lump on both flanks, N_i = 2 s_i f F_ax / cos(beta_i)
// (seed Eq. 5 lumped; s_i the lump's share of the wrap's load, f the
// normal-load factor), as F_ax times the set-up constant
// load_i = 2 s_i f / cos(beta_i) (docs/rom.md#contact, #lump-load-split).
template <class S>
inline S normal_force(const S& clamp_force, const S& load_per_axial) {
  return clamp_force * load_per_axial;
}

// The set-up constant of normal_force for a lump: 2 share factor / cos(beta).
inline double lump_load_per_axial(double share, double factor, double cos_beta) {
  return 2.0 * share * factor / cos_beta;
}

// The lumps' axial force with the link-passing ripple, F_ax (1 + A cos(theta)),
// written F_ax + F_ax (A cos(theta)): theta is the link phase of the
// loaded-bolt count's fundamental, A its relative amplitude (seed Eq. 5: the
// axial force is the sum of the bolt forces; docs/rom.md#link-ripple) [N].
template <class S>
inline S rippled_axial_force(const S& clamp_force, const S& amplitude, const S& cos_theta) {
  return clamp_force + clamp_force * (amplitude * cos_theta);
}

// Rate of the link phase with the chain's tension state, 2 alpha times the
// links passing per second, (2 alpha / L) v_c kL / (kL + T_s): the slack
// strand runs at v_c with a pitch of L (1 + T_s / kL) (docs/rom.md#link-ripple)
// [rad/s]; phase_per_m = 2 alpha / L, inv_D = 1 / (kL + T_s) in kL's unit.
template <class S>
inline S link_phase_rate(const S& phase_per_m, const S& v_chain, const S& kL, const S& inv_D) {
  return (phase_per_m * v_chain) * (kL * inv_D);
}

// Friction on a lump, F = -phi(v_rel) N (docs/rom.md#contact).
template <class S>
inline S lump_friction(const S& phi, const S& normal) {
  return -phi * normal;
}

// Friction torque on the driver, r1e (F1 + F2): what the chain transmits.
template <class S>
inline S friction_torque(const S& r1e, const S& F1, const S& F2) {
  return r1e * (F1 + F2);
}

// Change of the driven pitch radius with the chain's radial position,
// r2(rho) - r2 = rho (a1 + rho (a2 + rho a3)) (docs/rom.md#wedging).
template <class S>
inline S driven_radius_change(const S& rho, const S& a1, const S& a2, const S& a3) {
  return rho * (a1 + rho * (a2 + rho * a3));
}

// Load torque at the driven shaft with road load (docs/rom.md#road-load):
// tau_load + T0 tanh(w2 / w_eps) + c_v w2 + c_a w2 |w2| [N m], w_eps given as
// its inverse. tanh and abs are the core's (cvt::dm for double and float;
// Fixed and Dual carry their own), so a dual number w2 gives the slope too.
// road_load_torque_at takes tanh(w2 / w_eps) already evaluated (the plant
// keeps it with a state's contact, docs/rom.md#cost).
template <class S>
inline S road_load_torque_at(const S& tau_load, const S& T0, const S& tanh_w, const S& cv, const S& ca, const S& w2) {
  return tau_load + T0 * tanh_w + cv * w2 + ca * w2 * abs(w2);
}
template <class S>
inline S road_load_torque(const S& tau_load, const S& T0, const S& inv_w_eps, const S& cv, const S& ca,
                          const S& w2) {
  return road_load_torque_at(tau_load, T0, S(tanh(w2 * inv_w_eps)), cv, ca, w2);
}

}  // namespace cvt
