#pragma once
// The real-time reduced-order CVT plant (docs/rom.md): the seed's 2-DOF
// stick-slip oscillator (Eq. 8/9) made into a drive train, with the optional
// physics a plant type names in its feature mask (rom_features.hpp).
//
// CvtRom composes the pieces; it has no physics of its own. Each piece is
// one file under plant/feature/ with its states, its terms of the
// right-hand side, its block of the Jacobian, its energy terms and outputs,
// and an "off" version that is what the plant does without it (no states,
// no code):
//   drive_train.hpp    pulleys and link lumps (always)                       docs/rom.md#equations-of-motion
//   axial.hpp          the driver's clamping actuator and sheave              docs/rom.md#axial
//   radial.hpp         the chain's radial DOF: variable ratio, driven clamping docs/rom.md#wedging
//   polygon.hpp        chordal action and the link ripple                     docs/rom.md#polygon
//   tension.hpp        the chain's tension: creep, centrifugal tension, stops docs/rom.md#tension
//   road_load.hpp      speed-dependent load                                   docs/rom.md#road-load
//   deformation.hpp    flank angles (set-up only)                             docs/rom.md#deformation
//   contact_flat.hpp, contact_wedge.hpp   the lumps' friction, without and with the radial DOF (seed Eq. 7)
// A state flows through them in one order, read top to bottom in loads():
// radii -> clamping force -> chain tension -> link ripple -> contact forces,
// then the rows. The Jacobian follows the same order: each piece reports how
// its quantity moves with the states, the contact law turns that into the
// friction forces' partials (docs/rom.md#jacobian).
//
// Templated on the scalar T, the feature bits compiled in (Features) and the
// stateless ones carried but switched at set-up (Runtime, for the host
// dispatch; docs/rom.md#build-time); heap-free; inputs are a member set
// before each step (integrate/system.hpp). Other parts of the plant:
//   rom_layout.hpp     where each state sits, per feature mask
//   rom_units.hpp      internal units (fixed-point scaling and overflow)
//   rom_formulas.hpp   the formulas several parts share, one function each
//   rom_outputs.hpp    what a frame reports;  rom_energy.hpp   the ledger
//   rom_watchdog.hpp   the faults;  rom_step.hpp  the step with the block W solver
//   rom_sim.hpp        the frame stepper (substeps, ledger, watchdog)
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/integrate/system.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/feature/axial.hpp"
#include "cvtplant/plant/feature/contact_flat.hpp"
#include "cvtplant/plant/feature/contact_wedge.hpp"
#include "cvtplant/plant/feature/deformation.hpp"
#include "cvtplant/plant/feature/drive_train.hpp"
#include "cvtplant/plant/feature/polygon.hpp"
#include "cvtplant/plant/feature/radial.hpp"
#include "cvtplant/plant/feature/road_load.hpp"
#include "cvtplant/plant/feature/tension.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

template <class T, std::uint32_t Features = 0, std::uint32_t Runtime = 0>
class CvtRom {
 public:
  using Cfg = RomConfig<T, Features, Runtime>;
  using Layout = typename Cfg::Layout;
  using U = typename Cfg::U;
  using Scalar = T;
  using Acc = typename Cfg::Acc;
  static constexpr std::uint32_t kFeatures = Features;
  static constexpr std::uint32_t kRuntimeFeatures = Runtime;
  static constexpr int kStates = Cfg::N;
  static constexpr std::uint32_t kPositionMask = Layout::kPositionMask;
  using State = typename Cfg::State;
  using Jacobian = typename Cfg::Jacobian;

  using Core = RomDriveTrain<Cfg>;
  using Axial = RomAxial<Cfg>;
  using Radial = RomRadial<Cfg>;
  using Polygon = RomPolygon<Cfg>;
  using Tension = RomTension<Cfg>;
  using RoadLoad = RomRoadLoad<Cfg>;
  using Law = std::conditional_t<Cfg::kRadial, RomWedgeContact<Cfg>, RomFlatContact<Cfg>>;

  RomInputs<T> inputs;

