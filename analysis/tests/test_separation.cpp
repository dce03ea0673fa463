// Separation of two runs (docs/analysis.md#separation).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/analysis/separation.hpp"

using namespace cvt::analysis;

TEST_CASE("separation: an exponentially growing difference gives its rate") {
  const double dt = 1e-3, lambda = 3.0;
  std::vector<double> a(8000), b(8000);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = i * dt;
    a[i] = std::sin(2 * M_PI * 7 * t);
    // 1e-12 growing at lambda: 1e-12 e^{3 t} reaches 0.1 of std(a) near t = 8.4 s.
    b[i] = a[i] + 1e-12 * std::exp(lambda * t) * (1 + 0.5 * std::sin(2 * M_PI * 7 * t));
  }
  SeparationOptions o;
  o.dt = dt;
  const Separation s = separation_growth(a, b, o);
  CHECK(s.differ);
  CHECK(s.exponential_growth);
  CHECK(s.exponential.slope == doctest::Approx(lambda).epsilon(0.05));
  CHECK(s.exponential_r2 > s.power_law_r2);
}

TEST_CASE("separation: a phase drift grows like a power of time, not exponentially") {
  const double dt = 1e-3;
  std::vector<double> a(8000), b(8000);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = i * dt;
    a[i] = std::sin(2 * M_PI * 7 * t);
    b[i] = std::sin(2 * M_PI * 7 * (1 + 1e-9) * t);  // the distance grows like t
  }
  SeparationOptions o;
  o.dt = dt;
  const Separation s = separation_growth(a, b, o);
  CHECK(s.differ);
  CHECK_FALSE(s.exponential_growth);
  CHECK_FALSE(s.saturated);
  CHECK(s.power_law_exponent == doctest::Approx(1.0).epsilon(0.1));
  CHECK(s.rate_bound > 0);
  CHECK(s.rate_bound < 5.0);
}

TEST_CASE("separation: identical runs, bad input") {
  std::vector<double> a(1000);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::sin(0.1 * i);
  SeparationOptions o;
  CHECK_FALSE(separation_growth(a, a, o).differ);
  CHECK_THROWS(separation_growth(a, std::vector<double>(999), o));
  CHECK_THROWS(separation_growth(std::vector<double>(1000, 1.0), a, o));
}
