// cvt::Fixed<F>: conversions, saturation, rounding, division rules and the
// Eigen integration (docs/numerics.md#fixed-point).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <Eigen/Dense>

#include "cvtplant/scalar/fixed.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"

using cvt::Fixed;
using cvt::q16_16;

namespace {

constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
constexpr std::int32_t kMin = std::numeric_limits<std::int32_t>::min();
constexpr double kLsb = 1.0 / 65536.0;

q16_16 R(std::int32_t r) { return q16_16::from_raw(r); }

// Independent reference: round(n / d) half away from zero, with the division
// rules of the docs, computed from an exact integer quotient and remainder.
std::int64_t ref_div_round(std::int64_t n, std::int64_t d) {
  std::int64_t q = n / d, rem = n % d;  // C++ truncates toward zero
  const std::int64_t arem = rem < 0 ? -rem : rem, ad = d < 0 ? -d : d;
  if (2 * arem >= ad) q += ((n < 0) != (d < 0)) ? -1 : 1;
  return q;
}
std::int32_t sat(std::int64_t v) {
  return v > kMax ? kMax : v < kMin ? kMin : static_cast<std::int32_t>(v);
}

struct Lcg {  // deterministic, so a failure reproduces
  std::uint64_t s = 0x9E3779B97F4A7C15u;
  std::uint32_t next() {
    s = s * 6364136223846793005u + 1442695040888963407u;
    return static_cast<std::uint32_t>(s >> 32);
  }
};

}  // namespace

// Compile-time use: the whole type is constexpr.
static_assert(q16_16().raw() == 0);
static_assert(q16_16(1).raw() == 65536);
static_assert(q16_16(0.5).raw() == 32768);
static_assert((q16_16(3) * q16_16(0.5)).raw() == 98304);
static_assert((q16_16(1) / q16_16(4)).raw() == 16384);
static_assert(q16_16::max().raw() == kMax && q16_16::lowest().raw() == kMin);
static_assert(q16_16::epsilon().raw() == 1 && q16_16::min_positive().raw() == 1);

TEST_CASE("fixed: names") {
  CHECK(std::strcmp(q16_16::kName, "q16.16") == 0);
  CHECK(std::strcmp(Fixed<8>::kName, "q24.8") == 0);
  CHECK(std::strcmp(Fixed<30>::kName, "q2.30") == 0);
  CHECK(std::strcmp(Fixed<1>::kName, "q31.1") == 0);
}

TEST_CASE("fixed: from double rounds to nearest, ties away from zero") {
  CHECK(q16_16(0.5 * kLsb).raw() == 1);
  CHECK(q16_16(-0.5 * kLsb).raw() == -1);
  CHECK(q16_16(1.5 * kLsb).raw() == 2);
  CHECK(q16_16(-1.5 * kLsb).raw() == -2);
  CHECK(q16_16(2.5 * kLsb).raw() == 3);  // not banker's rounding
  CHECK(q16_16(0.49999999 * kLsb).raw() == 0);
  CHECK(q16_16(-0.49999999 * kLsb).raw() == 0);
  CHECK(q16_16(1.0 + 0.25 * kLsb).raw() == 65536);
  CHECK(q16_16(-1.0 - 0.75 * kLsb).raw() == -65537);
  CHECK(q16_16(3.14159265358979).to_double() == doctest::Approx(3.14159265358979).epsilon(0.5 * kLsb / 3.14));
}

TEST_CASE("fixed: from double saturates and maps NaN/inf as documented") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(q16_16(std::numeric_limits<double>::quiet_NaN()).raw() == 0);
  CHECK(q16_16(inf).raw() == kMax);
  CHECK(q16_16(-inf).raw() == kMin);
  CHECK(q16_16(1e300).raw() == kMax);
  CHECK(q16_16(-1e300).raw() == kMin);
  CHECK(q16_16(32768.0).raw() == kMax);            // one past max
  CHECK(q16_16(-32768.0).raw() == kMin);           // exactly lowest
  CHECK(q16_16(32768.0 - 0.6 * kLsb).raw() == kMax);  // rounds to max exactly
  CHECK(q16_16(32768.0 - 0.5 * kLsb).raw() == kMax);  // tie rounds away, past max: saturates
  CHECK(q16_16(32768.0 - 1.6 * kLsb).raw() == kMax - 1);
  CHECK(q16_16(-32768.0 - 0.4 * kLsb).raw() == kMin);
  CHECK(q16_16(-32768.0 - 0.6 * kLsb).raw() == kMin);
  CHECK(q16_16(std::numeric_limits<double>::denorm_min()).raw() == 0);
}

