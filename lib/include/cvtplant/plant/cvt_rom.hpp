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
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/integrate/system.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

// Internal units of the plant (docs/rom.md#fixed-point). Floating point runs
// in SI: every factor is 1 and folds away at compile time, so float and
// double results are those of the plain SI equations, bit for bit. Fixed point
// measures time in units of 2^-10 s and the lump and sheave displacements in
// 2^-10 m: the stick stiffness per time unit (1.2e4 at 3.3 kN) and the bolt
// stiffness per length unit (1483 N) then fit q16.16, and the step is 0.512
// units instead of 33 LSB of seconds. Velocities stay in m/s and rad/s, since
// 2^-10 m per 2^-10 s is 1 m/s: position rows need no factor at all.
template <class T>
struct RomUnits {
  static constexpr bool kScaled = false;
  static constexpr double time_s = 1.0;    // one time unit [s]
  static constexpr double length_m = 1.0;  // one unit of x1, x2, delta [m]
};
template <int FracBits>
struct RomUnits<Fixed<FracBits>> {
  static constexpr bool kScaled = true;
  static constexpr double time_s = 1.0 / 1024.0;
  static constexpr double length_m = time_s;  // = time unit x 1 m/s
};

// Everything a frame reports (docs/rom.md#outputs). Forces in N, torques in N m.
template <class T>
struct RomOutputs {
  T omega1_rad_s{}, omega2_rad_s{};
  T speed_ratio{};        // w1 / w2 (0 while |w2| < 1e-3 rad/s)
  T geometric_ratio{};    // r2 / r1 (varies with wedging)
  T radius1_m{}, radius2_m{};  // pitch radii (constant unless wedging)
  T slip{};               // (v1 - v_c) / v1 (0 while |v1| < 1e-3 m/s)
  T clamp_force_N{};      // F_ax acting on the lumps
  T torque_transmitted_Nm{};  // r1e (F1 + F2): friction torque on the driver
  T tau_in_Nm{}, tau_load_Nm{};  // as applied (held pulleys report the holding torque)
  T friction1_N{}, friction2_N{};            // tangential friction on the lumps
  T radial_friction1_N{}, radial_friction2_N{};  // along the flank, radial direction (wedging; seed Eq. 7 F_r)
  T v_rel1_m_s{}, v_rel2_m_s{};
  bool stick1 = false, stick2 = false;
};

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

  explicit CvtRom(const RomParams& p) : p_(p) {
    c_.r1 = T(p.r1_m);
    c_.r2 = T(p.r2_m);
    c_.inv_J1 = T(1.0 / p.J1_kgm2);
    c_.inv_J2 = T(1.0 / p.J2_kgm2);
    c_.inv_m = T(1.0 / p.lump_mass_kg);
    // Springs act on displacements, so they are stored per length unit.
    c_.k1 = T(p.k1_N_m * U::length_m);
    c_.c1 = T(p.c1_Ns_m);
    c_.k2 = T(p.k2_N_m * U::length_m);
    c_.c2 = T(p.c2_Ns_m);
    c_.friction = p.friction.template cast<T>();
    // docs/rom.md#deformation: beta_i = beta0 + Delta/2 sin(zeta_i - theta_c + pi/2),
    // Delta, theta_c from seed Eq. 4. The lumps sit at fixed wrap angles, so
    // 1/cos(beta_i) is a set-up constant and the feature costs nothing per step.
    double b1 = p.beta0_rad, b2 = p.beta0_rad;
    if constexpr (L::kDeform) {
      const double ratio = p.r1_m / p.r2_m;
      const double Delta = seed::deformation_amplitude_rad(ratio);
      const double theta_c = seed::deformation_centre_rad(ratio);
      b1 = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta1_rad);
      b2 = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta2_rad);
    }
    c_.inv_cos1 = T(1.0 / dm::cos(b1));
    c_.inv_cos2 = T(1.0 / dm::cos(b2));
    c_.hold1 = p.hold_driver_speed;
    c_.hold2 = p.hold_driven_speed;
    c_.stick_speed = T(p.stick_speed_m_s);
    // docs/rom.md#slope-floor: the edge of the sign's regularisation layer
    // (none for the exact sign) and the friction slope there.
    if (p.friction.sign != SignFunction::exact) {
      c_.floor_speed = T(1.0 / p.friction.lambda_s_m);
      c_.slope_floor = friction_characteristic_slope(c_.friction, c_.floor_speed);
    }
    c_.tu = T(U::time_s);
    if constexpr (L::kAxial) {
      // Per time unit in the constant (0.049 in fixed point, 3200 LSB): one
      // rounding of (F_cmd - F_h) x constant, not a rounded rate times 50.
      c_.inv_tau_h = T(U::time_s / p.actuator_tau_s);
      c_.clamp_max = T(p.clamp_max_N);
      c_.inv_ms = T(1.0 / p.sheave_mass_kg);
      c_.cs = T(p.sheave_damping_Ns_m);
      c_.K_ax = T(p.K_ax_N_m * U::length_m);
    }
    if constexpr (L::kRoad) {
      c_.T0 = T(p.road_T0_Nm);
      c_.cv = T(p.road_cv_Nms_rad);
      c_.ca = T(p.road_ca_Nms2_rad2);
      c_.inv_w_eps = T(1.0 / p.road_w_eps_rad_s);
    }
    if constexpr (L::kPolygon) {
      // docs/rom.md#polygon: half the angle one link subtends on the driver.
      c_.alpha = T(dm::asin_setup(p.pitch_m / (2.0 * p.r1_m)));
    }
    if constexpr (L::kWedge) {
      // docs/rom.md#wedging: r2(rho) from chain length conservation, as the
      // cubic through the exact solutions at rho = 0, +-e, +-2e (e = travel/2).
      const double e = 0.5 * p.radial_travel_m;
      const double fp1 = driven_radius_exact(p, e), fm1 = driven_radius_exact(p, -e);
      const double fp2 = driven_radius_exact(p, 2 * e), fm2 = driven_radius_exact(p, -2 * e);
      const double f0 = p.r2_m;
      const double a1 = (8.0 * (fp1 - fm1) - (fp2 - fm2)) / (12.0 * e);
      const double a2 = (16.0 * (fp1 + fm1) - (fp2 + fm2) - 30.0 * f0) / (24.0 * e * e);
      const double a3 = ((fp2 - fm2) - 2.0 * (fp1 - fm1)) / (12.0 * e * e * e);
      const double tb = dm::sin(p.beta0_rad) / dm::cos(p.beta0_rad);
      c_.a1 = T(a1);
      c_.a2 = T(a2);
      c_.a3 = T(a3);
      c_.two_tan_b0 = T(2.0 * tb);
      c_.tan1 = T(dm::sin(b1) / dm::cos(b1));
      c_.tan2 = T(dm::sin(b2) / dm::cos(b2));
      c_.inv_mr = T(1.0 / p.radial_mass_kg);
      c_.cr = T(p.radial_damping_Ns_m);
      c_.driven_force = T(2.0 * tb * p.driven_clamp_N);
      c_.travel = T(p.radial_travel_m);
      c_.k_stop = T(p.radial_stop_N_m);
      a_.k_stop = Acc(p.radial_stop_N_m);
      c_.q0 = friction_characteristic_slope(c_.friction, T(0));
      a_.mr = Acc(p.radial_mass_kg);
      a_.cr = Acc(p.radial_damping_Ns_m);
      a_.a1 = Acc(a1);
      a_.a2 = Acc(a2);
      a_.a3 = Acc(a3);
      a_.two_tan_b0 = Acc(2.0 * tb);
      a_.driven_force = Acc(2.0 * tb * p.driven_clamp_N);
    }
    // Accounting copies (docs/rom.md#energy-balance).
    a_.J1 = Acc(p.J1_kgm2);
    a_.J2 = Acc(p.J2_kgm2);
    a_.m = Acc(p.lump_mass_kg);
    a_.k1 = Acc(p.k1_N_m);
    a_.k2 = Acc(p.k2_N_m);
    a_.c1 = Acc(p.c1_Ns_m);
    a_.c2 = Acc(p.c2_Ns_m);
    a_.r2 = Acc(p.r2_m);
    a_.ms = Acc(p.sheave_mass_kg);
    a_.cs = Acc(p.sheave_damping_Ns_m);
    a_.K_ax = Acc(p.K_ax_N_m);
  }

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
    return rho * (S(c_.a1) + rho * (S(c_.a2) + rho * S(c_.a3)));
  }
  template <class S>
  S ratio_slope(const S& rho) const {
    return -(S(c_.a1) + rho * (S(c_.a2 + c_.a2) + rho * S(T(3) * c_.a3)));
  }

  // Effective driver radius r1e: r1, or r1 cos(psi) with chordal action.
  template <class S>
  S driver_radius(const Eigen::Matrix<S, kStates, 1>& x) const {
    if constexpr (L::kPolygon) return pitch_radius1(x) * cos(x(L::kPsi));
    return pitch_radius1(x);
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
    lump_contact(vt1, rhod * S(c_.inv_cos1), fax * S(c_.inv_cos1), S(c_.tan1), c.F1, c.Fr1);
    lump_contact(vt2, rhod * S(c_.inv_cos2), fax * S(c_.inv_cos2), S(c_.tan2), c.F2, c.Fr2);
    return c;
  }

  // Load torque at the driven shaft (docs/rom.md#road-load).
  template <class S>
  S load_torque(const S& w2) const {
    S tl(inputs.tau_load_Nm);
    if constexpr (L::kRoad) {
      tl = tl + S(c_.T0) * tanh(w2 * S(c_.inv_w_eps)) + S(c_.cv) * w2 + S(c_.ca) * w2 * abs(w2);
    }
    return tl;
  }

  // Friction of both lumps at a state, value and slope (non-wedging plants):
  // evaluated once per state and shared by the right-hand side, the Jacobian
  // and the power terms, since the exponentials and the atan are most of a
  // frame on a Cortex-M (docs/rom.md#cost).
  struct Contact {
    T r1e{};             // effective driver radius [m]
    T v_rel1{}, v_rel2{};  // slip speeds [m/s]
    FrictionEval<T> lump1{}, lump2{};
  };
  Contact contact(const State& x) const {
    static_assert(!L::kWedge, "wedging plants evaluate the contact inside derivative() (docs/rom.md#wedging)");
    Contact c;
    c.r1e = driver_radius(x);
    const T v1 = c.r1e * x(L::kW1);
    const T vc = c_.r2 * x(L::kW2);
    c.v_rel1 = (vc + x(L::kV1)) - v1;
    c.v_rel2 = (vc + x(L::kV2)) - v1;
    c.lump1 = friction_characteristic_and_slope(c_.friction, c.v_rel1);
    c.lump2 = friction_characteristic_and_slope(c_.friction, c.v_rel2);
    return c;
  }

  template <class S>
  void derivative(const Eigen::Matrix<S, kStates, 1>& x, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    if constexpr (L::kWedge) {
      derivative_wedge(x, dxdt);
    } else {
      const S r1e = driver_radius(x);
      const S v1 = r1e * x(L::kW1);
      const S vc = S(c_.r2) * x(L::kW2);
      derivative_given(x, r1e, friction_characteristic(c_.friction, S((vc + x(L::kV1)) - v1)),
                       friction_characteristic(c_.friction, S((vc + x(L::kV2)) - v1)), dxdt);
    }
  }
  // The same, with the friction already evaluated at x (c = contact(x)).
  void derivative(const State& x, const Contact& c, State& dxdt) const {
    derivative_given(x, c.r1e, c.lump1.phi, c.lump2.phi, dxdt);
  }

  // Analytic Jacobian (docs/rom.md#jacobian). Held pulleys get zero rows AND
  // columns: their speed never changes, so the columns multiply a zero
  // increment, and leaving them out keeps the LU pivots those of seed Eq. 9.
  // With wedging, dual numbers (docs/rom.md#wedging).
  void jacobian(const State& x, Jacobian& J) const {
    if constexpr (L::kWedge) {
      jacobian_by_duals(*this, x, J);
    } else {
      jacobian(x, contact(x), J, false);
    }
  }

  // The Jacobian from the friction already evaluated at x. With
  // `w_slope_floor` it is the matrix W of the real-time step instead
  // (docs/rom.md#slope-floor): inside the sign's regularisation layer
  // |v_rel| < 1/lambda the friction slope is raised to at least its value at
  // the layer's edge. Seed case 2 has mu(0) = 0, so at exact rest the true
  // slope is zero and a step would not see the stick stiffness that appears
  // within it. ROS2 is a W-method (order 2 for any W), so this changes the
  // step's error constant near stick, not its order.
  void jacobian(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    static_assert(!L::kWedge, "wedging plants use jacobian(x, J) (docs/rom.md#wedging)");
    J.setZero();
    const T w1 = x(L::kW1), w2 = x(L::kW2);
    const T r1e = c.r1e;
    const T fax = clamp_force(x);
    const T N1 = fax * c_.inv_cos1, N2 = fax * c_.inv_cos2;
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
    for (int j = 0; j < kStates; ++j) rw2[j] = T(0);
    if (free2) {
      T dtl = T(0);
      if constexpr (L::kRoad) {
        const T th = tanh(w2 * c_.inv_w_eps);
        dtl = c_.T0 * (T(1) - th * th) * c_.inv_w_eps + c_.cv + (c_.ca + c_.ca) * abs(w2);
      }
      rw2[L::kW2] = per_tau(-dtl * c_.inv_J2);
      rw2[L::kX1] = per_tau(c_.r2 * c_.k1 * c_.inv_J2);
      rw2[L::kV1] = per_tau(c_.r2 * c_.c1 * c_.inv_J2);
      rw2[L::kX2] = per_tau(c_.r2 * c_.k1 * c_.inv_J2);
      rw2[L::kV2] = per_tau(c_.r2 * c_.c1 * c_.inv_J2);
      for (int j = 0; j < kStates; ++j) J(L::kW2, j) = rw2[j];
    }
    // Partials of F_i w.r.t. the states, columns w1, w2, xd_i, delta, psi,
    // per time unit like g_i.
    T dF1[kStates], dF2[kStates];
    for (int j = 0; j < kStates; ++j) dF1[j] = dF2[j] = T(0);
    dF1[L::kW1] = -g1 * r1e;
    dF2[L::kW1] = -g2 * r1e;
    dF1[L::kW2] = g1 * c_.r2;
    dF2[L::kW2] = g2 * c_.r2;
    dF1[L::kV1] = g1;
    dF2[L::kV2] = g2;
    if constexpr (L::kAxial) {
      if (x(L::kDelta) > T(0)) {
        // dF_i/dF_ax = -phi(v_rel_i) / cos(beta_i)
        dF1[L::kDelta] = per_tau(-c.lump1.phi * c_.inv_cos1 * c_.K_ax);
        dF2[L::kDelta] = per_tau(-c.lump2.phi * c_.inv_cos2 * c_.K_ax);
      }
    }
    T sin_psi = T(0);
    if constexpr (L::kPolygon) {
      sin_psi = sin(x(L::kPsi));
      // dv_rel/dpsi = -dr1e/dpsi w1 = r1 sin(psi) w1
      const T dv = c_.r1 * sin_psi * w1;
      dF1[L::kPsi] = g1 * dv;
      dF2[L::kPsi] = g2 * dv;
    }
    if (!free1) dF1[L::kW1] = dF2[L::kW1] = T(0);
    if (!free2) dF1[L::kW2] = dF2[L::kW2] = T(0);

    if (free1) {
      for (int j = 0; j < kStates; ++j) J(L::kW1, j) = -r1e * (dF1[j] + dF2[j]) * c_.inv_J1;
      if constexpr (L::kPolygon) {
        const T F1 = -c.lump1.phi * N1;
        const T F2 = -c.lump2.phi * N2;
        // d(r1e)/dpsi = -r1 sin(psi)
        J(L::kW1, L::kPsi) += per_tau(c_.r1 * sin_psi * (F1 + F2) * c_.inv_J1);
      }
    }
    J(L::kX1, L::kV1) = T(1);
    J(L::kX2, L::kV2) = T(1);
    for (int j = 0; j < kStates; ++j) {
      J(L::kV1, j) = dF1[j] * im - c_.r2 * rw2[j];
      J(L::kV2, j) = dF2[j] * im - c_.r2 * rw2[j];
    }
    J(L::kV1, L::kX1) += per_tau(-(c_.k1 + c_.k2) * im);
    J(L::kV1, L::kX2) += per_tau(c_.k2 * im);
    J(L::kV1, L::kV1) += per_tau(-(c_.c1 + c_.c2) * im);
    J(L::kV1, L::kV2) += per_tau(c_.c2 * im);
    J(L::kV2, L::kX1) += per_tau(c_.k2 * im);
    J(L::kV2, L::kX2) += per_tau(-(c_.k1 + c_.k2) * im);
    J(L::kV2, L::kV1) += per_tau(c_.c2 * im);
    J(L::kV2, L::kV2) += per_tau(-(c_.c1 + c_.c2) * im);
    if constexpr (L::kAxial) {
      J(L::kFh, L::kFh) = -c_.inv_tau_h;
      J(L::kDelta, L::kDeltaDot) = T(1);
      J(L::kDeltaDot, L::kFh) = per_tau(c_.inv_ms);
      J(L::kDeltaDot, L::kDelta) = x(L::kDelta) > T(0) ? per_tau(-c_.K_ax * c_.inv_ms) : T(0);
      J(L::kDeltaDot, L::kDeltaDot) = per_tau(-c_.cs * c_.inv_ms);
    }
    if constexpr (L::kPolygon) J(L::kPsi, L::kW1) = per_tau(T(1));
  }

  // docs/rom.md#slope-floor for the dense W of the wedging plants: adds to J
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
    const T fax = clamp_force(x);
    const int v_col[2] = {L::kV1, L::kV2};
    const T inv_cos[2] = {c_.inv_cos1, c_.inv_cos2};
    for (int i = 0; i < 2; ++i) {
      const T vt = (vc + x(v_col[i])) - v1;
      if (!(abs(vt) < c_.floor_speed)) continue;
      const T slope = friction_characteristic_slope(c_.friction, vt);
      if (!(slope < c_.slope_floor)) continue;
      // Extra dF_i/dv_t (negative: friction opposes slip), per time unit.
      const T dg = -per_tau(c_.slope_floor - slope) * (fax * inv_cos[i]);
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

  RomOutputs<T> outputs(const State& x) const {
    RomOutputs<T> o;
    const T w1 = x(L::kW1), w2 = x(L::kW2);
    const T r1e = driver_radius(x);
    const T r2 = pitch_radius2(x);
    const T v1 = r1e * w1;
    const T vc = r2 * w2;
    const T fax = clamp_force(x);
    o.omega1_rad_s = w1;
    o.omega2_rad_s = w2;
    o.radius1_m = pitch_radius1(x);
    o.radius2_m = r2;
    o.geometric_ratio = r2 / o.radius1_m;
    const T w_tiny = T(1e-3);
    o.speed_ratio = abs(w2) < w_tiny ? T(0) : w1 / w2;
    o.slip = abs(v1) < w_tiny ? T(0) : (v1 - vc) / v1;
    o.clamp_force_N = fax;
    o.v_rel1_m_s = (vc + x(L::kV1)) - v1;
    o.v_rel2_m_s = (vc + x(L::kV2)) - v1;
    if constexpr (L::kWedge) {
      const WedgeContact<T> c = wedge_contact(o.v_rel1_m_s, o.v_rel2_m_s, x(L::kRhoDot), fax);
      o.friction1_N = c.F1;
      o.friction2_N = c.F2;
      o.radial_friction1_N = c.Fr1;
      o.radial_friction2_N = c.Fr2;
    } else {
      o.friction1_N = -friction_characteristic(c_.friction, o.v_rel1_m_s) * (fax * c_.inv_cos1);
      o.friction2_N = -friction_characteristic(c_.friction, o.v_rel2_m_s) * (fax * c_.inv_cos2);
    }
    o.torque_transmitted_Nm = r1e * (o.friction1_N + o.friction2_N);
    o.tau_in_Nm = c_.hold1 ? o.torque_transmitted_Nm : inputs.tau_in_Nm;
    const T strand = c_.k1 * x(L::kX1) + c_.c1 * x(L::kV1) + (c_.k1 * x(L::kX2) + c_.c1 * x(L::kV2));
    o.tau_load_Nm = c_.hold2 ? r2 * strand : load_torque(w2);
    o.stick1 = abs(o.v_rel1_m_s) < c_.stick_speed;
    o.stick2 = abs(o.v_rel2_m_s) < c_.stick_speed;
    return o;
  }

  // Stored energy [J] (docs/rom.md#energy-balance), in the accounting type.
  Acc stored_energy(const State& xs) const {
    Acc x[kStates];
    for (int i = 0; i < kStates; ++i) x[i] = to_acc(xs(i));
    if constexpr (U::kScaled) {
      // Displacements back to metres: energies of 1e5 J are only kept in float.
      x[L::kX1] *= Acc(U::length_m);
      x[L::kX2] *= Acc(U::length_m);
      if constexpr (L::kAxial) x[L::kDelta] *= Acc(U::length_m);
    }
    const Acc w1 = x[L::kW1], w2 = x[L::kW2];
    Acc r2 = a_.r2;
    Acc dr2 = Acc(0);
    if constexpr (L::kWedge) {
      const Acc rho = x[L::kRho];
      dr2 = rho * (a_.a1 + rho * (a_.a2 + rho * a_.a3));
      r2 += dr2;
    }
    const Acc vc = r2 * w2;
    const Acc u1 = vc + x[L::kV1], u2 = vc + x[L::kV2];
    const Acc dx = x[L::kX1] - x[L::kX2];
    Acc e = Acc(0.5) * (a_.J1 * w1 * w1 + a_.J2 * w2 * w2 + a_.m * (u1 * u1 + u2 * u2) +
                        a_.k1 * (x[L::kX1] * x[L::kX1] + x[L::kX2] * x[L::kX2]) + a_.k2 * dx * dx);
    if constexpr (L::kAxial) {
      Acc b = x[L::kDelta];
      if constexpr (L::kWedge) b -= a_.two_tan_b0 * x[L::kRho];
      const Acc d = b > Acc(0) ? b : Acc(0);
      e += Acc(0.5) * (a_.ms * x[L::kDeltaDot] * x[L::kDeltaDot] + a_.K_ax * d * d);
    }
    if constexpr (L::kWedge) {
      // Radial kinetic energy and the potential of the (constant) driven
      // clamping force through chain length conservation.
      const Acc pen = to_acc(stop_penetration(xs(L::kRho)));
      e += Acc(0.5) * a_.mr * x[L::kRhoDot] * x[L::kRhoDot] - a_.driven_force * dr2 +
           Acc(0.5) * a_.k_stop * pen * pen;
    }
    return e;
  }

  // Power terms at state x with the current inputs (docs/rom.md#energy-balance).
  RomPower<Acc> power(const State& xs) const {
    if constexpr (L::kWedge) {
      const RomOutputs<T> o = outputs(xs);
      RomPower<Acc> pw = power_given(xs, o.tau_in_Nm, o.tau_load_Nm, o.friction1_N, o.friction2_N, o.v_rel1_m_s,
                                     o.v_rel2_m_s);
      // Radial slip along the flank is rhodot / cos(beta_i).
      const Acc rd = to_acc(xs(L::kRhoDot));
      pw.friction_loss_W -= to_acc(o.radial_friction1_N) * rd * to_acc(c_.inv_cos1) +
                            to_acc(o.radial_friction2_N) * rd * to_acc(c_.inv_cos2);
      pw.damping_loss_W += a_.cr * rd * rd;
      return pw;
    } else {
      return power(xs, contact(xs));
    }
  }
  // The same, with the friction already evaluated at x (c = contact(x)); the
  // forces and torques as outputs() computes them.
  RomPower<Acc> power(const State& xs, const Contact& c) const {
    const T fax = clamp_force(xs);
    const T F1 = -c.lump1.phi * (fax * c_.inv_cos1);
    const T F2 = -c.lump2.phi * (fax * c_.inv_cos2);
    const T tau_in = c_.hold1 ? c.r1e * (F1 + F2) : inputs.tau_in_Nm;
    T tau_load;
    if (c_.hold2) {
      const T strand = c_.k1 * xs(L::kX1) + c_.c1 * xs(L::kV1) + (c_.k1 * xs(L::kX2) + c_.c1 * xs(L::kV2));
      tau_load = c_.r2 * strand;
    } else {
      tau_load = load_torque(xs(L::kW2));
    }
    return power_given(xs, tau_in, tau_load, F1, F2, c.v_rel1, c.v_rel2);
  }

  static Acc to_acc(const T& v) {
    if constexpr (std::is_floating_point_v<T>) return static_cast<Acc>(v);
    else return v.to_float();
  }

 private:
  // The power terms common to every feature set, from the applied torques and
  // the tangential friction forces (docs/rom.md#energy-balance).
  RomPower<Acc> power_given(const State& xs, const T& tau_in, const T& tau_load, const T& F1, const T& F2,
                            const T& vr1, const T& vr2) const {
    Acc x[kStates];
    for (int i = 0; i < kStates; ++i) x[i] = to_acc(xs(i));
    RomPower<Acc> pw;
    pw.input_W = to_acc(tau_in) * x[L::kW1];
    pw.load_W = to_acc(tau_load) * x[L::kW2];
    pw.friction_loss_W = -(to_acc(F1) * to_acc(vr1) + to_acc(F2) * to_acc(vr2));
    const Acc dv = x[L::kV1] - x[L::kV2];
    pw.damping_loss_W = a_.c1 * (x[L::kV1] * x[L::kV1] + x[L::kV2] * x[L::kV2]) + a_.c2 * dv * dv;
    if constexpr (L::kAxial) {
      pw.actuator_W = x[L::kFh] * x[L::kDeltaDot];
      pw.damping_loss_W += a_.cs * x[L::kDeltaDot] * x[L::kDeltaDot];
    }
    return pw;
  }

  // derivative() without wedging, given the effective driver radius and the
  // friction characteristic phi_i of each lump at x.
  template <class S>
  void derivative_given(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& phi1, const S& phi2,
                        Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S fax = clamp_force(x);
    // Friction grouping as in StickSlipOscillator (docs/rom.md#holds).
    const S F1 = -phi1 * (fax * S(c_.inv_cos1));
    const S F2 = -phi2 * (fax * S(c_.inv_cos2));
    drive_train_rows(x, r1e, S(c_.r2), F1, F2, fax, dxdt);
  }

  // The rows every feature set shares: pulleys, lumps, axial, polygon phase,
  // from the radii and the tangential friction forces. With wedging r2 varies
  // and the chain frame also accelerates with r2' w2 (docs/rom.md#wedging).
  template <class S>
  void drive_train_rows(const Eigen::Matrix<S, kStates, 1>& x, const S& r1e, const S& r2, const S& F1, const S& F2,
                        const S& fax, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const S w2 = x(L::kW2);
    const S x1 = x(L::kX1), xd1 = x(L::kV1), x2 = x(L::kX2), xd2 = x(L::kV2);
    // Spring groupings match StickSlipOscillator so that the held-pulley
    // scene reproduces seed Eq. 9 to the last bit (docs/rom.md#holds).
    const S mid = S(c_.k2) * (x1 - x2) + S(c_.c2) * (xd1 - xd2);
    const S strand1 = S(c_.k1) * x1 + S(c_.c1) * xd1;
    const S strand2 = S(c_.k1) * x2 + S(c_.c1) * xd2;
    // Rates per time unit (per_tau; docs/rom.md#fixed-point). Displacement
    // rows need no factor: length unit / time unit = 1 m/s.
    const S w1dot = c_.hold1 ? S(T(0)) : per_tau((S(inputs.tau_in_Nm) - r1e * (F1 + F2)) * S(c_.inv_J1));
    const S w2dot = c_.hold2 ? S(T(0)) : per_tau((r2 * (strand1 + strand2) - load_torque(w2)) * S(c_.inv_J2));
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
    // seed Eq. 7 solved for N: N (1 + tan(beta) q gr) = F_ax / cos(beta).
    // 1 + tan(beta) q gr >= 1 - mu_max tan(beta) > 0 (validate_scene).
    const S N = N0 / (S(T(1)) + tb * q * gr);
    F = -q * vt * N;
    Fr = -q * gr * N;
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
    const WedgeContact<S> c = wedge_contact(S((vc + x(L::kV1)) - v1), S((vc + x(L::kV2)) - v1), rhod, fax);
    drive_train_rows(x, r1e, r2, c.F1, c.F2, fax, dxdt);
    // m_r rho'' = 2 tan(beta0) F_b + sum F_r,i / cos(beta_i) - kappa(rho) 2 tan(beta0) F_ax2 - c_r rho' - F_stop
    dxdt(L::kRho) = rhod;
    dxdt(L::kRhoDot) = (S(c_.two_tan_b0) * fax + c.Fr1 * S(c_.inv_cos1) + c.Fr2 * S(c_.inv_cos2) -
                        ratio_slope(x(L::kRho)) * S(c_.driven_force) - S(c_.cr) * rhod -
                        S(c_.k_stop) * stop_penetration(x(L::kRho))) *
                       S(c_.inv_mr);
  }

  // Driven pitch radius that keeps the chain length of the set-up radii when
  // the driver radius is r1 + rho (set-up only): Newton on the chain length,
  // dL/dr2 = theta2 (docs/rom.md#wedging).
  static double driven_radius_exact(const RomParams& p, double rho) {
    const double C = p.center_distance_m;
    const double L0 = seed::chain_length_m(p.r1_m, p.r2_m, C), a = p.r1_m + rho;
    double b = p.r2_m;
    for (int i = 0; i < 30; ++i) b -= (seed::chain_length_m(a, b, C) - L0) / seed::wrap_angle_driven_rad(a, b, C);
    return b;
  }

  struct Consts {
    T r1{}, r2{}, inv_J1{}, inv_J2{}, inv_m{}, k1{}, c1{}, k2{}, c2{};
    FrictionParams<T> friction{};
    T inv_cos1{}, inv_cos2{}, stick_speed{};
    T tu{};  // one time unit [s] (RomUnits)
    bool hold1 = false, hold2 = false;
    T inv_tau_h{}, clamp_max{}, inv_ms{}, cs{}, K_ax{};
    T T0{}, cv{}, ca{}, inv_w_eps{};
    T alpha{};
    T a1{}, a2{}, a3{}, two_tan_b0{}, tan1{}, tan2{}, inv_mr{}, cr{}, driven_force{}, travel{}, k_stop{}, q0{};
    T floor_speed{}, slope_floor{};  // docs/rom.md#slope-floor
  };
  struct AccConsts {
    Acc J1{}, J2{}, m{}, k1{}, k2{}, c1{}, c2{}, r2{}, ms{}, cs{}, K_ax{};
    Acc mr{}, cr{}, a1{}, a2{}, a3{}, two_tan_b0{}, driven_force{}, k_stop{};
  };
  RomParams p_;
  Consts c_;
  AccConsts a_;
};

}  // namespace cvt
