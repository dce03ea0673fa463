#pragma once
// The energy bookkeeping of the reduced-order plant (docs/rom.md#energy-balance):
// the accounting type, the power terms at a state and the ledger of the work
// done, whose residual the watchdog checks.
#include <type_traits>

#include "cvtplant/plant/rom_formulas.hpp"

namespace cvt {

// The type the energy bookkeeping runs in: float for fixed point (energies of
// 1e5 J do not fit q16.16) and the plant's own type otherwise.
template <class T>
using RomAcc = std::conditional_t<std::is_same_v<T, double>, double, float>;

// Instantaneous power terms [W] (docs/rom.md#energy-balance): dE/dt =
// input + actuator - load - friction_loss - damping_loss.
template <class A>
struct RomPower {
  A input_W{}, actuator_W{}, load_W{}, friction_loss_W{}, damping_loss_W{};
};

// Work done since reset [J]; all losses counted positive.
//
// Each work term is a running sum of one trapezoid per substep, so after
// 1e7 frames in float the sum is 1e7 times its increments and an increment
// below half an ulp of the sum is lost: the ledger stops moving while the
// stored energy does, and the residual drifts. The sums are compensated
// (Kahan): the part of each increment that the addition rounded away is
// kept and added to the next one, so a sum is accurate to a few ulp
// whatever the number of terms (docs/rom.md#soak). This needs the
// additions done as written (-ffp-contract=off, no -ffast-math).
template <class A>
struct EnergyLedger {
  A stored0_J{}, stored_J{};
  A input_J{}, actuator_J{}, load_J{}, friction_loss_J{}, damping_loss_J{};
  // What each sum's last addition rounded away (Kahan compensation).
  A input_c{}, actuator_c{}, load_c{}, friction_loss_c{}, damping_loss_c{};

  // Adds the trapezoid h/2 (p0 + p1) of every power term (docs/rom.md#energy-balance).
  void add_trapezoid(const RomPower<A>& p0, const RomPower<A>& p1, A half_h) {
    add(input_J, input_c, half_h * (p0.input_W + p1.input_W));
    add(actuator_J, actuator_c, half_h * (p0.actuator_W + p1.actuator_W));
    add(load_J, load_c, half_h * (p0.load_W + p1.load_W));
    add(friction_loss_J, friction_loss_c, half_h * (p0.friction_loss_W + p1.friction_loss_W));
    add(damping_loss_J, damping_loss_c, half_h * (p0.damping_loss_W + p1.damping_loss_W));
  }

  // E - E0 - (W_in + W_act - W_load - W_fric - W_damp): zero for the exact
  // solution; positive = energy the inputs cannot explain.
  A residual_J() const {
    return (stored_J - stored0_J) - (input_J + actuator_J - load_J - friction_loss_J - damping_loss_J);
  }
  // The size of the energy flows, to make the residual relative.
  A scale_J() const {
    auto a = [](A v) { return v < A(0) ? -v : v; };
    return a(stored0_J) + a(stored_J) + a(input_J) + a(actuator_J) + a(load_J) + a(friction_loss_J) +
           a(damping_loss_J);
  }