TEST_CASE("fixed: from float follows the same rules in float") {
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(q16_16(0.5f * static_cast<float>(kLsb)).raw() == 1);
  CHECK(q16_16(-0.5f * static_cast<float>(kLsb)).raw() == -1);
  CHECK(q16_16(2.5f * static_cast<float>(kLsb)).raw() == 3);
  CHECK(q16_16(std::numeric_limits<float>::quiet_NaN()).raw() == 0);
  CHECK(q16_16(inf).raw() == kMax);
  CHECK(q16_16(-inf).raw() == kMin);
  CHECK(q16_16(32768.0f).raw() == kMax);
  CHECK(q16_16(-32768.0f).raw() == kMin);
  CHECK(q16_16(32767.99f).raw() == 2147483008);  // 32767.99f is exactly representable
  CHECK(q16_16(1.25f).raw() == 81920);
}

TEST_CASE("fixed: from integers of any width saturates") {
  CHECK(q16_16(32767).raw() == 32767 * 65536);
  CHECK(q16_16(32768).raw() == kMax);
  CHECK(q16_16(-32768).raw() == kMin);
  CHECK(q16_16(-32769).raw() == kMin);
  CHECK(q16_16(1000000000000LL).raw() == kMax);
  CHECK(q16_16(-1000000000000LL).raw() == kMin);
  CHECK(q16_16(4000000000u).raw() == kMax);
  CHECK(q16_16(static_cast<unsigned char>(7)).raw() == 7 * 65536);
  CHECK(Fixed<30>(1).raw() == (1 << 30));
  CHECK(Fixed<30>(2).raw() == kMax);
  CHECK(Fixed<30>(-2).raw() == kMin);
}

TEST_CASE("fixed: conversions out are exact / correctly rounded") {
  CHECK(R(kMin).to_double() == -32768.0);
  CHECK(R(kMax).to_double() == 32768.0 - kLsb);
  CHECK(R(1).to_double() == kLsb);
  CHECK(static_cast<double>(R(-3)) == -3 * kLsb);
  CHECK(R(kMax).to_float() == 32768.0f);                 // 31 bits -> nearest float
  CHECK(R(65536 + 1).to_float() == 1.0f + 0x1p-16f);     // exact (17 bits)
  CHECK(static_cast<float>(R(kMin)) == -32768.0f);
}

TEST_CASE("fixed: add/sub/neg saturate, INT_MIN negation included") {
  CHECK((R(kMax) + R(1)).raw() == kMax);
  CHECK((R(kMax) + R(kMax)).raw() == kMax);
  CHECK((R(kMin) - R(1)).raw() == kMin);
  CHECK((R(kMin) + R(kMin)).raw() == kMin);
  CHECK((R(kMin) + R(kMax)).raw() == -1);
  CHECK((R(0) - R(kMin)).raw() == kMax);
  CHECK((-R(kMin)).raw() == kMax);
  CHECK((-R(kMax)).raw() == kMin + 1);
  CHECK((-R(0)).raw() == 0);
  CHECK((+R(5)).raw() == 5);
  q16_16 a = R(kMax - 2);
  a += R(10);
  CHECK(a.raw() == kMax);
  a -= R(kMax);
  CHECK(a.raw() == 0);
}

TEST_CASE("fixed: multiplication rounds to nearest (ties away) and saturates") {
  const q16_16 half(0.5);
  CHECK((R(1) * half).raw() == 1);    // 0.5 LSB -> 1
  CHECK((R(-1) * half).raw() == -1);  // -0.5 LSB -> -1
  CHECK((R(3) * half).raw() == 2);    // 1.5 -> 2
  CHECK((R(1) * q16_16(0.25)).raw() == 0);  // 0.25 LSB -> 0
  CHECK((R(kMax) * R(kMax)).raw() == kMax);
  CHECK((R(kMax) * R(kMin)).raw() == kMin);
  CHECK((R(kMin) * R(kMin)).raw() == kMax);  // |product| = 2^62: widest case
  CHECK((R(kMin) * q16_16(-1)).raw() == kMax);
  CHECK((R(kMin) * q16_16(1)).raw() == kMin);
  CHECK((q16_16(181) * q16_16(181)).raw() == 32761 * 65536);  // fits; 181.1^2 does not
  CHECK((q16_16(181) * q16_16(181.1)).raw() == kMax);
  q16_16 m(3);
  m *= q16_16(-2.5);
  CHECK(m.raw() == -7.5 * 65536);
}

