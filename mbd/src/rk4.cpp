// Fixed-step RK4, the seed's method, for the chain model (docs/mbd.md#numerics).
// The stepping formula is the core's (cvtplant/integrate/explicit_rk.hpp); time
// rides along as the last state so time-varying clamping forces are sampled
// at each stage's own time.
#include <Eigen/Core>

#include <cmath>
#include <string>

#include "cvtplant/integrate/explicit_rk.hpp"
#include "integrators.hpp"

namespace cvt::mbd::detail {

namespace {

struct AutonomousChain {
  using Scalar = double;
  static constexpr int kStates = Eigen::Dynamic;
  const ChainModel* model;
  void derivative(const Eigen::VectorXd& x, Eigen::VectorXd& dx) const {
    const Eigen::Index n = x.size() - 1;
    dx.resize(x.size());
    if (!model->rhs(x(n), x.data(), dx.data())) throw RunFailure(model->fault().t_s, model->fault().quantity);
    dx(n) = 1.0;
  }
};

class Rk4 final : public Integrator {
 public:
  Rk4(const ChainModel& m, double t0, const double* y0, double dt, long long cap)
      : sys_{&m}, t0_(t0), dt_(dt), cap_(cap) {
    x_.resize(m.size() + 1);
    for (int i = 0; i < m.size(); ++i) x_(i) = y0[i];
    x_(m.size()) = t0;
  }

  void advance_to(double tout, double* y) override {
    // Steps are counted from t0 and the time is k dt, so no drift builds up.
    const long long target = std::llround((tout - t0_) / dt_);
    while (steps_ < target) {
      if (steps_before_ + steps_ >= cap_)
        throw RunFailure(t0_ + steps_ * dt_, "step cap of " + std::to_string(cap_) + " steps reached (raise --max-steps)");
      step_rk4(sys_, x_, dt_);
      ++steps_;
      x_(x_.size() - 1) = t0_ + static_cast<double>(steps_) * dt_;
    }
    for (Eigen::Index i = 0; i + 1 < x_.size(); ++i) y[i] = x_(i);
  }

  void set_step_cap(long long cap) override { cap_ = cap; }

  void reinit(double t, const double* y) override {
    // Steps count on from the new start (the cap spans both).
    steps_before_ += steps_;
    steps_ = 0;
    t0_ = t;
    for (Eigen::Index i = 0; i + 1 < x_.size(); ++i) x_(i) = y[i];
    x_(x_.size() - 1) = t;
  }

  SolverCounters counters() const override {
    SolverCounters c;
    c.steps = steps_before_ + steps_;
    c.rhs_evals = 4 * c.steps;
    return c;
  }

 private:
  AutonomousChain sys_;
  Eigen::VectorXd x_;
  double t0_, dt_;
  long long cap_;
  long long steps_ = 0, steps_before_ = 0;
};

}  // namespace

std::unique_ptr<Integrator> make_rk4(const ChainModel& m, double t0, const double* y0, double dt, long long cap) {
  return std::make_unique<Rk4>(m, t0, y0, dt, cap);
}

}  // namespace cvt::mbd::detail
