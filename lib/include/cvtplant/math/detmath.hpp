#pragma once
// Deterministic math for the scalar types of the core: abs, sqrt, atan, exp,
// tanh, sin, cos, sign for double and float here (cvt::dm), for Fixed<F>
// next to the type (scalar/fixed.hpp) and for dual numbers next to theirs
// (autodiff/dual.hpp). How generic code calls them: the end of this file.
//
// Same input -> same bits on x86-64, aarch64 and Cortex-M (with
// -ffp-contract=off): no libm transcendental is called; float/double use only
// + - * /, IEEE sqrt and bit manipulation; Fixed<F> uses integers only. Float
// paths never touch double. Methods, edge cases and the measured errors:
// docs/numerics.md#detmath.
//
// Edge rules (float/double): NaN in -> NaN out; exp overflows to +inf and
// underflows through subnormals to +0; atan(+-inf) = +-pi/2 (rounded);
// tanh(+-inf) = +-1; sin/cos(+-inf) = NaN; sign(+-0) = +-0, sign(NaN) = NaN.
// Edge rules (Fixed): saturate instead of overflowing; sqrt(x < 0) = 0.
#include <cstdint>

#include "cvtplant/math/detail/ieee.hpp"
#include "cvtplant/scalar/fixed.hpp"

namespace cvt::dm {

// ---------------------------------------------------------------- double
inline double abs(double x) { return __builtin_fabs(x); }
// Correctly rounded by IEEE 754; compiles to the hardware instruction where
// there is one (a libm call may remain only on the errno path for x < 0).
inline double sqrt(double x) { return __builtin_sqrt(x); }
inline double exp(double x) { return detail::exp_d(x); }
inline double atan(double x) { return detail::atan_ieee(x); }
inline double tanh(double x) { return detail::tanh_ieee(x); }
inline double sin(double x) { return detail::sin_cos_d(x, false); }
inline double cos(double x) { return detail::sin_cos_d(x, true); }
inline double sign(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : x; }

// ---------------------------------------------------------------- float
inline float abs(float x) { return __builtin_fabsf(x); }
inline float sqrt(float x) { return __builtin_sqrtf(x); }
inline float exp(float x) { return detail::exp_f(x); }
inline float atan(float x) { return detail::atan_ieee(x); }
inline float tanh(float x) { return detail::tanh_ieee(x); }
inline float sin(float x) { return detail::sin_cos_f(x, false); }
inline float cos(float x) { return detail::sin_cos_f(x, true); }
inline float sign(float x) { return x > 0.0f ? 1.0f : x < 0.0f ? -1.0f : x; }

// ---------------------------------------------------------------- set-up only (double)
// ln(v) for v in (0, 1e6] by Newton on exp, and asin(s) for |s| < 0.9 by
// Newton on sin: constants computed once at set-up, deterministic because
// they rest on exp and sin above (no libm). Far too slow for a step.
inline double log_setup(double v) {
  double y = 0.0;
  for (int i = 0; i < 60; ++i) y -= 1.0 - v / exp(y);
  return y;
}
inline double asin_setup(double s) {
  double y = s;
  for (int i = 0; i < 40; ++i) y -= (sin(y) - s) / cos(y);
  return y;
}

// ---------------------------------------------------------------- error bounds
// Measured maximum error (docs/numerics.md#detmath has the sweeps and the
// commands). float/double: in ulp of the exact result (ulp(y) = 2^(floor(log2|y|) - p + 1),
// subnormals: the smallest subnormal). Fixed: in LSB (2^-F), absolute.
// lib/tests/test_detmath.cpp asserts each of these.
template <class T>
struct max_error;

template <>
struct max_error<double> {
  static constexpr double sqrt = 0.5;   // IEEE, correctly rounded
  static constexpr double exp = 1.0;    // measured 0.94
  static constexpr double atan = 2.4;   // measured 2.27
  static constexpr double tanh = 1.5;   // measured 1.45
  static constexpr double sin = 1.0;    // measured 0.79
  static constexpr double cos = 1.0;    // measured 0.79
};

template <>
struct max_error<float> {
  static constexpr double sqrt = 0.5;
  static constexpr double exp = 1.0;    // measured 0.97
  static constexpr double atan = 2.2;   // measured 2.06
  static constexpr double tanh = 1.5;   // measured 1.42
  static constexpr double sin = 1.6;    // measured 1.55
  static constexpr double cos = 1.6;    // measured 1.55
};

// Fixed: correctly rounded except within 1e-4 LSB of a rounding tie (the
// internal Q60 error), for every F in [1, 30].
template <int F>
struct max_error<Fixed<F>> {
  static constexpr double sqrt = 0.5;
  static constexpr double exp = 0.5001;
  static constexpr double atan = 0.5001;
  static constexpr double tanh = 0.5001;
  static constexpr double sin = 0.5001;
  static constexpr double cos = 0.5001;
};

}  // namespace cvt::dm

namespace cvt {

// Generic code in namespace cvt calls the scalar math unqualified, exp(x):
// for double and float these using-declarations resolve it (argument-
// dependent lookup finds nothing for built-in types); Fixed<F> (fixed.hpp)
// and Dual<T, N> (dual.hpp) carry their overloads next to the type, and ADL
// finds them wherever the type is known, whatever the include order. Code
// that knows its type may call dm::exp(x) for double/float directly.
using dm::abs;
using dm::atan;
using dm::cos;
using dm::exp;
using dm::sign;
using dm::sin;
using dm::sqrt;
using dm::tanh;

}  // namespace cvt
