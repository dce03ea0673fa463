#pragma once
// The real-time reduced-order CVT plant (docs/rom.md): the seed's 2-DOF
// stick-slip oscillator (Eq. 8/9) made into a drive train.
//
//   state  [w1 w2 x1 xd1 x2 xd2 | Fh delta deltadot (axial) | rho rhodot (wedging) | psi (polygon)]
//   v1 = r1e w1, v_c = r2 w2, v_rel_i = (v_c + xd_i) - v1          docs/rom.md#kinematics
//   F_i = -mu(|v_rel_i|) s(v_rel_i) N_i,  N_i = F_ax / cos(beta_i)   docs/rom.md#contact
//   J1 w1' = tau_in - r1e (F1 + F2)                                  docs/rom.md#equations-of-motion
//   J2 w2' = r2 (k1 x1 + c1 xd1 + k1 x2 + c1 xd2) - tau_load
//   m (xd_i' + r2 w2') = F_i - k1 x_i - c1 xd_i -+ (k2 (x1-x2) + c2 (xd1-xd2))
//
// Templated on the scalar T and a compile-time feature mask (rom_params.hpp);
// heap-free; inputs are a member set before each step (integrate/system.hpp).
// This class is the plant as an integrator sees it: kinematics and contact,
// the right-hand side and its Jacobian. The other parts are their own pieces:
//   rom_layout.hpp     where each state sits, per feature mask
//   rom_units.hpp      internal units (fixed-point scaling and overflow)
//   rom_constants.hpp  the set-up constants in the plant's type and units
//   rom_formulas.hpp   the formulas several parts share, one function each
//   rom_tension.hpp    the chain's tension state (feature tension)
//   rom_outputs.hpp    what a frame reports
//   rom_energy.hpp     stored energy, power terms and the ledger
//   rom_watchdog.hpp   the faults and the per-state checks
//   rom_step.hpp       the integrator step with the block-eliminated W solver
//   rom_sim.hpp        the frame stepper (substeps, ledger, watchdog)
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/integrate/system.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/rom_constants.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/plant/rom_tension.hpp"
#include "cvtplant/plant/rom_units.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

// The shared contact of a plant with chordal action also carries cos and sin
// of the link-passing ripple's phase theta (docs/rom.md#link-ripple); an
// empty base without the feature.
template <class T, bool kPolygon>
struct RomContactRipple {};
template <class T>
struct RomContactRipple<T, true> {
  T ripple_cos{}, ripple_sin{};
};

template <class T, std::uint32_t Features = 0>
class CvtRom {
  using L = RomLayout<Features>;

 public:
  using Scalar = T;
  static constexpr std::uint32_t kFeatures = Features;
  static constexpr int kStates = L::kStates;
  static constexpr std::uint32_t kPositionMask = L::kPositionMask;
  using Layout = L;
  using U = RomUnits<T>;
  // The radial stiffness and friction slopes of wedging have no fixed-point
  // scaling yet (docs/rom.md#wedging).
  static_assert(!L::kWedge || !U::kScaled, "the wedging feature runs in floating point only");
  using State = Eigen::Matrix<T, kStates, 1>;
  using Jacobian = Eigen::Matrix<T, kStates, kStates>;
  using Acc = RomAcc<T>;

  RomInputs<T> inputs;

  explicit CvtRom(const RomParams& p) : p_(p), c_(p) {}

  const RomParams& params() const { return p_; }
  T polygon_half_angle_rad() const { return c_.alpha; }

  // Clamping command after actuator saturation [0, F_max] (docs/rom.md#axial).
  T saturated_command() const {
    const T f = inputs.clamp_N;
    if constexpr (L::kAxial) return f < T(0) ? T(0) : (f > c_.clamp_max ? c_.clamp_max : f);
    return f;
  }

  // Initial state from SI set-up values; axial states at the static
  // equilibrium of the current command (docs/rom.md#initial-state).
  State initial_state(const RomInitial& x0) const {
    State x = State::Zero();
    x(L::kW1) = T(x0.omega1_rad_s);
    x(L::kW2) = T(x0.omega2_rad_s);
    x(L::kX1) = T(x0.x1_m / U::length_m);
    x(L::kV1) = T(x0.xd1_m_s);
    x(L::kX2) = T(x0.x2_m / U::length_m);
    x(L::kV2) = T(x0.xd2_m_s);
    if constexpr (L::kAxial) {
      const T fh = saturated_command();
      x(L::kFh) = fh;
      x(L::kDelta) = T(to_double(fh) / p_.K_ax_N_m / U::length_m);
      x(L::kDeltaDot) = T(0);
    }
    if constexpr (L::kWedge) {
      // Bolt compression delta - 2 tan(beta0) rho at its static value.
      x(L::kRho) = T(x0.radius_offset_m);
      x(L::kDelta) += c_.two_tan_b0 * x(L::kRho);
      x(L::kRhoDot) = T(0);
    }
    if constexpr (L::kPolygon) x(L::kPsi) = T(x0.phase_rad);
    return x;
  }

  // A state in SI units (rad/s, m, m/s, N, rad), for logs and tests.
  Eigen::Matrix<double, kStates, 1> to_si(const State& x) const {
    Eigen::Matrix<double, kStates, 1> y;
    for (int i = 0; i < kStates; ++i) y(i) = to_double(x(i));
    y(L::kX1) *= U::length_m;
    y(L::kX2) *= U::length_m;
    if constexpr (L::kAxial) y(L::kDelta) *= U::length_m;
    return y;
  }

  // A rate per second as a rate per time unit (docs/rom.md#fixed-point). The
  // factor is applied to each equation's SI result, before anything large
  // multiplies it, so no intermediate leaves the fixed-point range.
  template <class S>
  S per_tau(const S& v) const {
    if constexpr (U::kScaled) return v * S(c_.tu);
    return v;
  }

  // Keeps the polygon phase in [-alpha, alpha) between steps (it is periodic
  // in the link pitch; wrapping outside the integrator keeps it bounded for
  // float and fixed point). docs/rom.md#polygon
  void wrap(State& x) const {
    if constexpr (L::kPolygon) {
      const T two_alpha = c_.alpha + c_.alpha;
      while (x(L::kPsi) >= c_.alpha) x(L::kPsi) -= two_alpha;
      while (x(L::kPsi) < -c_.alpha) x(L::kPsi) += two_alpha;
    } else {
      (void)x;
    }
  }

