// Stationarity over windows (docs/analysis.md#stationarity).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/analysis/stationarity.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {

std::vector<double> tone(std::size_t n, double dt, double hz, double trend_per_s = 0, double amp_growth = 0) {
  const std::vector<double> noise = testsig::white_noise(n, 4);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    x[i] = (1 + amp_growth * t) * std::sin(2 * M_PI * hz * t) + trend_per_s * t + 0.05 * noise[i];
  }
  return x;
}

}  // namespace

TEST_CASE("stationarity: a tone in noise is stationary, its line found in every window") {
  StationarityOptions o;
  o.dt = 1e-3;
  const Stationarity s = stationarity(tone(8000, 1e-3, 103.2), o);
  CHECK(s.stationary);
  REQUIRE(s.windows.size() == 4);
  CHECK(s.dominant_Hz == doctest::Approx(103.2).epsilon(1e-3));
  for (const auto& w : s.windows) {
    CHECK(w.t_end_s - w.t_begin_s == doctest::Approx(2.0));
    CHECK(w.dominant_line_Hz == doctest::Approx(103.2).epsilon(2e-3));
    CHECK(w.std == doctest::Approx(std::sqrt(0.5 + 0.0025)).epsilon(0.02));
  }
}

TEST_CASE("stationarity: a drift, a growing amplitude and a sweeping line are each caught") {
  StationarityOptions o;
  o.dt = 1e-3;
  const Stationarity drift = stationarity(tone(8000, 1e-3, 103.2, 0.5), o);
  CHECK_FALSE(drift.stationary);
  CHECK(drift.mean_shift > 0.5);
  const Stationarity grow = stationarity(tone(8000, 1e-3, 103.2, 0, 0.5), o);
  CHECK_FALSE(grow.stationary);
  CHECK(grow.std_ratio > 1.5);
  // A chirp from 100 to 120 Hz: same level and spread, the line moves.
  std::vector<double> chirp(8000);
  for (std::size_t i = 0; i < chirp.size(); ++i) {
    const double t = i * 1e-3;
    chirp[i] = std::sin(2 * M_PI * (100 * t + 1.25 * t * t));
  }
  const Stationarity sw = stationarity(chirp, o);
  CHECK_FALSE(sw.stationary);
  CHECK(sw.mean_shift < 0.5);
  CHECK(sw.std_ratio < 1.5);
  CHECK(sw.line_shift > sw.line_tolerance);
}

TEST_CASE("stationarity: refuses short windows and non-finite values") {
  StationarityOptions o;
  CHECK_THROWS(stationarity(std::vector<double>(200, 1.0), o));
  std::vector<double> x = tone(4000, 1e-3, 50);
  x[100] = NAN;
  CHECK_THROWS(stationarity(x, o));
}
