#pragma once
// Feature `wedging` (docs/rom.md#wedging, #wrap-tension, #driven-clamping,
// #end-stop): the chain's radial degree of freedom on the driver and with it
// a variable ratio. States rho = r1 - r1_m and rho':
//   r1 = r1_m + rho,  r2 = r2_m + a1 rho + a2 rho^2 + a3 rho^3  (chain length held)
//   kappa(rho) = -dr2/dr1 = theta1 / theta2
//   b = delta - 2 tan(beta0) rho                      the bolts' compression
//   e_i = x_i + g rho, g = eta theta1                 the strands' stretch
//   m_r rho'' = 2 tan(beta0) F_b + sum F_r,i / cos(beta_i) - kappa 2 tan(beta0) F_ax2
//               - c_r rho' - F_stop(rho) - g (F_s1 + F_s2)
//   d(v_c)/dt = r2 w2' - kappa rho' w2
// The contact on the flanks becomes seed Eq. 7's (feature/contact_wedge.hpp),
// the driven clamping F_ax2 an input with its actuator lag
// (feature/driven_clamp.hpp). Floating point only: the radial stiffness and
// friction slopes have no fixed-point scaling.
#include <cstdint>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// The strands' forces k1 e_i + c1 e_i' (seed Eq. 8).
template <class S>
struct Strands {
  S s1, s2;
};

// Without the radial DOF the radii are the set-up ones, the bolts' compression
// is delta and the strands' stretch the lumps' displacement.
template <class Cfg, bool kOn = Cfg::kRadial>
class RomRadial {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  RomRadial(const RomParams&, const double*) {}
  template <class X>
  void initial_state(const RomInitial&, X&) const {}
  template <class S>
  S pitch_radius1(const S& r1, const Vec<S>&) const {
    return r1;
  }
  template <class S>
  S pitch_radius2(const S& r2, const Vec<S>&) const {
    return r2;
  }
  template <class S>
  S bolt_compression(const S& delta, const Vec<S>&) const {
    return delta;
  }
  template <class A>
  A bolt_compression_acc(const A& delta, const A*) const {
    return delta;
  }
  template <class S>
  S stretch(const S& x_i, const Vec<S>&) const {
    return x_i;
  }
  template <class S>
  S stretch_rate(const S& xd_i, const Vec<S>&) const {
    return xd_i;
  }
  template <class S>
  S chain_acceleration(const S& r2_w2dot, const Vec<S>&) const {
    return r2_w2dot;
  }
  template <class S>
  S radial_speed(const Vec<S>&) const {
    return S(T(0));
  }
  template <class S>
  void rows(const Vec<S>&, const S&, const S&, const S&, const S&, const S&, const S&, Vec<S>&) const {}
  template <class Jac>
  void partials(const typename Cfg::State&, const T&, Jac&) const {}
  template <class Core>
  void driven_partials(const typename Cfg::State&, const T&, const Strands<T>&, const Core&, T*) const {}
  void chain_acceleration_partials(const typename Cfg::State&, const T&, T*) const {}
  template <class Core>
  void lump_row_partials(const Core&, typename Cfg::Jacobian&) const {}
  template <class Jac, class Clamp, class Core>
  void jacobian_rows(const typename Cfg::State&, const Clamp&, const Jac&, const Core&, typename Cfg::Jacobian&) const {}
  template <class A>
  A driven_radius_change_acc(const A*) const {
    return A(0);
  }
  template <class A>
  A stretch_acc(const A& v, const A&) const {
    return v;
  }
  template <class A>
  void add_stored_energy(const A*, const A&, const typename Cfg::State&, A&) const {}
  template <class A>
  void power(const typename Cfg::State&, const T&, const T&, const T&, const T&, RomPower<A>&) const {}
  bool radius_in_range(const typename Cfg::State&) const { return true; }
  void set_driven_clamp_N(double) {}
  void outputs(const typename Cfg::State&, RomOutputs<T>&) const {}
};

template <class Cfg>
class RomRadial<Cfg, true> {
  CVT_ROM_FEATURE_TYPES(Cfg);
  static_assert(!Cfg::U::kScaled, "the wedging feature runs in floating point only");