  // Axial force on the lumps: the input (no axial feature) or the bolt force
  // K_ax max(0, delta) (seed Eq. 5 lumped; docs/rom.md#axial).
  template <class S>
  S clamp_force(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kAxial) {
      // With wedging the chain's radial position rho changes the groove width
      // at the links: compression = delta - 2 tan(beta0) rho (docs/rom.md#wedging).
      S d = x(L::kDelta);
      if constexpr (L::kWedge) d = d - S(c_.two_tan_b0) * x(L::kRho);
      return d > S(T(0)) ? S(c_.K_ax) * d : S(T(0));
    } else {
      (void)x;
      return S(inputs.clamp_N);
    }
  }

  // Pitch radii (docs/rom.md#wedging): set-up values, or r1 + rho and
  // r2 + a1 rho + a2 rho^2 + a3 rho^3 with wedging.
  template <class S>
  S pitch_radius1(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kWedge) return S(c_.r1) + x(L::kRho);
    (void)x;
    return S(c_.r1);
  }
  template <class S>
  S pitch_radius2(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kWedge) return S(c_.r2) + driven_radius_change(x(L::kRho));
    (void)x;
    return S(c_.r2);
  }
  // r2(rho) - r2 and kappa(rho) = -dr2/drho (theta1/theta2 to 1e-2).
  template <class S>
  S driven_radius_change(const S& rho) const {
    return cvt::driven_radius_change(rho, S(c_.a1), S(c_.a2), S(c_.a3));
  }
  template <class S>
  S ratio_slope(const S& rho) const {
    return -(S(c_.a1) + rho * (S(c_.a2 + c_.a2) + rho * S(T(3) * c_.a3)));
  }

  // d kappa / d rho = -(2 a2 + 6 a3 rho).
  T ratio_slope_derivative(const T& rho) const { return -(T(c_.a2 + c_.a2) + rho * (T(6) * c_.a3)); }

  // Effective driver radius r1e: r1, or r1 cos(psi) with chordal action.
  template <class S>
  S driver_radius(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kPolygon) return pitch_radius1(x) * cos(x(L::kPsi));
    return pitch_radius1(x);
  }

  // docs/rom.md#link-ripple: cos(theta) of the loaded-bolt count's
  // fundamental at the link phase, theta = pi psi / alpha + phi0 (0 without
  // chordal action or with the ripple off, A = 0: F_ax (1 + 0) is F_ax, and
  // a plant without the ripple pays no cosine).
  template <class S>
  S ripple_cos(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kPolygon) {
      if (rippled()) return cos(ripple_angle(x(L::kPsi)));
    }
    (void)x;
    return S(T(0));
  }
  template <class S>
  S ripple_angle(const S& psi) const {
    return S(c_.rip_k) * psi + S(c_.rip_phase);
  }

  // The axial force that loads the lumps (docs/rom.md#link-ripple): the
  // sheave's or the chain's F_ax, with chordal action F_ax (1 + A cos theta).
  // The sheave's own balance keeps F_ax (docs/rom.md#axial). With the
  // ripple off (A = 0) F_ax itself, at no cost.
  template <class S>
  S lumps_axial_force(const S& fax, const S& cos_theta) const {
    if constexpr (L::kPolygon) {
      if (rippled()) return rippled_axial_force(fax, S(c_.rip_A), cos_theta);
    }
    (void)cos_theta;
    return fax;
  }
  // True when the plant carries the link-passing ripple (chordal action and
  // A != 0, docs/rom.md#link-ripple); the ripple's terms are skipped otherwise.
  bool rippled() const {
    if constexpr (L::kPolygon) return c_.rip_A != T(0);
    return false;
  }

  // False once the chain is through an end stop by another full travel: the
  // stop stiffness cannot hold what drives it (wedging only; the simulator
  // reports it as a fault, docs/rom.md#wedging).
  bool radius_in_range(const State& x) const {
    if constexpr (L::kWedge) {
      const T lim = c_.travel + c_.travel;
      return x(L::kRho) <= lim && x(L::kRho) >= -lim;
    }
    (void)x;
    return true;
  }

  // Penetration of the ratio end stops [m]: > 0 past +travel, < 0 past -travel.
  template <class S>
  S stop_penetration(const S& rho) const {
    const S tr(c_.travel);
    if (rho > tr) return rho - tr;
    if (rho < -tr) return rho + tr;
    return S(T(0));
  }

  // Contact forces on the lumps with wedging (seed Eq. 7, docs/rom.md#wedging):
  // the friction force opposes the slip velocity (v_t, g_r) in the flank
  // plane, g_r = rhodot / cos(beta_i), and its radial part F_r changes the
  // normal force, N = F_r tan(beta) + F_ax / cos(beta), F_r = -(phi/|v|) g_r N.
  template <class S>
  struct WedgeContact {
    S F1, F2;    // tangential [N]
    S Fr1, Fr2;  // radial, along the flank [N]
  };
  template <class S>
  WedgeContact<S> wedge_contact(const S& vt1, const S& vt2, const S& rhod, const S& fax) const {
    WedgeContact<S> c;
    lump_contact(vt1, rhod * S(c_.inv_cos1), normal_force(fax, S(c_.load1)), S(c_.tan1), c.F1, c.Fr1);
    lump_contact(vt2, rhod * S(c_.inv_cos2), normal_force(fax, S(c_.load2)), S(c_.tan2), c.F2, c.Fr2);
    return c;
  }

  // Forces of the two strands, k1 e_i + c1 e_i' (seed Eq. 8), with the
  // stretch e_i = x_i, or x_i + g rho with wedging (docs/rom.md#wrap-tension).
  template <class S>
  struct Strands {
    S s1, s2;
  };
  template <class S>
  Strands<S> strands(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kWedge) {
      const S g(c_.wrap_g), rho = x(L::kRho), rhod = x(L::kRhoDot);
      return {strand_force(S(c_.k1), S(c_.c1), strand_stretch(x(L::kX1), g, rho), strand_stretch(x(L::kV1), g, rhod)),
              strand_force(S(c_.k1), S(c_.c1), strand_stretch(x(L::kX2), g, rho), strand_stretch(x(L::kV2), g, rhod))};
    } else {
      return {strand_force(S(c_.k1), S(c_.c1), x(L::kX1), x(L::kV1)),
              strand_force(S(c_.k1), S(c_.c1), x(L::kX2), x(L::kV2))};
    }
  }

  // The chain's tension state at x with the chain at v_c = r2 w2
  // (docs/rom.md#tension): the strands' difference dT, the centrifugal
  // tension, the driver wrap's mean tension as the clamping force or the
  // sheave's stop sets it, the chain's axial force, the slack strand and the
  // creep strain. One division; no transcendental function.
  template <class S>
  ChainTension<S> chain_tension(const Eigen::Matrix<S, kStates, 1>& x, const S& vc) const {
    const S zero(T(0));
    ChainTension<S> t;
    const Strands<S> st = strands(x);
    t.dT = st.s1 + st.s2;
    t.T_c = centrifugal_tension(S(c_.ten_m), vc);  // kappa m' v_c^2
    // On its stop (or fixed) the sheave leaves the wrap the tension the
    // geometry gives it: T_stop = T_max + eta_s dT.
    t.T_1 = S(c_.ten_Tmax) + S(c_.ten_eta_s) * t.dT;
    S F1 = wrap_axial_force(S(c_.ten_cF), t.T_1, t.T_c);
    t.on_stop = true;
    if (!c_.ten_fixed) {
      // A free sheave holds the wrap at its clamping force, as long as that
      // does not close it past its stop: T_1 = min(T_clamp, T_stop).
      const S Fc = clamp_force(x);
      if (Fc < F1) {
        F1 = Fc;
        t.T_1 = clamped_wrap_tension(S(c_.ten_inv_cF), Fc, t.T_c);
        t.on_stop = false;
      }
    }
    t.lifted = !(F1 > zero);
    t.F_ax = t.lifted ? zero : F1;
    // The strands' mean is the wrap's less its excess eta_w dT; neither
    // strand carries compression.
    t.T_s = t.T_1 - S(c_.ten_k_ws) * t.dT;
    const S floor = t.dT < zero ? -t.dT : zero;
    t.floored = t.T_s < floor;
    if (t.floored) t.T_s = floor;
    t.inv_D = S(T(1)) / (S(c_.ten_kL) + in_tension_unit(t.T_s));
    t.eps = in_tension_unit(t.dT) * t.inv_D;
    t.creep = creep_speed(S(c_.ten_g), t.eps, vc);
    return t;
  }

  // A tension in RomUnits::tension_N (docs/rom.md#tension; N but in fixed point).
  template <class S>
  S in_tension_unit(const S& v) const {
    if constexpr (U::kScaled) return v * S(c_.ten_unit);
    return v;
  }

  // Load torque at the driven shaft (docs/rom.md#road-load).
  template <class S>
  S load_torque(const S& w2) const {
    S tl(inputs.tau_load_Nm);
    if constexpr (L::kRoad) {
      tl = road_load_torque(tl, S(c_.T0), S(c_.inv_w_eps), S(c_.cv), S(c_.ca), w2);
    }
    return tl;
  }

  // d tau_load / d w2 (docs/rom.md#road-load), zero without road load.
  T load_torque_slope(const T& w2) const {
    if constexpr (L::kRoad) {
      const T th = tanh(w2 * c_.inv_w_eps);
      return c_.T0 * (T(1) - th * th) * c_.inv_w_eps + c_.cv + (c_.ca + c_.ca) * abs(w2);
    }
    (void)w2;
    return T(0);
  }

  // Friction of both lumps at a state, value and slope (plants without
  // wedging): evaluated once per state and shared by the right-hand side, the
  // Jacobian and the power terms, since the exponentials and the atan are most
  // of a frame on a Cortex-M (docs/rom.md#cost).
  // With the tension feature it also carries the chain's tension state.
  // With chordal action it carries cos and sin of the ripple's link phase.
  struct FixedRatioContact : RomContactTension<T, L::kTension>, RomContactRipple<T, L::kPolygon> {
    T r1e{};             // effective driver radius [m]
    T v_rel1{}, v_rel2{};  // slip speeds [m/s]
    FrictionEval<T> lump1{}, lump2{};
  };
  // A wedging lump's contact forces and their partial derivatives with
  // respect to (v_t, g_r, N0) (lump_contact_partials, docs/rom.md#wedging-jacobian).
  struct LumpPartials {
    T F{}, Fr{};
    T dF[3]{}, dFr[3]{};
  };
  // The same sharing with wedging: each lump's tangential slip and its contact
  // forces with their partials, what the Jacobian, the right-hand side and the
  // power terms at the state need (docs/rom.md#cost).
  struct WedgeLumpContact : RomContactRipple<T, L::kPolygon> {
    T v_t1{}, v_t2{};  // tangential slip speeds [m/s]
    LumpPartials lump1{}, lump2{};
  };
  using Contact = std::conditional_t<L::kWedge, WedgeLumpContact, FixedRatioContact>;

  Contact contact(const State& x) const {
    Contact c;
    if constexpr (L::kPolygon) {
      // With the ripple off (A = 0) both stay 0: no term reads them then.
      if (rippled()) {
        const T theta = ripple_angle(x(L::kPsi));
        c.ripple_cos = cos(theta);
        c.ripple_sin = sin(theta);
      }
    }
    if constexpr (L::kWedge) {
      const T r1e = driver_radius(x);
      const T v1 = r1e * x(L::kW1);
      const T vc = pitch_radius2(x) * x(L::kW2);
      const T fax = clamp_force(x);
      const T rhod = x(L::kRhoDot);
      c.v_t1 = slip_velocity<T>(vc, x(L::kV1), v1);
      c.v_t2 = slip_velocity<T>(vc, x(L::kV2), v1);
      // The lumps press with the rippled force (docs/rom.md#link-ripple).
      const T fl = lumps_axial_force(fax, contact_ripple_cos(c));
      c.lump1 = lump_contact_partials(c.v_t1, rhod * c_.inv_cos1, normal_force(fl, c_.load1), c_.tan1);
      c.lump2 = lump_contact_partials(c.v_t2, rhod * c_.inv_cos2, normal_force(fl, c_.load2), c_.tan2);
    } else {
      c.r1e = driver_radius(x);
      const T v1 = c.r1e * x(L::kW1);
      const T vc = c_.r2 * x(L::kW2);
      T vc1 = vc;  // the chain's speed at the entry lump: faster by the creep (docs/rom.md#tension)
      if constexpr (L::kTension) {
        c.tension = chain_tension(x, vc);
        vc1 = vc + c.tension.creep;
      }
      c.v_rel1 = slip_velocity<T>(vc1, x(L::kV1), v1);
      c.v_rel2 = slip_velocity<T>(vc, x(L::kV2), v1);
      c.lump1 = friction_characteristic_and_slope(c_.friction, c.v_rel1);
      c.lump2 = friction_characteristic_and_slope(c_.friction, c.v_rel2);
    }
    return c;
  }

  // The link phase's rate psi' [rad/s] at x (c = contact(x)): w1, or with
  // the tension feature 2 alpha times the chain's link passing,
  // (2 alpha / L) v_c kL / (kL + T_s) (docs/rom.md#link-ripple). The
  // watchdog's 8 steps per link apply to it (docs/rom.md#polygon).
  T phase_rate(const State& x, const Contact& c) const {
    if constexpr (L::kPolygon && L::kTension)
      return link_phase_rate(c_.psi_per_m, c_.r2 * x(L::kW2), c_.ten_kL, c.tension.inv_D);
    (void)c;
    return x(L::kW1);
  }

  template <class S>
  void derivative(const Eigen::Matrix<S, kStates, 1>& x, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    if constexpr (L::kWedge) {
      derivative_wedge(x, dxdt);
    } else {
      const S r1e = driver_radius(x);
      const S v1 = r1e * x(L::kW1);
      const S vc = S(c_.r2) * x(L::kW2);
      if constexpr (L::kTension) {
        // docs/rom.md#tension: the entry lump meets the chain at the tight
        // strand's speed, and the lumps' normal load is the chain's axial force.
        const ChainTension<S> t = chain_tension(x, vc);
        derivative_given_tension(
            x, r1e, friction_characteristic(c_.friction, slip_velocity<S>(vc + t.creep, x(L::kV1), v1)),
            friction_characteristic(c_.friction, slip_velocity<S>(vc, x(L::kV2), v1)), t, ripple_cos(x), dxdt);
      } else {
        derivative_given(x, r1e, friction_characteristic(c_.friction, slip_velocity<S>(vc, x(L::kV1), v1)),
                         friction_characteristic(c_.friction, slip_velocity<S>(vc, x(L::kV2), v1)), ripple_cos(x),
                         dxdt);
      }
    }
  }
  // The same, with the friction already evaluated at x (c = contact(x)); bit
  // for bit derivative(x, dxdt), the fused friction values being the separate ones.
  void derivative(const State& x, const Contact& c, State& dxdt) const {
    if constexpr (L::kWedge) {
      const WedgeContact<T> w{c.lump1.F, c.lump2.F, c.lump1.Fr, c.lump2.Fr};
      derivative_wedge_given(x, driver_radius(x), pitch_radius2(x), clamp_force(x), w, dxdt);
    } else if constexpr (L::kTension) {
      derivative_given_tension(x, c.r1e, c.lump1.phi, c.lump2.phi, c.tension, contact_ripple_cos(c), dxdt);
    } else {
      derivative_given(x, c.r1e, c.lump1.phi, c.lump2.phi, contact_ripple_cos(c), dxdt);
    }
  }

  // The axial force at x (c = contact(x)) before the link-passing ripple:
  // the clamping force, or with the tension feature the chain's
  // (docs/rom.md#tension).
  T unrippled_axial_force(const State& x, const Contact& c) const {
    if constexpr (L::kTension) {
      (void)x;
      return c.tension.F_ax;
    } else {
      (void)c;
      return clamp_force(x);
    }
  }
  // The axial force on the lumps at x (c = contact(x)), with the
  // link-passing ripple under chordal action (docs/rom.md#link-ripple).
  T axial_force(const State& x, const Contact& c) const {
    return lumps_axial_force(unrippled_axial_force(x, c), contact_ripple_cos(c));
  }
  static T contact_ripple_cos(const Contact& c) {
    if constexpr (L::kPolygon) return c.ripple_cos;
    (void)c;
    return T(0);
  }

  // Analytic Jacobian (docs/rom.md#jacobian). Held pulleys get zero rows AND
  // columns: their speed never changes, so the columns multiply a zero
  // increment, and leaving them out keeps the LU pivots those of seed Eq. 9.
  // With wedging, the chain rule through the per-lump contact partials
  // (docs/rom.md#wedging-jacobian).
  void jacobian(const State& x, Jacobian& J) const { jacobian(x, contact(x), J, false); }

  // The Jacobian from the friction already evaluated at x. With
  // `w_slope_floor` it is the matrix W of the real-time step instead
  // (docs/rom.md#slope-floor): inside the sign's regularisation layer
  // |v_rel| < 1/lambda the friction slope is raised to at least its value at
  // the layer's edge. Seed case 2 has mu(0) = 0, so at exact rest the true
  // slope is zero and a step would not see the stick stiffness that appears
  // within it. ROS2 is a W-method (order 2 for any W), so this changes the
  // step's error constant near stick, not its order. With wedging the floor
  // acts through the tangential slip speed (add_w_slope_floor).
  void jacobian(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    J.setZero();
    jacobian_entries(x, c, J, w_slope_floor);
  }

  // jacobian(x, c, J, w_slope_floor) without zeroing J first: writes the rows
  // of the core states (w1, w2, xd1, xd2; with wedging also deltadot and
  // rhodot) whole and the entries of the other rows that can be nonzero, and
  // leaves every other entry of J as it was. These are the entries
  // RomWSolver::factor reads (docs/rom.md#structured-solve), so the step
  // passes a J it never zeroes: zeroing the 81 entries of the axial plant's J
  // each step was 170 instructions of a frame on the M4F (docs/rom.md#cost).
  void jacobian_entries(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    if constexpr (L::kWedge) {
      jacobian_wedge(x, c, J);
      if (w_slope_floor) add_w_slope_floor(x, J);
    } else {
      jacobian_fixed_ratio(x, c, J, w_slope_floor);
    }
  }

 private:
  // jacobian_entries without wedging (docs/rom.md#jacobian).
  void jacobian_fixed_ratio(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    const T w1 = x(L::kW1), w2 = x(L::kW2);
    const T r1e = c.r1e;
    const T fax = axial_force(x, c);
    const T N1 = normal_force(fax, c_.load1), N2 = normal_force(fax, c_.load2);
    // docs/rom.md#link-ripple: d(lumps' F_ax)/d F_ax = 1 + A cos(theta).
    T rip(1);
    if constexpr (L::kPolygon) {
      if (rippled()) rip = T(1) + c_.rip_A * c.ripple_cos;
    }
    T s1 = c.lump1.slope, s2 = c.lump2.slope;
    if (w_slope_floor) {
      if (abs(c.v_rel1) < c_.floor_speed && s1 < c_.slope_floor) s1 = c_.slope_floor;
      if (abs(c.v_rel2) < c_.floor_speed && s2 < c_.slope_floor) s2 = c_.slope_floor;
    }
    // dF_i/dv_rel_i = -phi'(v_rel) N_i, per time unit: phi' N alone (5e6
    // N s/m at 3.3 kN) would not fit q16.16, phi' per time unit does.
    const T g1 = -per_tau(s1) * N1;
    const T g2 = -per_tau(s2) * N2;
    const T im = c_.inv_m;
    const bool free1 = !c_.hold1, free2 = !c_.hold2;

    // Row of w2dot (also enters the lump rows through -r2 w2dot).
    T rw2[kStates];
    #pragma GCC unroll 16
    for (int j = 0; j < kStates; ++j) rw2[j] = T(0);
    if (free2) {
      const T dtl = load_torque_slope(w2);
      rw2[L::kW2] = per_tau(-dtl * c_.inv_J2);
      rw2[L::kX1] = per_tau(c_.r2 * c_.k1 * c_.inv_J2);
      rw2[L::kV1] = per_tau(c_.r2 * c_.c1 * c_.inv_J2);
      rw2[L::kX2] = per_tau(c_.r2 * c_.k1 * c_.inv_J2);
      rw2[L::kV2] = per_tau(c_.r2 * c_.c1 * c_.inv_J2);
    }
    #pragma GCC unroll 16
    for (int j = 0; j < kStates; ++j) J(L::kW2, j) = rw2[j];
    // Partials of F_i w.r.t. the states, columns w1, w2, xd_i, delta, psi,
    // per time unit like g_i.
    T dF1[kStates], dF2[kStates];
    #pragma GCC unroll 16
    for (int j = 0; j < kStates; ++j) dF1[j] = dF2[j] = T(0);
    dF1[L::kW1] = -g1 * r1e;
    dF2[L::kW1] = -g2 * r1e;
    dF1[L::kW2] = g1 * c_.r2;
    dF2[L::kW2] = g2 * c_.r2;
    dF1[L::kV1] = g1;
    dF2[L::kV2] = g2;
    if constexpr (L::kAxial) {
      bool bolt = x(L::kDelta) > T(0);
      // With tension the bolt force acts on the lumps only while it holds the
      // sheave off its stop (docs/rom.md#tension).
      if constexpr (L::kTension) bolt = bolt && !c.tension.on_stop;
      if (bolt) {
        // dF_i/dF_ax = -phi(v_rel_i) / cos(beta_i), times the ripple's factor.
        T kb = c_.K_ax;
        if constexpr (L::kPolygon) {
          if (rippled()) kb = kb * rip;
        }
        dF1[L::kDelta] = per_tau(-c.lump1.phi * c_.load1 * kb);
        dF2[L::kDelta] = per_tau(-c.lump2.phi * c_.load2 * kb);
      }
    }
    T sin_psi = T(0);
    if constexpr (L::kPolygon) {
      sin_psi = sin(x(L::kPsi));
      // dv_rel/dpsi = -dr1e/dpsi w1 = r1 sin(psi) w1
      const T dv = c_.r1 * sin_psi * w1;
      dF1[L::kPsi] = g1 * dv;
      dF2[L::kPsi] = g2 * dv;
      // docs/rom.md#link-ripple: d(lumps' F_ax)/dpsi = -F_ax A (pi/alpha) sin(theta).
      if (rippled()) {
        const T dfl = -(unrippled_axial_force(x, c) * (c_.rip_A * c_.rip_k)) * c.ripple_sin;
        dF1[L::kPsi] += per_tau(-c.lump1.phi * c_.load1 * dfl);
        dF2[L::kPsi] += per_tau(-c.lump2.phi * c_.load2 * dfl);
      }
    }
    if constexpr (L::kTension) tension_partials(x, c, g1, rip, dF1, dF2);
    if (!free1) dF1[L::kW1] = dF2[L::kW1] = T(0);
    if (!free2) dF1[L::kW2] = dF2[L::kW2] = T(0);

    // The constants in locals: J's entries are T too, and every store to J
    // would otherwise make the compiler read a constant of the plant again.
    const T inv_J1 = c_.inv_J1, r2 = c_.r2;
    if (free1) {
      #pragma GCC unroll 16
      for (int j = 0; j < kStates; ++j) J(L::kW1, j) = -r1e * (dF1[j] + dF2[j]) * inv_J1;
      if constexpr (L::kPolygon) {
        const T F1 = lump_friction(c.lump1.phi, N1);
        const T F2 = lump_friction(c.lump2.phi, N2);
        // d(r1e)/dpsi = -r1 sin(psi)
        J(L::kW1, L::kPsi) += per_tau(c_.r1 * sin_psi * (F1 + F2) * inv_J1);
      }
    } else {
      #pragma GCC unroll 16
      for (int j = 0; j < kStates; ++j) J(L::kW1, j) = T(0);
    }
    J(L::kX1, L::kV1) = T(1);
    J(L::kX2, L::kV2) = T(1);
    #pragma GCC unroll 16
    for (int j = 0; j < kStates; ++j) {
      J(L::kV1, j) = dF1[j] * im - r2 * rw2[j];
      J(L::kV2, j) = dF2[j] * im - r2 * rw2[j];
    }
    const T k1 = c_.k1, k2 = c_.k2, c1 = c_.c1, c2 = c_.c2;
    J(L::kV1, L::kX1) += per_tau(-(k1 + k2) * im);
    J(L::kV1, L::kX2) += per_tau(k2 * im);
    J(L::kV1, L::kV1) += per_tau(-(c1 + c2) * im);
    J(L::kV1, L::kV2) += per_tau(c2 * im);
    J(L::kV2, L::kX1) += per_tau(k2 * im);
    J(L::kV2, L::kX2) += per_tau(-(k1 + k2) * im);
    J(L::kV2, L::kV1) += per_tau(c2 * im);
    J(L::kV2, L::kV2) += per_tau(-(c1 + c2) * im);
    if constexpr (L::kAxial) {
      J(L::kFh, L::kFh) = -c_.inv_tau_h;
      J(L::kDelta, L::kDeltaDot) = T(1);
      J(L::kDeltaDot, L::kFh) = per_tau(c_.inv_ms);
      J(L::kDeltaDot, L::kDelta) = x(L::kDelta) > T(0) ? per_tau(-c_.K_ax * c_.inv_ms) : T(0);
      J(L::kDeltaDot, L::kDeltaDot) = per_tau(-c_.cs * c_.inv_ms);
    }
    if constexpr (L::kPolygon && L::kTension) {
      phase_row(x, c, J);
    } else if constexpr (L::kPolygon) {
      J(L::kPsi, L::kW1) = per_tau(T(1));
    }
  }

  // docs/rom.md#link-ripple: the row of psi' = (2 alpha / L) v_c rho with
  // rho = kL / (kL + T_s): d rho = -rho d T_s / (kL + T_s), and T_s's
  // partials per regime (slack_partials). Columns w2, x_i, xd_i and, with a
  // clamped sheave, delta.
  void phase_row(const State& x, const Contact& c, Jacobian& J) const {
    const ChainTension<T>& t = c.tension;
    const T vc = c_.r2 * x(L::kW2);
    const T rho = c_.ten_kL * t.inv_D;
    const SlackPartials sp = slack_partials(t, c_.ten_two_m_r2 * vc);
    // d psi' / d T_s [rad/s per N]: one product in the plant's range, then
    // the tension unit.
    const T d_Ts = -in_tension_unit((c_.psi_per_m * vc) * rho * t.inv_D);
    const T d_x = per_tau(d_Ts * sp.dT * c_.k1), d_xd = per_tau(d_Ts * sp.dT * c_.c1);
    J(L::kPsi, L::kX1) = d_x;
    J(L::kPsi, L::kX2) = d_x;
    J(L::kPsi, L::kV1) = d_xd;
    J(L::kPsi, L::kV2) = d_xd;
    // Every entry the structured solve reads is written, zeros included: the
    // step's J is never zeroed (jacobian_entries).
    J(L::kPsi, L::kW1) = T(0);
    J(L::kPsi, L::kW2) = c_.hold2 ? T(0) : per_tau(c_.psi_per_m * c_.r2 * rho + d_Ts * sp.w2);
    if constexpr (L::kAxial) {
      J(L::kPsi, L::kDelta) =
          sp.Fc != T(0) && x(L::kDelta) > T(0) ? per_tau(d_Ts * (sp.Fc * c_.K_ax)) : T(0);
    }
  }

  // d T_s / d dT, d T_s / d w2 and d T_s / d F_clamp in the slack strand's
  // regime (docs/rom.md#tension-jacobian); dTc = d T_c / d w2.
  struct SlackPartials {
    T dT{}, w2{}, Fc{};
  };
  SlackPartials slack_partials(const ChainTension<T>& t, const T& dTc) const {
    SlackPartials r;
    if (t.floored) {
      if (t.dT < T(0)) r.dT = T(-1);
    } else if (t.on_stop) {
      r.dT = c_.ten_eta_s - c_.ten_k_ws;
    } else {
      r.dT = -c_.ten_k_ws;
      r.w2 = dTc;
      r.Fc = c_.ten_inv_cF;
    }
    return r;
  }

 public:
  // docs/rom.md#tension-jacobian: the partials of F_1 through the entry
  // lump's creep speed, and of both lumps' friction through the chain's axial
  // force, added to dF_i (per time unit like g1 = dF_1/dv_rel,1). dT = F_s1 +
  // F_s2 has the columns x_i (k1) and xd_i (c1), T_c = kappa m' (r2 w2)^2 the column
  // w2, the clamping force the column delta (axial). The products are ordered
  // so that no intermediate leaves q16.16 in the range of docs/rom.md#fixed-point.
  // rip = 1 + A cos(theta) scales the partials through the lumps' normal
  // load under chordal action (docs/rom.md#link-ripple).
  void tension_partials(const State& x, const Contact& c, const T& g1, const T& rip, T (&dF1)[kStates],
                        T (&dF2)[kStates]) const {
    const ChainTension<T>& t = c.tension;
    const T vc = c_.r2 * x(L::kW2);
    const T dTc = c_.ten_two_m_r2 * vc;  // d T_c / d w2 = 2 kappa m' r2 v_c
    const SlackPartials sp = slack_partials(t, dTc);
    const T s_dT = sp.dT, s_w2 = sp.w2, s_Fc = sp.Fc;
    // creep = g eps v_c, eps = dT / (kL + T_s):
    //   d creep = g v_c (d dT - eps d T_s) / (kL + T_s) + g eps r2 d w2.
    const T gv = c_.ten_g * vc;
    const T q = gv * (T(1) - t.eps * s_dT) * t.inv_D;
    const T c_x = in_tension_unit(q * c_.k1), c_xd = in_tension_unit(q * c_.c1);
    const T gve = gv * t.eps * t.inv_D;
    const T c_w2 = c_.ten_g * t.eps * c_.r2 - in_tension_unit(gve * s_w2);
    dF1[L::kX1] += g1 * c_x;
    dF1[L::kX2] += g1 * c_x;
    dF1[L::kV1] += g1 * c_xd;
    dF1[L::kV2] += g1 * c_xd;
    dF1[L::kW2] += g1 * c_w2;
    if constexpr (L::kAxial) {
      if (s_Fc != T(0) && x(L::kDelta) > T(0)) dF1[L::kDelta] -= g1 * in_tension_unit(gve * (s_Fc * c_.K_ax));
    }
    if (t.lifted || !t.on_stop) return;  // the clamped regime's F_ax is the bolt force (axial rows)
    // On the stop F_ax = c_F (T_max + eta_s dT - T_c): dF_i/dF_ax = -phi_i load_i.
    T n1 = -c.lump1.phi * c_.load1, n2 = -c.lump2.phi * c_.load2;
    if (rippled()) {
      n1 = n1 * rip;
      n2 = n2 * rip;
    } else {
      (void)rip;
    }
    const T f_x = c_.ten_cF_eta_s * c_.k1, f_xd = c_.ten_cF_eta_s * c_.c1, f_w2 = -c_.ten_cF * dTc;
    const T n1x = per_tau(n1 * f_x), n2x = per_tau(n2 * f_x);
    const T n1v = per_tau(n1 * f_xd), n2v = per_tau(n2 * f_xd);
    dF1[L::kX1] += n1x;
    dF1[L::kX2] += n1x;
    dF1[L::kV1] += n1v;
    dF1[L::kV2] += n1v;
    dF1[L::kW2] += per_tau(n1 * f_w2);
    dF2[L::kX1] += n2x;
    dF2[L::kX2] += n2x;
    dF2[L::kV1] += n2v;
    dF2[L::kV2] += n2v;
    dF2[L::kW2] += per_tau(n2 * f_w2);
  }

  // docs/rom.md#slope-floor for the W of the wedging plants: adds to J
  // the part of the floor that acts through the tangential slip speed,
  // dF_i/dv_t,i raised by (floor - phi') F_ax / cos(beta_i) on the rows of w1
  // and xd_i and the columns w1, w2, xd_i. An approximation of the same floor
  // (the normal force's radial factor and the radial row are left out), which
  // a W-method allows.
  void add_w_slope_floor(const State& x, Jacobian& J) const {
    const T r1e = driver_radius(x);
    const T r2 = pitch_radius2(x);
    const T v1 = r1e * x(L::kW1);
    const T vc = r2 * x(L::kW2);
    const T fax = lumps_axial_force(clamp_force(x), ripple_cos(x));
    const int v_col[2] = {L::kV1, L::kV2};
    const T load[2] = {c_.load1, c_.load2};
    for (int i = 0; i < 2; ++i) {
      const T vt = slip_velocity<T>(vc, x(v_col[i]), v1);
      if (!(abs(vt) < c_.floor_speed)) continue;
      const T slope = friction_characteristic_slope(c_.friction, vt);
      if (!(slope < c_.slope_floor)) continue;
      // Extra dF_i/dv_t (negative: friction opposes slip), per time unit.
      const T dg = -per_tau(c_.slope_floor - slope) * normal_force(fax, load[i]);
      T dv[kStates];  // d v_t,i / dx
      for (int j = 0; j < kStates; ++j) dv[j] = T(0);
      if (!c_.hold1) dv[L::kW1] = -r1e;
      if (!c_.hold2) dv[L::kW2] = r2;
      dv[v_col[i]] = T(1);
      for (int j = 0; j < kStates; ++j) {
        if (dv[j] == T(0)) continue;
        const T dF = dg * dv[j];
        if (!c_.hold1) J(L::kW1, j) -= r1e * dF * c_.inv_J1;
        J(v_col[i], j) += dF * c_.inv_m;
      }
    }
  }

  // What a frame reports (rom_outputs.hpp) and the energy terms (rom_energy.hpp).
  RomOutputs<T> outputs(const State& x) const { return rom_outputs(*this, x); }
  Acc stored_energy(const State& x) const { return rom_stored_energy(*this, x); }
  RomPower<Acc> power(const State& x) const { return rom_power(*this, x); }
  // The same, with the friction already evaluated at x (c = contact(x)).
  RomPower<Acc> power(const State& x, const Contact& c) const { return rom_power(*this, x, c); }

  // The constants in the plant's scalar type and units (rom_constants.hpp).
  const RomConstants<T, Features>& constants() const { return c_; }

  // Wedging: the driven clamping F_ax2 [N] from now on (the simulator's
  // driven actuator sets it once per frame, docs/rom.md#driven-clamping).
  void set_driven_clamp_N(double f_N) {
    if constexpr (L::kWedge) c_.set_driven_clamp(f_N);
    else (void)f_N;
  }

 private:
  // derivative() without wedging, given the effective driver radius and the
  // friction characteristic phi_i of each lump at x; cos_theta is the
  // ripple's (ripple_cos, docs/rom.md#link-ripple).
  template <class S>
  void derivative_given(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& phi1, const S& phi2,
                        const S& cos_theta, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S fax = clamp_force(x);
    const S fl = lumps_axial_force(fax, cos_theta);
    // Friction grouping as in StickSlipOscillator (docs/rom.md#holds).
    const S F1 = lump_friction(phi1, normal_force(fl, S(c_.load1)));
    const S F2 = lump_friction(phi2, normal_force(fl, S(c_.load2)));
    drive_train_rows(x, r1e, S(c_.r2), F1, F2, fax, dxdt);
  }
  // The same with the tension feature (docs/rom.md#tension): the lumps press
  // with the chain's axial force, the sheave feels its bolt force; with
  // chordal action the link phase follows the chain's link passing
  // (docs/rom.md#link-ripple).
  template <class S>
  void derivative_given_tension(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& phi1, const S& phi2,
                                const ChainTension<S>& t, const S& cos_theta,
                                Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S fl = lumps_axial_force(t.F_ax, cos_theta);
    const S F1 = lump_friction(phi1, normal_force(fl, S(c_.load1)));
    const S F2 = lump_friction(phi2, normal_force(fl, S(c_.load2)));
    drive_train_rows(x, r1e, S(c_.r2), F1, F2, clamp_force(x), dxdt);
    if constexpr (L::kPolygon)
      dxdt(L::kPsi) = per_tau(link_phase_rate(S(c_.psi_per_m), S(c_.r2) * x(L::kW2), S(c_.ten_kL), t.inv_D));
  }

  // The rows every feature set shares: pulleys, lumps, axial, polygon phase,
  // from the radii and the tangential friction forces. With wedging r2 varies
  // and the chain frame also accelerates with r2' w2 (docs/rom.md#wedging).
  // Returns the strands' force F_s1 + F_s2 (the radial row's wrap tension).
  template <class S>
  S drive_train_rows(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& r2, const S& F1, const S& F2,
                        const S& fax, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S w2 = x(L::kW2);
    const S x1 = x(L::kX1), xd1 = x(L::kV1), x2 = x(L::kX2), xd2 = x(L::kV2);
    // Spring groupings match StickSlipOscillator so that the held-pulley
    // scene reproduces seed Eq. 9 to the last bit (docs/rom.md#holds).
    const S mid = S(c_.k2) * (x1 - x2) + S(c_.c2) * (xd1 - xd2);
    const Strands<S> st = strands(x);
    const S strand1 = st.s1, strand2 = st.s2;
    // Rates per time unit (per_tau; docs/rom.md#fixed-point). Displacement
    // rows need no factor: length unit / time unit = 1 m/s.
    const S w1dot = c_.hold1 ? S(T(0)) : per_tau((S(inputs.tau_in_Nm) - friction_torque(r1e, F1, F2)) * S(c_.inv_J1));
    const S w2dot =
        c_.hold2 ? S(T(0)) : per_tau((strand_torque(r2, strand1, strand2) - load_torque(w2)) * S(c_.inv_J2));
    S chain_acc = r2 * w2dot;
    // d(v_c)/dt = r2 w2' + r2' w2, r2' = -kappa(rho) rhodot (floating point only).
    if constexpr (L::kWedge) chain_acc = chain_acc - ratio_slope(x(L::kRho)) * x(L::kRhoDot) * w2;
    dxdt(L::kW1) = w1dot;
    dxdt(L::kW2) = w2dot;
    dxdt(L::kX1) = xd1;
    dxdt(L::kV1) = per_tau((F1 - strand1 - mid) * S(c_.inv_m)) - chain_acc;
    dxdt(L::kX2) = xd2;
    dxdt(L::kV2) = per_tau((F2 - strand2 + mid) * S(c_.inv_m)) - chain_acc;
    if constexpr (L::kAxial) {
      const S fh = x(L::kFh), dd = x(L::kDeltaDot);
      // inv_tau_h is per time unit already (a kN step times 50 1/s leaves q16.16).
      dxdt(L::kFh) = (S(saturated_command()) - fh) * S(c_.inv_tau_h);
      dxdt(L::kDelta) = dd;
      dxdt(L::kDeltaDot) = per_tau((fh - fax - S(c_.cs) * dd) * S(c_.inv_ms));
    }
    if constexpr (L::kPolygon) dxdt(L::kPsi) = per_tau(x(L::kW1));
    return strand1 + strand2;
  }

  // One lump of wedge_contact: tangential slip vt, radial slip along the
  // flank gr, N0 = F_ax / cos(beta_i), tb = tan(beta_i).
  template <class S>
  void lump_contact(const S& vt, const S& gr, const S& N0, const S& tb, S& F, S& Fr) const {
    const S s2 = vt * vt + gr * gr;
    // phi(|v|)/|v|; its limit phi'(0) at |v| = 0, where sqrt has no derivative.
    S q(c_.q0);
    if (s2 > S(T(1e-24))) {
      const S speed = sqrt(s2);
      q = friction_characteristic(c_.friction, speed) / speed;
    }
    S N;
    contact_forces(q, vt, gr, N0, tb, N, F, Fr);
  }

  // The forces of a lump from q = phi(|v|)/|v| (seed Eq. 7 solved for N):
  // N (1 + tan(beta) q gr) = F_ax / cos(beta), F = -q vt N, Fr = -q gr N.
  // 1 + tan(beta) q gr >= 1 - mu_max tan(beta) > 0 (validate_scene).
  template <class S>
  void contact_forces(const S& q, const S& vt, const S& gr, const S& N0, const S& tb, S& N, S& F, S& Fr) const {
    N = N0 / (S(T(1)) + tb * q * gr);
    F = -q * vt * N;
    Fr = -q * gr * N;
  }

  LumpPartials lump_contact_partials(const T& vt, const T& gr, const T& N0, const T& tb) const {
    const T s2 = vt * vt + gr * gr;
    T q(c_.q0), dq_vt(0), dq_gr(0);
    if (s2 > T(1e-24)) {
      const T speed = sqrt(s2);
      const FrictionEval<T> e = friction_characteristic_and_slope(c_.friction, speed);
      q = e.phi / speed;
      // dq/ds = (phi'(s) - q) / s and ds/dv = v / s.
      const T dq_s = (e.slope - q) / speed;
      dq_vt = dq_s * (vt / speed);
      dq_gr = dq_s * (gr / speed);
    }
    LumpPartials r;
    T N;
    contact_forces(q, vt, gr, N0, tb, N, r.F, r.Fr);
    const T inv_d = T(1) / (T(1) + tb * q * gr);
    // N = N0 / D with D = 1 + tb q gr.
    const T dN_vt = -N * tb * gr * dq_vt * inv_d;
    const T dN_gr = -N * tb * (q + gr * dq_gr) * inv_d;
    r.dF[0] = -(dq_vt * vt * N + q * N + q * vt * dN_vt);
    r.dF[1] = -(dq_gr * vt * N + q * vt * dN_gr);
    r.dF[2] = -q * vt * inv_d;
    r.dFr[0] = -(dq_vt * gr * N + q * gr * dN_vt);
    r.dFr[1] = -(dq_gr * gr * N + q * N + q * gr * dN_gr);
    r.dFr[2] = -q * gr * inv_d;
    return r;
  }

  // The Jacobian of derivative_wedge (docs/rom.md#wedging-jacobian): the
  // chain rule through the radii, the slip speeds, the bolt force and the
  // contact's partials (c = contact(x), lump_contact_partials). Held pulleys
  // get zero rows, like the dual-number Jacobian of the same right-hand side
  // (the test compares the two). Writes the entries jacobian_entries names.
  void jacobian_wedge(const State& x, const Contact& c, Jacobian& J) const {
    constexpr int N = kStates;
    const T w1 = x(L::kW1), w2 = x(L::kW2), rho = x(L::kRho), rhod = x(L::kRhoDot);
    const T r1p = pitch_radius1(x);
    const T r1e = driver_radius(x);
    T cpsi(1), spsi(0);
    if constexpr (L::kPolygon) {
      cpsi = cos(x(L::kPsi));
      spsi = sin(x(L::kPsi));
    }
    const T r2 = pitch_radius2(x);
    const T kap = ratio_slope(rho);  // -dr2/drho
    const T dkap = ratio_slope_derivative(rho);
    // The lumps' axial force carries the link-passing ripple's factor
    // 1 + A cos(theta) and its phase partial (docs/rom.md#link-ripple).
    T rip(1), dfl_psi(0);
    if constexpr (L::kPolygon) {
      if (rippled()) {
        rip = T(1) + c_.rip_A * c.ripple_cos;
        dfl_psi = -(clamp_force(x) * (c_.rip_A * c_.rip_k)) * c.ripple_sin;
      }
    }
    // dF_ax/dx: F_ax = K_ax (delta - 2 tan(beta0) rho) while compressed.
    T dfax[N];
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dfax[j] = T(0);
    if (x(L::kDelta) - c_.two_tan_b0 * rho > T(0)) {
      dfax[L::kDelta] = c_.K_ax;
      dfax[L::kRho] = -c_.K_ax * c_.two_tan_b0;
    }
    // d r1e/dx and the part of d vt_i/dx both lumps share.
    T dr1e[N], dvt[N];
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dr1e[j] = dvt[j] = T(0);
    dr1e[L::kRho] = cpsi;
    if constexpr (L::kPolygon) dr1e[L::kPsi] = -r1p * spsi;
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dvt[j] = -dr1e[j] * w1;
    dvt[L::kW1] = -r1e;
    dvt[L::kW2] = r2;
    dvt[L::kRho] += -kap * w2;
    // Tangential and radial friction of each lump and their gradients.
    T dF[2][N], dR[2][N];
    T Fsum(0);
    const int v_col[2] = {L::kV1, L::kV2};
    const T inv_cos[2] = {c_.inv_cos1, c_.inv_cos2};
    const T load[2] = {c_.load1, c_.load2};
    #pragma GCC unroll 16
    for (int i = 0; i < 2; ++i) {
      const LumpPartials& P = i == 0 ? c.lump1 : c.lump2;
      Fsum += P.F;
      #pragma GCC unroll 16
      for (int j = 0; j < N; ++j) {
        T dn = load[i] * dfax[j];
        if constexpr (L::kPolygon) {
          if (rippled()) dn = load[i] * (rip * dfax[j] + (j == L::kPsi ? dfl_psi : T(0)));
        }
        dF[i][j] = P.dF[0] * dvt[j] + P.dF[2] * dn;
        dR[i][j] = P.dFr[0] * dvt[j] + P.dFr[2] * dn;
      }
      dF[i][v_col[i]] += P.dF[0];
      dR[i][v_col[i]] += P.dFr[0];
      dF[i][L::kRhoDot] += P.dF[1] * inv_cos[i];
      dR[i][L::kRhoDot] += P.dFr[1] * inv_cos[i];
    }
    // The constants in locals: every store to J (entries of type T) would
    // otherwise make the compiler read them from the plant again.
    const T inv_J1 = c_.inv_J1, inv_J2 = c_.inv_J2, inv_m = c_.inv_m, inv_ms = c_.inv_ms, inv_mr = c_.inv_mr;
    const T k1 = c_.k1, k2 = c_.k2, c1 = c_.c1, c2 = c_.c2;
    // Driver row: J1 w1' = tau_in - r1e (F1 + F2); a held pulley's row is zero.
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j)
      J(L::kW1, j) = c_.hold1 ? T(0) : -(r1e * (dF[0][j] + dF[1][j]) + Fsum * dr1e[j]) * inv_J1;
    // Driven row: J2 w2' = r2 (strand1 + strand2) - tau_load.
    T dw2[N];
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dw2[j] = T(0);
    T w2dot(0);
    // Strand stretch x_i + g rho, x_i' + g rho' (docs/rom.md#wrap-tension).
    const Strands<T> st = strands(x);
    const T strand1 = st.s1, strand2 = st.s2;
    const T g = c_.wrap_g;
    if (!c_.hold2) {
      w2dot = (strand_torque(r2, strand1, strand2) - load_torque(w2)) * inv_J2;
      dw2[L::kX1] = dw2[L::kX2] = r2 * k1 * inv_J2;
      dw2[L::kV1] = dw2[L::kV2] = r2 * c1 * inv_J2;
      dw2[L::kW2] = -load_torque_slope(w2) * inv_J2;
      dw2[L::kRho] = (-kap * (strand1 + strand2) + r2 * T(2) * g * k1) * inv_J2;
      dw2[L::kRhoDot] = r2 * T(2) * g * c1 * inv_J2;
    }
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) J(L::kW2, j) = dw2[j];
    // Chain frame acceleration r2 w2' - kappa rhodot w2.
    T dca[N];
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dca[j] = r2 * dw2[j];
    dca[L::kRho] += -kap * w2dot - dkap * rhod * w2;
    dca[L::kRhoDot] += -kap * w2;
    dca[L::kW2] += -kap * rhod;
    // Lump rows: m (xd_i' + chain) = F_i - strand_i -+ mid.
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) {
      J(L::kV1, j) = dF[0][j] * inv_m - dca[j];
      J(L::kV2, j) = dF[1][j] * inv_m - dca[j];
    }
    J(L::kV1, L::kX1) += -(k1 + k2) * inv_m;
    J(L::kV1, L::kX2) += k2 * inv_m;
    J(L::kV1, L::kV1) += -(c1 + c2) * inv_m;
    J(L::kV1, L::kV2) += c2 * inv_m;
    J(L::kV2, L::kX1) += k2 * inv_m;
    J(L::kV2, L::kX2) += -(k1 + k2) * inv_m;
    J(L::kV2, L::kV1) += c2 * inv_m;
    J(L::kV2, L::kV2) += -(c1 + c2) * inv_m;
    // Each lump's strand also stretches with g rho.
    J(L::kV1, L::kRho) += -g * k1 * inv_m;
    J(L::kV2, L::kRho) += -g * k1 * inv_m;
    J(L::kV1, L::kRhoDot) += -g * c1 * inv_m;
    J(L::kV2, L::kRhoDot) += -g * c1 * inv_m;
    J(L::kX1, L::kV1) = T(1);
    J(L::kX2, L::kV2) = T(1);
    // Axial rows.
    J(L::kFh, L::kFh) = -c_.inv_tau_h;
    J(L::kDelta, L::kDeltaDot) = T(1);
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) J(L::kDeltaDot, j) = -dfax[j] * inv_ms;
    J(L::kDeltaDot, L::kFh) += inv_ms;
    J(L::kDeltaDot, L::kDeltaDot) += -c_.cs * inv_ms;
    // Radial rows: m_r rho'' = 2 tan(beta0) F_ax + sum Fr_i / cos(beta_i)
    //   - kappa 2 tan(beta0) F_ax2 - c_r rho' - F_stop - g (F_s1 + F_s2).
    J(L::kRho, L::kRhoDot) = T(1);
    const T two_tan_b0 = c_.two_tan_b0, inv_cos1 = c_.inv_cos1, inv_cos2 = c_.inv_cos2;
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j)
      J(L::kRhoDot, j) = (two_tan_b0 * dfax[j] + dR[0][j] * inv_cos1 + dR[1][j] * inv_cos2) * inv_mr;
    const T stop_slope = stop_penetration(rho) != T(0) ? c_.k_stop : T(0);
    J(L::kRhoDot, L::kRho) += (-dkap * c_.driven_force - stop_slope) * inv_mr;
    J(L::kRhoDot, L::kRhoDot) += -c_.cr * inv_mr;
    // - g (F_s1 + F_s2), the wrap-tension pull (docs/rom.md#wrap-tension).
    J(L::kRhoDot, L::kX1) += -g * k1 * inv_mr;
    J(L::kRhoDot, L::kX2) += -g * k1 * inv_mr;
    J(L::kRhoDot, L::kV1) += -g * c1 * inv_mr;
    J(L::kRhoDot, L::kV2) += -g * c1 * inv_mr;
    J(L::kRhoDot, L::kRho) += -T(2) * g * g * k1 * inv_mr;
    J(L::kRhoDot, L::kRhoDot) += -T(2) * g * g * c1 * inv_mr;
    if constexpr (L::kPolygon) J(L::kPsi, L::kW1) = T(1);
  }

  // derivative() with wedging (docs/rom.md#wedging): radii follow rho, the
  // chain frame accelerates with d(r2 w2)/dt, the friction is a vector.
  template <class S>
  void derivative_wedge(const Eigen::Matrix<S, kStates, 1>& x, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S rhod = x(L::kRhoDot);
    const S r1e = driver_radius(x);
    const S r2 = pitch_radius2(x);
    const S v1 = r1e * x(L::kW1);
    const S vc = r2 * x(L::kW2);
    const S fax = clamp_force(x);
    // The lumps press with the rippled force (docs/rom.md#link-ripple); the
    // radial balance keeps the bolt force.
    const WedgeContact<S> c = wedge_contact(slip_velocity<S>(vc, x(L::kV1), v1), slip_velocity<S>(vc, x(L::kV2), v1),
                                            rhod, lumps_axial_force(fax, ripple_cos(x)));
    derivative_wedge_given(x, r1e, r2, fax, c, dxdt);
  }

  // The same from the radii, the axial force and the contact forces at x.
  template <class S>
  void derivative_wedge_given(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& r2, const S& fax,
                              const WedgeContact<S>& c, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S rhod = x(L::kRhoDot);
    const S strands_sum = drive_train_rows(x, r1e, r2, c.F1, c.F2, fax, dxdt);
    // m_r rho'' = 2 tan(beta0) F_b + sum F_r,i / cos(beta_i) - kappa(rho) 2 tan(beta0) F_ax2 - c_r rho' - F_stop
    //            - g (F_s1 + F_s2)   (docs/rom.md#wrap-tension)
    dxdt(L::kRho) = rhod;
    dxdt(L::kRhoDot) = (S(c_.two_tan_b0) * fax + c.Fr1 * S(c_.inv_cos1) + c.Fr2 * S(c_.inv_cos2) -
                        ratio_slope(x(L::kRho)) * S(c_.driven_force) - S(c_.cr) * rhod -
                        S(c_.k_stop) * stop_penetration(x(L::kRho)) - wrap_tension_pull(S(c_.wrap_g), strands_sum)) *
                       S(c_.inv_mr);
  }

  RomParams p_;
  RomConstants<T, Features> c_;
};

}  // namespace cvt
