#pragma once
// Fixed<F> kernels of the deterministic math: pure integer arithmetic (docs/numerics.md#detmath).
// Internals run in Q60/Q61 (value * 2^60 in int64) with 64x64->128 products,
// so what reaches the Q(F) result is its final rounding plus internal error
// of order 2^-55: results are within 0.5 LSB plus a small fraction of an LSB.
#include <cstdint>

#include "cvtplant/math/detail/coeffs.hpp"
#include "cvtplant/math/detail/wide_int.hpp"

// Included by scalar/fixed.hpp only, once Fixed<F> is complete: the math
// overloads of Fixed<F> stand next to the type (found by ADL) and call these.

namespace cvt::dm::detail {

// round(v * 2^-s), ties away from zero, v < 2^62, s >= 0.
constexpr std::uint64_t shift_round_u(std::uint64_t v, int s) {
  if (s == 0) return v;
  if (s >= 64) return 0;
  return (v + (std::uint64_t{1} << (s - 1))) >> s;
}

// Signed value with `frac` fraction bits -> nearest Fixed<F>, saturating.
template <int F>
constexpr Fixed<F> round_to_fixed(std::int64_t v, int frac) {
  const std::uint64_t m = shift_round_u(abs_u64(v), frac - F);
  const std::int64_t r = v < 0 ? -static_cast<std::int64_t>(m) : static_cast<std::int64_t>(m);
  return Fixed<F>::from_raw(fixed_detail::saturate(r));
}

// ---------------------------------------------------------------- exp
// exp(r), |r| <= 0.35, Q60: Taylor to r^16 (truncation < 2^-75).
constexpr std::int64_t exp_q60(std::int64_t r) {
  std::int64_t acc = kInvFactQ60[16];
  for (int n = 15; n >= 0; --n) acc = mul_q60(acc, r) + kInvFactQ60[n];
  return acc;
}

// exp(x) = mant * 2^k for x in Q56, |x| < 64 (docs/numerics.md#exp).
struct ExpSplit {
  std::int64_t mant_q60;  // in [0.70, 1.42]
  int k;
};
constexpr ExpSplit exp_split_q56(std::int64_t x_q56) {
  const int k = static_cast<int>(mul_shift_round(x_q56, kInvLn2Q60, 116));  // round(x / ln2)
  const std::int64_t r_q56 = x_q56 - k * kLn2Q56;                           // |k| <= 93: no overflow
  return ExpSplit{exp_q60(r_q56 * 16), k};
}

template <int F>
constexpr Fixed<F> exp_fixed(Fixed<F> x) {
  const std::int64_t raw = x.raw();
  // exp(64) overflows every format; exp(-64) < 2^-92 rounds to 0 in every format.
  if (raw >= (std::int64_t{64} << F)) return Fixed<F>::max();
  if (raw <= -(std::int64_t{64} << F)) return Fixed<F>{};
  const ExpSplit s = exp_split_q56(raw * (std::int64_t{1} << (56 - F)));
  const int sh = 60 - F - s.k;            // result raw = mant * 2^-sh
  if (sh <= 0) return Fixed<F>::max();    // >= 0.7 * 2^(31-F+1): beyond max
  const std::uint64_t r = shift_round_u(static_cast<std::uint64_t>(s.mant_q60), sh);
  return Fixed<F>::from_raw(fixed_detail::saturate(static_cast<std::int64_t>(r)));
}

// ---------------------------------------------------------------- sin / cos
// Taylor in z = r^2 for |r| <= pi/4 (+margin), truncation < 2^-62.
constexpr std::int64_t sin_q60(std::int64_t r) {
  const std::int64_t z = mul_q60(r, r);
  std::int64_t acc = -kInvFactQ60[19];  // (-1)^9 / 19!
  for (int j = 8; j >= 0; --j) {
    const std::int64_t c = (j & 1) ? -kInvFactQ60[2 * j + 1] : kInvFactQ60[2 * j + 1];
    acc = mul_q60(acc, z) + c;
  }
  return mul_q60(acc, r);
}
constexpr std::int64_t cos_q60(std::int64_t r) {
  const std::int64_t z = mul_q60(r, r);
  std::int64_t acc = -kInvFactQ60[18];  // (-1)^9 / 18!
  for (int j = 8; j >= 0; --j) {
    const std::int64_t c = (j & 1) ? -kInvFactQ60[2 * j] : kInvFactQ60[2 * j];
    acc = mul_q60(acc, z) + c;
  }
  return acc;
}

// docs/numerics.md#sin-cos: |x| * 2/pi in exact 128-bit integer arithmetic
// (2/pi to 2^-63), so every representable argument reduces correctly.
template <int F>
constexpr Fixed<F> sin_cos_fixed(Fixed<F> x, bool want_cos) {
  const std::int64_t raw = x.raw();
  const U128 P = mul_u64(abs_u64(raw), static_cast<std::uint64_t>(kTwoOverPiQ62));
  const int point = F + 62;  // |x| 2/pi = P * 2^-point
  std::uint64_t k = shr(P, point);
  const std::uint64_t frac = shr(P, point - 60) & ((std::uint64_t{1} << 60) - 1);  // Q60
  std::int64_t f = static_cast<std::int64_t>(frac);
  if (frac >= (std::uint64_t{1} << 59)) {  // round k to nearest
    ++k;
    f -= std::int64_t{1} << 60;
  }
  const std::int64_t r = mul_q60(f, kPio2Q60);
  std::int64_t y = 0;
  const int n = static_cast<int>(k & 3u);
  if (want_cos) {
    y = n == 0 ? cos_q60(r) : n == 1 ? -sin_q60(r) : n == 2 ? -cos_q60(r) : sin_q60(r);
  } else {
    y = n == 0 ? sin_q60(r) : n == 1 ? cos_q60(r) : n == 2 ? -sin_q60(r) : -cos_q60(r);
    if (raw < 0) y = -y;
  }
  return round_to_fixed<F>(y, 60);
}

// ---------------------------------------------------------------- atan
// docs/numerics.md#atan: CORDIC vectoring of (1, |x|), normalised so the
// larger component has its top bit at 2^60; F + 24 iterations leave an angle
// residual below 2^-(F+23). Converges for any angle in [0, pi/2] without a
// pre-rotation (sum of atan(2^-i) = 1.74 rad > pi/2). No division.
template <int F>
constexpr Fixed<F> atan_fixed(Fixed<F> x) {
  const std::int64_t raw = x.raw();
  if (raw == 0) return Fixed<F>{};
  const std::uint64_t ay = abs_u64(raw);
  const std::uint64_t ax = std::uint64_t{1} << F;
  const std::uint64_t mx = ay > ax ? ay : ax;
  const int sh = clz64(mx) - 3;
  std::int64_t X = static_cast<std::int64_t>(ax << sh);
  std::int64_t Y = static_cast<std::int64_t>(ay << sh);
  std::int64_t z = 0;  // Q61
  for (int i = 0; i < F + 24; ++i) {
    const std::int64_t dx = asr(Y, i), dy = asr(X, i);
    if (Y > 0) {
      X += dx;
      Y -= dy;
      z += kAtan2iQ61[i];
    } else {
      X -= dx;
      Y += dy;
      z -= kAtan2iQ61[i];
    }
  }
  return round_to_fixed<F>(raw < 0 ? -z : z, 61);
}

// ---------------------------------------------------------------- tanh
// docs/numerics.md#tanh: tanh|x| = (1 - m) / (1 + m), m = exp(-2|x|) in Q60.
// The numerator is computed in absolute (not relative) precision, which is
// all a fixed-point result needs, so no small-argument branch is required.
template <int F>
constexpr Fixed<F> tanh_fixed(Fixed<F> x) {
  const std::int64_t raw = x.raw();
  const std::uint64_t a = abs_u64(raw);
  if (a >= (std::uint64_t{16} << F)) {  // 1 - tanh(16) = 2.5e-14 < 2^-31
    return raw < 0 ? -Fixed<F>::one() : Fixed<F>::one();
  }
  const ExpSplit s = exp_split_q56(-static_cast<std::int64_t>((2 * a) << (56 - F)));
  const std::uint64_t m = shift_round_u(static_cast<std::uint64_t>(s.mant_q60), -s.k);  // k <= 0
  const std::uint64_t one = std::uint64_t{1} << 60;
  const std::uint64_t den = one + m;  // in [2^60, 2^61]
  std::uint64_t rem = one - m, q = 0;
  // Restoring division, F + 1 quotient bits (the last one rounds): no 128-bit
  // divide needed and no precision lost to pre-shifting (rem < 2^62 throughout).
  for (int i = 0; i <= F; ++i) {
    rem <<= 1;
    q <<= 1;
    if (rem >= den) {
      rem -= den;
      q |= 1u;
    }
  }
  q = (q + 1) >> 1;
  const std::int64_t r = static_cast<std::int64_t>(q);
  return Fixed<F>::from_raw(static_cast<std::int32_t>(raw < 0 ? -r : r));
}

// ---------------------------------------------------------------- sqrt
// Correctly rounded: integer square root of raw * 2^F, then round to nearest
// (n - s^2 > s  <=>  n > (s + 1/2)^2 for integers; no ties possible).
// Negative arguments give 0 (docs/numerics.md#fixed-point, domain rules).
template <int F>
constexpr Fixed<F> sqrt_fixed(Fixed<F> x) {
  if (x.raw() <= 0) return Fixed<F>{};
  std::uint64_t n = static_cast<std::uint64_t>(x.raw()) << F;  // < 2^61
  std::uint64_t res = 0;
  std::uint64_t bit = std::uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= res + bit) {
      n -= res + bit;
      res = (res >> 1) + bit;
    } else {
      res >>= 1;
    }
    bit >>= 2;
  }
  if (n > res) ++res;
  return Fixed<F>::from_raw(static_cast<std::int32_t>(res));  // <= 2^30.5
}

}  // namespace cvt::dm::detail
