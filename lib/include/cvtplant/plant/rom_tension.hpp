#pragma once
// The chain's tension state of the reduced-order plant (feature `tension`,
// docs/rom.md#tension): what the plant computes once per state from the
// strands' force difference, the chain speed and the driver sheave's regime,
// and the formulas it is built from, one function each. The law itself is
// RomTension::chain (feature/tension.hpp); the plant's other pieces
// (contact, right-hand side, Jacobian, outputs, ledger) read its result.
//
// Fixed point (RomUnits): the tensions are in N like every force; the creep
// strain's denominator kL + T_s (a few kN) is taken in RomUnits::tension_N,
// so that its inverse keeps 1e-4 of resolution in q16.16.

namespace cvt {

// The tension state at one plant state (docs/rom.md#tension). S is the
// plant's scalar, or a dual number for the dual-number Jacobian.
template <class S>
struct ChainTension {
  S dT{};     // T_t - T_s = F_s1 + F_s2, the strands' force difference [N]
  S T_c{};    // the driver wrap's centrifugal tension kappa m' v_c^2 [N]
  S T_1{};    // the driver wrap's mean tension, min(T_clamp, T_stop) [N]
  S T_s{};    // slack strand, >= 0 and >= -dT (no strand in compression) [N]
  S F_ax{};   // the chain's axial force on the driver sheave, >= 0 [N]
  S inv_D{};  // 1 / (kL + T_s), in 1 / RomUnits::tension_N
  S eps{};    // creep strain dT / (kL + T_s) [-]
  S creep{};  // g eps v_c: the chain entering the driver wrap runs this much faster than v_c [m/s]
  bool on_stop = false;  // the sheave is on its stop (or fixed): T_1 = T_stop
  bool lifted = false;   // T_1 <= T_c: the wrap presses on nothing, F_ax = 0
  bool floored = false;  // T_s at its floor max(0, -dT)
};

// The shared contact carries the tension state with the feature and nothing
// without it: an empty base takes no space, so a plant without the feature
// copies and computes what it did before.
template <class T, bool kTension>
struct RomContactTension {};
template <class T>
struct RomContactTension<T, true> {
  ChainTension<T> tension{};
};

// Centrifugal tension of a chain of m kg per metre running at v_c, m v_c^2
// (docs/rom.md#tension; the plant's m is kappa m') [N]. q16.16 saturates
// above sqrt(32767 N / m), 77 m/s for Table 1's chain and the default kappa:
// the simulator faults tension-out-of-range there (docs/rom.md#watchdog).
template <class S>
inline S centrifugal_tension(const S& m_per_length, const S& vc) {
  return (m_per_length * vc) * vc;
}

// Axial force of the driver wrap at mean tension T against the centrifugal
// tension T_c, theta1 (T - T_c) / (2 tan beta0) = cF (T - T_c)
// (docs/rom.md#tension; the V-belt form of docs/rom.md#wrap-tension) [N].
template <class S>
inline S wrap_axial_force(const S& cF, const S& T, const S& Tc) {
  return cF * (T - Tc);
}

// The driver wrap's mean tension that a clamping force F holds, T_c + F / cF [N].
template <class S>
inline S clamped_wrap_tension(const S& inv_cF, const S& F, const S& Tc) {
  return F * inv_cF + Tc;
}

// Extra speed of the chain entering the driver wrap from the tight strand,
// (g eps) v_c: belt-creep theory's v_t = v_c (1 + eps) with gain g
// (docs/rom.md#tension) [m/s].
template <class S>
inline S creep_speed(const S& gain, const S& eps, const S& vc) {
  return (gain * eps) * vc;
}

}  // namespace cvt
