#pragma once
// The plant's core, present in every plant (docs/rom.md#state,
// #equations-of-motion): the seed's 2-DOF stick-slip oscillator (Eq. 8/9)
// made into a drive train. States w1, w2 (pulley speeds) and x_i, xd_i (the
// link lumps' displacement and velocity relative to the chain frame):
//   J1 w1' = tau_in - r1e (F1 + F2)
//   J2 w2' = r2 (F_s1 + F_s2) - tau_load,   F_s,i = k1 e_i + c1 e_i'
//   m (xd_i' + d(v_c)/dt) = F_i - F_s,i -+ (k2 (x1 - x2) + c2 (xd1 - xd2))
// The radii, the strands' stretch e_i, the chain frame's acceleration and
// the friction forces F_i come from the other pieces; this one holds the
// constants they share (inertias, springs, friction law, flank loads, holds).
#include <cstdint>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/feature/deformation.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

template <class Cfg>
class RomDriveTrain {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  RomDriveTrain(const RomParams& p, const RomFlankAngles& b) {
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
    inv_cos1 = T(1.0 / dm::cos(b.beta1_rad));
    inv_cos2 = T(1.0 / dm::cos(b.beta2_rad));
    // docs/rom.md#lump-load-split: the entry lump (1) carries the share s of
    // the wrap's normal load, the exit lump (2) the rest; set-up constants,
    // so the split costs nothing per step.
    load1 = T(lump_load_per_axial(p.entry_load_share, p.normal_load_factor, dm::cos(b.beta1_rad)));
    load2 = T(lump_load_per_axial(1.0 - p.entry_load_share, p.normal_load_factor, dm::cos(b.beta2_rad)));
    hold1 = p.hold_driver_speed;
    hold2 = p.hold_driven_speed;
    stick_speed = T(p.stick_speed_m_s);
    // docs/rom.md#slope-floor: the edge of the sign's regularisation layer
    // (none for the exact sign) and the friction slope there.
    if (p.friction.sign != SignFunction::exact) {
      floor_speed = T(1.0 / p.friction.lambda_s_m);
      slope_floor = friction_characteristic_slope(friction, floor_speed);
    }
    acc.J1 = Acc(p.J1_kgm2);
    acc.J2 = Acc(p.J2_kgm2);
    acc.m = Acc(p.lump_mass_kg);
    acc.k1 = Acc(p.k1_N_m);
    acc.k2 = Acc(p.k2_N_m);
    acc.c1 = Acc(p.c1_Ns_m);
    acc.c2 = Acc(p.c2_Ns_m);
    acc.r2 = Acc(p.r2_m);
  }

  template <class X>
  void initial_state(const RomInitial& x0, X& x) const {
    x(L::kW1) = T(x0.omega1_rad_s);
    x(L::kW2) = T(x0.omega2_rad_s);
    x(L::kX1) = T(x0.x1_m / U::length_m);
    x(L::kV1) = T(x0.xd1_m_s);
    x(L::kX2) = T(x0.x2_m / U::length_m);
    x(L::kV2) = T(x0.xd2_m_s);
  }
  template <class Y>
  void to_si(Y& y) const {
    y(L::kX1) *= U::length_m;
    y(L::kX2) *= U::length_m;
  }

  // w1' (zero for a held driver) from the friction torque r1e (F1 + F2).
  template <class S>
  S driver_row(const S& tau_in, const S& r1e, const S& F1, const S& F2) const {
    return hold1 ? S(T(0)) : Cfg::per_tau((tau_in - friction_torque(r1e, F1, F2)) * S(inv_J1));
  }
  // w2' (zero for a held driven pulley) from the strands' torque and the load.
  template <class S>
  S driven_row(const S& r2e, const S& strand1, const S& strand2, const S& load) const {
    return hold2 ? S(T(0)) : Cfg::per_tau((strand_torque(r2e, strand1, strand2) - load) * S(inv_J2));
  }
  // Every row of the core from w1', w2', the chain frame's acceleration and
  // the friction forces. Spring groupings match StickSlipOscillator so that
  // the held-pulley scene reproduces seed Eq. 9 to the last bit
  // (docs/rom.md#holds). Displacement rows need no time-unit factor: length
  // unit / time unit = 1 m/s.
  template <class S>
  void rows(const Vec<S>& x, const S& w1dot, const S& w2dot, const S& chain_acc, const S& F1, const S& F2,
            const S& strand1, const S& strand2, Vec<S>& dxdt) const {
    const S x1 = x(L::kX1), xd1 = x(L::kV1), x2 = x(L::kX2), xd2 = x(L::kV2);
    const S mid = S(k2) * (x1 - x2) + S(c2) * (xd1 - xd2);
    dxdt(L::kW1) = w1dot;
    dxdt(L::kW2) = w2dot;
    dxdt(L::kX1) = xd1;
    dxdt(L::kV1) = Cfg::per_tau((F1 - strand1 - mid) * S(inv_m)) - chain_acc;
    dxdt(L::kX2) = xd2;
    dxdt(L::kV2) = Cfg::per_tau((F2 - strand2 + mid) * S(inv_m)) - chain_acc;
  }

