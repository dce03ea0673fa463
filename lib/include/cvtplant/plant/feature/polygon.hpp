#pragma once
// Feature `polygon` (docs/rom.md#polygon, #link-ripple): chordal action of
// the links on the driver and the link-passing ripple of the axial force.
// State psi, the link phase in [-alpha, alpha), alpha = asin(L / (2 r1)):
//   r1e = r1 cos(psi)                                     effective driver radius
//   psi' = w1, or with the chain's tension state its link flux
//          (2 alpha / L) v_c kL / (kL + T_s)             docs/rom.md#link-ripple
//   F_lumps = F_ax (1 + A cos(theta)), theta = pi psi / alpha + pi (1 - d)
// (A = 0, the default, skips the ripple's terms: the plant is then bit for
// bit the one without it). The sheave's own balance keeps the smooth F_ax.
#include <cstdint>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/feature/axial.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// What the shared contact keeps of the ripple: cos and sin of its phase
// (0 with the ripple off); nothing without the feature.
template <class T, bool kOn>
struct RomRippleCache {};
template <class T>
struct RomRippleCache<T, true> {
  T ripple_cos{}, ripple_sin{};
};

template <class Cfg, bool kOn = Cfg::kPolygon>
class RomPolygon {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  using Cache = RomRippleCache<T, false>;
  explicit RomPolygon(const RomParams&) {}
  T half_angle() const { return T(0); }
  bool rippled() const { return false; }
  template <class X>
  void initial_state(const RomInitial&, X&) const {}
  void wrap(typename Cfg::State&) const {}
  template <class S>
  S driver_radius(const S& r1, const Vec<S>&) const {
    return r1;
  }
  template <class S>
  S ripple_cos(const Vec<S>&) const {
    return S(T(0));
  }
  void cache(const typename Cfg::State&, Cache&) const {}
  static T cached_cos(const Cache&) { return T(0); }
  T ripple_factor(const Cache&) const { return T(1); }
  template <class S>
  S lumps_force(const S& fax, const S&) const {
    return fax;
  }
  template <class S, class Loads, class Tension>
  void rows(const Vec<S>&, const Loads&, const Tension&, Vec<S>&) const {}
  T radius_factor(const typename Cfg::State&) const { return T(1); }
  template <class Jac>
  void partials(const typename Cfg::State&, const Cache&, const T&, const T&, Jac&) const {}
  template <class TCache, class Radial, class Core, class Tension>
  void jacobian_row(const typename Cfg::State&, const TCache&, const T&, const T&, const RomClampPartials<Cfg>&,
                    const Radial&, const Core&, const Tension&, typename Cfg::Jacobian&) const {}
};

template <class Cfg>
class RomPolygon<Cfg, true> {
  CVT_ROM_FEATURE_TYPES(Cfg);

 public:
  using Cache = RomRippleCache<T, true>;

  explicit RomPolygon(const RomParams& p) {
    // Half the angle one link subtends on the driver.
    const double alpha_rad = dm::asin_setup(p.pitch_m / (2.0 * p.r1_m));
    alpha_ = T(alpha_rad);
    // The loaded-bolt count's fundamental (2/pi) sin(pi d) cos(theta),
    // theta = pi psi / alpha + pi (1 - d), d the fractional part of the
    // links in the driver wrap (docs/rom.md#link-ripple).
    rip_A_ = T(rom_ripple_amplitude(p));
    rip_k_ = T(kPi / alpha_rad);
    rip_phase_ = T(kPi * (1.0 - rom_wrap_links_fraction(p)));
    psi_per_m_ = T(2.0 * alpha_rad / p.pitch_m);
  }

  T half_angle() const { return alpha_; }
  // 2 alpha / L: the link phase per metre of chain [rad/m].
  T phase_per_m() const { return psi_per_m_; }
  // True with the link-passing ripple (A != 0); its terms are skipped otherwise.
  bool rippled() const { return rip_A_ != T(0); }
  T ripple_amplitude() const { return rip_A_; }
  T ripple_wavenumber() const { return rip_k_; }

  template <class X>
  void initial_state(const RomInitial& x0, X& x) const {
    x(L::kPsi) = T(x0.phase_rad);
  }
  // Keeps psi in [-alpha, alpha) between steps (it is periodic in the link
  // pitch; wrapping outside the integrator keeps it bounded in float and
  // fixed point).
  void wrap(State& x) const {
    const T two_alpha = alpha_ + alpha_;
    while (x(L::kPsi) >= alpha_) x(L::kPsi) -= two_alpha;
    while (x(L::kPsi) < -alpha_) x(L::kPsi) += two_alpha;
  }

