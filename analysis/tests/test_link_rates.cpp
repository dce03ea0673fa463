// Link-passing rates and line attribution (docs/analysis.md#link-rates).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/analysis/link_rates.hpp"
#include "cvtplant/analysis/series.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {

// A train of narrow pulses at f Hz sampled every dt: a periodic signal whose
// harmonics reach far above the Nyquist frequency.
std::vector<double> pulses(std::size_t n, double dt, double f) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double ph = std::fmod(static_cast<double>(i) * dt * f, 1.0);
    const double d = std::min(ph, 1 - ph) / 0.04;  // pulse width: 4 % of the period
    x[i] = std::exp(-d * d);
  }
  return x;
}

}  // namespace

TEST_CASE("link rates: the event rate and its resolution") {
  std::vector<double> t;
  for (int k = 0; k < 500; ++k) t.push_back(0.013 + k / 103.0);
  const EventRate r = event_rate(t, 0.0, 10.0, 1e-3);
  CHECK(r.events == 500);
  CHECK(r.Hz == doctest::Approx(103.0).epsilon(1e-12));
  CHECK(r.resolution_Hz == doctest::Approx(103.0 * 2e-3 / (499 / 103.0)).epsilon(1e-9));
  CHECK(event_rate(t, 20.0, 30.0, 1e-3).Hz == 0);
}

TEST_CASE("link rates: rational ratios by continued fractions") {
  const RationalRatio a = rational_ratio(1.5, 1e-6);
  CHECK(a.p == 3);
  CHECK(a.q == 2);
  CHECK(a.rational);
  const RationalRatio b = rational_ratio(std::sqrt(2.0), 1e-4, 20);
  CHECK(b.p == 17);  // the best convergent with q <= 20
  CHECK(b.q == 12);
  CHECK(b.error_rel == doctest::Approx(std::fabs(std::sqrt(2.0) - 17.0 / 12) / std::sqrt(2.0)));
  CHECK_FALSE(b.rational);
  CHECK(rational_ratio(1.00005, 1e-3).rational);
}

TEST_CASE("link rates: aliases fold into [0, fs/2]") {
  CHECK(alias_Hz(1031.9, 1000) == doctest::Approx(31.9));
  CHECK(alias_Hz(516, 1000) == doctest::Approx(484));
  CHECK(alias_Hz(250, 1000) == doctest::Approx(250));
  CHECK(alias_Hz(2000, 1000) == doctest::Approx(0).epsilon(1e-12));
}

TEST_CASE("link rates: a sampled pulse train's lines are its harmonics, many seen as aliases") {
  const double f = 103.19, dt = 1e-3;
  const std::vector<double> x = pulses(8000, dt, f);
  const Lines l = spectral_lines(x, dt, 12);
  REQUIRE(l.Hz.size() >= 6);
  const double tol = 2.0 / (8000 * dt);
  const auto with = attribute_lines(l, {f}, 50, tol, 1000);
  int aliased = 0;
  for (const auto& a : with) {
    CHECK(a.explained);
    CHECK(std::fabs(a.residual_Hz) <= tol);
    aliased += a.coefficients[0] * f > 500;
  }
  CHECK(aliased >= 2);
  // Without folding the aliases are left unexplained.
  int unexplained = 0;
  for (const auto& a : attribute_lines(l, {f}, 50, tol)) unexplained += !a.explained;
  CHECK(unexplained >= 2);
  CHECK(line_power_fraction(x, dt, l.Hz, tol) > 0.99);
  CHECK(line_power_fraction(testsig::white_noise(8000, 3), dt, l.Hz, tol) < 0.05);
}

TEST_CASE("link rates: two incommensurate rates explain their combination lines") {
  const double f1 = 31.0, f2 = 31.0 * std::sqrt(2.0), dt = 1e-3;
  std::vector<double> x(8000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i * dt;
    // A product of the two (a modulation) has lines at f2 - f1 and f2 + f1.
    x[i] = std::sin(2 * M_PI * f1 * t) + 0.5 * std::sin(2 * M_PI * f2 * t) * (1 + 0.6 * std::sin(2 * M_PI * f1 * t));
  }
  const double tol = 2.0 / (8000 * dt);
  const auto a = attribute_lines(spectral_lines(x, dt, 6), {f1, f2}, 4, tol, 1000);
  bool diff = false, sum = false;
  for (const auto& l : a) {
    CHECK(l.explained);
    diff = diff || (l.coefficients == std::vector<int>{-1, 1});
    sum = sum || (l.coefficients == std::vector<int>{1, 1});
  }
  CHECK(diff);
  CHECK(sum);
}