TEST_CASE("fixed: multiplication is the correctly rounded product (random, 0.5 LSB)") {
  // Exact product a*b*2^-16 rounded half away from zero equals the result
  // bit for bit, i.e. the error bound is 0.5 LSB and ties go away from zero.
  Lcg g;
  for (int i = 0; i < 200000; ++i) {
    const std::int32_t a = static_cast<std::int32_t>(g.next()) >> (g.next() % 24);
    const std::int32_t b = static_cast<std::int32_t>(g.next()) >> (g.next() % 24);
    const std::int64_t p = std::int64_t{a} * b;
    const std::int32_t expect = sat(ref_div_round(p, 65536));
    REQUIRE((R(a) * R(b)).raw() == expect);
  }
}

TEST_CASE("fixed: division rounds to nearest, saturates, and defines x/0") {
  CHECK((q16_16(1) / q16_16(3)).raw() == 21845);   // 21845.33
  CHECK((q16_16(2) / q16_16(3)).raw() == 43691);   // 43690.67
  CHECK((q16_16(-2) / q16_16(3)).raw() == -43691);
  CHECK((R(1) / q16_16(2)).raw() == 1);    // 0.5 LSB tie -> away from zero
  CHECK((R(-1) / q16_16(2)).raw() == -1);
  CHECK((R(1) / q16_16(-2)).raw() == -1);
  CHECK((R(5) / R(0)).raw() == kMax);
  CHECK((R(-5) / R(0)).raw() == kMin);
  CHECK((R(0) / R(0)).raw() == 0);
  CHECK((R(kMin) / R(0)).raw() == kMin);
  CHECK((R(kMin) / q16_16(-1)).raw() == kMax);
  CHECK((R(kMax) / R(1)).raw() == kMax);
  CHECK((R(kMin) / R(-1)).raw() == kMax);
  CHECK((R(kMin) / R(1)).raw() == kMin);
  CHECK((q16_16(1) / R(kMin)).raw() == -2);  // 2^32 / -2^31 exactly
  q16_16 d(10);
  d /= q16_16(4);
  CHECK(d.raw() == 2.5 * 65536);
}

TEST_CASE("fixed: division is the correctly rounded quotient (random, 0.5 LSB)") {
  Lcg g;
  for (int i = 0; i < 200000; ++i) {
    const std::int32_t a = static_cast<std::int32_t>(g.next()) >> (g.next() % 28);
    std::int32_t b = static_cast<std::int32_t>(g.next()) >> (g.next() % 31);
    if (b == 0) b = 1;
    const std::int32_t expect = sat(ref_div_round(std::int64_t{a} * 65536, b));
    REQUIRE((R(a) / R(b)).raw() == expect);
  }
}

TEST_CASE("fixed: mixed operations with int") {
  CHECK((q16_16(1.5) * 3).raw() == 4.5 * 65536);
  CHECK((3 * q16_16(1.5)).raw() == 4.5 * 65536);
  CHECK((q16_16(20000) * 2).raw() == kMax);
  CHECK((q16_16(-20000) * 2).raw() == kMin);
  CHECK((R(kMin) * -1).raw() == kMax);
  CHECK((R(7) / 2).raw() == 4);   // 3.5 -> 4
  CHECK((R(-7) / 2).raw() == -4);
  CHECK((R(7) / 0).raw() == kMax);
  CHECK((R(-7) / 0).raw() == kMin);
  CHECK((R(0) / 0).raw() == 0);
  CHECK((R(kMin) / -1).raw() == kMax);
  q16_16 a(1);
  a *= 5;
  a /= 2;
  CHECK(a.raw() == 2.5 * 65536);
}

TEST_CASE("fixed: comparisons follow the raw order") {
  CHECK(R(kMin) < R(kMin + 1));
  CHECK(R(kMax) > R(kMax - 1));
  CHECK(R(-1) < R(0));
  CHECK(R(3) <= R(3));
  CHECK(R(3) >= R(3));
  CHECK(R(3) == R(3));
  CHECK(R(3) != R(4));
  CHECK_FALSE(R(4) < R(3));
}

