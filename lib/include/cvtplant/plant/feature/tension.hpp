#pragma once
// Feature `tension` (docs/rom.md#tension, #tension-radial): the chain's
// tension state. No state of its own: a function of the state, evaluated
// once per state with the friction (the contact) and read by the Jacobian,
// the right-hand side, the outputs and the ledger:
//   dT  = F_s1 + F_s2                              the strands' force difference
//   T_c = kappa m' v_c^2                           the driver wrap's centrifugal tension
//   T_1 = F_clamp / c_F + T_c                      sheave held by its clamping force
//       = T_max + eta_s dT                         sheave on its stop (fixed ratio only)
//   F_ax = c_F (T_1 - T_c) >= 0                    the chain's axial force on the lumps
//   T_s = T_1 - (eta_w + 1/2) dT >= max(0, -dT)    the slack strand
//   eps = dT / (kL + T_s),  creep = g eps v_c      the entry lump meets the chain faster
// c_F = theta1 / (2 tan beta0): at the set-up radii, or with the radial DOF
// theta1(rho) = 2 pi kappa(rho) / (1 + kappa(rho)) (the running radii move;
// the radial end stops are then the sheaves' stops).
// Energy: the creep loss F_1 g eps v_c (docs/rom.md#tension-energy).
//
// Fixed point (RomUnits): the tensions are in N like every force; the creep
// strain's denominator kL + T_s (a few kN) is taken in RomUnits::tension_N,
// so that its inverse keeps 1e-4 of resolution in q16.16.
#include <cstdint>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/feature/axial.hpp"
#include "cvtplant/plant/feature/radial.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/plant/rom_tension.hpp"

namespace cvt {

// The loads at a state carry the tension state with the feature (an empty
// base without it).
template <class S, bool kOn>
struct RomTensionLoads {};
template <class S>
struct RomTensionLoads<S, true> {
  ChainTension<S> tension{};
};

// Without the feature the lumps press with the clamping force and the chain
// runs at v_c everywhere.
template <class Cfg, bool kOn = Cfg::kTension>
class RomTension {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  using Cache = RomContactTension<T, false>;
  explicit RomTension(const RomParams&) {}
  bool fixed_sheaves() const { return false; }
  template <class S, class StrandsAt, class Radial, class Loads>
  void chain(const Vec<S>&, const StrandsAt&, const Radial&, Loads& l) const {
    l.fax = l.fclamp;
  }
  template <class S, class Loads>
  S entry_speed(const S& vc, const Loads&) const {
    return vc;
  }
  void cache(const RomTensionLoads<T, false>&, Cache&) const {}
  template <class Jac, class Radial, class Core>
  void partials(const typename Cfg::State&, const Cache&, const RomClampPartials<Cfg>& dfc, const T&, const T&,
                const Radial&, const Core&, Jac& jac) const {
    dfc.each([&](int col, const T& d) { jac.axial(col, d); });
  }
  template <class A>
  void power(const Cache&, const T&, RomPower<A>&) const {}
  void outputs(const RomTensionLoads<T, false>&, RomOutputs<T>&) const {}
};

template <class Cfg>
class RomTension<Cfg, true> {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  using Cache = RomContactTension<T, true>;

  explicit RomTension(const RomParams& p) {
    // The driver wrap's axial force per N of wrap tension, theta1 / (2 tan
    // beta0), at the set-up radii.
    const double theta1 = seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, p.center_distance_m);
    const double tb = dm::sin(p.beta0_rad) / dm::cos(p.beta0_rad);
    const double cF = theta1 / (2.0 * tb);
    const double m = p.centrifugal_gain * p.chain_mass_kg_m;
    m_ = T(m);
    two_m_r2_ = T(2.0 * m * p.r2_m);
    two_m_ = T(2.0 * m);
    cF_ = T(cF);
    inv_cF_ = T(1.0 / cF);
    // With the radial DOF 1 / c_F(rho) = 2 tan(beta0) (1 + kappa) / (2 pi
    // kappa) = (tan(beta0) / pi) (1 + 1 / kappa).
    tan_pi_ = T(tb / kPi);
    Tmax_ = T(p.stop_tension_N);
    eta_s_ = T(p.stop_tension_share);
    cF_eta_s_ = T(cF * p.stop_tension_share);
    k_ws_ = T(p.wrap_excess_share + 0.5);
    kL_ = T(p.chain_stiffness_N / U::tension_N);
    unit_ = T(1.0 / U::tension_N);
    g_ = T(p.creep_gain);
    fixed_ = p.fixed_sheaves;
    // Fixed point: m v_c^2 saturates above sqrt(Q max / m); the simulator faults there.
    if constexpr (U::kScaled) w2_max_ = m > 0.0 ? T(dm::sqrt(T::max().to_double() / m) / p.r2_m) : T::max();
  }

