// Intel (little-endian) signal packing and the float<->raw conversions used
// by the generated codec (messages.hpp). The DBC's Intel start bit is the
// signal's least significant bit counted from bit 0 of byte 0, so a payload
// is one little-endian 64-bit word and a signal is a bit field in it
// (docs/can.md#layout).
#pragma once

#include <cstdint>

namespace cvt::can::bits {

constexpr uint64_t load_le64(const uint8_t* d) noexcept {
  uint64_t w = 0;
  for (int i = 7; i >= 0; --i) w = (w << 8) | d[i];
  return w;
}

constexpr void store_le64(uint64_t w, uint8_t* d) noexcept {
  for (int i = 0; i < 8; ++i) {
    d[i] = static_cast<uint8_t>(w & 0xFFu);
    w >>= 8;
  }
}

constexpr uint64_t mask(unsigned len) noexcept {
  return len >= 64 ? ~uint64_t{0} : ((uint64_t{1} << len) - 1u);
}

constexpr uint64_t get_unsigned(uint64_t word, unsigned start, unsigned len) noexcept {
  return (word >> start) & mask(len);
}

constexpr int64_t get_signed(uint64_t word, unsigned start, unsigned len) noexcept {
  const uint64_t u = get_unsigned(word, start, len);
  const uint64_t sign = uint64_t{1} << (len - 1u);
  // Two's-complement sign extension without relying on implementation-defined
  // right shifts of negative numbers.
  return (u & sign) ? static_cast<int64_t>(u | ~mask(len)) : static_cast<int64_t>(u);
}

constexpr uint64_t put(uint64_t word, unsigned start, unsigned len, uint64_t raw) noexcept {
  const uint64_t m = mask(len) << start;
  return (word & ~m) | ((raw << start) & m);
}

// True for every finite float; false for NaN and +-inf. Written with
// comparisons only so it needs no libm and survives any -ffinite-math-only
// mistake being caught by the NaN tests rather than silently passing.
constexpr bool is_finite(float x) noexcept {
  return x >= -3.40282347e38f && x <= 3.40282347e38f;
}

// Round half away from zero, for |x| < 2^31 (the caller has range-checked x).
// docs/can.md#rounding: truncation, the common DBC-tool bug, would bias every
// encoded value towards zero by up to one LSB.
constexpr int32_t round_to_i32(float x) noexcept {
  const int32_t t = static_cast<int32_t>(x);  // toward zero, exact in range
  // Exact: x and t share their integer part, so the fraction is representable.
  const float frac = x - static_cast<float>(t);
  if (frac >= 0.5f) return t + 1;
  if (frac <= -0.5f) return t - 1;
  return t;
}

}  // namespace cvt::can::bits