  // What a state's evaluation keeps for the Jacobian, the right-hand side
  // and the ledger's power terms: the friction (or with the radial DOF the
  // contact forces and their partials), the tension state and the ripple's
  // phase, since the exponentials, the atan and the cosines are most of a
  // frame on a Cortex-M (docs/rom.md#cost).
  struct Contact : Tension::Cache, Polygon::Cache, Law::Cache, RoadLoad::Cache {
    T r1e{};  // effective driver radius [m]
  };

  // Every load the rows read at a state, in any scalar S (a dual number for
  // the dual-number Jacobian).
  template <class S>
  struct Loads : RomTensionLoads<S, Cfg::kTension> {
    S r1e{}, r2{}, vc{};  // effective driver radius, driven radius [m], chain speed [m/s]
    S fclamp{};           // the sheave's clamping force: input or bolt force [N]
    S fax{};              // the chain's axial force on the lumps, before the link ripple [N]
    S fl{};               // the lumps' axial force [N]
    S F1{}, F2{}, Fr1{}, Fr2{};  // tangential and radial friction on the lumps [N]
  };

  // `features`: the plant's run-time mask, Features plus those of Runtime the
  // scene asks for.
  explicit CvtRom(const RomParams& p, std::uint32_t features = Features)
      : p_(p),
        features_(Features | (features & Runtime)),
        flanks_(rom_flank_angles(p, rom_feature_on<Cfg>(features_, rom_feature::deformation))),
        core_(p, flanks_),
        axial_(p),
        radial_(p, flanks_.tan_beta),
        polygon_(p),
        tension_(p),
        road_(p, features_),
        law_(core_, flanks_.tan_beta) {}

  const RomParams& params() const { return p_; }
  std::uint32_t features() const { return features_; }
  const Core& core() const { return core_; }
  const Radial& radial() const { return radial_; }
  const Tension& tension() const { return tension_; }
  const Polygon& polygon() const { return polygon_; }
  T polygon_half_angle_rad() const { return polygon_.half_angle(); }

  // The clamping command after the actuator's saturation (axial), else the
  // clamping force itself.
  T saturated_command() const { return axial_.saturated_command(inputs.clamp_N); }

  // Initial state from SI set-up values; the actuator and the bolts at the
  // static equilibrium of the current command (docs/rom.md#axial).
  State initial_state(const RomInitial& x0) const {
    State x = State::Zero();
    core_.initial_state(x0, x);
    axial_.initial_state(saturated_command(), x);
    radial_.initial_state(x0, x);
    polygon_.initial_state(x0, x);
    return x;
  }
  // A state in SI units (rad/s, m, m/s, N, rad), for logs and tests.
  Eigen::Matrix<double, kStates, 1> to_si(const State& x) const {
    Eigen::Matrix<double, kStates, 1> y;
    for (int i = 0; i < kStates; ++i) y(i) = to_double(x(i));
    core_.to_si(y);
    axial_.to_si(y);
    return y;
  }
  template <class S>
  static S per_tau(const S& v) {
    return Cfg::per_tau(v);
  }
  // Keeps the link phase in [-alpha, alpha) between steps (docs/rom.md#polygon).
  void wrap(State& x) const { polygon_.wrap(x); }
  // False once the chain is through a radial end stop by another full travel.
  bool radius_in_range(const State& x) const { return radial_.radius_in_range(x); }

  // --- the quantities of a state, in the order they depend on each other ---
  template <class S>
  S pitch_radius1(const Eigen::Matrix<S, kStates, 1>& x) const {
    return radial_.pitch_radius1(S(core_.r1), x);
  }
  template <class S>
  S pitch_radius2(const Eigen::Matrix<S, kStates, 1>& x) const {
    return radial_.pitch_radius2(S(core_.r2), x);
  }
  template <class S>
  S driver_radius(const Eigen::Matrix<S, kStates, 1>& x) const {
    return polygon_.driver_radius(pitch_radius1(x), x);
  }
  template <class S>
  S ratio_slope(const S& rho) const {
    return radial_.ratio_slope(rho);
  }
  // The sheave's clamping force: the input, or the bolt force (axial).
  template <class S>
  S clamp_force(const Eigen::Matrix<S, kStates, 1>& x) const {
    return axial_.clamp_force(x, radial_, S(inputs.clamp_N));
  }
  template <class S>
  Strands<S> strands(const Eigen::Matrix<S, kStates, 1>& x) const {
    using L = Layout;
    return {strand_force(S(core_.k1), S(core_.c1), radial_.stretch(x(L::kX1), x), radial_.stretch_rate(x(L::kV1), x)),
            strand_force(S(core_.k1), S(core_.c1), radial_.stretch(x(L::kX2), x), radial_.stretch_rate(x(L::kV2), x))};
  }