  bool fixed_sheaves() const { return fixed_; }
  // kL in RomUnits::tension_N (the link flux's kL / (kL + T_s)).
  T chain_stiffness() const { return kL_; }
  // The driven speed above which kappa m' v_c^2 leaves the fixed-point range.
  T speed_limit() const { return w2_max_; }

  // The tension state at x from the strands' forces (strands_at()), the chain speed
  // l.vc and the clamping force l.fclamp; sets l.tension and l.fax, the
  // chain's axial force on the lumps. One division (two with the radial
  // DOF); no transcendental function.
  template <class S, class StrandsAt, class Radial, class Loads>
  void chain(const Vec<S>& x, const StrandsAt& strands_at, const Radial& radial, Loads& l) const {
    const S zero(T(0));
    ChainTension<S>& t = l.tension;
    const Strands<S> st = strands_at();
    t.dT = st.s1 + st.s2;
    t.T_c = centrifugal_tension(S(m_), l.vc);  // kappa m' v_c^2
    S F1;
    if constexpr (Cfg::kRadial) {
      // The sheave is held by its clamping force wherever the chain runs; its
      // stops are the chain's radial end stops (feature/radial.hpp).
      const S Fc = l.fclamp;
      F1 = Fc;
      t.T_1 = clamped_wrap_tension(inv_wrap_factor(radial.ratio_slope(x(L::kRho))), Fc, t.T_c);
      t.on_stop = false;
    } else {
      (void)x;
      (void)radial;
      // On its stop (or fixed) the sheave leaves the wrap the tension the
      // geometry gives it: T_stop = T_max + eta_s dT.
      t.T_1 = S(Tmax_) + S(eta_s_) * t.dT;
      F1 = wrap_axial_force(S(cF_), t.T_1, t.T_c);
      t.on_stop = true;
      if (!fixed_) {
        // A free sheave holds the wrap at its clamping force, as long as that
        // does not close it past its stop: T_1 = min(T_clamp, T_stop).
        const S Fc = l.fclamp;
        if (Fc < F1) {
          F1 = Fc;
          t.T_1 = clamped_wrap_tension(S(inv_cF_), Fc, t.T_c);
          t.on_stop = false;
        }
      }
    }
    t.lifted = !(F1 > zero);
    t.F_ax = t.lifted ? zero : F1;
    // The strands' mean is the wrap's less its excess eta_w dT; neither
    // strand carries compression.
    t.T_s = t.T_1 - S(k_ws_) * t.dT;
    const S floor = t.dT < zero ? -t.dT : zero;
    t.floored = t.T_s < floor;
    if (t.floored) t.T_s = floor;
    t.inv_D = S(T(1)) / (S(kL_) + in_tension_unit(t.T_s));
    t.eps = in_tension_unit(t.dT) * t.inv_D;
    t.creep = creep_speed(S(g_), t.eps, l.vc);
    l.fax = t.F_ax;
  }
  // The chain's speed where it enters the driver wrap: faster by the creep.
  template <class S, class Loads>
  S entry_speed(const S& vc, const Loads& l) const {
    return vc + l.tension.creep;
  }
  void cache(const RomTensionLoads<T, true>& l, Cache& c) const { c.tension = l.tension; }

