// Delay and dimension estimators (docs/analysis.md#embedding).
#include <doctest/doctest.h>

#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

TEST_CASE("FNN (Kennel Rtol=10, Atol=2): Lorenz needs m = 3") {
  const auto x = testsig::lorenz_x(10000);
  FnnOptions o;
  o.tau = average_mutual_information(x, 200).tau;
  // AMI first minimum of Lorenz x at dt=0.01 is near 0.17 time units.
  CHECK(o.tau >= 12);
  CHECK(o.tau <= 22);
  const FnnResult r = false_nearest_neighbours(x, o);
  CHECK(r.dimension == 3);
  CHECK(r.fraction[1] > 0.02);   // m=2 still has false neighbours
  CHECK(r.fraction[2] <= 0.01);  // m=3 unfolds the attractor
}

TEST_CASE("FNN: Henon needs m = 2 (tau = 1)") {
  const auto x = testsig::henon_x(5000);
  FnnOptions o;
  o.tau = 1;
  const FnnResult r = false_nearest_neighbours(x, o);
  CHECK(r.dimension == 2);
  CHECK(r.fraction[0] > 0.5);
}

TEST_CASE("FNN: white noise never reaches the threshold") {
  const auto x = testsig::white_noise(4000);
  FnnOptions o;
  o.tau = 1;
  o.m_max = 8;
  const FnnResult r = false_nearest_neighbours(x, o);
  CHECK_FALSE(r.reached);
  // Atol criterion: neighbours in noise are far apart in units of the std.
  CHECK(*std::min_element(r.fraction.begin(), r.fraction.end()) > 0.05);
}

TEST_CASE("Cao: E1 saturates at m = 3 for Lorenz, m = 2 for Henon; E2 ~ 1 for noise") {
  const auto x = testsig::lorenz_x(10000);
  CaoOptions o;
  o.tau = average_mutual_information(x, 200).tau;
  CHECK(cao(x, o).dimension == 3);
  CaoOptions h;
  h.tau = 1;
  CHECK(cao(testsig::henon_x(5000), h).dimension == 2);
  // Noise: future values are independent of the neighbour relation.
  const CaoResult n = cao(testsig::white_noise(4000), h);
  for (double e2 : n.e2) CHECK(std::abs(e2 - 1) < 0.1);
}

TEST_CASE("AMI: first minimum of a sine lies near a quarter period") {
  const auto x = testsig::sine(8000, 40.0);
  const AmiResult r = average_mutual_information(x, 100);
  // A quarter period is 10 samples. Histogram MI of a sine is jagged (bin
  // aliasing), so only the bracket [quarter/2, 1.3 quarter] is asserted; the
  // autocorrelation's first zero is within one sample of the quarter period.
  CHECK(r.tau >= 5);
  CHECK(r.tau <= 13);
  CHECK(std::abs(r.tau_acf_zero - 10) <= 1);
}

TEST_CASE("embedding estimators reject bad input") {
  CHECK_THROWS_AS(false_nearest_neighbours(std::vector<double>(50, 1.0), FnnOptions{}), InputError);
  std::vector<double> x = testsig::sine(500, 20);
  x[100] = std::nan("");
  CHECK_THROWS_AS(average_mutual_information(x, 10), InputError);
  FnnOptions o;
  o.tau = 0;
  CHECK_THROWS_AS(false_nearest_neighbours(testsig::sine(500, 20), o), InputError);
}
