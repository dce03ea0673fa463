// The reference stepped frame by frame (docs/mbd.md#stepping).
#include "cvtplant/mbd/stepper.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "integrators.hpp"

namespace cvt::mbd {

struct Stepper::Solver {
  std::unique_ptr<detail::Integrator> integ;
};

const char* step_fault_name(StepFault f) {
  switch (f) {
    case StepFault::none: return "none";
    case StepFault::input: return "input";
    case StepFault::ledger: return "ledger";
    case StepFault::torn_chain: return "torn_chain";
    case StepFault::runaway: return "runaway";
    case StepFault::step_cap: return "step_cap";
    case StepFault::solver: return "solver";
    case StepFault::state: return "state";
  }
  return "state";
}

namespace {

// A failure's kind from what the model and the integrators report
// (docs/mbd.md#failures).
StepFault classify(const std::string& q) {
  const auto has = [&q](const char* w) { return q.find(w) != std::string::npos; };
  if (has("energy ledger")) return StepFault::ledger;
  if (has("came apart")) return StepFault::torn_chain;
  if (has("runaway")) return StepFault::runaway;
  if (has("step cap")) return StepFault::step_cap;
  if (has("BDF") || has("CVODE") || has("KLU")) return StepFault::solver;
  return StepFault::state;
}

std::string at_time(double t, const std::string& q) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "at t = %.6g s: ", t);
  return buf + q;
}

}  // namespace

void Stepper::build(const MbdParams& params) {
  if (!(opt_.frame_s > 0 && opt_.frame_s <= 1.0)) throw std::invalid_argument("stepper: frame in (0, 1] s");
  if (!(opt_.rtol > 0 && opt_.rtol < 1)) throw std::invalid_argument("stepper: rtol in (0, 1)");
  if (!(opt_.settle_rtol > 0 && opt_.settle_rtol < 1)) throw std::invalid_argument("stepper: settle rtol in (0, 1)");
  if (!(opt_.ledger_tol > 0)) throw std::invalid_argument("stepper: ledger tolerance > 0");
  if (opt_.max_steps_per_frame < 1) throw std::invalid_argument("stepper: step cap per frame >= 1");
  model_ = std::make_unique<ChainModel>(params);  // std::invalid_argument for bad parameters
  solver_ = std::make_unique<Solver>();
  y_ = model_->initial_state();
  start_.states = model_->size();
  start_.jacobian_nnz = model_->pattern().nnz();
}

Stepper::Stepper(const MbdParams& params, const StepperOptions& options, const Snapshot& release) : opt_(options) {
  build(params);
  if (release.y.size() != y_.size()) throw std::invalid_argument("stepper: release snapshot of another model");
  if (release.t_s != 0.0) throw std::invalid_argument("stepper: a release snapshot is taken at t = 0");
  y_ = release.y;
  in_ = release.inputs;
  if (release.outputs.fault != StepFault::none) {
    fail(release.outputs.fault, release.fault_what);
    return;
  }
  release_at(params);
  // As save() does to the stepper the snapshot came from.
  if (solver_->integ && !faulted()) solver_->integ->reinit(0.0, y_.data());
}

Stepper::Stepper(const MbdParams& params, const StepperOptions& options) : opt_(options) {
  build(params);
  in_.clamp1_N = model_->clamp_force(0, 0.0);
  in_.clamp2_N = model_->clamp_force(1, 0.0);
  in_.tau_in_Nm = params.tau_in_Nm.at(0.0);
  in_.tau_load_Nm = params.tau_load_Nm.at(0.0);
  try {
    RunOptions ro;
    ro.settle_rtol = opt_.settle_rtol;
    ro.linear_solver = opt_.linear_solver;
    detail::settle_and_start(*model_, y_, ro, start_);
  } catch (const RunFailure& e) {
    fail(classify(e.quantity), e.what());
    return;
  }
  if (model_->driver_sheave_locked()) {
    // docs/mbd.md#stepping: released with the driver clamping that held the
    // ratio, the mean of the locked sheave's axial force over the hold's last
    // 20 ms (the link passing modulates it), or at the release.
    double sum = 0;
    int n = 0;
    for (const Sample& h : start_.hold_samples)
      if (h.t_s >= -0.02 - 1e-9) {
        sum += h.F_ax_N[0];
        ++n;
      }
    in_.clamp1_N = n > 0 ? sum / n : model_->sample(0.0, y_.data()).F_ax_N[0];
  }
  release_at(params);
}

// The release (t = 0): the loads of the run, the ledger from here, the BDF.
void Stepper::release_at(const MbdParams& params) {
  model_->set_phase(ChainModel::Phase::run);
  if (params.hold1.active) y_[static_cast<std::size_t>(model_->pulley_speed(0))] = params.hold1.omega_rad_s;
  if (params.hold2.active) y_[static_cast<std::size_t>(model_->pulley_speed(1))] = params.hold2.omega_rad_s;
  model_->reset_ledger(y_.data());
  model_->hold_inputs(in_.clamp1_N, in_.clamp2_N, in_.tau_in_Nm, in_.tau_load_Nm);
  energy0_J_ = model_->energy_J(y_.data());
  floor_J_ = model_->tolerance_energy_J();
  start_.energy0_J = energy0_J_;
  start_.ledger_floor_J = floor_J_;
  try {
    solver_->integ = detail::make_bdf(*model_, 0.0, y_.data(), opt_.rtol, opt_.max_steps_per_frame, true,
                                        opt_.linear_solver);
  } catch (const RunFailure& e) {
    fail(StepFault::solver, e.what());
    return;
  }
  evaluate();
}

Stepper::~Stepper() = default;

