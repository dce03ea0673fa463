// Benettin's two-trajectory method on a restartable flow (docs/analysis.md#two-trajectory).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/analysis/two_trajectory.hpp"
#include "cvtplant/integrate/explicit_rk.hpp"

using namespace cvt::analysis;

namespace {

// A system of the core's integrators (integrate/system.hpp) stepped by its
// RK4, restartable anywhere.
template <class Sys>
class Rk4Flow : public RestartableFlow {
 public:
  using State = Eigen::Matrix<double, Sys::kStates, 1>;
  Rk4Flow(Sys s, const State& y, double h) : sys_(s), y_(y), h_(h) {}
  double t_s() const override { return t_; }
  std::vector<double> state() const override { return std::vector<double>(y_.data(), y_.data() + Sys::kStates); }
  void restart(double t, const std::vector<double>& y) override {
    t_ = t;
    for (int i = 0; i < Sys::kStates; ++i) y_(i) = y[static_cast<std::size_t>(i)];
  }
  void advance(double dt) override {
    const long n = std::lround(dt / h_);
    for (long i = 0; i < n; ++i) cvt::step_rk4(sys_, y_, h_);
    t_ += static_cast<double>(n) * h_;
  }

 private:
  Sys sys_;
  State y_;
  double h_, t_ = 0;
};

// Hopf normal form: r' = r (1 - r^2), theta' = 1; exponents 0 (along the
// cycle r = 1) and -2 (across it).
struct Hopf {
  using Scalar = double;
  static constexpr int kStates = 2;
  template <class S>
  void derivative(const Eigen::Matrix<S, 2, 1>& y, Eigen::Matrix<S, 2, 1>& d) const {
    const S r2 = y(0) * y(0) + y(1) * y(1);
    d(0) = y(0) * (S(1) - r2) - y(1);
    d(1) = y(1) * (S(1) - r2) + y(0);
  }
};

// A linear sink x' = -x, y' = -3 y.
struct Sink {
  using Scalar = double;
  static constexpr int kStates = 2;
  template <class S>
  void derivative(const Eigen::Matrix<S, 2, 1>& y, Eigen::Matrix<S, 2, 1>& d) const {
    d(0) = -y(0);
    d(1) = S(-3) * y(1);
  }
};

}  // namespace

TEST_CASE("two trajectories: Lorenz's largest exponent, 0.9056") {
  Rk4Flow<Lorenz> flow(Lorenz{}, Eigen::Vector3d(1, 1, 20), 0.005);
  flow.advance(50);  // onto the attractor
  TwoTrajectoryOptions o;
  o.t_renorm_s = 0.1;
  o.warmup = 100;
  o.intervals = 10000;
  o.batches = 20;
  const TwoTrajectoryResult r = largest_exponent_two_trajectories(flow, {1, 1, 1}, o);
  CHECK(r.intervals == 10000);
  CHECK(r.lambda == doctest::Approx(0.9056).epsilon(0.03));
  CHECK(std::fabs(r.lambda - 0.9056) < 2 * r.ci95 + 0.01);
  CHECK(r.ci95 < 0.05);
  CHECK(r.cumulative.back() == doctest::Approx(r.lambda));
}

TEST_CASE("two trajectories: a limit cycle's largest exponent is zero, a sink's its eigenvalue") {
  Rk4Flow<Hopf> cyc(Hopf{}, Eigen::Vector2d(0.5, 0.0), 0.001);
  cyc.advance(20);
  TwoTrajectoryOptions o;
  o.t_renorm_s = 0.5;
  o.warmup = 20;
  o.intervals = 400;
  const TwoTrajectoryResult c = largest_exponent_two_trajectories(cyc, {1, 1}, o);
  CHECK(std::fabs(c.lambda) < 1e-3);
  // The sink: the slowest direction wins, -1 exactly.
  Rk4Flow<Sink> s(Sink{}, Eigen::Vector2d(1.0, 1.0), 0.001);
  const TwoTrajectoryResult l = largest_exponent_two_trajectories(s, {1, 1}, o);
  CHECK(l.lambda == doctest::Approx(-1.0).epsilon(1e-6));
  // A zero weight leaves a component out: only the fast direction is measured.
  Rk4Flow<Sink> s2(Sink{}, Eigen::Vector2d(1.0, 1.0), 0.001);
  CHECK(largest_exponent_two_trajectories(s2, {0, 1}, o).lambda == doctest::Approx(-3.0).epsilon(1e-6));
}

TEST_CASE("two trajectories: bad options") {
  Rk4Flow<Sink> f(Sink{}, Eigen::Vector2d(1.0, 1.0), 0.01);
  TwoTrajectoryOptions o;
  CHECK_THROWS_AS(largest_exponent_two_trajectories(f, {1, 1, 1}, o), std::invalid_argument);
  CHECK_THROWS_AS(largest_exponent_two_trajectories(f, {0, 0}, o), std::invalid_argument);
  o.delta0 = 2;
  CHECK_THROWS_AS(largest_exponent_two_trajectories(f, {1, 1}, o), std::invalid_argument);
}
