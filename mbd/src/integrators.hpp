#pragma once
// The two integrators of the chain model (docs/mbd.md#numerics). Both advance
// the full ODE state, energy ledger included, to a requested time.
#include <memory>
#include <vector>

#include "cvtplant/mbd/model.hpp"
#include "cvtplant/mbd/run.hpp"

namespace cvt::mbd::detail {

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Advances to t_s (exactly; BDF interpolates) and writes the state to y.
  // Throws RunFailure.
  virtual void advance_to(double t_s, double* y) = 0;
  virtual SolverCounters counters() const = 0;
  // Starts afresh from y at t_s (BDF: order 1, history dropped): a restored
  // state continues as a new integration from it.
  virtual void reinit(double t_s, const double* y) = 0;
  // Total steps allowed from the start (the work done so far counts).
  virtual void set_step_cap(long long cap) = 0;
};

// SUNDIALS CVODE, BDF with Newton iteration on the model's sparse Jacobian,
// its linear systems by the chain's block elimination or KLU
// (docs/mbd.md#linear-algebra). step_cap bounds the total steps.
// stop_at_outputs: never step past a requested time (the inputs may change
// there, docs/mbd.md#stepping); otherwise CVODE steps past and interpolates.
std::unique_ptr<Integrator> make_bdf(const ChainModel& m, double t0_s, const double* y0, double rtol,
                                     long long step_cap, bool stop_at_outputs = false,
                                     LinearSolver solver = LinearSolver::chain);

// docs/mbd.md#start-up: the settle at rest and, for a start at speed, the
// spin-up and the hold, from the model's initial state to the release at
// t = 0 (y: the released state). Throws RunFailure.
void settle_and_start(ChainModel& model, std::vector<double>& y, const RunOptions& opt, RunStats& stats);
// Classical RK4 with a fixed step (the core's implementation).
std::unique_ptr<Integrator> make_rk4(const ChainModel& m, double t0_s, const double* y0, double dt_s,
                                     long long step_cap);

}  // namespace cvt::mbd::detail