  // docs/rom.md#tension-jacobian, #tension-radial: the partials of the
  // entry lump's slip through the creep, and of the lumps' axial force, in
  // the order the trace hashes were recorded with (the clamping force's
  // partials first, then the creep's, then the stop's). dfc: the clamping
  // force's partials (feature/axial.hpp); vc, r2e the chain speed and driven
  // radius at x.
  // Inlined: the contact law's arrays it adds to then stay in registers
  // (an out-of-line call took them to memory, docs/rom.md#cost).
  template <class Jac, class Radial, class Core>
  [[gnu::always_inline]] void partials(const State& x, const Cache& c, const RomClampPartials<Cfg>& dfc, const T& vc,
                                       const T& r2e, const Radial& radial, const Core& k, Jac& jac) const {
    const ChainTension<T>& t = c.tension;
    const Slack sp = slack(x, t, vc, r2e, radial);
    // Clamped, the lumps press with the clamping force.
    if (!t.lifted && !t.on_stop)
      dfc.each([&](int col, const T& d) { jac.axial(col, d); });
    // creep = g eps v_c, eps = dT / (kL + T_s):
    //   d creep = g v_c (d dT - eps d T_s) / (kL + T_s) + g eps d v_c.
    const T gv = g_ * vc;
    const T q = gv * (T(1) - t.eps * sp.dT) * t.inv_D;
    const T c_x = in_tension_unit(q * k.k1), c_xd = in_tension_unit(q * k.c1);
    const T gve = gv * t.eps * t.inv_D;
    const T c_w2 = g_ * t.eps * r2e - in_tension_unit(gve * sp.w2);
    jac.slip(0, L::kX1, c_x);
    jac.slip(0, L::kX2, c_x);
    jac.slip(0, L::kV1, c_xd);
    jac.slip(0, L::kV2, c_xd);
    if (!k.hold2) jac.slip(0, L::kW2, c_w2);  // a held driven pulley's speed is no state
    if (sp.Fc != T(0))
      dfc.each([&](int col, const T& d) { jac.slip(0, col, -in_tension_unit(gve * (sp.Fc * d))); });
    if constexpr (Cfg::kRadial) {
      // The strands' stretch g rho moves dT; the driven radius moves v_c and
      // T_c; the wrap angle moves c_F (floating point: no tension unit).
      const T g2 = radial.wrap_g() + radial.wrap_g();
      jac.slip(0, L::kRho, q * (g2 * k.k1) + g_ * t.eps * sp.vc_rho - gve * sp.rho);
      jac.slip(0, L::kRhoDot, q * (g2 * k.c1));
    }
    if (t.lifted || !t.on_stop) return;
    // On the stop F_ax = c_F (T_max + eta_s dT - T_c).
    const T f_x = cF_eta_s_ * k.k1, f_xd = cF_eta_s_ * k.c1, f_w2 = -cF_ * (two_m_r2_ * vc);
    jac.axial(L::kX1, f_x);
    jac.axial(L::kX2, f_x);
    jac.axial(L::kV1, f_xd);
    jac.axial(L::kV2, f_xd);
    jac.axial(L::kW2, f_w2);
  }

  // docs/rom.md#link-ripple: the row of psi' = (2 alpha / L) v_c rho_k with
  // rho_k = kL / (kL + T_s): d rho_k = -rho_k d T_s / (kL + T_s), and T_s's
  // partials per regime. Columns w2, x_i, xd_i, the clamping force's (delta;
  // rho with the radial DOF) and the radial DOF's.
  template <class Radial, class Core>
  void link_flux_row(const State& x, const Cache& c, const T& vc, const T& r2e, const RomClampPartials<Cfg>& dfc,
                     const Radial& radial, const Core& k, const T& psi_per_m, typename Cfg::Jacobian& J) const {
    const ChainTension<T>& t = c.tension;
    const T rho_k = kL_ * t.inv_D;
    const Slack sp = slack(x, t, vc, r2e, radial);
    // d psi' / d T_s [rad/s per N]: one product in the plant's range, then
    // the tension unit.
    const T d_Ts = -in_tension_unit((psi_per_m * vc) * rho_k * t.inv_D);
    const T d_x = Cfg::per_tau(d_Ts * sp.dT * k.k1), d_xd = Cfg::per_tau(d_Ts * sp.dT * k.c1);
    J(L::kPsi, L::kX1) = d_x;
    J(L::kPsi, L::kX2) = d_x;
    J(L::kPsi, L::kV1) = d_xd;
    J(L::kPsi, L::kV2) = d_xd;
    // Every entry the structured solve reads is written, zeros included: the
    // step's J is never zeroed.
    J(L::kPsi, L::kW1) = T(0);
    J(L::kPsi, L::kW2) = k.hold2 ? T(0) : Cfg::per_tau(psi_per_m * r2e * rho_k + d_Ts * sp.w2);
    if constexpr (Cfg::kRadial) {
      J(L::kPsi, L::kDelta) = T(0);
      J(L::kPsi, L::kDeltaDot) = T(0);
      J(L::kPsi, L::kRho) = T(0);
      if (sp.Fc != T(0))
        dfc.each([&](int col, const T& d) { J(L::kPsi, col) = d_Ts * (sp.Fc * d); });
      const T g2 = radial.wrap_g() + radial.wrap_g();
      J(L::kPsi, L::kRho) += psi_per_m * sp.vc_rho * rho_k + d_Ts * (sp.dT * (g2 * k.k1) + sp.rho);
      J(L::kPsi, L::kRhoDot) = d_Ts * sp.dT * (g2 * k.c1);
    } else if constexpr (Cfg::kAxial) {
      J(L::kPsi, L::kDelta) = sp.Fc != T(0) && dfc.on ? Cfg::per_tau(d_Ts * (sp.Fc * dfc.delta)) : T(0);
    }
  }

