// cvt::dm: accuracy against long-double references, symmetry, monotonicity
// and special values for double, float and Fixed<F> (docs/numerics.md#detmath).
// The asserted bounds are dm::max_error<T>, which are the measured maxima of
// much larger sweeps (the docs give the commands); these sweeps re-check them.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "cvtplant/math/detmath.hpp"

namespace dm = cvt::dm;
using cvt::Fixed;
using cvt::q16_16;

namespace {

struct Lcg {
  std::uint64_t s = 0x2545F4914F6CDD1Du;
  std::uint64_t next() {
    s = s * 6364136223846793005u + 1442695040888963407u;
    return s;
  }
  long double unit() { return static_cast<long double>(next() >> 11) * 0x1p-53L; }
};

// ulp of the exact result y in format T (subnormals: the smallest subnormal).
template <class T>
long double ulp_of(long double y) {
  int e = 0;
  std::frexp(y, &e);
  constexpr int p = std::numeric_limits<T>::digits;
  int u = e - p;
  const int umin = std::numeric_limits<T>::min_exponent - p;
  if (u < umin) u = umin;
  return std::ldexp(1.0L, u);
}

template <class T>
double ulp_err(T got, long double ref) {
  return static_cast<double>(std::fabs(static_cast<long double>(got) - ref) / ulp_of<T>(ref));
}

using Fn = long double (*)(long double);

// Sweep: dense linear over [lo, hi] plus log-uniform magnitudes over
// [tiny, big] with both signs. Returns the worst ulp error.
template <class T, class Dm>
double sweep(Dm f, Fn ref, long double lo, long double hi, long double tiny, long double big, int n) {
  Lcg g;
  double worst = 0;
  for (int i = 0; i <= n; ++i) {
    const T x = static_cast<T>(lo + (hi - lo) * i / n);
    worst = std::max(worst, ulp_err<T>(f(x), ref(static_cast<long double>(x))));
  }
  for (int i = 0; i < n; ++i) {
    const long double l = std::log(tiny) + g.unit() * (std::log(big) - std::log(tiny));
    T x = static_cast<T>(std::exp(l));
    if (g.next() & 1) x = -x;
    const long double r = ref(static_cast<long double>(x));
    if (std::fabs(r) > static_cast<long double>(std::numeric_limits<T>::max())) continue;
    worst = std::max(worst, ulp_err<T>(f(x), r));
  }
  return worst;
}

long double ref_exp(long double x) { return std::exp(x); }
long double ref_atan(long double x) { return std::atan(x); }
long double ref_tanh(long double x) { return std::tanh(x); }
long double ref_sin(long double x) { return std::sin(x); }
long double ref_cos(long double x) { return std::cos(x); }

template <class T>
bool same_bits(T a, T b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

TEST_CASE_TEMPLATE("detmath: accuracy vs long double", T, double, float) {
  using E = dm::max_error<T>;
  const bool dbl = sizeof(T) == 8;
  const long double exp_hi = dbl ? 709.78L : 88.72L, exp_lo = dbl ? -745.0L : -103.9L;
  const int n = 30000;
  double w = 0;

  w = sweep<T>([](T x) { return cvt::exp(x); }, ref_exp, exp_lo, exp_hi, 1e-30L, dbl ? 700.0L : 87.0L, n);
  MESSAGE("exp worst " << w << " ulp");
  CHECK(w <= E::exp);
  w = sweep<T>([](T x) { return cvt::exp(x); }, ref_exp, -1.0L, 1.0L, 1e-30L, 1.0L, n);
  CHECK(w <= E::exp);

  w = sweep<T>([](T x) { return cvt::atan(x); }, ref_atan, -4.0L, 4.0L, 1e-30L, 1e30L, n);
  MESSAGE("atan worst " << w << " ulp");
  CHECK(w <= E::atan);

  w = sweep<T>([](T x) { return cvt::tanh(x); }, ref_tanh, -3.0L, 3.0L, 1e-30L, 40.0L, n);
  MESSAGE("tanh worst " << w << " ulp");
  CHECK(w <= E::tanh);

  // sin/cos: near and far, up to the largest finite values (Payne-Hanek).
  const long double far = dbl ? 1e300L : 3e38L;
  w = sweep<T>([](T x) { return cvt::sin(x); }, ref_sin, -10.0L, 10.0L, 1e-30L, 1e5L, n);
  w = std::max(w, sweep<T>([](T x) { return cvt::sin(x); }, ref_sin, 1e5L, 2e6L, 1e5L, far, n));
  MESSAGE("sin worst " << w << " ulp");
  CHECK(w <= E::sin);
  w = sweep<T>([](T x) { return cvt::cos(x); }, ref_cos, -10.0L, 10.0L, 1e-30L, 1e5L, n);
  w = std::max(w, sweep<T>([](T x) { return cvt::cos(x); }, ref_cos, 1e5L, 2e6L, 1e5L, far, n));
  MESSAGE("cos worst " << w << " ulp");
  CHECK(w <= E::cos);

  w = sweep<T>([](T x) { return cvt::sqrt(cvt::abs(x)); }, [](long double x) { return std::sqrt(std::fabs(x)); },
               0.0L, 100.0L, 1e-30L, 1e30L, n);
  CHECK(w <= E::sqrt);
}

TEST_CASE_TEMPLATE("detmath: hard cases for argument reduction", T, double, float) {
  // Arguments next to multiples of pi/2, where the reduced argument cancels
  // most bits: the classic failure of a naive x - k*pi/2.
  using E = dm::max_error<T>;
  const long double pio2 = 1.5707963267948966192313216916397514L;
  double w = 0;
  for (int k = 1; k < 200000; k += 7) {
    const T x0 = static_cast<T>(k * pio2);
    T x = x0;
    for (int j = 0; j < 3; ++j) {
      w = std::max(w, ulp_err<T>(cvt::sin(x), std::sin(static_cast<long double>(x))));
      w = std::max(w, ulp_err<T>(cvt::cos(x), std::cos(static_cast<long double>(x))));
      x = std::nextafter(x, std::numeric_limits<T>::infinity());
    }
  }
  MESSAGE("near k*pi/2 worst " << w << " ulp");
  CHECK(w <= std::max(E::sin, E::cos));
  // Known hard double: 6381956970095103 * 2^797 is within 2^-60.9 of a multiple of pi/2.
  if (sizeof(T) == 8) {
    const double hard = std::ldexp(6381956970095103.0, 797);
    CHECK(ulp_err<double>(cvt::sin(hard), std::sin(static_cast<long double>(hard))) <= E::sin);
    CHECK(ulp_err<double>(cvt::cos(hard), std::cos(static_cast<long double>(hard))) <= E::cos);
  }
}

TEST_CASE_TEMPLATE("detmath: odd/even symmetry is exact", T, double, float) {
  Lcg g;
  for (int i = 0; i < 20000; ++i) {
    const T x = static_cast<T>(std::exp(-20.0L + 30.0L * g.unit()));
    CHECK(same_bits(cvt::atan(-x), static_cast<T>(-cvt::atan(x))));
    CHECK(same_bits(cvt::tanh(-x), static_cast<T>(-cvt::tanh(x))));
    CHECK(same_bits(cvt::sin(-x), static_cast<T>(-cvt::sin(x))));
    CHECK(same_bits(cvt::cos(-x), cvt::cos(x)));
    CHECK(same_bits(cvt::sign(-x), static_cast<T>(-cvt::sign(x))));
  }
}

TEST_CASE_TEMPLATE("detmath: monotone where the function is", T, double, float) {
  // Consecutive representable arguments across the polynomial/division/exp
  // switch points and the reduction boundaries must never step backwards.
  const T starts[] = {T(0.41421), T(0.5493), T(2.41421), T(-0.35), T(0.34), T(9.9), T(19.0), T(1e-8), T(-700)};
  for (T s : starts) {
    T x = s, pa = cvt::atan(x), pt = cvt::tanh(x), pe = cvt::exp(x);
    for (int i = 0; i < 20000; ++i) {
      x = std::nextafter(x, std::numeric_limits<T>::infinity());
      const T a = cvt::atan(x), t = cvt::tanh(x), e = cvt::exp(x);
      REQUIRE(a >= pa);
      REQUIRE(t >= pt);
      REQUIRE(e >= pe);
      pa = a;
      pt = t;
      pe = e;
    }
  }
  // Coarse monotonicity over the full range.
  T prev_a = cvt::atan(T(-1e30)), prev_t = cvt::tanh(T(-50)), prev_e = cvt::exp(T(-800));
  for (int i = -4000; i <= 4000; ++i) {
    const T x = static_cast<T>(i) * T(0.03);
    CHECK(cvt::atan(x) >= prev_a);
    CHECK(cvt::tanh(x) >= prev_t);
    CHECK(cvt::exp(x) >= prev_e);
    prev_a = cvt::atan(x);
    prev_t = cvt::tanh(x);
    prev_e = cvt::exp(x);
  }
  // sin increasing on [-pi/2, pi/2], cos decreasing on [0, pi]
  T ps = cvt::sin(T(-1.5707)), pc = cvt::cos(T(0));
  for (int i = 1; i <= 10000; ++i) {
    const T xs = T(-1.5707) + static_cast<T>(i) * T(3.1414 / 10000);
    const T xc = static_cast<T>(i) * T(3.1415 / 10000);
    CHECK(cvt::sin(xs) >= ps);
    CHECK(cvt::cos(xc) <= pc);
    ps = cvt::sin(xs);
    pc = cvt::cos(xc);
  }
}

TEST_CASE_TEMPLATE("detmath: special values", T, double, float) {
  const T inf = std::numeric_limits<T>::infinity();
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T pio2 = static_cast<T>(1.5707963267948966192313216916397514L);  // correctly rounded
  // NaN propagates everywhere
  CHECK(std::isnan(cvt::exp(nan)));
  CHECK(std::isnan(cvt::atan(nan)));
  CHECK(std::isnan(cvt::tanh(nan)));
  CHECK(std::isnan(cvt::sin(nan)));
  CHECK(std::isnan(cvt::cos(nan)));
  CHECK(std::isnan(cvt::sqrt(nan)));
  CHECK(std::isnan(cvt::abs(nan)));
  CHECK(std::isnan(cvt::sign(nan)));
  // infinities
  CHECK(cvt::exp(inf) == inf);
  CHECK(cvt::exp(-inf) == T(0));
  CHECK(cvt::atan(inf) == pio2);
  CHECK(cvt::atan(-inf) == -pio2);
  CHECK(cvt::tanh(inf) == T(1));
  CHECK(cvt::tanh(-inf) == T(-1));
  CHECK(std::isnan(cvt::sin(inf)));
  CHECK(std::isnan(cvt::cos(-inf)));
  CHECK(cvt::abs(-inf) == inf);
  CHECK(cvt::sign(-inf) == T(-1));
  // zeros keep their sign where the function is odd
  CHECK(std::signbit(cvt::atan(T(-0.0))));
  CHECK(std::signbit(cvt::tanh(T(-0.0))));
  CHECK(std::signbit(cvt::sin(T(-0.0))));
  CHECK(cvt::cos(T(-0.0)) == T(1));
  CHECK(cvt::exp(T(-0.0)) == T(1));
  CHECK(cvt::sign(T(0)) == T(0));
  CHECK(std::signbit(cvt::sign(T(-0.0))));
  CHECK_FALSE(std::signbit(cvt::abs(T(-0.0))));
  CHECK(cvt::sign(T(3)) == T(1));
  CHECK(cvt::sign(T(-1e-30)) == T(-1));
  CHECK(std::isnan(cvt::sqrt(T(-1))));
  // saturating large arguments
  CHECK(cvt::tanh(T(30)) == T(1));
  CHECK(cvt::atan(std::numeric_limits<T>::max()) == pio2);
  CHECK(cvt::atan(std::numeric_limits<T>::denorm_min()) == std::numeric_limits<T>::denorm_min());
  CHECK(cvt::exp(std::numeric_limits<T>::denorm_min()) == T(1));
  CHECK(cvt::sin(std::numeric_limits<T>::denorm_min()) == std::numeric_limits<T>::denorm_min());
  CHECK(cvt::tanh(std::numeric_limits<T>::denorm_min()) == std::numeric_limits<T>::denorm_min());
}

TEST_CASE("detmath: exp overflow and underflow thresholds (double)") {
  // ln(DBL_MAX) = 709.782712893383996..., the largest double with a finite
  // result is 0x1.62e42fefa39efp+9.
  CHECK(std::isfinite(cvt::exp(0x1.62e42fefa39efp+9)));
  CHECK(cvt::exp(0x1.62e42fefa39f0p+9) == std::numeric_limits<double>::infinity());
  CHECK(cvt::exp(1000.0) == std::numeric_limits<double>::infinity());
  // Gradual underflow: exp(-745.13) is the smallest subnormal, below -745.1332 it rounds to 0.
  CHECK(cvt::exp(-745.13) == std::numeric_limits<double>::denorm_min());
  CHECK(cvt::exp(-745.14) == 0.0);
  CHECK(cvt::exp(-1e10) == 0.0);
  const double sub = cvt::exp(-730.0);  // deep subnormal, still within the bound
  CHECK(ulp_err<double>(sub, std::exp(-730.0L)) <= dm::max_error<double>::exp);
}

TEST_CASE("detmath: exp overflow and underflow thresholds (float)") {
  // ln(FLT_MAX) = 88.7228391..., the largest float with a finite result is 0x1.62e42ep+6.
  CHECK(std::isfinite(cvt::exp(0x1.62e42ep+6f)));
  CHECK(cvt::exp(0x1.62e430p+6f) == std::numeric_limits<float>::infinity());
  CHECK(cvt::exp(-103.97f) == std::numeric_limits<float>::denorm_min());
  CHECK(cvt::exp(-103.98f) == 0.0f);
  CHECK(ulp_err<float>(cvt::exp(-95.0f), std::exp(-95.0L)) <= dm::max_error<float>::exp);
}

// ------------------------------------------------------------------ Fixed

namespace {

template <int F, class Dm>
double sweep_fixed(Dm f, Fn ref, std::int64_t stride) {
  const long double lsb = std::ldexp(1.0L, -F);
  const long double hi = static_cast<long double>(INT32_MAX) * lsb, lo = static_cast<long double>(INT32_MIN) * lsb;
  double worst = 0;
  auto one = [&](std::int64_t r) {
    const auto x = Fixed<F>::from_raw(static_cast<std::int32_t>(r));
    long double y = ref(static_cast<long double>(r) * lsb);
    y = y > hi ? hi : y < lo ? lo : y;  // saturation is the specified result
    worst = std::max(worst, static_cast<double>(std::fabs(static_cast<long double>(f(x).raw()) * lsb - y) / lsb));
  };
  for (std::int64_t r = INT32_MIN; r <= INT32_MAX; r += stride) one(r);
  for (std::int64_t r = -70000; r <= 70000; r += 7) one(r);  // dense around 0
  one(INT32_MIN);
  one(INT32_MAX);
  return worst;
}

template <int F>
void check_fixed_accuracy(std::int64_t stride) {
  using E = dm::max_error<Fixed<F>>;
  CAPTURE(F);
  double w;
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::exp(x); }, ref_exp, stride);
  MESSAGE("Fixed<" << F << "> exp worst " << w << " LSB");
  CHECK(w <= E::exp);
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::atan(x); }, ref_atan, stride);
  MESSAGE("Fixed<" << F << "> atan worst " << w << " LSB");
  CHECK(w <= E::atan);
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::tanh(x); }, ref_tanh, stride);
  MESSAGE("Fixed<" << F << "> tanh worst " << w << " LSB");
  CHECK(w <= E::tanh);
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::sin(x); }, ref_sin, stride);
  CHECK(w <= E::sin);
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::cos(x); }, ref_cos, stride);
  CHECK(w <= E::cos);
  w = sweep_fixed<F>([](Fixed<F> x) { return cvt::sqrt(x); },
                     [](long double x) { return x < 0 ? 0.0L : std::sqrt(x); }, stride);
  CHECK(w <= E::sqrt);
}

}  // namespace

