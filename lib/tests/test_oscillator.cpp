// The seed's stick-slip oscillator (Eq. 9) reproduces section 3 / Figs. 9-10
// (docs/physics.md#oscillator).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"

namespace {

using Osc = cvt::StickSlipOscillator<double>;

struct RunStats {
  Eigen::Vector4d final_state;
  double x1_peak_to_peak_late;   // over the last window
  double x1_peak_to_peak_early;  // over the window before it
};

RunStats run(const Osc& sys, Eigen::Vector4d x, double t_end, double window, cvt::Method m, double h) {
  RunStats r{};
  double lo_late = 1e300, hi_late = -1e300, lo_early = 1e300, hi_early = -1e300;
  const long n = std::lround(t_end / h);
  for (long i = 1; i <= n; ++i) {
    cvt::step(m, sys, x, h);
    const double t = static_cast<double>(i) * h;
    if (t > t_end - window) {
      lo_late = std::min(lo_late, x(0));
      hi_late = std::max(hi_late, x(0));
    } else if (t > t_end - 2 * window) {
      lo_early = std::min(lo_early, x(0));
      hi_early = std::max(hi_early, x(0));
    }
  }
  r.final_state = x;
  r.x1_peak_to_peak_late = hi_late - lo_late;
  r.x1_peak_to_peak_early = hi_early - lo_early;
  return r;
}

}  // namespace

TEST_CASE("Coulomb friction: every start converges to the analytic sliding equilibrium (seed Fig. 9)") {
  const Osc sys(cvt::OscillatorParams<double>::seed_section3(cvt::friction_presets::oscillator_coulomb<double>()));
  // x* = mu0 m g (2/pi) atan(lambda v) / k1, computed by hand from Eq. 9.
  const double x_star = 0.25 * 9.81 * (2.0 / M_PI) * std::atan(1e4 * 3.5) / 25.0;
  CHECK(sys.sliding_equilibrium_m() == doctest::Approx(x_star).epsilon(1e-12));
  for (const Eigen::Vector4d& x0 : {Eigen::Vector4d(0, 0, 0, 0), Eigen::Vector4d(0, 3, 0, 6),
                                   Eigen::Vector4d(0.5, -2, -0.5, 2), Eigen::Vector4d(-1, 5, 1, -5)}) {
    CAPTURE(x0.transpose());
    const RunStats r = run(sys, x0, 40.0, 5.0, cvt::Method::ros2, 1e-3);
    CHECK(r.final_state(0) == doctest::Approx(x_star).epsilon(1e-5));
    CHECK(r.final_state(2) == doctest::Approx(x_star).epsilon(1e-5));
    CHECK(std::fabs(r.final_state(1)) < 1e-5);
    CHECK(std::fabs(r.final_state(3)) < 1e-5);
  }
}

TEST_CASE("Stribeck friction: [0 3 0 6] ends on a sustained oscillation, [0 0 0 0] at rest (seed Fig. 10)") {
  const Osc sys(cvt::OscillatorParams<double>::seed_section3(cvt::friction_presets::oscillator_stribeck<double>()));
  SUBCASE("self-sustained oscillation") {
    const RunStats r = run(sys, Eigen::Vector4d(0, 3, 0, 6), 100.0, 20.0, cvt::Method::rk4, 1e-4);
    CHECK(r.x1_peak_to_peak_late > 0.5);  // metres: a large stick-slip cycle
    // Neither decaying nor growing: the last two windows agree to 2 %.
    CHECK(r.x1_peak_to_peak_late == doctest::Approx(r.x1_peak_to_peak_early).epsilon(0.02));
  }
  SUBCASE("rest") {
    const RunStats r = run(sys, Eigen::Vector4d(0, 0, 0, 0), 60.0, 5.0, cvt::Method::rk4, 1e-4);
    CHECK(r.x1_peak_to_peak_late < 1e-5);
    CHECK(r.final_state(0) == doctest::Approx(sys.sliding_equilibrium_m()).epsilon(1e-5));
    CHECK(std::fabs(r.final_state(1)) < 1e-5);
  }
}