 private:
  static void add(A& sum, A& comp, A x) {
    const A y = x - comp;
    const A t = sum + y;
    comp = (t - sum) - y;
    sum = t;
  }
};

// A plant value in the accounting type.
template <class T>
inline RomAcc<T> rom_to_acc(const T& v) {
  if constexpr (std::is_floating_point_v<T>) return static_cast<RomAcc<T>>(v);
  else return v.to_float();
}

// Stored energy of `plant` (a CvtRom) at state xs [J], in the accounting type:
// E = 1/2 J1 w1^2 + 1/2 J2 w2^2 + 1/2 m sum (v_c + xd_i)^2 + 1/2 k1 sum x_i^2
//   + 1/2 k2 (x1 - x2)^2 (+ sheave, radial and end-stop terms).
template <class Plant>
inline RomAcc<typename Plant::Scalar> rom_stored_energy(const Plant& plant,
                                                      const typename Plant::State& xs) {
  using L = typename Plant::Layout;
  using U = typename Plant::U;
  using Acc = RomAcc<typename Plant::Scalar>;
  const auto& a = plant.constants().acc;
  Acc x[Plant::kStates];
  for (int i = 0; i < Plant::kStates; ++i) x[i] = rom_to_acc(xs(i));
  if constexpr (U::kScaled) {
    // Displacements back to metres: energies of 1e5 J are only kept in float.
    x[L::kX1] *= Acc(U::length_m);
    x[L::kX2] *= Acc(U::length_m);
    if constexpr (L::kAxial) x[L::kDelta] *= Acc(U::length_m);
  }
  const Acc w1 = x[L::kW1], w2 = x[L::kW2];
  Acc r2 = a.r2;
  Acc dr2 = Acc(0);
  if constexpr (L::kWedge) {
    dr2 = driven_radius_change(x[L::kRho], a.a1, a.a2, a.a3);
    r2 += dr2;
  }
  const Acc vc = r2 * w2;
  const Acc u1 = vc + x[L::kV1], u2 = vc + x[L::kV2];
  const Acc dx = x[L::kX1] - x[L::kX2];
  // Strand stretches (docs/rom.md#wrap-tension).
  Acc e1 = x[L::kX1], e2 = x[L::kX2];
  if constexpr (L::kWedge) {
    e1 = strand_stretch(e1, a.wrap_g, x[L::kRho]);
    e2 = strand_stretch(e2, a.wrap_g, x[L::kRho]);
  }
  Acc e = Acc(0.5) * (a.J1 * w1 * w1 + a.J2 * w2 * w2 + a.m * (u1 * u1 + u2 * u2) +
                      a.k1 * (e1 * e1 + e2 * e2) + a.k2 * dx * dx);
  if constexpr (L::kAxial) {
    Acc b = x[L::kDelta];
    if constexpr (L::kWedge) b -= a.two_tan_b0 * x[L::kRho];
    const Acc d = b > Acc(0) ? b : Acc(0);
    e += Acc(0.5) * (a.ms * x[L::kDeltaDot] * x[L::kDeltaDot] + a.K_ax * d * d);
  }
  if constexpr (L::kWedge) {
    // Radial kinetic energy and the potential of the (constant) driven
    // clamping force through chain length conservation.
    const Acc pen = rom_to_acc(plant.stop_penetration(xs(L::kRho)));
    e += Acc(0.5) * a.mr * x[L::kRhoDot] * x[L::kRhoDot] - a.driven_force * dr2 + Acc(0.5) * a.k_stop * pen * pen;
  }
  return e;
}

// The power terms common to every feature set, from the applied torques and
// the tangential friction forces.
template <class Plant>
inline RomPower<RomAcc<typename Plant::Scalar>> rom_power_given(
    const Plant& plant, const typename Plant::State& xs, const typename Plant::Scalar& tau_in,
    const typename Plant::Scalar& tau_load, const typename Plant::Scalar& F1, const typename Plant::Scalar& F2,
    const typename Plant::Scalar& vr1, const typename Plant::Scalar& vr2) {
  using L = typename Plant::Layout;
  using Acc = RomAcc<typename Plant::Scalar>;
  const auto& a = plant.constants().acc;
  Acc x[Plant::kStates];
  for (int i = 0; i < Plant::kStates; ++i) x[i] = rom_to_acc(xs(i));
  RomPower<Acc> pw;
  pw.input_W = rom_to_acc(tau_in) * x[L::kW1];
  pw.load_W = rom_to_acc(tau_load) * x[L::kW2];
  pw.friction_loss_W = -(rom_to_acc(F1) * rom_to_acc(vr1) + rom_to_acc(F2) * rom_to_acc(vr2));
  const Acc dv = x[L::kV1] - x[L::kV2];
  // Strand stretch rates (docs/rom.md#wrap-tension).
  Acc sv1 = x[L::kV1], sv2 = x[L::kV2];
  if constexpr (L::kWedge) {
    sv1 = strand_stretch(sv1, a.wrap_g, x[L::kRhoDot]);
    sv2 = strand_stretch(sv2, a.wrap_g, x[L::kRhoDot]);
  }
  pw.damping_loss_W = a.c1 * (sv1 * sv1 + sv2 * sv2) + a.c2 * dv * dv;
  if constexpr (L::kAxial) {
    pw.actuator_W = x[L::kFh] * x[L::kDeltaDot];
    pw.damping_loss_W += a.cs * x[L::kDeltaDot] * x[L::kDeltaDot];
  }
  return pw;
}

// The power terms of a wedging plant with its contact at xs (rom_power).
template <class Plant>
inline RomPower<RomAcc<typename Plant::Scalar>> rom_power_wedging(const Plant& plant,
                                                                  const typename Plant::State& xs,
                                                                  const typename Plant::Contact& contact) {
  using T = typename Plant::Scalar;
  using L = typename Plant::Layout;
  using Acc = RomAcc<T>;
  const auto& c = plant.constants();
  const T F1 = contact.lump1.F, F2 = contact.lump2.F;
  const T tau_in = c.hold1 ? friction_torque(plant.driver_radius(xs), F1, F2) : plant.inputs.tau_in_Nm;
  T tau_load;
  if (c.hold2) {
    const auto st = plant.strands(xs);
    tau_load = strand_torque(plant.pitch_radius2(xs), st.s1, st.s2);
  } else {
    tau_load = plant.load_torque(xs(L::kW2));
  }
  RomPower<Acc> pw = rom_power_given(plant, xs, tau_in, tau_load, F1, F2, contact.v_t1, contact.v_t2);
  // Radial slip along the flank is rhodot / cos(beta_i).
  const Acc rd = rom_to_acc(xs(L::kRhoDot));
  pw.friction_loss_W -= rom_to_acc(contact.lump1.Fr) * rd * rom_to_acc(c.inv_cos1) +
                        rom_to_acc(contact.lump2.Fr) * rd * rom_to_acc(c.inv_cos2);
  pw.damping_loss_W += c.acc.cr * rd * rd;
  return pw;
}

// The power terms of a plant without wedging with its contact at xs (rom_power).
template <class Plant>
inline RomPower<RomAcc<typename Plant::Scalar>> rom_power_fixed_ratio(const Plant& plant,
                                                                      const typename Plant::State& xs,
                                                                      const typename Plant::Contact& contact) {
  using T = typename Plant::Scalar;
  using L = typename Plant::Layout;
  const auto& c = plant.constants();
  const T fax = plant.axial_force(xs, contact);
  const T F1 = lump_friction(contact.lump1.phi, normal_force(fax, c.load1));
  const T F2 = lump_friction(contact.lump2.phi, normal_force(fax, c.load2));
  const T tau_in = c.hold1 ? friction_torque(contact.r1e, F1, F2) : plant.inputs.tau_in_Nm;
  T tau_load;
  if (c.hold2) {
    const auto st = plant.strands(xs);
    tau_load = strand_torque(c.r2, st.s1, st.s2);
  } else {
    tau_load = plant.load_torque(xs(L::kW2));
  }
  if constexpr (L::kTension) {
    RomPower<RomAcc<T>> pw = rom_power_given(plant, xs, tau_in, tau_load, F1, F2, contact.v_rel1, contact.v_rel2);
    // docs/rom.md#tension-energy: the creep loss F_1 g eps v_c, the power the
    // driver puts into chain that runs faster than the lumps' frame.
    pw.friction_loss_W += rom_to_acc(F1) * rom_to_acc(contact.tension.creep);
    return pw;
  } else {
    return rom_power_given(plant, xs, tau_in, tau_load, F1, F2, contact.v_rel1, contact.v_rel2);
  }
}

// The power terms with the contact already evaluated at xs (contact =
// plant.contact(xs)); forces and torques as rom_outputs() computes them, so
// the terms are bit for bit those of the outputs (the fused friction values
// being the separate ones).
template <class Plant>
inline RomPower<RomAcc<typename Plant::Scalar>> rom_power(const Plant& plant, const typename Plant::State& xs,
                                                          const typename Plant::Contact& contact) {
  if constexpr (Plant::Layout::kWedge) return rom_power_wedging(plant, xs, contact);
  else return rom_power_fixed_ratio(plant, xs, contact);
}

// The power terms at xs with the plant's current inputs [W].
template <class Plant>
inline RomPower<RomAcc<typename Plant::Scalar>> rom_power(const Plant& plant,
                                                          const typename Plant::State& xs) {
  return rom_power(plant, xs, plant.contact(xs));
}

}  // namespace cvt
