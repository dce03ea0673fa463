#pragma once
// The two integrators of the chain model (docs/mbd.md#numerics). Both advance
// the full ODE state, energy ledger included, to a requested time.
#include <memory>

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
};

// SUNDIALS CVODE, BDF with Newton iteration, KLU sparse direct solver and the
// model's sparse Jacobian. step_cap bounds the total steps.
std::unique_ptr<Integrator> make_bdf(const ChainModel& m, double t0_s, const double* y0, double rtol,
                                     long long step_cap);
// Classical RK4 with a fixed step (the core's implementation).
std::unique_ptr<Integrator> make_rk4(const ChainModel& m, double t0_s, const double* y0, double dt_s,
                                     long long step_cap);

}  // namespace cvt::mbd::detail
