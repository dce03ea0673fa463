// The ripple of a window (docs/analysis.md#ripple) on signals whose spread and
// frequency are known in closed form.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/ripple.hpp"

using namespace cvt::analysis;

namespace {
constexpr double kPi = 3.14159265358979323846;

// y(t) = 3000 + 400 t (a trend the detrend removes) + sum of a_k cos(2 pi f_k t + p_k), 1 ms samples over 3 s.
struct Signal {
  std::vector<double> t, y;
};
Signal lines(const std::vector<double>& amp, const std::vector<double>& hz, double dt = 1e-3) {
  Signal s;
  for (int i = 0; i < static_cast<int>(3.0 / dt); ++i) {
    const double t = i * dt;
    double v = 3000.0 + 400.0 * t;
    for (std::size_t k = 0; k < amp.size(); ++k) v += amp[k] * std::cos(2 * kPi * hz[k] * t + 0.3 + k);
    s.t.push_back(t);
    s.y.push_back(v);
  }
  return s;
}
std::string error_of(const std::vector<double>& t, const std::vector<double>& y, double a, double b) {
  try {
    ripple_window(t, y, a, b);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("ripple: a sine on a trend has std a/sqrt(2), peak to peak 2a, its frequency and amplitude") {
  const Signal s = lines({50.0}, {120.0});
  const RippleWindow r = ripple_window(s.t, s.y, 1.0, 1.5);
  CHECK(r.samples == 500);
  CHECK(r.mean == doctest::Approx(3000.0 + 400.0 * 1.2495).epsilon(1e-3));
  CHECK(r.std == doctest::Approx(50.0 / std::sqrt(2.0)).epsilon(1e-2));
  CHECK(r.peak_to_peak == doctest::Approx(100.0).epsilon(1e-2));
  // 1 ms samples, 500 of them zero-padded to 1024: bins of 0.98 Hz.
  CHECK(std::fabs(r.peak_hz - 120.0) < 1.0);
  CHECK(r.line_amplitude == doctest::Approx(50.0).epsilon(2e-2));
}

TEST_CASE("ripple: the line's amplitude is that of the dominant line, the std that of all") {
  // A harmonic at twice the frequency lies outside the +-20 % band.
  const Signal s = lines({50.0, 30.0}, {120.0, 240.0});
  const RippleWindow r = ripple_window(s.t, s.y, 2.0, 2.5);
  CHECK(std::fabs(r.peak_hz - 120.0) < 1.0);
  CHECK(r.line_amplitude == doctest::Approx(50.0).epsilon(2e-2));
  CHECK(r.std == doctest::Approx(std::sqrt((50.0 * 50.0 + 30.0 * 30.0) / 2.0)).epsilon(1e-2));
  // A lower threshold above the fundamental finds the harmonic.
  RippleOptions o;
  o.min_hz = 200.0;
  const RippleWindow h = ripple_window(s.t, s.y, 2.0, 2.5, o);
  CHECK(std::fabs(h.peak_hz - 240.0) < 1.0);
  CHECK(h.line_amplitude == doctest::Approx(30.0).epsilon(3e-2));
}

TEST_CASE("ripple: a chirp inside the band keeps its amplitude") {
  // Frequency rising from 100 to 120 Hz over the window (phase 2 pi (100 t' + 20 t'^2)), as the
  // link frequency does while the pulleys accelerate.
  Signal s;
  for (int i = 0; i < 2500; ++i) {
    const double t = 0.5 + i * 2e-4, u = t - 0.5;
    s.t.push_back(t);
    s.y.push_back(2000.0 - 300.0 * t + 40.0 * std::cos(2 * kPi * (100.0 * u + 20.0 * u * u)));
  }
  const RippleWindow r = ripple_window(s.t, s.y, 0.5, 1.0);
  CHECK(r.peak_hz >= 99.0);
  CHECK(r.peak_hz <= 121.0);
  CHECK(r.line_amplitude == doctest::Approx(40.0).epsilon(5e-2));
  CHECK(r.std == doctest::Approx(40.0 / std::sqrt(2.0)).epsilon(2e-2));
}

TEST_CASE("ripple: a sine in white noise keeps its frequency; std and amplitude add the noise's share") {
  // 60 N at 150 Hz plus Gaussian noise of sigma 20 N (Box-Muller on a fixed
  // linear congruential sequence), 1 ms samples, a 2 s window.
  Signal s = lines({60.0}, {150.0});
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;
  };
  const double sigma = 20.0;
  for (std::size_t i = 0; i < s.y.size(); ++i)
    s.y[i] += sigma * std::sqrt(-2.0 * std::log(uniform())) * std::cos(2 * kPi * uniform());
  const RippleWindow r = ripple_window(s.t, s.y, 0.5, 2.5);
  CHECK(std::fabs(r.peak_hz - 150.0) < 0.5);
  // Variances add: a^2/2 + sigma^2.
  CHECK(r.std == doctest::Approx(std::sqrt(60.0 * 60.0 / 2.0 + sigma * sigma)).epsilon(2e-2));
  // The band [125, 180] Hz holds 55/500 of the white noise's power, which
  // the line's amplitude takes in: sqrt(a^2 + 2 (55/500) sigma^2).
  const double band_share = (150.0 * 1.2 - 150.0 / 1.2) / 500.0;
  CHECK(r.line_amplitude == doctest::Approx(std::sqrt(60.0 * 60.0 + 2.0 * band_share * sigma * sigma)).epsilon(2e-2));
}

TEST_CASE("ripple: bad input is refused with the reason") {
  const Signal s = lines({50.0}, {120.0});
  CHECK(error_of(s.t, s.y, 1.0, 1.01).find("fewer than 16 samples") != std::string::npos);
  CHECK(error_of(s.t, s.y, 1.5, 1.0).find("must end after it begins") != std::string::npos);
  std::vector<double> t = s.t, y = s.y;
  t[1200] += 4e-4;
  CHECK(error_of(t, s.y, 1.0, 1.5).find("uniform step") != std::string::npos);
  y[3] = std::numeric_limits<double>::quiet_NaN();
  CHECK(error_of(s.t, y, 1.0, 1.5).find("non-finite value at sample 3") != std::string::npos);
  y.pop_back();
  CHECK(error_of(s.t, y, 1.0, 1.5).find("differ in length") != std::string::npos);
  const std::vector<double> flat(s.t.size(), 5.0);
  CHECK(error_of(s.t, flat, 1.0, 1.5).find("constant window") != std::string::npos);
}
