#pragma once
// Running the chain model (docs/mbd.md#numerics): settle, release, integrate
// with CVODE BDF + KLU (default) or fixed-step RK4 (the seed's method), and
// hand every output sample to the caller as it is made, so memory does not
// grow with the run length.
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cvtplant/mbd/model.hpp"
#include "cvtplant/mbd/params.hpp"

namespace cvt::mbd {

enum class Method { bdf, rk4 };

// How the BDF solves its Newton systems (docs/mbd.md#linear-algebra): the
// chain's own block elimination (a closed chain of links bordered by the
// pulleys and sheaves), or SUNDIALS' KLU sparse LU on the same Jacobian.
enum class LinearSolver { chain, klu };

struct RunOptions {
  Method method = Method::bdf;
  double t_end_s = 1.0;
  double rtol = 5e-7;           // bdf: relative tolerance (docs/mbd.md#tolerances)
  double dt_s = 1e-6;           // rk4: fixed step
  double sample_s = 1e-3;       // output interval (rk4: rounded to a whole number of steps)
  long long max_steps = 100000000;  // cap on integrator steps (work); exceeding it stops the run
  double ledger_tol = 1e-6;     // the run stops when the energy ledger is off by more (relative)
  double settle_rtol = 1e-8;    // the start-up settle, the same for every method and tolerance
  LinearSolver linear_solver = LinearSolver::chain;  // bdf (and the start-up)
};

// What the integrator did (RK4: steps and 4 right-hand sides per step).
struct SolverCounters {
  long long steps = 0, rhs_evals = 0, jac_evals = 0, linear_setups = 0, newton_iters = 0;
  long long error_test_fails = 0, newton_fails = 0;
  SolverCounters& operator+=(const SolverCounters& o) {
    steps += o.steps;
    rhs_evals += o.rhs_evals;
    jac_evals += o.jac_evals;
    linear_setups += o.linear_setups;
    newton_iters += o.newton_iters;
    error_test_fails += o.error_test_fails;
    newton_fails += o.newton_fails;
    return *this;
  }
};

struct RunStats : SolverCounters {
  long long samples = 0;
  double wall_s = 0, settle_wall_s = 0;
  // CPU time of the process over the run [s]: on a busy host, what the wall
  // time would be on an idle core.
  double cpu_s = 0;
  double settle_cpu_s = 0;  // of it, the settle and the start at speed (before the release)
  double ledger_residual_max_rel = 0;  // max over samples of |ledger residual| / ledger scale
  double energy0_J = 0;                // E_kin + E_el at the release
  double ledger_floor_J = 0;           // smallest ledger scale (see ledger_scale_J)
  int states = 0;
  long long jacobian_nnz = 0;
  // A start at speed (docs/mbd.md#start-at-speed): the integrator steps of
  // the spin-up and the hold, and the hold sampled every millisecond up to
  // the release (t < 0; the driver's tau_in is its holding torque).
  long long start_steps = 0;
  std::vector<Sample> hold_samples;
};

// How steady the hold of a start at speed was over its last window_s
// (docs/mbd.md#start-at-speed): the driven speed's range (max - min) and the
// change of the means of the driver's holding torque and of the axial forces
// between the window's two halves, each relative to the window's mean.
struct HoldSteadiness {
  double window_s = 0;
  double omega2_mean_rad_s = 0, omega2_range_rel = 0;
  double holding_torque_mean_Nm = 0, holding_torque_change_rel = 0;
  double F_ax_mean_N[2] = {0, 0}, F_ax_change_rel[2] = {0, 0};
};
// Throws std::invalid_argument if the samples do not cover the window.
HoldSteadiness hold_steadiness(const std::vector<Sample>& hold_samples, double window_s);


// A run that went bad: the time and the quantity, for the user, and what the
// run had done until then.
struct RunFailure : std::runtime_error {
  double t_s;
  std::string quantity;
  RunStats stats;
  RunFailure(double t, const std::string& q);
};

// Called for every sample, the state vector alongside (for per-link output).
using SampleSink = std::function<void(const Sample&, const ChainModel&, const double* y)>;
// Called with the simulated time now and then (progress display).
using ProgressSink = std::function<void(double t_s)>;

// Ledger residual of a sample: (E - E0) - (W_in - W_load - D_fric - D_damp + W_clamp),
// and the scale it is measured against: the largest term of the balance, but
// not less than floor_J (ChainModel::tolerance_energy_J(): below that the
// integrator's absolute tolerances, not its accuracy, set the residual).
// docs/mbd.md#energy-ledger
double ledger_residual_J(const Sample& s, double energy0_J);
double ledger_scale_J(const Sample& s, double energy0_J, double floor_J);

// Runs params for opt.t_end_s after the settle. Throws RunFailure if the
// integrator fails, a state goes bad or the ledger does not close;
// std::invalid_argument for options out of range.
RunStats simulate(const MbdParams& params, const RunOptions& opt, const SampleSink& on_sample,
                  const ProgressSink& on_progress = {});

}  // namespace cvt::mbd
