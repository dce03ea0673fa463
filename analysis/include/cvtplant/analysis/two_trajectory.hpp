#pragma once
// The largest Lyapunov exponent of a flow that can only be stepped, read and
// restarted (docs/analysis.md#two-trajectory): Benettin's method with two
// trajectories. Every renormalisation interval the reference state is
// copied, displaced by delta0 along the current deviation direction (in a
// weighted norm), both are advanced from the same time by the same stepper,
// and the growth of their distance is the interval's stretch; the deviation
// is then scaled back to delta0 along its new direction. This needs neither
// the equations nor their Jacobian, only a stepper that restarts from any
// state (a black box, e.g. the multibody reference's integrator).
#include <cstdint>
#include <functional>
#include <vector>

namespace cvt::analysis {

// What the method needs of a flow.
class RestartableFlow {
 public:
  virtual ~RestartableFlow() = default;
  virtual double t_s() const = 0;
  virtual std::vector<double> state() const = 0;
  // Continue from state y at time t (the integrator restarts there).
  virtual void restart(double t_s, const std::vector<double>& y) = 0;
  // Advance by dt_s; throws std::runtime_error if the flow fails.
  virtual void advance(double dt_s) = 0;
};

struct TwoTrajectoryOptions {
  double t_renorm_s = 0.02;  // renormalisation interval
  int warmup = 50;           // intervals that align the deviation, not accumulated
  int intervals = 500;       // intervals accumulated
  int batches = 10;          // for the confidence interval (batch means, Student t)
  double delta0 = 1e-6;      // the deviation's size in the weighted norm
  std::uint64_t seed = 20260601u;  // the first direction
  // Called after each interval with (intervals done, warmup + intervals), e.g.
  // by a progress bar; empty: not called.
  std::function<void(int done, int total)> progress;
};

struct TwoTrajectoryResult {
  double lambda = 0;          // [1/time unit]
  double ci95 = 0;            // half-width, batch means
  std::vector<double> batch_lambda;
  std::vector<double> t_s, cumulative;  // the running estimate after each accumulated interval
  std::vector<double> stretch;          // ln(d / delta0) per accumulated interval
  double max_stretch = 0;     // the largest one-interval growth (linearity: must stay << ln(1/delta0))
  int intervals = 0;
};

// weights: per state component, the norm's weight (0: the component is
// neither displaced nor measured, e.g. a quantity that feeds nothing back).
// Throws std::invalid_argument for bad options or weights that do not match
// the state, std::runtime_error if the flow fails.
TwoTrajectoryResult largest_exponent_two_trajectories(RestartableFlow& flow, const std::vector<double>& weights,
                                                      const TwoTrajectoryOptions& opt);

}  // namespace cvt::analysis
