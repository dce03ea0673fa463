#pragma once
// Feature `axial` (docs/rom.md#axial): the driver sheave's clamping as
// dynamics. States F_h (actuator force), delta, delta' (bolt compression of
// the lumped wrap):
//   tau_h F_h' = sat(F_cmd, 0, F_max) - F_h
//   m_s delta'' = F_h - F_b - c_s delta'
//   F_b = K_ax max(0, b),  b = delta (- 2 tan(beta0) rho with the radial DOF)   seed Eq. 5, lumped
// The clamping input is then the command F_cmd; without the feature it is
// the clamping force itself. Energy: the actuator's work F_h delta' is an
// input, c_s delta'^2 a loss, 1/2 m_s delta'^2 + 1/2 K_ax max(0, b)^2 stored.
#include <cstdint>

#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

// The clamping force's partial derivatives d F_clamp / d x_col: in delta,
// and in rho with the radial DOF; none while the bolt is slack or without
// the feature (the force is then an input). The columns are compile-time
// constants, so the pieces that read them (each()) index J and the contact
// law's arrays with constants: the compiler keeps those in registers.
template <class Cfg>
struct RomClampPartials {
  using T = typename Cfg::Scalar;
  bool on = false;  // the bolt compressed
  T delta{}, rho{};
  // f(col, d F_clamp / d x_col) for each partial, delta first.
  template <class Fn>
  void each(Fn&& f) const {
    if constexpr (Cfg::kAxial) {
      if (!on) return;
      f(Cfg::Layout::kDelta, delta);
      if constexpr (Cfg::kRadial) f(Cfg::Layout::kRho, rho);
    } else {
      (void)f;
    }
  }
};

template <class Cfg, bool kOn = Cfg::kAxial>
class RomAxial {
  using T = typename Cfg::Scalar;

 public:
  explicit RomAxial(const RomParams&) {}
  // Without the feature the clamping input is the clamping force.
  T saturated_command(const T& clamp_N) const { return clamp_N; }
  template <class X>
  void initial_state(const T&, X&) const {}
  template <class Y>
  void to_si(Y&) const {}
  template <class Y>
  void to_si_acc(Y*) const {}
  template <class S, class Radial>
  S clamp_force(const typename Cfg::template Vec<S>&, const Radial&, const S& clamp_input) const {
    return clamp_input;
  }
  template <class Radial>
  RomClampPartials<Cfg> clamp_partials(const typename Cfg::State&, const Radial&) const {
    return {};
  }
  template <class S>
  void rows(const typename Cfg::template Vec<S>&, const T&, const S&, typename Cfg::template Vec<S>&) const {}
  void jacobian_rows(const typename Cfg::State&, const RomClampPartials<Cfg>&, typename Cfg::Jacobian&) const {}
  template <class A, class Radial>
  void add_stored_energy(const A*, const Radial&, A&) const {}
  template <class A, class Power>
  void power(const A*, Power&) const {}
};

template <class Cfg>
class RomAxial<Cfg, true> {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  explicit RomAxial(const RomParams& p)
      // Per time unit in the constant (0.049 in fixed point, 3200 LSB): one
      // rounding of (F_cmd - F_h) x constant, not a rounded rate times 50.
      : inv_tau_h_(T(U::time_s / p.actuator_tau_s)),
        clamp_max_(T(p.clamp_max_N)),
        inv_ms_(T(1.0 / p.sheave_mass_kg)),
        cs_(T(p.sheave_damping_Ns_m)),
        K_ax_(T(p.K_ax_N_m * U::length_m)),
        K_ax_si_(p.K_ax_N_m),
        acc_ms_(Acc(p.sheave_mass_kg)),
        acc_cs_(Acc(p.sheave_damping_Ns_m)),
        acc_K_ax_(Acc(p.K_ax_N_m)) {}

  // The clamping command after the actuator's saturation to [0, F_max].
  T saturated_command(const T& f) const { return f < T(0) ? T(0) : (f > clamp_max_ ? clamp_max_ : f); }

  // Actuator and bolt at the static equilibrium of the command fh: F_h = fh,
  // delta = fh / K_ax (the radial DOF adds its own offset).
  template <class X>
  void initial_state(const T& fh, X& x) const {
    x(L::kFh) = fh;
    x(L::kDelta) = T(to_double(fh) / K_ax_si_ / U::length_m);
    x(L::kDeltaDot) = T(0);
  }
  template <class Y>
  void to_si(Y& y) const {
    y(L::kDelta) *= U::length_m;
  }