  // Every load at x, evaluated afresh (any scalar S). Inlined, like rows():
  // a call would pass the loads through memory (docs/rom.md#cost).
  template <class S>
  [[gnu::always_inline]] Loads<S> loads(const Eigen::Matrix<S, kStates, 1>& x) const {
    using L = Layout;
    Loads<S> l;
    l.r1e = driver_radius(x);
    l.r2 = pitch_radius2(x);
    const S v1 = l.r1e * x(L::kW1);
    l.vc = l.r2 * x(L::kW2);
    l.fclamp = clamp_force(x);
    tension_.chain(x, [&] { return strands(x); }, radial_, l);
    l.fl = polygon_.lumps_force(l.fax, polygon_.ripple_cos(x));
    law_.forces(core_, slip_velocity<S>(tension_.entry_speed(l.vc, l), x(L::kV1), v1),
                slip_velocity<S>(l.vc, x(L::kV2), v1), radial_.radial_speed(x), l.fl, l.F1, l.F2, l.Fr1, l.Fr2);
    return l;
  }

  // The lumps' friction forces at slip speeds v1, v2, radial speed rho' and
  // lumps' axial force fl, by the plant's contact law (tests, analysis).
  template <class S>
  struct LumpForces {
    S F1{}, F2{}, Fr1{}, Fr2{};
  };
  template <class S>
  LumpForces<S> lump_forces(const S& v1, const S& v2, const S& rho_dot, const S& fl) const {
    LumpForces<S> f;
    law_.forces(core_, v1, v2, rho_dot, fl, f.F1, f.F2, f.Fr1, f.Fr2);
    return f;
  }

  // The contact of a state (Contact above), evaluated once and shared.
  Contact contact(const State& x) const {
    using L = Layout;
    Contact c;
    polygon_.cache(x, c);
    road_.cache(x(L::kW2), c);
    Loads<T> l;
    c.r1e = driver_radius(x);
    l.r2 = pitch_radius2(x);
    const T v1 = c.r1e * x(L::kW1);
    l.vc = l.r2 * x(L::kW2);
    l.fclamp = clamp_force(x);
    tension_.chain(x, [&] { return strands(x); }, radial_, l);
    tension_.cache(l, c);
    const T fl = polygon_.lumps_force(l.fax, Polygon::cached_cos(c));
    law_.evaluate(core_, slip_velocity<T>(tension_.entry_speed(l.vc, l), x(L::kV1), v1), slip_velocity<T>(l.vc, x(L::kV2), v1),
                  radial_.radial_speed(x), fl, c);
    return c;
  }

  // The loads at x from its contact c (bit for bit those of loads(x)).
  Loads<T> loads(const State& x, const Contact& c) const {
    using L = Layout;
    Loads<T> l;
    l.r1e = c.r1e;
    l.r2 = pitch_radius2(x);
    l.vc = l.r2 * x(L::kW2);
    l.fclamp = clamp_force(x);
    if constexpr (Cfg::kTension) {
      l.tension = c.tension;
      l.fax = c.tension.F_ax;
    } else {
      l.fax = l.fclamp;
    }
    l.fl = polygon_.lumps_force(l.fax, Polygon::cached_cos(c));
    Law::forces(core_, c, l.fl, l.F1, l.F2, l.Fr1, l.Fr2);
    return l;
  }