 public:
  // tan_beta: tan of the lumps' flank angles (feature/deformation.hpp).
  RomRadial(const RomParams& p, const double* tan_beta) {
    // r2(rho) from chain length conservation: the cubic through the exact
    // solutions at rho = 0, +-e, +-2e (e = travel / 2).
    const double e = 0.5 * p.radial_travel_m;
    auto r2_at = [&p](double rho) { return seed::driven_pitch_radius_m(p.r1_m, p.r2_m, p.center_distance_m, rho); };
    const double fp1 = r2_at(e), fm1 = r2_at(-e);
    const double fp2 = r2_at(2 * e), fm2 = r2_at(-2 * e);
    const double f0 = p.r2_m;
    const double a1_m = (8.0 * (fp1 - fm1) - (fp2 - fm2)) / (12.0 * e);
    const double a2_1_m = (16.0 * (fp1 + fm1) - (fp2 + fm2) - 30.0 * f0) / (24.0 * e * e);
    const double a3_1_m2 = ((fp2 - fm2) - 2.0 * (fp1 - fm1)) / (12.0 * e * e * e);
    const double tb = dm::sin(p.beta0_rad) / dm::cos(p.beta0_rad);
    a1_ = T(a1_m);
    a2_ = T(a2_1_m);
    a3_ = T(a3_1_m2);
    two_tan_b0_ = T(2.0 * tb);
    tan1_ = T(tan_beta[0]);
    tan2_ = T(tan_beta[1]);
    inv_mr_ = T(1.0 / p.radial_mass_kg);
    cr_ = T(p.radial_damping_Ns_m);
    two_tan_b0_si_ = 2.0 * tb;
    driven_force_ = T(2.0 * tb * p.driven_clamp_N);
    driven_clamp_si_N_ = p.driven_clamp_N;
    travel_ = T(p.radial_travel_m);
    k_stop_ = T(p.radial_stop_N_m);
    // docs/rom.md#wrap-tension: g = eta theta1 at the set-up radii.
    const double g = p.wrap_tension_share * seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, p.center_distance_m);
    wrap_g_ = T(g);
    acc_.mr = Acc(p.radial_mass_kg);
    acc_.cr = Acc(p.radial_damping_Ns_m);
    acc_.a1 = Acc(a1_m);
    acc_.a2 = Acc(a2_1_m);
    acc_.a3 = Acc(a3_1_m2);
    acc_.two_tan_b0 = Acc(2.0 * tb);
    acc_.driven_force = Acc(2.0 * tb * p.driven_clamp_N);
    acc_.k_stop = Acc(p.radial_stop_N_m);
    acc_.wrap_g = Acc(g);
  }

  // The chain starts at rho = radius_offset, at rest, with the bolts at the
  // compression the actuator's command gives (delta moves with rho).
  template <class X>
  void initial_state(const RomInitial& x0, X& x) const {
    x(L::kRho) = T(x0.radius_offset_m);
    x(L::kDelta) += two_tan_b0_ * x(L::kRho);
    x(L::kRhoDot) = T(0);
  }

  // --- geometry ---
  template <class S>
  S pitch_radius1(const S& r1, const Vec<S>& x) const {
    return r1 + x(L::kRho);
  }
  template <class S>
  S pitch_radius2(const S& r2, const Vec<S>& x) const {
    return r2 + driven_radius_change(x(L::kRho));
  }
  // r2(rho) - r2, the cubic above.
  template <class S>
  S driven_radius_change(const S& rho) const {
    return cvt::driven_radius_change(rho, S(a1_), S(a2_), S(a3_));
  }
  // kappa(rho) = -dr2/drho (theta1 / theta2 to 1e-5) and d kappa / d rho.
  template <class S>
  S ratio_slope(const S& rho) const {
    return -(S(a1_) + rho * (S(a2_ + a2_) + rho * S(T(3) * a3_)));
  }
  T ratio_slope_derivative(const T& rho) const { return -(T(a2_ + a2_) + rho * (T(6) * a3_)); }
  template <class S>
  S bolt_compression(const S& delta, const Vec<S>& x) const {
    return delta - S(two_tan_b0_) * x(L::kRho);
  }
  template <class S>
  S radial_speed(const Vec<S>& x) const {
    return x(L::kRhoDot);
  }
  template <class A>
  A bolt_compression_acc(const A& delta, const A* x) const {
    A b = delta;
    b -= acc_.two_tan_b0 * x[L::kRho];
    return b;
  }
  T two_tan_beta0() const { return two_tan_b0_; }
  T tan_beta(int lump) const { return lump == 0 ? tan1_ : tan2_; }
  // Penetration of the ratio end stops [m]: > 0 past +travel, < 0 past -travel.
  template <class S>
  S stop_penetration(const S& rho) const {
    const S tr(travel_);
    if (rho > tr) return rho - tr;
    if (rho < -tr) return rho + tr;
    return S(T(0));
  }
  // False once the chain is through an end stop by another full travel: the
  // stop stiffness cannot hold what drives it (the fault radius-out-of-range).
  bool radius_in_range(const State& x) const {
    const T lim = travel_ + travel_;
    return x(L::kRho) <= lim && x(L::kRho) >= -lim;
  }
  T travel() const { return travel_; }

  // --- the strands (docs/rom.md#wrap-tension) ---
  template <class S>
  S stretch(const S& x_i, const Vec<S>& x) const {
    return strand_stretch(x_i, S(wrap_g_), x(L::kRho));
  }
  template <class S>
  S stretch_rate(const S& xd_i, const Vec<S>& x) const {
    return strand_stretch(xd_i, S(wrap_g_), x(L::kRhoDot));
  }
  T wrap_g() const { return wrap_g_; }

  // d(r2 w2)/dt = r2 w2' + r2' w2, r2' = -kappa rho'.
  template <class S>
  S chain_acceleration(const S& r2_w2dot, const Vec<S>& x) const {
    return r2_w2dot - ratio_slope(x(L::kRho)) * x(L::kRhoDot) * x(L::kW2);
  }

  // rho' and rho'' from the bolt force, the lumps' radial friction and the
  // strands' force sum (docs/rom.md#wedging, #wrap-tension).
  template <class S>
  void rows(const Vec<S>& x, const S& f_b, const S& Fr1, const S& Fr2, const S& inv_cos1, const S& inv_cos2,
            const S& strands_sum, Vec<S>& dxdt) const {
    const S rhod = x(L::kRhoDot);
    dxdt(L::kRho) = rhod;
    dxdt(L::kRhoDot) = (S(two_tan_b0_) * f_b + Fr1 * inv_cos1 + Fr2 * inv_cos2 -
                        ratio_slope(x(L::kRho)) * S(driven_force_) - S(cr_) * rhod -
                        S(k_stop_) * stop_penetration(x(L::kRho)) - wrap_tension_pull(S(wrap_g_), strands_sum)) *
                       S(inv_mr_);
  }

  // Partials of the slip speeds through the radii: d r1e / d rho = cos(psi)
  // (r1e_factor), d v_c / d rho = -kappa w2 (docs/rom.md#wedging-jacobian).
  template <class Jac>
  void partials(const State& x, const T& r1e_factor, Jac& jac) const {
    jac.driver_radius(L::kRho, r1e_factor);
    jac.slip_both(L::kRho, -ratio_slope(x(L::kRho)) * x(L::kW2));
  }

  // The driven row's and the chain frame's partials in rho and rho' (the
  // driven radius and the strands' stretch), given the driven row dw2 and w2'.
  template <class Core>
  void driven_partials(const State& x, const T& r2, const Strands<T>& st, const Core& k, T* dw2) const {
    if (k.hold2) return;
    const T kap = ratio_slope(x(L::kRho));
    const T g = wrap_g_;
    const T k1 = k.k1, c1 = k.c1, inv_J2 = k.inv_J2;
    dw2[L::kRho] = (-kap * (st.s1 + st.s2) + r2 * T(2) * g * k1) * inv_J2;
    dw2[L::kRhoDot] = r2 * T(2) * g * c1 * inv_J2;
  }
  void chain_acceleration_partials(const State& x, const T& w2dot, T* dca) const {
    const T rho = x(L::kRho), rhod = x(L::kRhoDot), w2 = x(L::kW2);
    const T kap = ratio_slope(rho);
    const T dkap = ratio_slope_derivative(rho);
    dca[L::kRho] += -kap * w2dot - dkap * rhod * w2;
    dca[L::kRhoDot] += -kap * w2;
    dca[L::kW2] += -kap * rhod;
  }
  // The lumps' rows' strand-stretch entries.
  template <class Core>
  void lump_row_partials(const Core& k, typename Cfg::Jacobian& J) const {
    const T g = wrap_g_, k1 = k.k1, c1 = k.c1, inv_m = k.inv_m;
    J(L::kV1, L::kRho) += -g * k1 * inv_m;
    J(L::kV2, L::kRho) += -g * k1 * inv_m;
    J(L::kV1, L::kRhoDot) += -g * c1 * inv_m;
    J(L::kV2, L::kRhoDot) += -g * c1 * inv_m;
  }
  // The rows of rho and rho': dfc the bolt force's partials, jac.dR the
  // lumps' radial friction's (feature/contact_wedge.hpp).
  template <class Jac, class Clamp, class Core>
  void jacobian_rows(const State& x, const Clamp& dfc, const Jac& jac, const Core& k, typename Cfg::Jacobian& J) const {
    constexpr int N = Cfg::N;
    const T rho = x(L::kRho);
    T dfb[N];
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) dfb[j] = T(0);
    dfc.each([&](int col, const T& d) { dfb[col] = d; });
    const T(&dR)[2][N] = jac.dR;
    const T inv_cos1 = k.inv_cos1, inv_cos2 = k.inv_cos2, k1 = k.k1, c1 = k.c1;
    J(L::kRho, L::kRhoDot) = T(1);
    const T two_tan_b0 = two_tan_b0_, inv_mr = inv_mr_;
    #pragma GCC unroll 16
    for (int j = 0; j < N; ++j) J(L::kRhoDot, j) = (two_tan_b0 * dfb[j] + dR[0][j] * inv_cos1 + dR[1][j] * inv_cos2) * inv_mr;
    const T stop_slope = stop_penetration(rho) != T(0) ? k_stop_ : T(0);
    J(L::kRhoDot, L::kRho) += (-ratio_slope_derivative(rho) * driven_force_ - stop_slope) * inv_mr;
    J(L::kRhoDot, L::kRhoDot) += -cr_ * inv_mr;
    // - g (F_s1 + F_s2), the wrap-tension pull.
    const T g = wrap_g_;
    J(L::kRhoDot, L::kX1) += -g * k1 * inv_mr;
    J(L::kRhoDot, L::kX2) += -g * k1 * inv_mr;
    J(L::kRhoDot, L::kV1) += -g * c1 * inv_mr;
    J(L::kRhoDot, L::kV2) += -g * c1 * inv_mr;
    J(L::kRhoDot, L::kRho) += -T(2) * g * g * k1 * inv_mr;
    J(L::kRhoDot, L::kRhoDot) += -T(2) * g * g * c1 * inv_mr;
  }

  // Radial kinetic energy, the driven clamping's potential through the chain
  // length, -2 tan(beta0) F_ax2 (r2 - r2_m), and the end stop's spring [J];
  // dr2 = r2 - r2_m, x in SI, accounting type.
  template <class A>
  void add_stored_energy(const A* x, const A& dr2, const State& xs, A& e) const {
    const A pen = rom_to_acc(stop_penetration(xs(L::kRho)));
    e += A(0.5) * acc_.mr * x[L::kRhoDot] * x[L::kRhoDot] - acc_.driven_force * dr2 + A(0.5) * acc_.k_stop * pen * pen;
  }
  // The lumps' radial friction loss sum F_r,i g_r,i (g_r,i = rho' / cos(beta_i))
  // and the radial damping c_r rho'^2 [W].
  template <class A>
  void power(const State& xs, const T& Fr1, const T& Fr2, const T& inv_cos1, const T& inv_cos2,
             RomPower<A>& pw) const {
    const A rd = rom_to_acc(xs(L::kRhoDot));
    pw.friction_loss_W -= rom_to_acc(Fr1) * rd * rom_to_acc(inv_cos1) + rom_to_acc(Fr2) * rd * rom_to_acc(inv_cos2);
    pw.damping_loss_W += acc_.cr * rd * rd;
  }
  template <class A>
  A driven_radius_change_acc(const A* x) const {
    return cvt::driven_radius_change(x[L::kRho], acc_.a1, acc_.a2, acc_.a3);
  }
  template <class A>
  A stretch_acc(const A& v, const A& rho) const {
    return strand_stretch(v, acc_.wrap_g, rho);
  }

  // The driven (secondary) clamping F_ax2 [N] from now on; the same products
  // as the set-up, so the set-up value gives the same bits
  // (docs/rom.md#driven-clamping).
  void set_driven_clamp_N(double f_N) {
    driven_clamp_si_N_ = f_N;
    driven_force_ = T(two_tan_b0_si_ * f_N);
    acc_.driven_force = Acc(two_tan_b0_si_ * f_N);
  }

  // What a frame reports of the radial DOF (docs/rom.md#driven-clamping,
  // #end-stop): the driven clamping force F_ax2, and the chain pressed into
  // a ratio end stop, underdrive (rho < -travel) or overdrive (rho > travel).
  void outputs(const State& x, RomOutputs<T>& o) const {
    o.driven_clamp_force_N = T(driven_clamp_si_N_);
    const T pen = stop_penetration(x(L::kRho));
    o.stop_overdrive = pen > T(0);
    o.stop_underdrive = pen < T(0);
  }

 private:
  T a1_{}, a2_{}, a3_{}, two_tan_b0_{}, tan1_{}, tan2_{}, inv_mr_{}, cr_{}, driven_force_{}, travel_{}, k_stop_{};
  T wrap_g_{};
  double two_tan_b0_si_ = 0.0;
  double driven_clamp_si_N_ = 0.0;  // F_ax2 in N, as reported (RomOutputs)
  struct {
    Acc mr{}, cr{}, a1{}, a2{}, a3{}, two_tan_b0{}, driven_force{}, k_stop{}, wrap_g{};
  } acc_;
};

}  // namespace cvt
