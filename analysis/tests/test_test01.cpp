// 0-1 test for chaos (docs/analysis.md#test01).
#include <doctest/doctest.h>

#include "cvtplant/analysis/test01.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

TEST_CASE("0-1 test: logistic r=4 -> K ~ 1, sine -> K ~ 0, quasi-periodic -> K ~ 0") {
  std::vector<double> lg(3000);
  double v = 0.3;
  for (auto& s : lg) s = v = 4 * v * (1 - v);
  CHECK(test01(lg, {}).k_median > 0.9);
  CHECK(std::abs(test01(testsig::sine(3000, 13.7), {}).k_median) < 0.1);
  std::vector<double> q(3000);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = std::sin(0.9 * i) + 0.6 * std::sin(0.9 * std::sqrt(2.0) * i);
  CHECK(std::abs(test01(q, {}).k_median) < 0.15);
  // Noise also gives K ~ 1: the test alone cannot separate chaos from noise.
  CHECK(test01(testsig::white_noise(3000), {}).k_median > 0.9);
}
