#pragma once
// The energy bookkeeping of the reduced-order plant (docs/rom.md#energy-balance):
// the accounting type, the power terms at a state and the ledger of the work
// done, whose residual the watchdog checks.
#include <type_traits>


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

}  // namespace cvt