  // The link phase's rate psi' [rad/s] at x (c = contact(x)); the watchdog's
  // 8 steps per link apply to it (docs/rom.md#polygon, #link-ripple).
  T phase_rate(const State& x, const Contact& c) const {
    return polygon_.phase_rate(x, pitch_radius2(x) * x(Layout::kW2), c, tension_);
  }

  // --- the right-hand side ---
  template <class S>
  void derivative(const Eigen::Matrix<S, kStates, 1>& x, Eigen::Matrix<S, kStates, 1>& dxdt) const {
    rows(x, loads(x), road_.load_torque(S(inputs.tau_load_Nm), x(Layout::kW2)), dxdt);
  }
  // The same from the contact already evaluated at x (c = contact(x)); bit
  // for bit derivative(x, dxdt).
  void derivative(const State& x, const Contact& c, State& dxdt) const {
    rows(x, loads(x, c), road_.load_torque(inputs.tau_load_Nm, x(Layout::kW2), c), dxdt);
  }

  // --- the Jacobian (docs/rom.md#jacobian) ---
  // Held pulleys get zero rows (and at a fixed ratio zero columns: their
  // speed never changes, so the columns multiply a zero increment, and
  // leaving them out keeps the LU pivots those of seed Eq. 9).
  void jacobian(const State& x, Jacobian& J) const { jacobian(x, contact(x), J, false); }
  // With `w_slope_floor` it is the matrix W of the real-time step instead
  // (docs/rom.md#slope-floor): inside the sign's regularisation layer the
  // friction slope is raised to at least its value at the layer's edge.
  // ROS2 is a W-method (order 2 for any W), so this changes the step's error
  // constant near stick, not its order.
  void jacobian(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    J.setZero();
    jacobian_entries(x, c, J, w_slope_floor);
  }
  // jacobian(x, c, J, w_slope_floor) without zeroing J first: writes every
  // entry RomWSolver::factor reads (docs/rom.md#structured-solve) and leaves
  // the others as they were, so the step passes a J it never zeroes (zeroing
  // the 81 entries of the axial plant's J each step was 170 instructions of
  // a frame on the M4F, docs/rom.md#cost).
  void jacobian_entries(const State& x, const Contact& c, Jacobian& J, bool w_slope_floor) const {
    using L = Layout;
    constexpr int N = kStates;
    const T w1 = x(L::kW1);
    const T r2 = pitch_radius2(x);
    const T vc = r2 * x(L::kW2);
    const T fax = unrippled_axial_force(x, c);
    const T fl = polygon_.lumps_force(fax, Polygon::cached_cos(c));
    // The friction forces' partials, from what moves each quantity: the
    // slip speeds v_c + xd_i - r1e w1, the radii, the ripple, the clamping
    // force and the chain's tension.
    typename Law::Jac jac(core_, c, fl, polygon_.ripple_factor(c), polygon_.rippled(), w1, w_slope_floor);
    jac.slip_both(L::kW1, -c.r1e);
    jac.slip_both(L::kW2, r2);
    jac.slip_unit(0, L::kV1);
    jac.slip_unit(1, L::kV2);
    radial_.partials(x, polygon_.radius_factor(x), jac);
    polygon_.partials(x, c, pitch_radius1(x), fax, jac);
    const RomClampPartials<Cfg> dfc = axial_.clamp_partials(x, radial_);
    tension_.partials(x, c, dfc, vc, r2, radial_, core_, jac);
    jac.finish();

    // The rows.
    jac.driver_row(c.r1e, J);
    const Strands<T> st = strands(x);
    T rw2[N];  // the driven row
    core_.driven_partials(r2, road_.load_torque_slope(x(L::kW2), c), rw2);
    radial_.driven_partials(x, r2, st, core_, rw2);
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) J(L::kW2, j) = rw2[j];
    T dca[N];  // the chain frame's acceleration d(v_c)/dt
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dca[j] = r2 * rw2[j];
    if constexpr (Cfg::kRadial) {
      const T w2dot = core_.driven_row(r2, st.s1, st.s2, road_.load_torque(inputs.tau_load_Nm, x(L::kW2), c));
      radial_.chain_acceleration_partials(x, w2dot, dca);
    }
    core_.lump_rows(jac.dF, dca, J);
    radial_.lump_row_partials(core_, J);
    axial_.jacobian_rows(x, dfc, J);
    radial_.jacobian_rows(x, dfc, jac, core_, J);
    polygon_.jacobian_row(x, c, vc, r2, dfc, radial_, core_, tension_, J);
    if constexpr (Law::kWedge) {
      if (w_slope_floor) law_.add_w_slope_floor(core_, c, c.r1e, r2, fl, J);
    }
  }

  // The chain's axial force at x before the link ripple (c = contact(x)):
  // the clamping force, or with the tension feature the chain's.
  T unrippled_axial_force(const State& x, const Contact& c) const {
    if constexpr (Cfg::kTension) {
      (void)x;
      return c.tension.F_ax;
    } else {
      (void)c;
      return clamp_force(x);
    }
  }
  // The lumps' axial force at x, with the link ripple (docs/rom.md#link-ripple).
  T axial_force(const State& x, const Contact& c) const {
    return polygon_.lumps_force(unrippled_axial_force(x, c), Polygon::cached_cos(c));
  }

  // --- what a frame reports and the energy terms ---
  RomOutputs<T> outputs(const State& x) const {
    using L = Layout;
    const Loads<T> l = loads(x);
    RomOutputs<T> o;
    const T w1 = x(L::kW1), w2 = x(L::kW2);
    const T v1 = l.r1e * w1;
    o.omega1_rad_s = w1;
    o.omega2_rad_s = w2;
    o.radius1_m = pitch_radius1(x);
    o.radius2_m = l.r2;
    o.geometric_ratio = l.r2 / o.radius1_m;
    const T w_tiny = T(1e-3);
    o.speed_ratio = abs(w2) < w_tiny ? T(0) : w1 / w2;
    o.slip = abs(v1) < w_tiny ? T(0) : (v1 - l.vc) / v1;
    o.clamp_force_N = l.fl;
    o.v_rel1_m_s = slip_velocity<T>(tension_.entry_speed(l.vc, l), x(L::kV1), v1);
    o.v_rel2_m_s = slip_velocity<T>(l.vc, x(L::kV2), v1);
    o.friction1_N = l.F1;
    o.friction2_N = l.F2;
    o.radial_friction1_N = l.Fr1;
    o.radial_friction2_N = l.Fr2;
    o.torque_transmitted_Nm = friction_torque(l.r1e, l.F1, l.F2);
    o.tau_in_Nm = core_.hold1 ? o.torque_transmitted_Nm : inputs.tau_in_Nm;
    o.tau_load_Nm = applied_load(x, l.r2);
    o.stick1 = abs(o.v_rel1_m_s) < core_.stick_speed;
    o.stick2 = abs(o.v_rel2_m_s) < core_.stick_speed;
    radial_.outputs(x, o);
    tension_.outputs(l, o);
    return o;
  }

  // Stored energy at x [J], in the accounting type (docs/rom.md#energy-balance).
  Acc stored_energy(const State& xs) const {
    using L = Layout;
    Acc x[kStates];
    for (int i = 0; i < kStates; ++i) x[i] = rom_to_acc(xs(i));
    if constexpr (U::kScaled) {
      // Displacements back to metres: energies of 1e5 J are only kept in float.
      x[L::kX1] *= Acc(U::length_m);
      x[L::kX2] *= Acc(U::length_m);
      axial_.to_si_acc(x);
    }
    Acc r2 = core_.acc.r2;
    const Acc dr2 = radial_.driven_radius_change_acc(x);
    if constexpr (Cfg::kRadial) r2 += dr2;
    const Acc e1 = radial_.stretch_acc(x[L::kX1], radial_rho_acc(x));
    const Acc e2 = radial_.stretch_acc(x[L::kX2], radial_rho_acc(x));
    Acc e = core_.stored_energy(x, r2, e1, e2);
    axial_.add_stored_energy(x, radial_, e);
    radial_.add_stored_energy(x, dr2, xs, e);
    return e;
  }
  // The power terms at x with its contact c [W]: bit for bit what outputs()
  // computes (the fused friction values being the separate ones).
  RomPower<Acc> power(const State& xs, const Contact& c) const {
    using L = Layout;
    Acc x[kStates];
    for (int i = 0; i < kStates; ++i) x[i] = rom_to_acc(xs(i));
    const Loads<T> l = loads(xs, c);
    const T tau_in = core_.hold1 ? friction_torque(c.r1e, l.F1, l.F2) : inputs.tau_in_Nm;
    const Acc sv1 = radial_.stretch_acc(x[L::kV1], radial_rho_dot_acc(x));
    const Acc sv2 = radial_.stretch_acc(x[L::kV2], radial_rho_dot_acc(x));
    RomPower<Acc> pw =
        core_.power(x, tau_in, applied_load(xs, l.r2, c), l.F1, l.F2, Law::slip1(c), Law::slip2(c), sv1, sv2);
    axial_.power(x, pw);
    radial_.power(xs, l.Fr1, l.Fr2, core_.inv_cos1, core_.inv_cos2, pw);
    tension_.power(c, l.F1, pw);
    return pw;
  }
  RomPower<Acc> power(const State& x) const { return power(x, contact(x)); }

  // The driven (secondary) clamping F_ax2 [N] from now on, with the radial
  // DOF (the simulator's driven actuator sets it once per frame,
  // docs/rom.md#driven-clamping).
  void set_driven_clamp_N(double f_N) { radial_.set_driven_clamp_N(f_N); }

 private:
  // The right-hand side from the loads at x and the load torque; inlined
  // into each right-hand side (a call passed the loads through memory).
  template <class S>
  [[gnu::always_inline]] void rows(const Eigen::Matrix<S, kStates, 1>& x, const Loads<S>& l, const S& load,
            Eigen::Matrix<S, kStates, 1>& dxdt) const {
    const Strands<S> st = strands(x);
    const S w1dot = core_.driver_row(S(inputs.tau_in_Nm), l.r1e, l.F1, l.F2);
    const S w2dot = core_.driven_row(l.r2, st.s1, st.s2, load);
    const S chain_acc = radial_.chain_acceleration(l.r2 * w2dot, x);
    core_.rows(x, w1dot, w2dot, chain_acc, l.F1, l.F2, st.s1, st.s2, dxdt);
    axial_.rows(x, saturated_command(), l.fclamp, dxdt);
    radial_.rows(x, l.fclamp, l.Fr1, l.Fr2, S(core_.inv_cos1), S(core_.inv_cos2), st.s1 + st.s2, dxdt);
    polygon_.rows(x, l, tension_, dxdt);
  }

  // The load torque as applied: the holding torque of a held driven pulley.
  T applied_load(const State& x, const T& r2) const {
    if (core_.hold2) return holding_torque(x, r2);
    return road_.load_torque(inputs.tau_load_Nm, x(Layout::kW2));
  }
  // The same at x from its contact c.
  T applied_load(const State& x, const T& r2, const Contact& c) const {
    if (core_.hold2) return holding_torque(x, r2);
    return road_.load_torque(inputs.tau_load_Nm, x(Layout::kW2), c);
  }
  T holding_torque(const State& x, const T& r2) const {
    const Strands<T> st = strands(x);
    return strand_torque(r2, st.s1, st.s2);
  }
  Acc radial_rho_acc(const Acc* x) const {
    if constexpr (Cfg::kRadial) return x[Layout::kRho];
    (void)x;
    return Acc(0);
  }
  Acc radial_rho_dot_acc(const Acc* x) const {
    if constexpr (Cfg::kRadial) return x[Layout::kRhoDot];
    (void)x;
    return Acc(0);
  }

  RomParams p_;
  std::uint32_t features_;
  RomFlankAngles flanks_;
  Core core_;
  Axial axial_;
  Radial radial_;
  Polygon polygon_;
  Tension tension_;
  RoadLoad road_;
  Law law_;
};

}  // namespace cvt
