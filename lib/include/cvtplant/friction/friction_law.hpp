#pragma once
// Friction coefficient laws of the seed paper (docs/physics.md#friction):
//   constant   mu = mu0                                         (seed sec. 3, "Coulomb")
//   case 1     mu = a + (mu0 - a)(1 - exp(-|v|/b))               (seed Eq. 6, case 1)
//   case 2     mu = mu0 (1 - exp(-kappa|v|))(1 + (sigma-1) exp(-chi|v|))
//                                                               (seed Eq. 6, case 2 / sec. 3 Stribeck)
// and the sign functions that regularise the set-valued sign(v_rel):
//   exact      sign(v)
//   atan       2/pi * atan(lambda v)                             (seed Eq. 9)
//   tanh       tanh(lambda v)
// Templated on the parameter scalar T and the evaluation scalar S, so the same
// code runs in double/float/fixed and in dual numbers for Jacobians.
#include <cstdint>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

enum class FrictionLaw : std::uint8_t { constant, case1, case2 };
enum class SignFunction : std::uint8_t { exact, atan, tanh };

template <class T>
struct FrictionParams {
  FrictionLaw law = FrictionLaw::constant;
  T mu0 = T(0.25);        // kinetic coefficient [-]
  T a = T(0);             // case 1: starting coefficient [-]
  T b_m_s = T(1);         // case 1: velocity scale [m/s]
  T sigma = T(1);         // case 2: static/kinetic ratio parameter [-]
  T kappa_s_m = T(1);     // case 2: rate of growth [s/m]
  T chi_s_m = T(1);       // case 2: Stribeck decay [s/m]
  SignFunction sign = SignFunction::atan;
  T lambda_s_m = T(1e4);  // slope of the smoothed sign [s/m]

  // Converts the parameters to another scalar type (set-up time only).
  template <class U>
  FrictionParams<U> cast() const {
    FrictionParams<U> p;
    p.law = law;
    p.mu0 = U(static_cast<double>(mu0));
    p.a = U(static_cast<double>(a));
    p.b_m_s = U(static_cast<double>(b_m_s));
    p.sigma = U(static_cast<double>(sigma));
    p.kappa_s_m = U(static_cast<double>(kappa_s_m));
    p.chi_s_m = U(static_cast<double>(chi_s_m));
    p.sign = sign;
    p.lambda_s_m = U(static_cast<double>(lambda_s_m));
    return p;
  }
};

// Named presets: the seed's parameter sets (docs/physics.md#friction-presets).
namespace friction_presets {

// The seed's kinetic coefficient and smoothed sign (Eq. 9, lambda = 1e4)
// under `law`; every preset starts from it.
template <class T>
constexpr FrictionParams<T> seed_law(FrictionLaw law) {
  FrictionParams<T> p;
  p.law = law;
  p.mu0 = T(seed::kMu0);
  p.sign = SignFunction::atan;
  p.lambda_s_m = T(seed::kOscSignSlope_s_m);
  return p;
}

// Case 2 (Stribeck) with the seed's mu0 and sign.
template <class T>
constexpr FrictionParams<T> seed_stribeck(double sigma, double kappa_s_m, double chi_s_m) {
  FrictionParams<T> p = seed_law<T>(FrictionLaw::case2);
  p.sigma = T(sigma);
  p.kappa_s_m = T(kappa_s_m);
  p.chi_s_m = T(chi_s_m);
  return p;
}

// Seed section 3, constant coefficient ("classical Coulomb-Amonton").
template <class T>
constexpr FrictionParams<T> oscillator_coulomb() {
  return seed_law<T>(FrictionLaw::constant);
}

// Seed section 3, Stribeck: mu0 = 0.25, sigma = 6.5, chi = 1, kappa = 5, lambda = 1e4.
template <class T>
constexpr FrictionParams<T> oscillator_stribeck() {
  return seed_stribeck<T>(seed::kOscStribeckSigma, seed::kOscStribeckKappa_s_m, seed::kOscStribeckChi_s_m);
}

// Seed Table 2, case 1 (Coulomb-like with a start-up ramp): a = 0.003, b = 0.1, mu0 = 0.25.
template <class T>
constexpr FrictionParams<T> table2_case1() {
  FrictionParams<T> p = seed_law<T>(FrictionLaw::case1);
  p.a = T(seed::kCase1A);
  p.b_m_s = T(seed::kCase1B_m_s);
  return p;
}

// Seed Table 2, case 2 (Stribeck): mu0 = 0.25, sigma = 3.5, kappa = 10, chi = 3.
template <class T>
constexpr FrictionParams<T> table2_case2() {
  return seed_stribeck<T>(seed::kCase2Sigma, seed::kCase2Kappa_s_m, seed::kCase2Chi_s_m);
}

}  // namespace friction_presets

