// Fixed-point steps and friction at the edge of the Q range
// (docs/numerics.md#fixed-point-steps): the methods' weights, the carried
// rounding remainder, and the friction slope when (lambda v)^2 leaves the
// range.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/integrate/increment.hpp"
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace {

using Q = cvt::q16_16;
using V2 = Eigen::Matrix<Q, 2, 1>;

// Mean spacing of the upward zero crossings of v1 over the second half of a
// 20 s run of the seed's Stribeck oscillator from [0 3 0 6] (the cycle of
// docs/physics.md#oscillator, about 8 periods), with the step actually taken
// as the time axis.
template <class T>
double stribeck_period_s(cvt::Method m, double dt) {
  const auto pd = cvt::OscillatorParams<double>::seed_section3(cvt::friction_presets::oscillator_stribeck<double>());
  const cvt::StickSlipOscillator<T> sys(pd.template cast<T>());
  typename cvt::StickSlipOscillator<T>::State x;
  x << T(0.0), T(3.0), T(0.0), T(6.0);
  const T h = cvt::from_double<T>(dt);
  const double ha = cvt::to_double(h);
  const long n = std::lround(20.0 / ha);
  double prev = cvt::to_double(x(1)), first = -1, last = -1;
  int crossings = 0;
  for (long i = 1; i <= n; ++i) {
    cvt::step(m, sys, x, h);
    const double v = cvt::to_double(x(1)), t = static_cast<double>(i) * ha;
    if (prev < 0 && v >= 0 && t > 10.0) {
      if (first < 0) first = t;
      last = t;
      ++crossings;
    }
    prev = v;
  }
  return crossings >= 2 ? (last - first) / (crossings - 1) : 0.0;
}

}  // namespace

TEST_CASE("fixed-point steps keep the method's weights: the q16.16 oscillator period is the double one") {
  // With h/6 and h/2 rounded first, RK4 at 1e-4 s (7 LSB) advanced 6/7 of
  // each step: the period came out 16.6 % long (8.3 % at 2e-4 s, -33 % at
  // 6.1e-5 s). Measured now: within 0.14 % down to 6.1e-5 s. The methods
  // with fractional weights: RK4 (1/6, 1/2), Heun (1/2), ROS2 (3/2, 1/2).
  const double ref = stribeck_period_s<double>(cvt::Method::rk4, 1e-4);
  REQUIRE(ref == doctest::Approx(1.26683).epsilon(1e-4));
  for (cvt::Method m : {cvt::Method::rk4, cvt::Method::heun, cvt::Method::ros2}) {
    for (double dt : {6.2e-5, 1e-4, 5e-4}) {
      const double p = stribeck_period_s<Q>(m, dt);
      CAPTURE(cvt::method_name(m));
      CAPTURE(dt);
      CHECK(std::fabs(p / ref - 1.0) < 0.005);
    }
  }
}

TEST_CASE("fixed_increment: one rounding of the exact weighted sum, and with a carry no drift") {
  // h = 7 LSB, k = 179 LSB per unit: h k (3 + (-1)) / 2 = 1253 / 65536 LSB.
  const Q h = Q::from_raw(7);
  V2 k1, k2;
  k1 << Q::from_raw(179), Q::from_raw(-5);
  k2 << Q::from_raw(-179), Q::from_raw(3);
  // One step: the exact raw increment rounded once.
  V2 x = V2::Zero();
  cvt::fixed_increment<2>(x, h, {3, 1}, {&k1, &k2}, nullptr);
  CHECK(x(0).raw() == 0);  // 7 * 358 / 2 / 65536 = 0.019 LSB
  // Many steps without a carry: every increment rounds to 0, the state stalls.
  // With the carry the sum follows the exact increments within half an LSB.
  cvt::IncrementCarry<Q, 2> carry;
  V2 y = V2::Zero();
  const long n = 1000000;
  for (long i = 0; i < n; ++i) cvt::fixed_increment<2>(y, h, {3, 1}, {&k1, &k2}, &carry);
  const double exact0 = 7.0 * (3 * 179 - 179) / 2.0 / 65536.0 * n;  // in LSB
  const double exact1 = 7.0 * (3 * -5 + 3) / 2.0 / 65536.0 * n;
  CHECK(std::fabs(y(0).raw() - exact0) <= 0.5);
  CHECK(std::fabs(y(1).raw() - exact1) <= 0.5);
  // RK4's weights with D = 6 and an increment that saturates.
  V2 z;
  z << Q::max() - Q::from_raw(1), Q(0);
  V2 big;
  big << Q::max(), Q::lowest();
  cvt::fixed_increment<6>(z, Q::max(), {1, 2, 2, 1}, {&big, &big, &big, &big}, nullptr);
  CHECK(z(0) == Q::max());
  CHECK(z(1) == Q::lowest());
}

TEST_CASE("fixed-point friction: the slope where (lambda v)^2 leaves the Q range") {
  // lambda = 1e4 s/m: (lambda v)^2 saturates above 18 mm/s of slip. The slope
  // of phi stayed at mu 2/pi lambda / 32768 = 0.049 s/m at every faster slip
  // (true: 7e-8 s/m at 15 m/s), a Jacobian coupling that does not exist.
  const auto pd = cvt::friction_presets::table2_case1<double>();
  const auto pq = pd.cast<Q>();
  const double lsb = 1.0 / 65536.0;
  for (double v : {-15.0, -3.0, -0.5, -0.05, -0.015, -1e-3, 1e-3, 0.015, 0.05, 0.5, 3.0, 15.0, 400.0}) {
    CAPTURE(v);
    const auto e = cvt::friction_characteristic_and_slope(pq, Q(v));
    const auto r = cvt::friction_characteristic_and_slope(pd, cvt::to_double(Q(v)));
    // phi to the 1.4 LSB of the sign (2/pi is rounded once); the slope
    // relative to its own size where it is large, in LSB where it is small.
    CHECK(std::fabs(cvt::to_double(e.phi) - r.phi) <= 2.0 * lsb);
    CHECK(std::fabs(cvt::to_double(e.slope) - r.slope) <= 4.0 * lsb + 2e-3 * std::fabs(r.slope));
    // phi is bit for bit the right-hand side's friction_characteristic.
    CHECK(e.phi == cvt::friction_characteristic(pq, Q(v)));
  }
}
