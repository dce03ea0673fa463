#pragma once
// The multibody reference as a plant stepped frame by frame
// (docs/mbd.md#stepping): new inputs each frame (clamping forces, input and
// load torque), the signals the real-time plant reports, the energy ledger
// checked every frame, the state saved and restored in memory. A failure
// mid-run (ledger, torn chain, runaway, step cap, solver) sets the fault
// state; nothing is thrown into the caller's loop once it is built.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/mbd/model.hpp"
#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"

namespace cvt::mbd {

// Inputs held over a frame (zero-order hold, as the real-time plant's).
struct StepInputs {
  double clamp1_N = 0;      // driver clamping force (clamped sheaves; ignored on fixed sheaves)
  double clamp2_N = 0;      // driven clamping force
  double tau_in_Nm = 0;     // input torque on the driver
  double tau_load_Nm = 0;   // load torque on the driven pulley (the parameters' road load is added)
};

// Why the stepper stopped (docs/mbd.md#stepping): input (a non-finite input,
// or a clamping force <= 0 on clamped sheaves), ledger, torn_chain, runaway,
// step_cap, solver (CVODE), state (any other bad state: a bolt through the
// groove, a link off the drive, a sheave open to the shaft).
enum class StepFault : std::uint8_t { none, input, ledger, torn_chain, runaway, step_cap, solver, state };
const char* step_fault_name(StepFault f);  // "none", "ledger", ...

// What a frame reports. Names and units follow the real-time plant's signal
// list (cvtplant/plant/rom_signals.hpp) where they mean the same quantity.
struct StepOutputs {
  double t_s = 0;
  double omega1_rad_s = 0, omega2_rad_s = 0;  // omega1, omega2
  double speed_ratio = 0;      // omega1 / omega2 (0 while |omega2| < 1e-3 rad/s)
  double geometric_ratio = 0;  // r2 / r1 of the running radii
  double r1_m = 0, r2_m = 0;   // running radii: mean bolt radius in each wrap
  double F_ax1_N = 0, F_ax2_N = 0;  // axial force of the chain on each pulley (F_ax: the driver's)
  double slip = 0;             // driver slip (v1 - v_chain) / v1, v1 = omega1 r1 (0 while |v1| < 1e-3 m/s)
  double slip1_m_s = 0, slip2_m_s = 0;  // surface speed minus chain speed in each wrap
  double torque_transmitted_Nm = 0;  // friction torque the chain exerts on the driver pulley
  double torque_driven_Nm = 0;       // the chain's torque on the driven pulley
  double tau_in_Nm = 0, tau_load_Nm = 0;  // torques as applied (road load included)
  double tension_tight_N = 0, tension_slack_N = 0;  // T_tight, T_slack
  double sheave1_m = 0, sheave2_m = 0;  // movable sheaves' openings (clamped)
  bool sheave1_on_stop = false, sheave2_on_stop = false;  // on a ratio end stop (fixed sheaves: true)
  // Energy ledger since the release (rom_signals' energy group).
  double E_stored_J = 0, W_in_J = 0, W_actuator_J = 0, W_load_J = 0, W_friction_J = 0, W_damping_J = 0;
  double E_residual_J = 0, ledger_residual_rel = 0;
  StepFault fault = StepFault::none;
};

struct StepperOptions {
  double frame_s = 1e-3;              // one step() advances by frames x frame_s
  double rtol = 5e-7;                 // BDF relative tolerance (docs/mbd.md#tolerances)
  long long max_steps_per_frame = 200000;  // integrator steps a frame may take before it faults
  double ledger_tol = 1e-6;           // relative ledger residual that faults the run
  double settle_rtol = 1e-8;          // the start-up (docs/mbd.md#start-up)
  LinearSolver linear_solver = LinearSolver::chain;  // docs/mbd.md#linear-algebra
};

class Stepper {
 public:
  // Builds the model, settles it and (params.start) brings it to speed; the
  // release is t = 0 with the parameters' input profiles at t = 0 as the
  // first inputs (with the start's ratio lock, the driver clamping is the
  // force that held the ratio). Throws std::invalid_argument for bad parameters or options;
  // a start-up that fails leaves the stepper faulted.
  Stepper(const MbdParams& params, const StepperOptions& options = {});
  struct Snapshot;
  // Starts from `release`, a snapshot a stepper of the same parameters and
  // options saved at its release (t = 0), without the start-up: the outputs
  // are, bit for bit, those of that stepper after the save() (docs/mbd.md#stepping).
  // start_stats() stays empty. Throws std::invalid_argument for a snapshot of
  // another model size or of another time than the release.
  Stepper(const MbdParams& params, const StepperOptions& options, const Snapshot& release);
  ~Stepper();
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  // Advances by `frames` (>= 1) frames with `in` held; returns the outputs at
  // the end. Faulted: does nothing and returns the last outputs. Never throws.
  const StepOutputs& step(const StepInputs& in, int frames = 1);
  const StepOutputs& outputs() const { return out_; }
  const StepInputs& inputs() const { return in_; }
  bool faulted() const { return out_.fault != StepFault::none; }
  const std::string& fault_message() const { return fault_what_; }  // "at t = T s: quantity"
  double t_s() const { return out_.t_s; }
  SolverCounters counters() const;
  const ChainModel& model() const { return *model_; }
  const double* state() const { return y_.data(); }
  // The release state as simulate() would report it (start-up work, hold samples).
  const RunStats& start_stats() const { return start_; }

  // A saved state. Saving restarts the integrator at the saved state (BDF
  // from order 1, as a restore does), so the run that goes on after save()
  // and every run after restore() of it give the same outputs for the same
  // inputs, bit for bit (docs/mbd.md#stepping).
  struct Snapshot {
    double t_s = 0;
    std::vector<double> y;
    StepInputs inputs;
    StepOutputs outputs;
    std::string fault_what;
  };
  Snapshot save();
  // Throws std::invalid_argument for a snapshot of another model size.
  void restore(const Snapshot& s);

 private:
  void build(const MbdParams& params);       // checks the options, makes the model at rest
  void release_at(const MbdParams& params);  // the run from t = 0 with in_ held
  void evaluate();               // fills out_ from y_ at t
  void fail(StepFault f, const std::string& what);

  StepperOptions opt_;
  std::unique_ptr<ChainModel> model_;
  std::vector<double> y_;
  struct Solver;
  std::unique_ptr<Solver> solver_;
  StepInputs in_;
  StepOutputs out_;
  double energy0_J_ = 0, floor_J_ = 0;
  long long frames_done_ = 0;
  std::string fault_what_;
  RunStats start_;
};

}  // namespace cvt::mbd