  // The bolt force F_b = K_ax max(0, b) (seed Eq. 5, lumped), b the bolt
  // compression: delta, less 2 tan(beta0) rho with the radial DOF
  // (docs/rom.md#wedging).
  template <class S, class Radial>
  S clamp_force(const Vec<S>& x, const Radial& radial, const S&) const {
    const S d = radial.bolt_compression(x(L::kDelta), x);
    return d > S(T(0)) ? S(K_ax_) * d : S(T(0));
  }
  template <class Radial>
  RomClampPartials<Cfg> clamp_partials(const State& x, const Radial& radial) const {
    RomClampPartials<Cfg> g;
    if (radial.bolt_compression(x(L::kDelta), x) > T(0)) {
      g.on = true;
      g.delta = K_ax_;
      if constexpr (Cfg::kRadial) g.rho = -K_ax_ * radial.two_tan_beta0();
    }
    return g;
  }

  // F_h', delta', delta'' with the sheave's bolt force f_b and the saturated
  // command.
  template <class S>
  void rows(const Vec<S>& x, const T& command, const S& f_b, Vec<S>& dxdt) const {
    const S fh = x(L::kFh), dd = x(L::kDeltaDot);
    // inv_tau_h is per time unit already (a kN step times 50 1/s leaves q16.16).
    dxdt(L::kFh) = (S(command) - fh) * S(inv_tau_h_);
    dxdt(L::kDelta) = dd;
    dxdt(L::kDeltaDot) = Cfg::per_tau((fh - f_b - S(cs_) * dd) * S(inv_ms_));
  }

  // The rows of F_h, delta and delta'. The W solver reads three entries of
  // the delta' row at a fixed ratio, and the whole row with the radial DOF,
  // whose bolt force also depends on rho (docs/rom.md#structured-solve); J is
  // never zeroed, so every entry it reads is written.
  void jacobian_rows(const State& x, const RomClampPartials<Cfg>& dfb, typename Cfg::Jacobian& J) const {
    (void)x;
    J(L::kFh, L::kFh) = -inv_tau_h_;
    J(L::kDelta, L::kDeltaDot) = T(1);
    if constexpr (Cfg::kRadial) {
      const T inv_ms = inv_ms_;
      #pragma GCC unroll 16
      for (int j = 0; j < Cfg::N; ++j) J(L::kDeltaDot, j) = T(0);
      dfb.each([&](int col, const T& d) { J(L::kDeltaDot, col) = -d * inv_ms; });
      J(L::kDeltaDot, L::kFh) += inv_ms;
      J(L::kDeltaDot, L::kDeltaDot) += -cs_ * inv_ms;
    } else {
      J(L::kDeltaDot, L::kFh) = Cfg::per_tau(inv_ms_);
      J(L::kDeltaDot, L::kDelta) = dfb.on ? Cfg::per_tau(-dfb.delta * inv_ms_) : T(0);
      J(L::kDeltaDot, L::kDeltaDot) = Cfg::per_tau(-cs_ * inv_ms_);
    }
  }

  // 1/2 m_s delta'^2 + 1/2 K_ax max(0, b)^2 [J]; x in SI, accounting type.
  template <class A, class Radial>
  void add_stored_energy(const A* x, const Radial& radial, A& e) const {
    const A b = radial.bolt_compression_acc(x[L::kDelta], x);
    const A d = b > A(0) ? b : A(0);
    e += A(0.5) * (acc_ms_ * x[L::kDeltaDot] * x[L::kDeltaDot] + acc_K_ax_ * d * d);
  }
  template <class Y>
  void to_si_acc(Y* y) const {
    y[L::kDelta] *= Acc(U::length_m);
  }
  // The actuator's work F_h delta' and the sheave's damping c_s delta'^2 [W].
  template <class A, class Power>
  void power(const A* x, Power& pw) const {
    pw.actuator_W = x[L::kFh] * x[L::kDeltaDot];
    pw.damping_loss_W += acc_cs_ * x[L::kDeltaDot] * x[L::kDeltaDot];
  }

  T K_ax() const { return K_ax_; }

 private:
  T inv_tau_h_, clamp_max_, inv_ms_, cs_, K_ax_;
  double K_ax_si_;
  Acc acc_ms_, acc_cs_, acc_K_ax_;
};

}  // namespace cvt
