// Target tests of the Cortex-M port itself: the heap-free formatter and the
// hard-float code generation the core relies on. Expected strings and bit
// patterns are worked out by hand (IEEE-754 binary32/binary64, round to
// nearest even), not copied from a run.
#include <cstdint>
#include <cstring>
#include <limits>

#include "cvtplant/port/console.hpp"
#include "harness.hpp"

using namespace cvt::port;

namespace {
const char* fmt_f(double v, int decimals) {
  static char buf[48];
  format_f64(buf, sizeof buf, v, decimals);
  return buf;
}
std::uint32_t bits_of(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
}  // namespace

CVT_TARGET_TEST(port_format_integers) {
  char buf[32];
  CHECK_EQ(format_i64(buf, sizeof buf, 0), 1u);
  CHECK_STR_EQ(buf, "0");
  format_i64(buf, sizeof buf, std::numeric_limits<std::int64_t>::min());
  CHECK_STR_EQ(buf, "-9223372036854775808");
  format_i64(buf, sizeof buf, std::numeric_limits<std::int32_t>::min());
  CHECK_STR_EQ(buf, "-2147483648");
  format_u64(buf, sizeof buf, std::numeric_limits<std::uint64_t>::max());
  CHECK_STR_EQ(buf, "18446744073709551615");
  format_hex(buf, sizeof buf, 0xDEADBEEFu, 8);
  CHECK_STR_EQ(buf, "0xDEADBEEF");
  format_hex(buf, sizeof buf, 0x1u, 4);
  CHECK_STR_EQ(buf, "0x0001");
  format_hex(buf, sizeof buf, 0x123456789ABCDEF0ull, 16);
  CHECK_STR_EQ(buf, "0x123456789ABCDEF0");
}

CVT_TARGET_TEST(port_format_truncates_never_overflows) {
  char buf[8];
  std::memset(buf, 'X', sizeof buf);
  // cap 4: three characters and the NUL; the return value counts what fits.
  CHECK_EQ(format_u64(buf, 4, 12345u), 3u);
  CHECK_STR_EQ(buf, "123");
  CHECK_EQ(buf[4], 'X');  // untouched beyond cap
  CHECK_EQ(format_u64(buf, 0, 7u), 0u);
}

CVT_TARGET_TEST(port_format_floats) {
  CHECK_STR_EQ(fmt_f(3.14159, 3), "3.142");
  CHECK_STR_EQ(fmt_f(-2.5, 0), "-3");      // half away from zero
  CHECK_STR_EQ(fmt_f(0.9996, 3), "1.000");  // rounding carries into the integer
  CHECK_STR_EQ(fmt_f(-0.0, 2), "-0.00");
  CHECK_STR_EQ(fmt_f(123456789.0, 1), "123456789.0");
  CHECK_STR_EQ(fmt_f(1e20, 3), "1.000000e+20");
  CHECK_STR_EQ(fmt_f(std::numeric_limits<double>::quiet_NaN(), 3), "nan");
  CHECK_STR_EQ(fmt_f(std::numeric_limits<double>::infinity(), 3), "inf");
  CHECK_STR_EQ(fmt_f(-std::numeric_limits<double>::infinity(), 3), "-inf");
}

// The FPU is on (Reset_Handler sets CPACR) and float arithmetic rounds as
// IEEE binary32: 1/3 = 0x3EAAAAAB, 0.1f = 0x3DCCCCCD.
CVT_TARGET_TEST(port_fpu_ieee_single) {
  volatile float one = 1.0f, three = 3.0f, tenth = 0.1f;
  CHECK_EQ(bits_of(one / three), 0x3EAAAAABu);
  CHECK_EQ(bits_of(tenth), 0x3DCCCCCDu);
  volatile float two = 2.0f;
  const float r = __builtin_sqrtf(two);
  CHECK_EQ(bits_of(r), 0x3FB504F3u);  // correctly rounded sqrt(2)
}

// double is soft-float on the M4F (libgcc) and hardware on the M7; both must
// give the IEEE result: 0.1 + 0.2 = 0x3FD3333333333334.
CVT_TARGET_TEST(port_double_ieee) {
  volatile double a = 0.1, b = 0.2;
  CHECK_EQ(bits_of(a + b), 0x3FD3333333333334ull);
}

// -ffp-contract=off must hold on the target: with a = b = 1 + 2^-13 and
// c = -(1 + 2^-12), a*b = 1 + 2^-12 + 2^-26 rounds to 1 + 2^-12, so the
// unfused a*b + c is exactly 0, while a fused multiply-add gives 2^-26.
CVT_TARGET_TEST(port_no_fma_contraction) {
  volatile float a = 1.0f + 0x1p-13f, b = 1.0f + 0x1p-13f, c = -(1.0f + 0x1p-12f);
  const float r = a * b + c;
  CHECK_EQ(bits_of(r), 0u);
}
