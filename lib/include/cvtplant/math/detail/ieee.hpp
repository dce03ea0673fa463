#pragma once
// float and double kernels of cvt::dm (docs/numerics.md#detmath).
// Only + - * / , IEEE sqrt and exact bit manipulation: every operation is
// correctly rounded, so with -ffp-contract=off the results are bit-identical
// on every IEEE-754 target. The float paths never touch double (a double
// operation is a soft-float library call on a Cortex-M4F).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "cvtplant/math/detail/coeffs.hpp"
#include "cvtplant/math/detail/wide_int.hpp"

namespace cvt::dm::detail {

inline std::uint32_t bits(float x) { std::uint32_t u; std::memcpy(&u, &x, 4); return u; }
inline std::uint64_t bits(double x) { std::uint64_t u; std::memcpy(&u, &x, 8); return u; }
inline float f32_from_bits(std::uint32_t u) { float x; std::memcpy(&x, &u, 4); return x; }
inline double f64_from_bits(std::uint64_t u) { double x; std::memcpy(&x, &u, 8); return x; }

// 2^k for normal exponents only.
inline float pow2f(int k) { return f32_from_bits(static_cast<std::uint32_t>(k + 127) << 23); }
inline double pow2d(int k) { return f64_from_bits(static_cast<std::uint64_t>(k + 1023) << 52); }

template <class T, std::size_t N>
inline T horner(const T (&c)[N], T z) {
  T acc = c[N - 1];
  for (std::size_t i = N - 1; i-- > 0;) acc = acc * z + c[i];
  return acc;
}

// ---------------------------------------------------------------- exp
// docs/numerics.md#exp: x = k*ln2 + r, exp(x) = 2^k * (1 + r + r^2 P(r)).
inline double exp_d(double x) {
  if (x != x) return x;
  if (x > 710.0) return std::numeric_limits<double>::infinity();
  if (x < -746.0) return 0.0;
  const double t = x * kLog2eD;
  const int k = static_cast<int>(t >= 0.0 ? t + 0.5 : t - 0.5);
  const double kd = static_cast<double>(k);
  const double r = (x - kd * kLn2HiD) - kd * kLn2LoD;  // first product and difference exact
  const double y = 1.0 + (r + r * r * horner(kExpD, r));
  // Scale by 2^k with one rounding at most (only the subnormal case rounds).
  if (k > 1023) return y * pow2d(1023) * 2.0;  // overflows to inf naturally
  if (k < -1022) return (y * pow2d(k + 128)) * pow2d(-128);
  return y * pow2d(k);
}

inline float exp_f(float x) {
  if (x != x) return x;
  if (x > 89.0f) return std::numeric_limits<float>::infinity();
  if (x < -104.0f) return 0.0f;
  const float t = x * kLog2eF;
  const int k = static_cast<int>(t >= 0.0f ? t + 0.5f : t - 0.5f);
  const float kf = static_cast<float>(k);
  const float r = (x - kf * kLn2HiF) - kf * kLn2LoF;
  const float y = 1.0f + (r + r * r * horner(kExpF, r));
  if (k > 127) return y * pow2f(127) * 2.0f;
  if (k < -126) return (y * pow2f(k + 64)) * pow2f(-64);
  return y * pow2f(k);
}

// ---------------------------------------------------------------- atan
// docs/numerics.md#atan: three intervals split at tan(pi/8), tan(3pi/8); at
// most one division.
template <class T>
struct AtanConst;
template <>
struct AtanConst<double> {
  static constexpr double lo = 0x1.a827999fcef32p-2;   // tan(pi/8)
  static constexpr double hi = 0x1.3504f333f9de6p+1;   // tan(3pi/8)
  static constexpr double pio4_hi = kPio4HiD, pio4_lo = kPio4LoD, pio2_hi = kPio2HiD, pio2_lo = kPio2LoD;
  static double poly(double z) { return horner(kAtanD, z); }
};
template <>
struct AtanConst<float> {
  static constexpr float lo = 0x1.a8279ap-2f;
  static constexpr float hi = 0x1.3504f4p+1f;
  static constexpr float pio4_hi = kPio4HiF, pio4_lo = kPio4LoF, pio2_hi = kPio2HiF, pio2_lo = kPio2LoF;
  static float poly(float z) { return horner(kAtanF, z); }
};

template <class T>
inline T atan_ieee(T x) {
  using C = AtanConst<T>;
  if (x != x) return x;
  const T ax = x < T(0) ? -x : x;
  if (ax == T(0)) return x;  // keeps the sign of zero
  T base_hi = T(0), base_lo = T(0), t = ax;
  if (ax > C::hi) {  // atan(x) = pi/2 - atan(1/x); also covers +inf (t = -0)
    t = T(-1) / ax;
    base_hi = C::pio2_hi;
    base_lo = C::pio2_lo;
  } else if (ax > C::lo) {  // atan(x) = pi/4 + atan((x-1)/(x+1))
    t = (ax - T(1)) / (ax + T(1));
    base_hi = C::pio4_hi;
    base_lo = C::pio4_lo;
  }
  const T z = t * t;
  const T y = base_hi + (base_lo + (t + t * z * C::poly(z)));
  return x < T(0) ? -y : y;
}

// ---------------------------------------------------------------- tanh
// docs/numerics.md#tanh: odd polynomial below atanh(1/2), then
// 1 - 2/(exp(2|x|)+1) (no cancellation there since the result is >= 1/2),
// then exactly +-1 once 1 - tanh is below half an ulp of 1.
template <class T>
struct TanhConst;
template <>
struct TanhConst<double> {
  static constexpr double poly_max = 0.5493;  // < atanh(1/2) = 0.549306...
  static constexpr double one_min = 22.0;      // 2 e^-44 < 2^-54
  static double poly(double z) { return horner(kTanhD, z); }
  static double ex(double v) { return exp_d(v); }
};
template <>
struct TanhConst<float> {
  static constexpr float poly_max = 0.5493f;
  static constexpr float one_min = 10.0f;  // 2 e^-20 < 2^-25
  static float poly(float z) { return horner(kTanhF, z); }
  static float ex(float v) { return exp_f(v); }
};

template <class T>
inline T tanh_ieee(T x) {
  using C = TanhConst<T>;
  if (x != x) return x;
  const T ax = x < T(0) ? -x : x;
  if (ax == T(0)) return x;
  T y;
  if (ax < C::poly_max) {
    const T z = ax * ax;
    y = ax + ax * z * C::poly(z);
  } else if (ax < C::one_min) {
    y = T(1) - T(2) / (C::ex(ax + ax) + T(1));
  } else {
    y = T(1);
  }
  return x < T(0) ? -y : y;
}

// ---------------------------------------------------------------- sin / cos
// docs/numerics.md#sin-cos. Kernels on |r| <= pi/4 (+ small margin); the
// reduced argument is r_hi + r_lo with |r_lo| <= ulp(r_hi)/2.
inline double sin_kernel_d(double hi, double lo) {
  const double z = hi * hi;
  // sin(hi + lo) = sin(hi) + lo*cos(hi) + O(lo^2), cos(hi) ~ 1 - z/2
  return hi + (hi * z * horner(kSinD, z) + lo * (1.0 - 0.5 * z));
}
inline double cos_kernel_d(double hi, double lo) {
  const double z = hi * hi;
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  // (1 - w) - hz recovers the rounding error of w exactly (Sterbenz).
  return w + (((1.0 - w) - hz) + (z * z * horner(kCosD, z) - hi * lo));
}
inline float sin_kernel_f(float r) {
  const float z = r * r;
  return r + r * z * horner(kSinF, z);
}
inline float cos_kernel_f(float r) {
  const float z = r * r;
  const float hz = 0.5f * z;
  const float w = 1.0f - hz;
  return w + (((1.0f - w) - hz) + z * z * horner(kCosF, z));
}

// Error-free a + b = s + e (Knuth TwoSum, no branch, no magnitude condition).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// Below this |x| the Cody-Waite reduction is used: k = round(|x| 2/pi) < 2^20
// keeps k*P1, k*P2, k*P3 exact. Above it, Payne-Hanek.
inline constexpr double kCodyWaiteMaxD = 0x1.921fb5p+20;  // ~1.647e6, just under 2^20 * pi/2

// |x| = k*pi/2 + (hi + lo), for pi/4 <= |x| < kCodyWaiteMaxD.
inline int reduce_cody_waite_d(double ax, double& hi, double& lo) {
  const int k = static_cast<int>(ax * kTwoOverPiD + 0.5);
  const double kd = static_cast<double>(k);
  const double a = ax - kd * kPio2P1;  // exact (Sterbenz; k*P1 exact)
  double s1, e1, s2, e2;
  two_sum(a, -(kd * kPio2P2), s1, e1);  // k*P2 exact
  two_sum(s1, -(kd * kPio2P3), s2, e2);  // k*P3 exact
  const double tail = (e1 + e2) - kd * kPio2P4;
  hi = s2 + tail;
  lo = tail - (hi - s2);
  return k & 3;
}

// Window of 2/pi: the bits with weight 2^-i0 .. 2^-(i0 + 32*N - 1), as N words
// most significant first. Bits of weight >= 2^-(e-2) times an integer scaled by
// 2^e are multiples of 4 and cannot change the quadrant, so they are skipped.
template <std::size_t N>
inline void two_over_pi_window(int i0, std::uint32_t (&w)[N]) {
  const int b = i0 - 1, q = b >> 5, s = b & 31;
  for (int j = 0; j < static_cast<int>(N); ++j) {
    const std::uint32_t a0 = kTwoOverPiBits[q + j];
    const std::uint32_t a1 = kTwoOverPiBits[q + j + 1];
    w[j] = s == 0 ? a0 : (a0 << s) | (a1 >> (32 - s));
  }
}

// Payne-Hanek for double, every finite |x| >= pi/4 (used above kCodyWaiteMaxD).
// |x| = m 2^e; P = m * window is |x| * 2/pi (mod 4) with the binary point at
// bit `point`; the 128 bits below it are the fraction f, r = f * pi/2.
inline int reduce_payne_hanek_d(double ax, double& hi, double& lo) {
  const std::uint64_t u = bits(ax);
  const int e = static_cast<int>(u >> 52) - 1075;
  const std::uint64_t m = (u & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
  const int i0 = e - 1 > 1 ? e - 1 : 1;
  std::uint32_t w[6];
  two_over_pi_window(i0, w);
  // 64 x 192 -> 256-bit schoolbook product, little-endian limbs.
  std::uint32_t res[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  const std::uint32_t ml[2] = {static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(m >> 32)};
  for (int i = 0; i < 2; ++i) {
    std::uint64_t carry = 0;
    for (int j = 0; j < 6; ++j) {
      const std::uint64_t t = std::uint64_t{ml[i]} * w[5 - j] + res[i + j] + carry;
      res[i + j] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    res[i + 6] = static_cast<std::uint32_t>(carry);
  }
  auto limb = [&](int i) -> std::uint64_t { return i < 8 ? res[i] : 0u; };
  auto get64 = [&](int lowbit) -> std::uint64_t {  // bits [lowbit, lowbit + 63]
    const int wd = lowbit >> 5, sh = lowbit & 31;
    const std::uint64_t v = limb(wd) | (limb(wd + 1) << 32);
    return sh == 0 ? v : (v >> sh) | (limb(wd + 2) << (64 - sh));
  };
  const int point = i0 + 191 - e;  // 190 .. 245
  int quadrant = static_cast<int>(get64(point) & 3u);
  std::uint64_t fh = get64(point - 64), fl = get64(point - 128);
  const bool neg = (fh >> 63) != 0;
  if (neg) {  // fraction >= 1/2: round k up, f -= 1 (two's complement negate)
    ++quadrant;
    fl = ~fl + 1u;
    fh = ~fh + (fl == 0 ? 1u : 0u);
  }
  // R = floor(|f| 2^128 * (pi/2) 2^127 / 2^128): |r| = R * 2^-127.
  const U128 A = mul_u64(fh, kPio2Q127Hi), B = mul_u64(fh, kPio2Q127Lo), C = mul_u64(fl, kPio2Q127Hi);
  const U128 D = mul_u64(fl, kPio2Q127Lo);
  U128 mid = add_u64(U128{0, B.lo}, C.lo);
  mid = add_u64(mid, D.hi);
  U128 R = add_u64(A, B.hi);
  R = add_u64(R, C.hi);
  R = add_u64(R, mid.hi);
  // Normalise and split into a 53-bit head and a tail (docs/numerics.md#sin-cos).
  if (R.hi == 0 && R.lo == 0) {
    hi = 0.0;
    lo = 0.0;
  } else {
    const int lz = R.hi != 0 ? clz64(R.hi) : 64 + clz64(R.lo);
    U128 Nn = R;
    if (lz >= 64) {
      Nn = U128{R.lo << (lz - 64), 0};
    } else if (lz > 0) {
      Nn = U128{(R.hi << lz) | (R.lo >> (64 - lz)), R.lo << lz};
    }
    const std::uint64_t head = Nn.hi >> 11;                              // 53 bits
    const std::uint64_t tail = ((Nn.hi & 0x7ffu) << 53) | (Nn.lo >> 11);  // next 64 bits
    const double h = static_cast<double>(head) * pow2d(-52 - lz);
    const double t = static_cast<double>(tail) * pow2d(-116 - lz);
    hi = h + t;
    lo = t - (hi - h);
  }
  if (neg) {
    hi = -hi;
    lo = -lo;
  }
  return quadrant & 3;
}

// Payne-Hanek for float, every finite |x| >= pi/4: exact integer arithmetic,
// no double, no helper calls. Returns the quadrant and r in [-pi/4, pi/4].
inline int reduce_payne_hanek_f(float ax, float& r) {
  const std::uint32_t u = bits(ax);
  const int e = static_cast<int>(u >> 23) - 150;  // ax = m * 2^e
  const std::uint64_t m = (u & 0x7fffffu) | 0x800000u;
  const int i0 = e - 1 > 1 ? e - 1 : 1;
  std::uint32_t w[3];
  two_over_pi_window(i0, w);
  // 24 x 96 -> 120-bit product.
  const std::uint64_t p2 = m * w[2], p1 = m * w[1], p0 = m * w[0];
  const std::uint64_t c1 = (p2 >> 32) + (p1 & 0xffffffffu);
  const std::uint64_t c0 = (c1 >> 32) + (p1 >> 32) + (p0 & 0xffffffffu);
  const std::uint64_t top = (c0 >> 32) + (p0 >> 32);
  const U128 P{(top << 32) | (c0 & 0xffffffffu), ((c1 & 0xffffffffu) << 32) | (p2 & 0xffffffffu)};
  const int point = i0 + 95 - e;  // 94 .. 120
  int quadrant = static_cast<int>(shr(P, point) & 3u);
  // The 64 fraction bits just below the binary point, read as signed: a
  // fraction >= 1/2 becomes f - 1 and k rounds up.
  const std::int64_t f = static_cast<std::int64_t>((P.hi << (128 - point)) | (P.lo >> (point - 64)));
  if (f < 0) ++quadrant;
  // |r| * 2^63 = (|f| 2^-64) (pi/2 2^63), truncated: error <= 2^-63 absolute.
  const std::uint64_t R = mul_u64(abs_u64(f), kPio2Q63).hi;
  float mag = 0.0f;
  if (R != 0) {
    // Correctly rounded (to nearest even) conversion of R * 2^-63 to float.
    const int lz = clz64(R);
    const std::uint64_t n = R << lz;  // |r| = (n / 2^63) * 2^-lz
    std::uint64_t mant = n >> 40;     // 24 significant bits
    const std::uint64_t rest = n & ((std::uint64_t{1} << 40) - 1);
    const std::uint64_t half = std::uint64_t{1} << 39;
    if (rest > half || (rest == half && (mant & 1u))) ++mant;
    int ex = -lz;
    if (mant >> 24) {
      mant >>= 1;
      ++ex;
    }
    mag = f32_from_bits((static_cast<std::uint32_t>(ex + 127) << 23) |
                        (static_cast<std::uint32_t>(mant) & 0x7fffffu));
  }
  r = f < 0 ? -mag : mag;
  return quadrant & 3;
}

inline double sin_cos_d(double x, bool want_cos) {
  if (!(x - x == 0.0)) return x - x;  // NaN for NaN and +-inf
  const double ax = __builtin_fabs(x);
  double hi = ax, lo = 0.0;
  int n = 0;
  if (ax >= kPio4HiD) {
    n = ax < kCodyWaiteMaxD ? reduce_cody_waite_d(ax, hi, lo) : reduce_payne_hanek_d(ax, hi, lo);
  }
  double y;
  if (want_cos) {
    switch (n) {
      case 0: y = cos_kernel_d(hi, lo); break;
      case 1: y = -sin_kernel_d(hi, lo); break;
      case 2: y = -cos_kernel_d(hi, lo); break;
      default: y = sin_kernel_d(hi, lo); break;
    }
    return y;
  }
  switch (n) {
    case 0: y = sin_kernel_d(hi, lo); break;
    case 1: y = cos_kernel_d(hi, lo); break;
    case 2: y = -sin_kernel_d(hi, lo); break;
    default: y = -cos_kernel_d(hi, lo); break;
  }
  return (bits(x) >> 63) ? -y : y;  // sign bit, so sin(-0) = -0
}

inline float sin_cos_f(float x, bool want_cos) {
  if (!(x - x == 0.0f)) return x - x;
  const float ax = __builtin_fabsf(x);
  float r = ax;
  int n = 0;
  if (ax >= kPio4HiF) n = reduce_payne_hanek_f(ax, r);
  float y;
  if (want_cos) {
    switch (n) {
      case 0: y = cos_kernel_f(r); break;
      case 1: y = -sin_kernel_f(r); break;
      case 2: y = -cos_kernel_f(r); break;
      default: y = sin_kernel_f(r); break;
    }
    return y;
  }
  switch (n) {
    case 0: y = sin_kernel_f(r); break;
    case 1: y = cos_kernel_f(r); break;
    case 2: y = -sin_kernel_f(r); break;
    default: y = -cos_kernel_f(r); break;
  }
  return (bits(x) >> 31) ? -y : y;
}

}  // namespace cvt::dm::detail
