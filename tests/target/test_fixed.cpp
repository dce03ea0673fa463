// Fixed point (lib/include/cvtplant/scalar/fixed.hpp) on the target: the
// 64-bit intermediates and divisions run through the Cortex-M code paths
// (umull/smull, libgcc's __aeabi_ldivmod), so the rules of
// docs/numerics.md#fixed-point are re-checked here, not only on x86-64.
// Inputs go through volatile so nothing is folded at compile time; expected
// raw values are worked out by hand from value = raw * 2^-16.
#include <cstdint>
#include <cstring>
#include <limits>

#include "cvtplant/scalar/fixed.hpp"
#include "harness.hpp"

using cvt::q16_16;

namespace {
constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
constexpr std::int32_t kMin = std::numeric_limits<std::int32_t>::min();

q16_16 raw(std::int32_t r) {
  volatile std::int32_t v = r;
  return q16_16::from_raw(v);
}
double dbl(double d) {
  volatile double v = d;
  return v;
}
float flt(float f) {
  volatile float v = f;
  return v;
}
}  // namespace

CVT_TARGET_TEST(fixed_conversions_round_half_away) {
  CHECK_EQ(q16_16(dbl(1.5)).raw(), 98304);       // 1.5 * 2^16
  CHECK_EQ(q16_16(dbl(-2.5)).raw(), -163840);
  CHECK_EQ(q16_16(dbl(0x1p-17)).raw(), 1);       // exactly half an LSB -> away from zero
  CHECK_EQ(q16_16(dbl(-0x1p-17)).raw(), -1);
  CHECK_EQ(q16_16(flt(0x1p-17f)).raw(), 1);      // float path, same rule
  CHECK_EQ(q16_16(flt(-0x1p-17f)).raw(), -1);
  CHECK_EQ(q16_16(dbl(0x1p-18)).raw(), 0);       // a quarter LSB rounds to 0
}

CVT_TARGET_TEST(fixed_conversions_saturate_and_nan) {
  CHECK_EQ(q16_16(dbl(std::numeric_limits<double>::quiet_NaN())).raw(), 0);
  CHECK_EQ(q16_16(dbl(1e10)).raw(), kMax);
  CHECK_EQ(q16_16(dbl(-std::numeric_limits<double>::infinity())).raw(), kMin);
  CHECK_EQ(q16_16(flt(std::numeric_limits<float>::infinity())).raw(), kMax);
  volatile int big = 40000, edge = -32768, below = -32769;
  CHECK_EQ(q16_16(big).raw(), kMax);    // 40000 > 32767.99998
  CHECK_EQ(q16_16(edge).raw(), kMin);   // -32768 is exactly representable
  CHECK_EQ(q16_16(below).raw(), kMin);
  // 2^-16 as float is 0x37800000.
  const float lsb = raw(1).to_float();
  std::uint32_t bits;
  std::memcpy(&bits, &lsb, sizeof bits);
  CHECK_EQ(bits, 0x37800000u);
}

CVT_TARGET_TEST(fixed_arithmetic_and_saturation) {
  CHECK_EQ((raw(98304) * raw(163840)).raw(), 245760);  // 1.5 * 2.5 = 3.75
  CHECK_EQ((raw(1) * raw(32768)).raw(), 1);             // 2^-17 -> ties away
  CHECK_EQ((raw(-1) * raw(32768)).raw(), -1);
  CHECK_EQ((q16_16::max() * raw(2 << 16)).raw(), kMax);
  CHECK_EQ((q16_16::lowest() * raw(2 << 16)).raw(), kMin);
  CHECK_EQ((raw(kMax) + raw(65536)).raw(), kMax);
  CHECK_EQ((raw(kMin) - raw(65536)).raw(), kMin);
  CHECK_EQ((-raw(kMin)).raw(), kMax);  // the one negation that does not fit
}

CVT_TARGET_TEST(fixed_division_rules) {
  CHECK_EQ((raw(65536) / raw(3 << 16)).raw(), 21845);    // 65536/3 = 21845.33
  CHECK_EQ((raw(-65536) / raw(3 << 16)).raw(), -21845);
  CHECK_EQ((raw(2 << 16) / raw(3 << 16)).raw(), 43691);  // 43690.67
  CHECK_EQ((raw(65536) / raw(0)).raw(), kMax);
  CHECK_EQ((raw(-65536) / raw(0)).raw(), kMin);
  CHECK_EQ((raw(0) / raw(0)).raw(), 0);
  volatile int three = 3;
  CHECK_EQ((raw(65536) / three).raw(), 21845);
  CHECK_EQ((raw(kMax) * three).raw(), kMax);
}