void Stepper::fail(StepFault f, const std::string& what) {
  out_.fault = f;
  fault_what_ = what;
}

SolverCounters Stepper::counters() const {
  return solver_ && solver_->integ ? solver_->integ->counters() : SolverCounters{};
}

const StepOutputs& Stepper::step(const StepInputs& in, int frames) {
  if (faulted()) return out_;
  const double t_now = static_cast<double>(frames_done_) * opt_.frame_s;
  if (frames < 1) {
    fail(StepFault::input, at_time(t_now, "frames per step must be >= 1"));
    return out_;
  }
  for (double v : {in.clamp1_N, in.clamp2_N, in.tau_in_Nm, in.tau_load_Nm})
    if (!std::isfinite(v)) {
      fail(StepFault::input, at_time(t_now, "an input is not finite"));
      return out_;
    }
  if (model_->clamped() && !(in.clamp1_N > 0 && in.clamp2_N > 0)) {
    fail(StepFault::input, at_time(t_now, "clamping forces must be > 0 on clamped sheaves"));
    return out_;
  }
  in_ = in;
  model_->hold_inputs(in.clamp1_N, in.clamp2_N, in.tau_in_Nm, in.tau_load_Nm);
  const double t_end = static_cast<double>(frames_done_ + frames) * opt_.frame_s;
  try {
    // The cap counts per frame: the integrator's cap is cumulative.
    solver_->integ->set_step_cap(counters().steps + opt_.max_steps_per_frame * frames);
    solver_->integ->advance_to(t_end, y_.data());
  } catch (const RunFailure& e) {
    fail(classify(e.quantity), e.what());
    return out_;
  }
  frames_done_ += frames;
  const std::string bad = model_->state_problem(y_.data());
  if (!bad.empty()) {
    fail(classify(bad), at_time(t_end, bad));
    return out_;
  }
  evaluate();
  return out_;
}

void Stepper::evaluate() {
  const double t = static_cast<double>(frames_done_) * opt_.frame_s;
  const Sample s = model_->sample(t, y_.data());
  StepOutputs& o = out_;
  o.t_s = t;
  o.omega1_rad_s = s.omega_rad_s[0];
  o.omega2_rad_s = s.omega_rad_s[1];
  o.speed_ratio = std::fabs(s.omega_rad_s[1]) < 1e-3 ? 0.0 : s.omega_rad_s[0] / s.omega_rad_s[1];
  o.r1_m = s.radius_m[0];
  o.r2_m = s.radius_m[1];
  o.geometric_ratio = s.radius_m[1] / s.radius_m[0];
  o.F_ax1_N = s.F_ax_N[0];
  o.F_ax2_N = s.F_ax_N[1];
  o.slip1_m_s = s.slip_m_s[0];
  o.slip2_m_s = s.slip_m_s[1];
  const double v1 = s.omega_rad_s[0] * s.radius_m[0];
  o.slip = std::fabs(v1) < 1e-3 || !std::isfinite(v1) ? 0.0 : s.slip_m_s[0] / v1;
  o.torque_transmitted_Nm = s.chain_torque_Nm[0];
  o.torque_driven_Nm = s.chain_torque_Nm[1];
  o.tau_in_Nm = s.tau_in_Nm;
  o.tau_load_Nm = s.tau_load_Nm;
  o.tension_tight_N = s.tension_tight_N;
  o.tension_slack_N = s.tension_slack_N;
  o.sheave1_m = s.sheave_opening_m[0];
  o.sheave2_m = s.sheave_opening_m[1];
  const MbdParams& p = model_->params();
  const bool fixed = !model_->clamped();
  o.sheave1_on_stop = fixed || std::fabs(s.sheave_opening_m[0]) >= p.sheave_stop_m;
  o.sheave2_on_stop = fixed || std::fabs(s.sheave_opening_m[1]) >= p.sheave_stop_m;
  o.E_stored_J = s.E_kin_J + s.E_el_J;
  o.W_in_J = s.W_in_J;
  o.W_actuator_J = s.W_clamp_J;
  o.W_load_J = s.W_load_J;
  o.W_friction_J = s.D_friction_J;
  o.W_damping_J = s.D_damping_J;
  o.E_residual_J = ledger_residual_J(s, energy0_J_);
  o.ledger_residual_rel = std::fabs(o.E_residual_J) / ledger_scale_J(s, energy0_J_, floor_J_);
  if (!std::isfinite(o.ledger_residual_rel)) {
    fail(StepFault::ledger, at_time(t, "energy ledger is not finite"));
  } else if (o.ledger_residual_rel > opt_.ledger_tol) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "energy ledger residual %.3g (relative) exceeds %.3g", o.ledger_residual_rel,
                  opt_.ledger_tol);
    fail(StepFault::ledger, at_time(t, buf));
  }
}

Stepper::Snapshot Stepper::save() {
  if (solver_->integ && !faulted()) solver_->integ->reinit(out_.t_s, y_.data());
  Snapshot s;
  s.t_s = out_.t_s;
  s.y = y_;
  s.inputs = in_;
  s.outputs = out_;
  s.fault_what = fault_what_;
  return s;
}

void Stepper::restore(const Snapshot& s) {
  if (s.y.size() != y_.size()) throw std::invalid_argument("stepper: snapshot of another model");
  y_ = s.y;
  in_ = s.inputs;
  out_ = s.outputs;
  fault_what_ = s.fault_what;
  frames_done_ = std::llround(s.t_s / opt_.frame_s);
  model_->hold_inputs(in_.clamp1_N, in_.clamp2_N, in_.tau_in_Nm, in_.tau_load_Nm);
  if (solver_->integ) solver_->integ->reinit(s.t_s, y_.data());
}

}  // namespace cvt::mbd