TEST_CASE("detmath: Fixed accuracy vs long double over the whole raw range") {
  check_fixed_accuracy<16>(60013);
  check_fixed_accuracy<8>(600011);
  check_fixed_accuracy<24>(600011);
  check_fixed_accuracy<30>(600011);
}

TEST_CASE("detmath: Fixed symmetry, monotonicity and edges") {
  using Q = q16_16;
  const Q one = Q(1);
  for (std::int32_t r = -3000000; r <= 3000000; r += 977) {
    const Q x = Q::from_raw(r);
    CHECK(cvt::atan(-x) == -cvt::atan(x));
    CHECK(cvt::tanh(-x) == -cvt::tanh(x));
    CHECK(cvt::sin(-x) == -cvt::sin(x));
    CHECK(cvt::cos(-x) == cvt::cos(x));
    CHECK(cvt::abs(x) == (r < 0 ? -x : x));
    CHECK(cvt::sign(x) == (r > 0 ? one : r < 0 ? -one : Q()));
  }
  // monotone over consecutive raw values through the interesting regions
  const std::int32_t starts[] = {-800000, -30000, 0, 20000, 40000, 160000, 650000, 1000000};
  for (std::int32_t s : starts) {
    Q pa = cvt::atan(Q::from_raw(s)), pt = cvt::tanh(Q::from_raw(s)), pe = cvt::exp(Q::from_raw(s));
    Q ps = cvt::sqrt(Q::from_raw(s));
    for (std::int32_t r = s + 1; r < s + 12000; ++r) {
      const Q x = Q::from_raw(r);
      REQUIRE(cvt::atan(x) >= pa);
      REQUIRE(cvt::tanh(x) >= pt);
      REQUIRE(cvt::exp(x) >= pe);
      REQUIRE(cvt::sqrt(x) >= ps);
      pa = cvt::atan(x);
      pt = cvt::tanh(x);
      pe = cvt::exp(x);
      ps = cvt::sqrt(x);
    }
  }
  // saturation and domain rules
  CHECK(cvt::exp(Q(11)) == Q::max());  // e^11 = 59874 > 32768
  CHECK(cvt::exp(Q::max()) == Q::max());
  CHECK(cvt::exp(Q::lowest()) == Q());
  CHECK(cvt::exp(Q(-12)) == Q());      // e^-12 = 6.1e-6 < 0.5 LSB (7.6e-6)
  CHECK(cvt::exp(Q(-11)).raw() == 1);  // e^-11 = 1.67e-5 = 1.1 LSB
  CHECK(cvt::exp(Q()) == one);
  CHECK(cvt::sqrt(Q(-4)) == Q());
  CHECK(cvt::sqrt(Q::lowest()) == Q());
  CHECK(cvt::sqrt(Q(4)) == Q(2));
  CHECK(cvt::sqrt(Q::max()).raw() == 11863283);  // sqrt(32768 - 2^-16) * 2^16 = 11863283.20
  CHECK(cvt::abs(Q::lowest()) == Q::max());
  CHECK(cvt::tanh(Q::lowest()) == -one);
  CHECK(cvt::tanh(Q::max()) == one);
  // Reference values from 40-digit arithmetic (mpmath), in LSB:
  CHECK(cvt::atan(Q::max()).raw() == 102942);      // atan(32768 - 2^-16) = 102941.708
  CHECK(cvt::atan(Q::lowest()).raw() == -102942);  // atan(-32768) = -102941.708
  CHECK(cvt::sin(Q::lowest()).raw() == -60808);    // sin(-32768) = -60807.993
  CHECK(cvt::cos(Q::lowest()).raw() == 24441);     // cos(-32768) = 24440.854
  CHECK(cvt::sign(Q::lowest()) == -one);
}

TEST_CASE("detmath: Fixed functions are usable in constant expressions") {
  constexpr q16_16 e1 = cvt::exp(q16_16(1));
  static_assert(e1.raw() == 178145, "round(e * 65536) = 178145");
  constexpr q16_16 s = cvt::sqrt(q16_16(2));
  static_assert(s.raw() == 92682, "round(sqrt(2) * 65536) = 92682");
  constexpr q16_16 a = cvt::atan(q16_16(1));
  static_assert(a.raw() == 51472, "round(pi/4 * 65536) = 51472");
  CHECK(e1.raw() == 178145);
}
