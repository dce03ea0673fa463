// The verdict (docs/analysis.md#classify).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/series.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

TEST_CASE("classify: sine -> periodic") {
  CHECK(classify(testsig::sine(5000, 37.3), {}).classification == "periodic");
}

TEST_CASE("classify: two incommensurate tones -> quasi_periodic") {
  std::vector<double> q(8000);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = std::sin(0.2 * i) + 0.6 * std::sin(0.2 * std::sqrt(2.0) * i + 1);
  CHECK(classify(q, {}).classification == "quasi_periodic");
}

TEST_CASE("classify: white noise is never called chaotic") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Classification c = classify(testsig::white_noise(4000, seed), {});
    CHECK(c.classification != "chaotic");
    CHECK_FALSE(c.deterministic);
    CHECK(c.rqa.det < 0.5);
    CHECK(c.t01.k_median > 0.8);  // the 0-1 test alone would have been fooled
  }
}

TEST_CASE("classify: Lorenz x -> chaotic") {
  ClassifyOptions o;
  o.dt = 0.01;
  const Classification c = classify(testsig::lorenz_x(10000), o);
  CHECK(c.classification == "chaotic");
  CHECK(c.lle.fit.slope == doctest::Approx(0.9056).epsilon(0.15));
}

TEST_CASE("classify: a damped oscillation -> fixed_point") {
  std::vector<double> d(4000);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::exp(-0.003 * i) * std::sin(0.3 * i);
  CHECK(classify(d, {}).classification == "fixed_point");
}

TEST_CASE("classify: a slowly damped oscillation (60-fold over the series) -> fixed_point") {
  // Decay rate chosen so that the first/last quarter std ratio is ~60, below
  // the 100x rule: the geometric rule (>= 1.5x per quarter) must catch it.
  std::vector<double> d(8000);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::exp(-0.0007 * i) * std::sin(2 * M_PI * i / 950.0);
  const Classification c = classify(d, {});
  CHECK(c.amplitude_decay < 100);
  CHECK(c.amplitude_decay > 10);
  CHECK(c.classification == "fixed_point");
}

TEST_CASE("classify: a transient that levels off onto a cycle is not a fixed point") {
  // (1 + 4 e^{-t/T}) sin: the amplitude falls 5x early, then stays: the last
  // quarters differ by < 1.5x, so neither decay rule may fire.
  std::vector<double> d(8000);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (1 + 4 * std::exp(-0.003 * i)) * std::sin(2 * M_PI * i / 97.0);
  const Classification c = classify(d, {});
  CHECK(c.classification != "fixed_point");
}

TEST_CASE("classify: the verdict does not depend on the series' scale") {
  // Sums of squares of 1e300-sized samples overflow and those of 1e-300-sized
  // ones underflow: the statistics must be scale-free, and a plain sine times
  // either factor is the same periodic signal (it was called a fixed point).
  const std::vector<double> base = testsig::sine(5000, 37.3);
  const Classification ref = classify(base, {});
  REQUIRE(ref.classification == "periodic");
  for (double k : {1e300, -1e300, 1e-300, 1.7e308 / 1.01}) {
    std::vector<double> x(base);
    for (double& v : x) v *= k;
    const Classification c = classify(x, {});
    CAPTURE(k);
    CHECK(c.classification == ref.classification);
    CHECK(c.amplitude_decay == doctest::Approx(ref.amplitude_decay).epsilon(1e-12));
    CHECK(std::isfinite(stddev(x)));
    CHECK(stddev(x) == doctest::Approx(std::abs(k) * stddev(base)).epsilon(1e-12));
    const std::vector<double> z = zscore(x), zb = zscore(base);
    double worst = 0;
    for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(z[i] - (k > 0 ? zb[i] : -zb[i])));
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("series statistics: power-of-two normalisation leaves ordinary series bit for bit") {
  // mean and stddev by the plain formulas, for a series of ordinary scale.
  const std::vector<double> x = testsig::lorenz_x(3000);
  double s = 0;
  for (double v : x) s += v;
  const double m = s / static_cast<double>(x.size());
  double q = 0;
  for (double v : x) q += (v - m) * (v - m);
  CHECK(mean(x) == m);
  CHECK(stddev(x) == std::sqrt(q / static_cast<double>(x.size())));
}