// mu(|v|) for speed = |v_rel| >= 0. docs/physics.md#friction
template <class T, class S>
S friction_coefficient(const FrictionParams<T>& p, const S& speed_m_s) {
  switch (p.law) {
    case FrictionLaw::case1:
      return S(p.a) + S(p.mu0 - p.a) * (S(1) - exp(-speed_m_s / S(p.b_m_s)));
    case FrictionLaw::case2:
      return S(p.mu0) * (S(1) - exp(-S(p.kappa_s_m) * speed_m_s)) *
             (S(1) + S(p.sigma - T(1)) * exp(-S(p.chi_s_m) * speed_m_s));
    case FrictionLaw::constant:
    default:
      return S(p.mu0);
  }
}

// Regularised sign s(v). docs/physics.md#sign-functions
template <class T, class S>
S friction_sign(const FrictionParams<T>& p, const S& v_m_s) {
  switch (p.sign) {
    case SignFunction::exact:
      return sign(v_m_s);
    case SignFunction::tanh:
      return tanh(S(p.lambda_s_m) * v_m_s);
    case SignFunction::atan:
    default:
      // 2/pi as a constant, so float and fixed round it once.
      return S(T(kTwoOverPi)) * atan(S(p.lambda_s_m) * v_m_s);
  }
}

// Signed friction characteristic phi(v) = mu(|v|) * s(v): the friction force on
// a body sliding at v_rel against a surface is F = -phi(v_rel) * N.
template <class T, class S>
S friction_characteristic(const FrictionParams<T>& p, const S& v_rel_m_s) {
  return friction_coefficient(p, abs(v_rel_m_s)) * friction_sign(p, v_rel_m_s);
}

// phi(v_rel) and d phi / d v_rel together (docs/physics.md#friction-derivative):
// the plant's Jacobian and right-hand side need both at the same slip speed,
// and the exponentials and the atan are most of their cost. phi is bit for bit
// friction_characteristic(p, v): the same operations in the same order.
template <class T>
struct FrictionEval {
  T phi{};    // mu(|v|) s(v) [-]
  T slope{};  // d phi / d v [s/m]
};

template <class T>
FrictionEval<T> friction_characteristic_and_slope(const FrictionParams<T>& p, const T& v_rel_m_s) {
  const T speed = abs(v_rel_m_s);
  const T s = friction_sign(p, v_rel_m_s);
  // ds/dv
  T ds = T(0);
  switch (p.sign) {
    case SignFunction::exact:
      ds = T(0);
      break;
    case SignFunction::tanh:
      ds = p.lambda_s_m * (T(1) - s * s);
      break;
    case SignFunction::atan:
    default: {
      const T lv = p.lambda_s_m * v_rel_m_s;
      if constexpr (is_fixed_point_v<T>) {
        // Scaling and overflow (fixed point): (lambda v)^2 leaves the Q range
        // above |lambda v| = 181 and saturated to 32768, which left a spurious
        // slope of the sign, 2/pi lambda / 32768 (0.19 s/m at lambda = 1e4;
        // 0.049 s/m of phi at mu = 0.25), at every faster slip: a Jacobian
        // coupling of the lumps to the pulley speeds that does not exist, and
        // in gross slip the fixed-point step settled the lumps 21 LSB away
        // from their steady state. Above |lambda v| = 128 the
        // slope is 2/pi (lambda / |lambda v|) / |lambda v| / (1 + (lambda v)^-2),
        // divisions whose results stay in range (0.39 s/m at most).
        const T alv = abs(lv);
        if (alv > T(128)) {
          const T q = T(1) / alv;
          ds = T(kTwoOverPi) * ((p.lambda_s_m / alv) / alv) / (T(1) + q * q);
          break;
        }
      }
      ds = T(kTwoOverPi) * p.lambda_s_m / (T(1) + lv * lv);
      break;
    }
  }
  // mu(|v|) and dmu/d|v|, sharing the exponentials; mu as in friction_coefficient.
  T mu = p.mu0, dmu = T(0);
  switch (p.law) {
    case FrictionLaw::case1: {
      const T e = exp(-speed / p.b_m_s);
      mu = p.a + (p.mu0 - p.a) * (T(1) - e);
      dmu = (p.mu0 - p.a) / p.b_m_s * e;
      break;
    }
    case FrictionLaw::case2: {
      const T ek = exp(-p.kappa_s_m * speed);
      const T ec = exp(-p.chi_s_m * speed);
      const T g1 = T(1) - ek;
      const T g2 = T(1) + (p.sigma - T(1)) * ec;
      mu = p.mu0 * g1 * g2;
      dmu = p.mu0 * (p.kappa_s_m * ek * g2 - g1 * (p.sigma - T(1)) * p.chi_s_m * ec);
      break;
    }
    case FrictionLaw::constant:
    default:
      break;
  }
  FrictionEval<T> r;
  r.phi = mu * s;
  // d|v|/dv * s = sign(v) * s(v) = |s(v)| for an odd s. At v = 0 the |v| kink
  // of mu multiplies s(0) = 0, so the expression is exact there too.
  r.slope = dmu * abs(s) + mu * ds;
  return r;
}

// d phi / d v_rel, analytic, for Jacobians (docs/physics.md#friction-derivative).
template <class T>
T friction_characteristic_slope(const FrictionParams<T>& p, const T& v_rel_m_s) {
  return friction_characteristic_and_slope(p, v_rel_m_s).slope;
}

}  // namespace cvt
