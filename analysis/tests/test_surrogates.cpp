// IAAFT surrogates and the rank test (docs/analysis.md#surrogates).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cvtplant/analysis/series.hpp"
#include "cvtplant/analysis/surrogates.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {

// Gaussian AR(1), x_i = 0.9 x_{i-1} + e_i: linear, time-reversible.
std::vector<double> ar1(std::size_t n, unsigned seed) {
  std::mt19937 g(seed);
  std::normal_distribution<double> d(0, 1);
  std::vector<double> x(n);
  double v = 0;
  for (auto& s : x) s = v = 0.9 * v + d(g);
  return x;
}

// The test's options at embedding (m, tau), predicting tau ahead, with or
// without the exponent statistic.
SurrogateTestOptions embedded(int m, int tau, int theiler, double dt, bool exponent) {
  SurrogateTestOptions o;
  o.m = m;
  o.tau = o.horizon = tau;
  o.theiler = theiler;
  o.dt = dt;
  o.exponent = exponent;
  return o;
}

bool five_smooth(std::size_t n) {
  for (std::size_t p : {2u, 3u, 5u})
    while (n % p == 0) n /= p;
  return n == 1;
}

}  // namespace

TEST_CASE("surrogates: end matching keeps 90 % of the series and joins its ends") {
  const std::vector<double> x = testsig::sine(4000, 37.3);
  const Segment s = end_matched_segment(x, 0.9);
  CHECK(s.length >= 3600);
  CHECK(s.begin + s.length <= x.size());
  CHECK(five_smooth(s.length));
  // The whole series ends mid-cycle; the chosen segment ends where it began.
  const double whole = (x.front() - x.back()) * (x.front() - x.back());
  CHECK(s.mismatch < 1e-3 * whole);
  CHECK_THROWS(end_matched_segment(std::vector<double>(10, 1.0)));
}

TEST_CASE("surrogates: an IAAFT surrogate keeps the values exactly and the spectrum closely") {
  const std::vector<double> x = ar1(4096, 3);
  const Surrogate s = iaaft(x, 11);
  std::vector<double> a = x, b = s.x;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  CHECK(a == b);                   // a permutation of the data
  CHECK(s.spectrum_error < 0.05);  // Fourier amplitudes within 5 % (L2)
  CHECK(s.x != x);
  // Deterministic for a seed, different for another.
  CHECK(iaaft(x, 11).x == s.x);
  CHECK(iaaft(x, 12).x != s.x);
}

TEST_CASE("surrogates: time-reversal asymmetry of a sawtooth and of a reversible process") {
  // A slow rise and a drop in one sample: the increments at lag 1 are 1/9
  // (nine times) and -1, so <d^3>/<d^2>^1.5 follows in closed form.
  std::vector<double> saw(9000);
  for (std::size_t i = 0; i < saw.size(); ++i) saw[i] = static_cast<double>(i % 10) / 9.0;
  const double d2 = (9 * std::pow(1.0 / 9, 2) + 1) / 10, d3 = (9 * std::pow(1.0 / 9, 3) - 1) / 10;
  CHECK(time_reversal_asymmetry(saw, 1) == doctest::Approx(d3 / std::pow(d2, 1.5)).epsilon(1e-3));
  CHECK(std::fabs(time_reversal_asymmetry(ar1(20000, 5), 1)) < 0.05);
}

TEST_CASE("surrogates: prediction error of noise is sqrt(1 + 1/k), of Lorenz small") {
  // For independent samples the mean of k neighbours' futures is independent
  // of the future predicted: error variance 1 + 1/k of the variance.
  PredictionOptions o;
  o.m = 2;
  o.neighbours = 5;
  const double e = prediction_error(testsig::white_noise(8000, 9), o);
  CHECK(e == doctest::Approx(std::sqrt(1.2)).epsilon(0.05));
  PredictionOptions l;
  l.m = 3;
  l.tau = 18;
  l.horizon = 18;
  l.theiler = 100;
  CHECK(prediction_error(testsig::lorenz_x(8000), l) < 0.1);
}

TEST_CASE("surrogates: Lorenz is nonlinear against its surrogates, a linear Gaussian process is not") {
  const SurrogateTestOptions o = embedded(3, 18, 100, 0.01, false);
  const SurrogateTest lz = surrogate_test(testsig::lorenz_x(5000), o);
  REQUIRE(lz.statistics.size() == 2);
  CHECK(lz.statistics[1].name == "prediction_error");
  CHECK(lz.statistics[1].rank_low == 1);  // the data predicts better than every surrogate
  CHECK(lz.statistics[1].p == doctest::Approx(0.05));
  CHECK(lz.nonlinear);
  CHECK(lz.segment.length >= 4500);

  const SurrogateTest lin = surrogate_test(ar1(5000, 21), embedded(2, 1, 10, 1, true));
  REQUIRE(lin.statistics.size() == 3);
  CHECK_FALSE(lin.nonlinear);
  for (const auto& s : lin.statistics) {
    CHECK(s.surrogates.size() == 19);
    CHECK(s.rank_low + s.rank_high <= 21);
  }
}