  template <class S>
  S driver_radius(const S& r1, const Vec<S>& x) const {
    return r1 * cos(x(L::kPsi));
  }
  // d r1e / d r1 = cos(psi).
  T radius_factor(const State& x) const { return cos(x(L::kPsi)); }

  template <class S>
  S ripple_angle(const S& psi) const {
    return S(rip_k_) * psi + S(rip_phase_);
  }
  // cos(theta) of the ripple at x; 0 with the ripple off (no cosine then).
  template <class S>
  S ripple_cos(const Vec<S>& x) const {
    if (rippled()) return cos(ripple_angle(x(L::kPsi)));
    return S(T(0));
  }
  // The shared contact's cos and sin of theta (both stay 0 with the ripple off).
  void cache(const State& x, Cache& c) const {
    if (rippled()) {
      const T theta = ripple_angle(x(L::kPsi));
      c.ripple_cos = cos(theta);
      c.ripple_sin = sin(theta);
    }
  }
  static T cached_cos(const Cache& c) { return c.ripple_cos; }
  // d F_lumps / d F_ax = 1 + A cos(theta) (1 with the ripple off).
  T ripple_factor(const Cache& c) const { return rippled() ? T(1) + rip_A_ * c.ripple_cos : T(1); }

  // The link phase's rate psi' [rad/s] at x with the contact c: w1, or with
  // the tension feature the chain's link flux at v_c (docs/rom.md#link-ripple).
  // The watchdog's 8 steps per link apply to it (docs/rom.md#polygon).
  template <class Contact, class Tension>
  T phase_rate(const State& x, const T& vc, const Contact& c, const Tension& tension) const {
    if constexpr (Cfg::kTension) {
      (void)x;
      return link_phase_rate(psi_per_m_, vc, tension.chain_stiffness(), c.tension.inv_D);
    } else {
      (void)vc, (void)c, (void)tension;
      return x(L::kW1);
    }
  }

  // The lumps' axial force F_ax (1 + A cos theta); F_ax itself with the ripple off.
  template <class S>
  S lumps_force(const S& fax, const S& cos_theta) const {
    if (rippled()) return rippled_axial_force(fax, S(rip_A_), cos_theta);
    return fax;
  }

  // psi': the driver's turn w1, or with the tension feature the chain's
  // link flux at v_c (docs/rom.md#link-ripple).
  template <class S, class Loads, class Tension>
  void rows(const Vec<S>& x, const Loads& l, const Tension& tension, Vec<S>& dxdt) const {
    if constexpr (Cfg::kTension)
      dxdt(L::kPsi) = Cfg::per_tau(link_phase_rate(S(psi_per_m_), l.vc, S(tension.chain_stiffness()), l.tension.inv_D));
    else
      dxdt(L::kPsi) = Cfg::per_tau(x(L::kW1));
  }

  // Partials through the driver radius, d r1e / d psi = -r1 sin(psi), and
  // through the lumps' axial force, d F_lumps / d psi = -F_ax A (pi/alpha)
  // sin(theta) (fax: the unrippled F_ax), as the contact law's jac takes them.
  template <class Jac>
  void partials(const State& x, const Cache& c, const T& r1, const T& fax, Jac& jac) const {
    jac.driver_radius(L::kPsi, -r1 * sin(x(L::kPsi)));
    if (rippled()) jac.lumps_force(L::kPsi, -(fax * (rip_A_ * rip_k_)) * c.ripple_sin);
  }

  // The row of psi': d w1 / d w1 = 1, or with the tension feature the link
  // flux's partials (RomTension::link_flux_row). Every entry the W solver
  // reads is written (its J is never zeroed).
  template <class TCache, class Radial, class Core, class Tension>
  void jacobian_row(const State& x, const TCache& c, const T& vc, const T& r2e, const RomClampPartials<Cfg>& dfc,
                    const Radial& radial, const Core& core, const Tension& tension, typename Cfg::Jacobian& J) const {
    if constexpr (Cfg::kTension) {
      tension.link_flux_row(x, c, vc, r2e, dfc, radial, core, psi_per_m_, J);
    } else {
      (void)x, (void)c, (void)vc, (void)r2e, (void)dfc, (void)radial, (void)core, (void)tension;
      J(L::kPsi, L::kW1) = Cfg::per_tau(T(1));
    }
  }

 private:
  T alpha_{}, rip_A_{}, rip_k_{}, rip_phase_{}, psi_per_m_{};
};

}  // namespace cvt
