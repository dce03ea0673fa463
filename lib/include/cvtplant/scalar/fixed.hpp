#pragma once
// Signed saturating fixed point: 32-bit storage, 64-bit intermediates.
// Format, rounding and every overflow / domain rule: docs/numerics.md#fixed-point
//
//   value = raw * 2^-FracBits,   raw in [INT32_MIN, INT32_MAX]
//
// Rules in one place (each is tested in lib/tests/test_fixed.cpp):
//   - every operation saturates to [lowest(), max()] instead of wrapping;
//   - conversions, *, / round to nearest, ties away from zero;
//   - x / 0 gives max() for x > 0, lowest() for x < 0, and 0 for 0 / 0;
//   - from double/float: NaN -> 0, +inf -> max(), -inf -> lowest();
//   - -lowest() == max() (the one value whose negation does not fit).
// Everything is constexpr and heap-free; no floating point is touched except
// in the explicit conversions to and from float/double.
#include <cstdint>
#include <limits>
#include <type_traits>

namespace cvt {

namespace fixed_detail {

inline constexpr std::int64_t kRawMax = std::numeric_limits<std::int32_t>::max();
inline constexpr std::int64_t kRawMin = std::numeric_limits<std::int32_t>::min();

constexpr std::int32_t saturate(std::int64_t v) {
  return v > kRawMax ? static_cast<std::int32_t>(kRawMax)
         : v < kRawMin ? static_cast<std::int32_t>(kRawMin)
                       : static_cast<std::int32_t>(v);
}

// round(v / 2^s), ties away from zero, for 0 < s < 63 and |v| < 2^62.
constexpr std::int64_t shift_round(std::int64_t v, int s) {
  const std::int64_t half = std::int64_t{1} << (s - 1);
  return v >= 0 ? (v + half) >> s : -((-v + half) >> s);
}

// "q<integer bits incl. sign>.<fraction bits>", e.g. "q16.16".
struct Name {
  char text[8];
};
constexpr Name make_name(int frac_bits) {
  Name n{};
  int i = 0;
  auto put = [&](int v) {
    if (v >= 10) n.text[i++] = static_cast<char>('0' + v / 10);
    n.text[i++] = static_cast<char>('0' + v % 10);
  };
  n.text[i++] = 'q';
  put(32 - frac_bits);
  n.text[i++] = '.';
  put(frac_bits);
  n.text[i] = '\0';
  return n;
}

}  // namespace fixed_detail

template <int FracBits>
class Fixed {
  static_assert(FracBits >= 1 && FracBits <= 30,
                "Fixed<F>: 1 <= F <= 30 (1.0 and a rounding bit must fit in int32)");

 public:
  static constexpr int kFracBits = FracBits;
  static constexpr std::int32_t kOneRaw = std::int32_t{1} << FracBits;

 private:
  static constexpr fixed_detail::Name kNameStorage = fixed_detail::make_name(FracBits);

 public:
  static constexpr const char* kName = kNameStorage.text;

  constexpr Fixed() = default;

  // Integers of any width: exact when in range, otherwise saturated.
  template <class I, std::enable_if_t<std::is_integral_v<I> && !std::is_same_v<I, bool>, int> = 0>
  explicit constexpr Fixed(I v) : raw_(from_integer(v)) {}

  // docs/numerics.md#fixed-point (conversion): round to nearest, ties away
  // from zero; NaN -> 0; out of range (incl. +-inf) saturates.
  explicit constexpr Fixed(double v) : raw_(from_double_raw(v)) {}
  // Same rules, computed in float only (no double helper calls on an FPU-less
  // double target such as Cortex-M4F).
  explicit constexpr Fixed(float v) : raw_(from_float_raw(v)) {}

  static constexpr Fixed from_raw(std::int32_t r) {
    Fixed f;
    f.raw_ = r;
    return f;
  }
  constexpr std::int32_t raw() const { return raw_; }

  // Exact: every raw value is representable in double (31 significant bits).
  constexpr double to_double() const { return static_cast<double>(raw_) * (1.0 / kOneRaw); }
  // Correctly rounded (one int->float rounding, then an exact power-of-2 scale).
  constexpr float to_float() const { return static_cast<float>(raw_) * (1.0f / kOneRaw); }
  explicit constexpr operator double() const { return to_double(); }
  explicit constexpr operator float() const { return to_float(); }

  static constexpr Fixed max() { return from_raw(std::numeric_limits<std::int32_t>::max()); }
  static constexpr Fixed lowest() { return from_raw(std::numeric_limits<std::int32_t>::min()); }
  static constexpr Fixed min_positive() { return from_raw(1); }
  static constexpr Fixed epsilon() { return from_raw(1); }  // one LSB = 2^-FracBits
  static constexpr Fixed one() { return from_raw(kOneRaw); }