  // The driven row's partials at a fixed ratio: the load's slope dtl and the
  // strands' springs and dampers through r2 (per time unit); zero when held.
  void driven_partials(const T& r2e, const T& dtl, T* rw2) const {
    #pragma GCC unroll 16
    for (int j = 0; j < Cfg::N; ++j) rw2[j] = T(0);
    if (hold2) return;
    rw2[L::kW2] = Cfg::per_tau(-dtl * inv_J2);
    rw2[L::kX1] = Cfg::per_tau(r2e * k1 * inv_J2);
    rw2[L::kV1] = Cfg::per_tau(r2e * c1 * inv_J2);
    rw2[L::kX2] = Cfg::per_tau(r2e * k1 * inv_J2);
    rw2[L::kV2] = Cfg::per_tau(r2e * c1 * inv_J2);
  }
  // The rows of x_i and xd_i: dF the friction forces' partials, dca the
  // chain frame acceleration's, per time unit.
  void lump_rows(const T (&dF)[2][Cfg::N], const T* dca, typename Cfg::Jacobian& J) const {
    // The constants in locals: every store to J (entries of type T) would
    // otherwise make the compiler read them from the plant again.
    const T im = inv_m, k1_ = k1, k2_ = k2, c1_ = c1, c2_ = c2;
    J(L::kX1, L::kV1) = T(1);
    J(L::kX2, L::kV2) = T(1);
    #pragma GCC unroll 16
    for (int j = 0; j < Cfg::N; ++j) {
      J(L::kV1, j) = dF[0][j] * im - dca[j];
      J(L::kV2, j) = dF[1][j] * im - dca[j];
    }
    J(L::kV1, L::kX1) += Cfg::per_tau(-(k1_ + k2_) * im);
    J(L::kV1, L::kX2) += Cfg::per_tau(k2_ * im);
    J(L::kV1, L::kV1) += Cfg::per_tau(-(c1_ + c2_) * im);
    J(L::kV1, L::kV2) += Cfg::per_tau(c2_ * im);
    J(L::kV2, L::kX1) += Cfg::per_tau(k2_ * im);
    J(L::kV2, L::kX2) += Cfg::per_tau(-(k1_ + k2_) * im);
    J(L::kV2, L::kV1) += Cfg::per_tau(c2_ * im);
    J(L::kV2, L::kV2) += Cfg::per_tau(-(c1_ + c2_) * im);
  }

  // 1/2 J1 w1^2 + 1/2 J2 w2^2 + 1/2 m sum (v_c + xd_i)^2 + 1/2 k1 sum e_i^2
  // + 1/2 k2 (x1 - x2)^2 [J]; x in SI, accounting type; r2e the driven radius,
  // e_i the strands' stretch.
  template <class A>
  A stored_energy(const A* x, const A& r2e, const A& e1, const A& e2) const {
    const A w1 = x[L::kW1], w2 = x[L::kW2];
    const A vc = r2e * w2;
    const A u1 = vc + x[L::kV1], u2 = vc + x[L::kV2];
    const A dx = x[L::kX1] - x[L::kX2];
    return A(0.5) * (acc.J1 * w1 * w1 + acc.J2 * w2 * w2 + acc.m * (u1 * u1 + u2 * u2) + acc.k1 * (e1 * e1 + e2 * e2) +
                     acc.k2 * dx * dx);
  }
  // The core's power terms from the applied torques, the tangential friction
  // forces at their slip speeds and the strands' stretch rates [W].
  template <class A>
  RomPower<A> power(const A* x, const T& tau_in, const T& tau_load, const T& F1, const T& F2, const T& vr1,
                    const T& vr2, const A& sv1, const A& sv2) const {
    RomPower<A> pw;
    pw.input_W = rom_to_acc(tau_in) * x[L::kW1];
    pw.load_W = rom_to_acc(tau_load) * x[L::kW2];
    pw.friction_loss_W = -(rom_to_acc(F1) * rom_to_acc(vr1) + rom_to_acc(F2) * rom_to_acc(vr2));
    const A dv = x[L::kV1] - x[L::kV2];
    pw.damping_loss_W = acc.c1 * (sv1 * sv1 + sv2 * sv2) + acc.c2 * dv * dv;
    return pw;
  }

  T r1{}, r2{}, inv_J1{}, inv_J2{}, inv_m{}, k1{}, c1{}, k2{}, c2{};
  FrictionParams<T> friction{};
  T inv_cos1{}, inv_cos2{}, stick_speed{};
  T load1{}, load2{};  // normal force per axial force of each lump (normal_force)
  bool hold1 = false, hold2 = false;
  T floor_speed{}, slope_floor{};  // docs/rom.md#slope-floor
  struct Accounting {
    Acc J1{}, J2{}, m{}, k1{}, k2{}, c1{}, c2{}, r2{};
  };
  Accounting acc;  // the energy ledger's copies, in the accounting type
};

}  // namespace cvt
