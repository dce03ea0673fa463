#pragma once
// 64x64 -> 128-bit integer products built from 32-bit limbs. One code path on
// every target (arm-none-eabi has no __int128), so the tested path is the path
// that runs on the controller. Used by the fixed-point math and the float
// argument reduction (docs/numerics.md#detmath).
#include <cstdint>

namespace cvt::dm::detail {

struct U128 {
  std::uint64_t hi;
  std::uint64_t lo;
};

constexpr U128 mul_u64(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t m32 = 0xffffffffu;
  const std::uint64_t a0 = a & m32, a1 = a >> 32, b0 = b & m32, b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const std::uint64_t mid = (p00 >> 32) + (p01 & m32) + (p10 & m32);  // < 3 * 2^32
  return U128{p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32), (mid << 32) | (p00 & m32)};
}

constexpr U128 add_u64(U128 a, std::uint64_t b) {
  const std::uint64_t lo = a.lo + b;
  return U128{a.hi + (lo < b ? 1u : 0u), lo};
}

// a >> s for 0 <= s < 128 (caller guarantees the result fits in 64 bits).
constexpr std::uint64_t shr(U128 a, int s) {
  if (s == 0) return a.lo;
  if (s < 64) return (a.lo >> s) | (a.hi << (64 - s));
  return a.hi >> (s - 64);
}

constexpr std::uint64_t abs_u64(std::int64_t v) {
  // Two's-complement magnitude without the UB of negating INT64_MIN.
  return v < 0 ? ~static_cast<std::uint64_t>(v) + 1u : static_cast<std::uint64_t>(v);
}

// round(a * b / 2^s), ties away from zero; 1 <= s < 128, result must fit in int64.
constexpr std::int64_t mul_shift_round(std::int64_t a, std::int64_t b, int s) {
  const bool neg = (a < 0) != (b < 0);
  U128 p = mul_u64(abs_u64(a), abs_u64(b));
  // add 2^(s-1) to the 128-bit product
  if (s - 1 < 64) {
    p = add_u64(p, std::uint64_t{1} << (s - 1));
  } else {
    p.hi += std::uint64_t{1} << (s - 1 - 64);
  }
  const std::uint64_t m = shr(p, s);
  return neg ? -static_cast<std::int64_t>(m) : static_cast<std::int64_t>(m);
}

// Q60 product: values |v| < 8 stored as v * 2^60.
constexpr std::int64_t mul_q60(std::int64_t a, std::int64_t b) { return mul_shift_round(a, b, 60); }

// Arithmetic (flooring) right shift without relying on implementation-defined
// behaviour of >> on negative values before C++20.
constexpr std::int64_t asr(std::int64_t v, int s) {
  return v >= 0 ? (v >> s) : ~((~v) >> s);
}

constexpr int clz64(std::uint64_t v) {  // v != 0
  int n = 0;
  if ((v >> 32) == 0) { n += 32; v <<= 32; }
  if ((v >> 48) == 0) { n += 16; v <<= 16; }
  if ((v >> 56) == 0) { n += 8; v <<= 8; }
  if ((v >> 60) == 0) { n += 4; v <<= 4; }
  if ((v >> 62) == 0) { n += 2; v <<= 2; }
  if ((v >> 63) == 0) { n += 1; }
  return n;
}

}  // namespace cvt::dm::detail