  // --- arithmetic (docs/numerics.md#fixed-point) ---------------------------
  constexpr Fixed operator-() const { return from_raw(fixed_detail::saturate(-std::int64_t{raw_})); }
  constexpr Fixed operator+() const { return *this; }

  friend constexpr Fixed operator+(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(std::int64_t{a.raw_} + b.raw_));
  }
  friend constexpr Fixed operator-(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(std::int64_t{a.raw_} - b.raw_));
  }
  // |a.raw * b.raw| <= 2^62, so the wide product never overflows.
  friend constexpr Fixed operator*(Fixed a, Fixed b) {
    const std::int64_t p = std::int64_t{a.raw_} * b.raw_;
    return from_raw(fixed_detail::saturate(fixed_detail::shift_round(p, FracBits)));
  }
  friend constexpr Fixed operator/(Fixed a, Fixed b) { return from_raw(div_raw(a.raw_, b.raw_)); }

  // Mixed with integers: exact scaling, then saturation.
  friend constexpr Fixed operator*(Fixed a, int b) {
    return from_raw(fixed_detail::saturate(std::int64_t{a.raw_} * b));
  }
  friend constexpr Fixed operator*(int a, Fixed b) { return b * a; }
  friend constexpr Fixed operator/(Fixed a, int b) {
    // a / b = a.raw / b in raw units; reuse the rounding/zero rules of div_raw
    // by dividing by the integer as if it were raw b * 2^F.
    return from_raw(div_wide(std::int64_t{a.raw_}, std::int64_t{b}));
  }

  constexpr Fixed& operator+=(Fixed o) { return *this = *this + o; }
  constexpr Fixed& operator-=(Fixed o) { return *this = *this - o; }
  constexpr Fixed& operator*=(Fixed o) { return *this = *this * o; }
  constexpr Fixed& operator/=(Fixed o) { return *this = *this / o; }
  constexpr Fixed& operator*=(int o) { return *this = *this * o; }
  constexpr Fixed& operator/=(int o) { return *this = *this / o; }

  friend constexpr bool operator==(Fixed a, Fixed b) { return a.raw_ == b.raw_; }
  friend constexpr bool operator!=(Fixed a, Fixed b) { return a.raw_ != b.raw_; }
  friend constexpr bool operator<(Fixed a, Fixed b) { return a.raw_ < b.raw_; }
  friend constexpr bool operator<=(Fixed a, Fixed b) { return a.raw_ <= b.raw_; }
  friend constexpr bool operator>(Fixed a, Fixed b) { return a.raw_ > b.raw_; }
  friend constexpr bool operator>=(Fixed a, Fixed b) { return a.raw_ >= b.raw_; }

 private:
  template <class I>
  static constexpr std::int32_t from_integer(I v) {
    constexpr std::int64_t lim = fixed_detail::kRawMax >> FracBits;  // largest integer that fits
    if constexpr (std::is_signed_v<I>) {
      if (static_cast<long long>(v) > lim) return static_cast<std::int32_t>(fixed_detail::kRawMax);
      if (static_cast<long long>(v) < -lim - 1) return static_cast<std::int32_t>(fixed_detail::kRawMin);
      return static_cast<std::int32_t>(static_cast<std::int64_t>(v) * kOneRaw);
    } else {
      if (static_cast<unsigned long long>(v) > static_cast<unsigned long long>(lim))
        return static_cast<std::int32_t>(fixed_detail::kRawMax);
      return static_cast<std::int32_t>(static_cast<std::int64_t>(v) * kOneRaw);
    }
  }

  static constexpr std::int32_t from_double_raw(double v) {
    if (v != v) return 0;  // NaN
    const double s = v * static_cast<double>(kOneRaw);  // exact: power-of-2 scale
    // Anything at or beyond raw max + 1/2 rounds (away from zero) past max.
    if (s >= 2147483647.5) return static_cast<std::int32_t>(fixed_detail::kRawMax);
    if (s <= -2147483648.5) return static_cast<std::int32_t>(fixed_detail::kRawMin);
    // |s| < 2^31 + 1: trunc and the fractional remainder are exact in double.
    const std::int64_t t = static_cast<std::int64_t>(s);
    const double frac = s - static_cast<double>(t);
    std::int64_t r = t;
    if (frac >= 0.5) r = t + 1;
    if (frac <= -0.5) r = t - 1;
    return fixed_detail::saturate(r);
  }

  static constexpr std::int32_t from_float_raw(float v) {
    if (v != v) return 0;
    const float s = v * static_cast<float>(kOneRaw);
    // 2^31 is the first float not below max + 1/2 (floats there are 128 apart).
    if (s >= 2147483648.0f) return static_cast<std::int32_t>(fixed_detail::kRawMax);
    if (s < -2147483648.0f) return static_cast<std::int32_t>(fixed_detail::kRawMin);
    const std::int32_t t = static_cast<std::int32_t>(s);  // in range, exact trunc
    const float frac = s - static_cast<float>(t);         // exact (|s| < 2^31, integer part fits)
    std::int64_t r = t;
    if (frac >= 0.5f) r = std::int64_t{t} + 1;
    if (frac <= -0.5f) r = std::int64_t{t} - 1;
    return fixed_detail::saturate(r);
  }

  // round(num * 2^F / den) with the division rules of docs/numerics.md#fixed-point.
  static constexpr std::int32_t div_raw(std::int32_t num, std::int32_t den) {
    if (den == 0) {
      return num > 0 ? static_cast<std::int32_t>(fixed_detail::kRawMax)
             : num < 0 ? static_cast<std::int32_t>(fixed_detail::kRawMin)
                       : 0;
    }
    // |num| * 2^F <= 2^61: fits in 64 bits; work on magnitudes so that the
    // rounding is symmetric (ties away from zero).
    const std::uint64_t un = static_cast<std::uint64_t>(num < 0 ? -std::int64_t{num} : std::int64_t{num}) << FracBits;
    const std::uint64_t ud = static_cast<std::uint64_t>(den < 0 ? -std::int64_t{den} : std::int64_t{den});
    const std::uint64_t q = (un + ud / 2) / ud;
    const bool neg = (num < 0) != (den < 0);
    // q <= 2^61, so the signed conversion is exact before saturating.
    const std::int64_t sq = neg ? -static_cast<std::int64_t>(q) : static_cast<std::int64_t>(q);
    return fixed_detail::saturate(sq);
  }

  // round(num / den) for a raw numerator and an integer divisor.
  static constexpr std::int32_t div_wide(std::int64_t num, std::int64_t den) {
    if (den == 0) {
      return num > 0 ? static_cast<std::int32_t>(fixed_detail::kRawMax)
             : num < 0 ? static_cast<std::int32_t>(fixed_detail::kRawMin)
                       : 0;
    }
    const std::uint64_t un = static_cast<std::uint64_t>(num < 0 ? -num : num);
    const std::uint64_t ud = static_cast<std::uint64_t>(den < 0 ? -den : den);
    const std::uint64_t q = (un + ud / 2) / ud;
    const bool neg = (num < 0) != (den < 0);
    const std::int64_t sq = neg ? -static_cast<std::int64_t>(q) : static_cast<std::int64_t>(q);
    return fixed_detail::saturate(sq);
  }

  std::int32_t raw_ = 0;
};