TEST_CASE("fixed: other formats follow the same rules") {
  using q8 = Fixed<8>;
  CHECK(q8(0.5 / 256).raw() == 1);
  CHECK((q8(100) * q8(100)).raw() == 10000 * 256);
  CHECK((q8(1) / q8(3)).raw() == 85);
  using q30 = Fixed<30>;
  CHECK((q30(0.5) * q30(0.5)).raw() == (1 << 28));
  CHECK((q30(1) / q30(0.5)).raw() == kMax);  // 2 does not fit in q2.30
  CHECK((-q30::lowest()).raw() == kMax);
}

// --- Eigen --------------------------------------------------------------

TEST_CASE("fixed + Eigen: 4x4 multiply within the per-element rounding bound") {
  // Each element is a sum of 4 products, each rounded once (0.5 LSB) and
  // summed exactly (no saturation here): |error| <= 4 * 0.5 = 2 LSB.
  Eigen::Matrix4d Ad;
  Ad << 1.25, -0.5, 0.75, 0.125, -2.0, 3.5, 0.3, -0.7, 0.9, 0.01, -1.1, 2.2, 0.33, -0.44, 0.55, 1.66;
  Eigen::Matrix4d Bd;
  Bd << 0.2, 1.1, -0.3, 0.4, 0.5, -0.6, 0.7, -0.8, 1.9, 0.1, 0.0, 2.5, -1.0, 0.25, 0.125, 0.0625;
  Eigen::Matrix<q16_16, 4, 4> A, B;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      A(i, j) = q16_16(Ad(i, j));
      B(i, j) = q16_16(Bd(i, j));
    }
  // Reference from the already-quantised inputs, so only the product's own
  // rounding is measured.
  Eigen::Matrix4d Aq, Bq;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      Aq(i, j) = A(i, j).to_double();
      Bq(i, j) = B(i, j).to_double();
    }
  const Eigen::Matrix<q16_16, 4, 4> C = A * B;
  const Eigen::Matrix4d Cd = Aq * Bq;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) CHECK(std::abs(C(i, j).to_double() - Cd(i, j)) <= 2.0 * kLsb);
  const Eigen::Matrix<q16_16, 4, 4> S = A + B - A;
  CHECK((S.array() == B.array()).all());
}

TEST_CASE("fixed + Eigen: partialPivLu().solve() of a well-conditioned 4x4 system") {
  // Diagonally dominant, condition number ~3 (2-norm). The fixed-point LU
  // makes O(n^2) roundings of 0.5 LSB each; measured error 0.61 LSB
  // (docs/numerics.md#fixed-point), asserted at 2 LSB. A broken pivot or ADL
  // path would be off by orders of magnitude.
  Eigen::Matrix4d Ad;
  Ad << 4.0, -1.0, 0.5, 0.25, -1.0, 5.0, -0.75, 0.5, 0.5, -0.75, 3.0, -1.0, 0.25, 0.5, -1.0, 4.5;
  Eigen::Vector4d bd(1.0, -2.0, 0.5, 3.0);
  Eigen::Matrix<q16_16, 4, 4> A;
  Eigen::Matrix<q16_16, 4, 1> b;
  for (int i = 0; i < 4; ++i) {
    b(i) = q16_16(bd(i));
    for (int j = 0; j < 4; ++j) A(i, j) = q16_16(Ad(i, j));
  }
  const Eigen::Matrix<q16_16, 4, 1> x = A.partialPivLu().solve(b);
  const Eigen::Vector4d xd = Ad.partialPivLu().solve(bd);  // inputs are exact in q16.16
  double worst = 0;
  for (int i = 0; i < 4; ++i) worst = std::max(worst, std::abs(x(i).to_double() - xd(i)) / kLsb);
  MESSAGE("q16.16 LU solve max error [LSB]: " << worst);
  CHECK(worst <= 2.0);
  // Residual in fixed point: |A| row sums <= 6.25, so 2 LSB of solution error
  // plus 4 product roundings bound it by 6.25 * 2 + 2 < 16 LSB.
  const Eigen::Matrix<q16_16, 4, 1> res = A * x - b;
  for (int i = 0; i < 4; ++i) CHECK(std::abs(res(i).to_double()) <= 16.0 * kLsb);
}
