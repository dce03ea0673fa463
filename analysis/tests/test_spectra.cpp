// Lyapunov spectra of the reference systems against public values
// (docs/analysis.md#validation lists the published values and their sources).
#include <doctest/doctest.h>

#include <cmath>
#include <tuple>

#include "cvtplant/analysis/lyapunov.hpp"
#include "cvtplant/analysis/systems.hpp"

using namespace cvt::analysis;

namespace {

// The run of a spectrum: step (flows), transient, warm-up, accumulation.
BenettinOptions run(double dt, double t_transient, double t_warmup, double t_end) {
  BenettinOptions o;
  std::tie(o.dt, o.t_transient, o.t_warmup, o.t_end) = std::make_tuple(dt, t_transient, t_warmup, t_end);
  return o;
}

}  // namespace

TEST_CASE("logistic map r=4: lambda = ln 2") {
  const BenettinOptions o = run(BenettinOptions{}.dt, 1000, 10, 1e6);
  const SpectrumResult r = lyapunov_map(Logistic{}, Eigen::Matrix<double, 1, 1>(0.3), o);
  // 1e6 iterations: batch-means CI is ~2e-3; 5e-3 allows 2.5 CI.
  CHECK(std::abs(r.exponents[0] - std::log(2.0)) < 5e-3);
  CHECK(std::abs(r.exponents[0] - std::log(2.0)) <= 2.5 * r.ci95[0] + 1e-4);
  // For a 1-D map the exponent is the mean of ln|f'|, identical to trace_mean.
  CHECK(r.exponents[0] == doctest::Approx(r.trace_mean).epsilon(1e-12));
}

TEST_CASE("Henon map: (0.41922, -1.62319), sum = ln b") {
  const BenettinOptions o = run(BenettinOptions{}.dt, 1000, 100, 1e6);
  const SpectrumResult r = lyapunov_map(Henon{}, Eigen::Vector2d(0.1, 0.1), o);
  // Published to 5 digits; 1e6 iterations give a CI of ~1e-3.
  CHECK(std::abs(r.exponents[0] - 0.41922) < 3e-3);
  CHECK(std::abs(r.exponents[1] + 1.62319) < 3e-3);
  // |det J| = b at every step, so the sum is exact up to rounding.
  CHECK(std::abs(r.sum - std::log(0.3)) < 1e-9);
  CHECK(std::abs(r.trace_mean - std::log(0.3)) < 1e-9);
}

TEST_CASE("Lorenz: (0.9056, 0, -14.5723), sum = -(sigma+1+beta)") {
  const BenettinOptions o = run(0.005, 50, 10, 2000);
  const SpectrumResult r = lyapunov_flow(Lorenz{}, Eigen::Vector3d(1, 1, 1), o);
  // T = 2000: the finite-time fluctuation of lambda_1 is ~0.01 (the CI); 0.03 is 3 CI.
  CHECK(std::abs(r.exponents[0] - 0.9056) < 0.03);
  CHECK(std::abs(r.exponents[1]) < 0.01);
  CHECK(std::abs(r.exponents[2] + 14.5723) < 0.03);
  CHECK(std::abs(r.exponents[0] - 0.9056) <= 3 * r.ci95[0] + 0.005);
  // Liouville: the sum equals the mean trace, here the constant -(10+1+8/3).
  CHECK(std::abs(r.sum - (-(10 + 1 + 8.0 / 3.0))) < 1e-3);
  CHECK(std::abs(r.sum - r.trace_mean) < 1e-3);
  CHECK(r.zero_index == 1);
  // The flow-direction growth rate is the neutral exponent: near 0.
  CHECK(std::abs(r.flow_direction_rate) < 0.01);
}

TEST_CASE("Roessler: (0.0714, 0, -5.3943)") {
  const BenettinOptions o = run(0.01, 200, 50, 20000);
  const SpectrumResult r = lyapunov_flow(Rossler{}, Eigen::Vector3d(1, 1, 0), o);
  // T = 2e4 (about 3300 orbits): CI ~ 2e-3 on lambda_1; 6e-3 tolerance is ~3 CI.
  CHECK(std::abs(r.exponents[0] - 0.0714) < 6e-3);
  CHECK(std::abs(r.exponents[1]) < 3e-3);
  CHECK(std::abs(r.exponents[2] + 5.3943) < 0.02);
  CHECK(std::abs(r.sum - r.trace_mean) < 1e-3);
}

TEST_CASE("Lorenz spectrum converges as dt halves (RK4)") {
  const SpectrumResult a = lyapunov_flow(Lorenz{}, Eigen::Vector3d(1, 1, 1), run(0.01, 20, 5, 100));
  const SpectrumResult b = lyapunov_flow(Lorenz{}, Eigen::Vector3d(1, 1, 1), run(0.005, 20, 5, 100));
  // Same (finite) time: the trajectories decorrelate by t=100 so only the
  // trace, a smooth functional, is compared tightly.
  CHECK(std::abs(a.sum - b.sum) < 1e-3);
  CHECK(std::abs(a.exponents[2] - b.exponents[2]) < 0.2);
}

TEST_CASE("bad Benettin options are rejected") {
  BenettinOptions o;
  o.dt = 0;
  CHECK_THROWS_AS(lyapunov_flow(Lorenz{}, Eigen::Vector3d(1, 1, 1), o), std::invalid_argument);
  o.dt = 1.0;  // RK4 on Lorenz at dt=1 diverges: reported, not silently wrong
  o.t_end = 100;
  CHECK_THROWS_AS(lyapunov_flow(Lorenz{}, Eigen::Vector3d(1, 1, 1), o), std::runtime_error);
}