using q16_16 = Fixed<16>;

// True for Fixed<F>: generic code branches on it where fixed point needs
// another order of operations than floating point (docs/numerics.md#fixed-point-steps).
template <class T>
struct is_fixed_point : std::false_type {};
template <int F>
struct is_fixed_point<Fixed<F>> : std::true_type {};
template <class T>
inline constexpr bool is_fixed_point_v = is_fixed_point<T>::value;

}  // namespace cvt

// The math of Fixed<F> sits next to the type, found by argument-dependent
// lookup wherever a Fixed<F> is used (docs/numerics.md#scalar-math): integer
// kernels only, each correctly rounded to within 0.5001 LSB
// (dm::max_error<Fixed<F>>), saturating at lowest()/max() instead of
// overflowing. Domain rules: sqrt(x < 0) = 0; exp saturates to max() above
// ln(max()) and rounds to 0 below -64; sign(0) = 0.
#include "cvtplant/math/detail/fixed_math.hpp"

namespace cvt {

template <int F>
constexpr Fixed<F> abs(Fixed<F> x) { return x.raw() < 0 ? -x : x; }  // -lowest() saturates to max()
template <int F>
constexpr Fixed<F> sqrt(Fixed<F> x) { return dm::detail::sqrt_fixed(x); }
template <int F>
constexpr Fixed<F> exp(Fixed<F> x) { return dm::detail::exp_fixed(x); }
template <int F>
constexpr Fixed<F> atan(Fixed<F> x) { return dm::detail::atan_fixed(x); }
template <int F>
constexpr Fixed<F> tanh(Fixed<F> x) { return dm::detail::tanh_fixed(x); }
template <int F>
constexpr Fixed<F> sin(Fixed<F> x) { return dm::detail::sin_cos_fixed(x, false); }
template <int F>
constexpr Fixed<F> cos(Fixed<F> x) { return dm::detail::sin_cos_fixed(x, true); }
template <int F>
constexpr Fixed<F> sign(Fixed<F> x) {
  return x.raw() > 0 ? Fixed<F>::one() : x.raw() < 0 ? -Fixed<F>::one() : Fixed<F>{};
}

}  // namespace cvt