  // The creep loss F_1 g eps v_c (docs/rom.md#tension-energy): the driver
  // pushes chain that runs faster than the lumps' frame.
  template <class A>
  void power(const Cache& c, const T& F1, RomPower<A>& pw) const {
    pw.friction_loss_W += rom_to_acc(F1) * rom_to_acc(c.tension.creep);
  }
  void outputs(const RomTensionLoads<T, true>& l, RomOutputs<T>& o) const {
    const ChainTension<T>& t = l.tension;
    o.tension_slack_N = t.T_s;
    o.tension_tight_N = t.T_s + t.dT;
    o.centrifugal_tension_N = t.T_c;
    o.creep_strain = t.eps;
    o.sheave_on_stop = t.on_stop;
  }

 private:
  // A tension in RomUnits::tension_N (N, but in fixed point).
  template <class S>
  S in_tension_unit(const S& v) const {
    if constexpr (U::kScaled) return v * S(unit_);
    return v;
  }
  // 1 / c_F(rho) = (tan(beta0) / pi) (1 + 1 / kappa): theta1 = 2 pi kappa /
  // (1 + kappa), kappa = theta1 / theta2 (docs/rom.md#tension-radial).
  template <class S>
  S inv_wrap_factor(const S& kappa) const {
    return S(tan_pi_) + S(tan_pi_) / kappa;
  }

  // d T_s / d dT, d T_s / d w2 and d T_s / d F_clamp in the slack strand's
  // regime (docs/rom.md#tension-jacobian); with the radial DOF also d T_s /
  // d rho through T_c and c_F (not through dT or F_clamp, which have their
  // own partials) and d v_c / d rho.
  struct Slack {
    T dT{}, w2{}, Fc{}, rho{}, vc_rho{};
  };
  template <class Radial>
  Slack slack(const State& x, const ChainTension<T>& t, const T& vc, const T& r2e, const Radial& radial) const {
    Slack r;
    T dTc_w2;
    if constexpr (Cfg::kRadial) dTc_w2 = (two_m_ * r2e) * vc;
    else dTc_w2 = two_m_r2_ * vc;
    if constexpr (Cfg::kRadial) {
      const T rho = x(L::kRho);
      const T kap = radial.ratio_slope(rho);
      r.vc_rho = -kap * x(L::kW2);
      if (!t.floored) {
        // T_s = F_clamp / c_F(rho) + T_c - k_ws dT.
        const T dinv_cF = -(tan_pi_ / (kap * kap)) * radial.ratio_slope_derivative(rho);
        r.rho = (two_m_ * vc) * r.vc_rho + t.F_ax * dinv_cF;
      }
    } else {
      (void)x;
      (void)r2e;
      (void)radial;
    }
    if (t.floored) {
      if (t.dT < T(0)) r.dT = T(-1);
    } else if (t.on_stop) {
      r.dT = eta_s_ - k_ws_;
    } else {
      r.dT = -k_ws_;
      r.w2 = dTc_w2;
      if constexpr (Cfg::kRadial) r.Fc = tan_pi_ + tan_pi_ / radial.ratio_slope(x(L::kRho));
      else r.Fc = inv_cF_;
    }
    return r;
  }

  T m_{}, two_m_r2_{}, two_m_{}, cF_{}, inv_cF_{}, tan_pi_{}, Tmax_{}, eta_s_{}, cF_eta_s_{}, k_ws_{};
  T kL_{}, unit_{}, g_{};
  bool fixed_ = false;
  T w2_max_{};
};

}  // namespace cvt
