// Delay and dimension estimators (docs/analysis.md#embedding).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/neighbours.hpp"
#include "cvtplant/analysis/series.hpp"
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

namespace {

// Brute-force nearest neighbour outside the Theiler window: the smallest
// squared distance, the lowest index among equals (docs/analysis.md#fnn).
bool brute_nearest(const Embedding& e, std::size_t i, int w, std::size_t& j, double& d) {
  double best = 0;
  bool found = false;
  for (std::size_t k = 0; k < e.n; ++k) {
    if (std::labs(static_cast<long>(k) - static_cast<long>(i)) <= w) continue;
    double d2 = 0;
    for (int c = 0; c < e.m; ++c) d2 += (e.row(i)[c] - e.row(k)[c]) * (e.row(i)[c] - e.row(k)[c]);
    if (!found || d2 < best) {
      best = d2;
      j = k;
      found = true;
    }
  }
  d = std::sqrt(best);
  return found;
}

// Kennel's two criteria over every point, as docs/analysis.md#fnn states them,
// on the brute-force neighbours.
std::vector<double> brute_fnn(const std::vector<double>& x, const FnnOptions& o, int theiler) {
  const double ra = stddev(x);  // R_A, the library's (not under test here)
  std::vector<double> out;
  for (int m = 1; m <= o.m_max; ++m) {
    const Embedding e = delay_embed(x, m, o.tau, static_cast<std::size_t>(o.tau));
    std::size_t valid = 0, fals = 0;
    for (std::size_t i = 0; i < e.n; ++i) {
      std::size_t j;
      double d;
      if (!brute_nearest(e, i, theiler, j, d) || !(d > 0)) continue;
      const double extra = std::abs(x[i + static_cast<std::size_t>(m * o.tau)] - x[j + static_cast<std::size_t>(m * o.tau)]);
      ++valid;
      fals += (extra / d > o.rtol || std::sqrt(d * d + extra * extra) / ra > o.atol);
    }
    out.push_back(static_cast<double>(fals) / static_cast<double>(valid));
  }
  return out;
}

}  // namespace

TEST_CASE("FNN equals brute force (Lorenz, Henon, a coarsely quantised series with tied distances)") {
  std::vector<double> quantised = testsig::lorenz_x(1500);
  for (double& v : quantised) v = std::round(v * 2) / 2;  // few distinct values: many exact ties
  struct Case {
    std::vector<double> x;
    int tau;
  };
  for (const Case& c : {Case{testsig::lorenz_x(2000), 15}, Case{testsig::henon_x(1500), 1}, Case{quantised, 15}}) {
    FnnOptions o;
    o.tau = c.tau;
    o.m_max = 6;
    const FnnResult r = false_nearest_neighbours(c.x, o);
    const std::vector<double> ref = brute_fnn(c.x, o, r.theiler);
    REQUIRE(r.fraction.size() == ref.size());
    for (std::size_t k = 0; k < ref.size(); ++k) CHECK_MESSAGE(r.fraction[k] == ref[k], "m = " << k + 1);
  }
}

TEST_CASE("delay neighbours: the brute-force neighbour and distance, with any hint, in every dimension") {
  // Values on a coarse grid tie often: the lowest index among equals must
  // win with and without a hint.
  std::vector<double> x = testsig::white_noise(800, 3);
  for (double& v : x) v = std::round(v * 3);
  const int tau = 2;
  DelayNeighbours nn(x, tau);
  for (int m : {1, 2, 3, 4}) {
    const Embedding e = delay_embed(x, m, tau, tau);
    nn.set_dimension(m, e.n);
    REQUIRE(nn.size() == e.n);
    std::vector<bool> seen(e.n, false);
    for (int w : {0, 5}) {
      for (std::size_t p = 0; p < nn.size(); ++p) {
        const std::size_t i = nn.row_of(p);
        REQUIRE(i < e.n);
        seen[i] = true;
        std::size_t jb = 0, j = 0;
        double db = 0, d = 0;
        REQUIRE(brute_nearest(e, i, w, jb, db));
        for (std::size_t hint : {DelayNeighbours::kNoHint, std::size_t{0}, i + 1, (i * 37) % e.n, e.n - 1, e.n + 10}) {
          REQUIRE(nn.nearest(p, w, j, d, hint));
          CHECK(j == jb);
          CHECK(d == db);
        }
      }
    }
    CHECK(std::count(seen.begin(), seen.end(), true) == static_cast<long>(e.n));  // labels cover every row once
  }
}
