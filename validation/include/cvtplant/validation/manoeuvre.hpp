#pragma once
// Manoeuvres on a clamped, shifting CVT (docs/validation.md#manoeuvres): a
// test rig's run of the multibody reference and of the real-time plant from
// the same operating point with the same inputs. Each model starts held at
// the operating point (the reference by its ratio lock, the plant by a lock
// of its radial state), is released at t = 0 and is driven frame by frame
// with the driver clamping as a factor on the reference's holding force, the
// driven clamping as a factor on the operating point's, and the torques.
// The reference runs through the stepping interface (docs/mbd.md#stepping),
// its runs cached by every input (docs/validation.md#cache).
#include <string>
#include <utility>
#include <vector>

#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// Where a manoeuvre starts (docs/validation.md#operating-points).
struct OperatingPoint {
  double omega1_rad_s = 150.0;  // primary speed
  double ratio = 1.5;           // geometric ratio r2/r1 on the pitch line where the chain starts
  double tau_in_Nm = 60.0;      // input torque
  double clamp2_N = 12500.0;    // driven clamping force
};

// The driver radius at which a chain of the pitch line of (r1_m, r2_m, c_m)
// runs at the geometric ratio r2/r1 = ratio [m]. Throws InputError outside
// (0.2, 5).
double driver_radius_for_ratio(double r1_m, double r2_m, double c_m, double ratio);

// The road load c_v [N m s/rad] that carries the operating point's torque at
// its speeds, c_v omega2 = tau_in ratio with omega2 = omega1 / ratio: the
// load a vehicle at constant speed puts on the driven shaft, so both models
// hold their speeds at the start and find new ones after a shift.
double balancing_road_cv(const OperatingPoint& op);

// The clamping that carries a torque T on the driver radius r1 with a safety
// factor S: T cos(beta0) S / (2 mu0 r1) (docs/mbd-production.md#envelope) [N].
double capacity_clamp_N(double torque_Nm, double r1_m, double mu0, double beta0_rad, double safety);

struct Manoeuvre {
  std::string name;
  std::string kind;  // hold, clamp-step, sweep, kick-down, slip, ... (what the goals group by)
  OperatingPoint start;
  double t_end_s = 0.3;  // after the release
  // After the release (piecewise linear in t [s], held outside):
  cvt::mbd::TimeProfile clamp1_factor = cvt::mbd::TimeProfile::constant(1.0);  // on the reference's holding driver clamping
  cvt::mbd::TimeProfile clamp2_factor = cvt::mbd::TimeProfile::constant(1.0);  // on start.clamp2_N
  cvt::mbd::TimeProfile tau_in_Nm;    // empty: start.tau_in_Nm throughout
  cvt::mbd::TimeProfile tau_load_Nm;  // added to the balancing road load; empty: 0
  // End 20 ms after the whole driver wrap first slides by more than
  // kGrossSlip_m_s (a reference in gross slip runs away and gets costly).
  bool stop_at_gross_slip = false;
};

// The inputs over the frame that starts at t_s, with the driver clamping
// the factor times hold_clamp1_N.
struct RigInputs {
  double clamp1_N = 0, clamp2_N = 0, tau_in_Nm = 0, tau_load_Nm = 0;  // tau_load: besides the road load
};
RigInputs manoeuvre_inputs(const Manoeuvre& m, double hold_clamp1_N, double t_s);

// Throws InputError for a manoeuvre out of range (speeds, ratio, forces,
// factors not positive, a length outside (0, 60] s).
void check_manoeuvre(const Manoeuvre& m);

// --- the reference

struct ReferenceConfig {
  cvt::mbd::ParameterSet set = cvt::mbd::ParameterSet::production;
  double rtol = 5e-7;  // BDF relative tolerance (docs/mbd.md#tolerances)
  long long max_steps_per_frame = 200000;
  // Changes to the set's parameters by the names of its field list
  // (cvt::mbd::visit_mbd_params: "friction.mu0", "joint_rot_damping_Nms_rad"):
  // the choices the set's sources leave open (docs/validation.md#uncertainty).
  std::vector<std::pair<std::string, double>> overrides;
};

// The set's parameters with the overrides; throws InputError for an unknown
// name or a field that is not a number.
cvt::mbd::MbdParams config_params(const ReferenceConfig& c);

// The reference's parameters for a manoeuvre's start (clamped sheaves, the
// chain at the ratio, its start at speed with the ratio lock, the torques
// and the balancing road load at the release).
cvt::mbd::MbdParams manoeuvre_params(const Manoeuvre& m, const ReferenceConfig& c);

// The cache key of a manoeuvre's reference run: every field of its
// parameters, the stepping options and the manoeuvre's inputs.
std::string manoeuvre_key(const Manoeuvre& m, const ReferenceConfig& c);

// Each manoeuvre's reference run, in order: from the cache, or run and
// stored. Manoeuvres that share a start run from one start: its state is
// saved and restored (docs/mbd.md#stepping: a run after save() and one after
// restore() give the same samples), so a run is the same whichever other
// manoeuvres run with it. A run the reference cannot finish (a fault) is
// kept to there with its reason; on_progress gets the simulated time of the
// runs made. Throws InputError for a bad manoeuvre or configuration.
std::vector<ReferenceRun> reference_manoeuvres(const std::vector<Manoeuvre>& ms, const ReferenceConfig& c,
                                               const std::string& cache_dir,
                                               const cvt::mbd::ProgressSink& on_progress = {});

// The driver clamping that held the reference's ratio at a run's start
// (the run's first clamping over its factor) [N].
double reference_hold_clamp1_N(const Manoeuvre& m, const Series& reference);

// --- the plant

// How the plant held the operating point: the driver clamping that holds
// its radial position (found by trial releases from the locked state), and
// the driver radius's rate at that clamping.
struct PlantHold {
  double clamp1_N = 0;
  double r1_rate_m_s = 0;
  int trials = 0;
};

// The plant of scene `plant` (its features, which must include wedging,
// parameters and numerics; its inputs and initial state are the
// manoeuvre's) through the manoeuvre: held at the operating point (radial
// state and primary speed locked) for at least 0.2 s, as the reference's
// start, and until the driven pulley has found its speed under the load
// (at most 5 s: the plant's lumps start unloaded), then released with
// the inputs of manoeuvre_inputs. With a reference run, its holding
// clamping is the plant's too (the same inputs); without, the plant's own. Samples every frame from t =
// 0, stopping as the reference's rule says. Throws InputError for a plant
// without wedging, RunError if it faults.
Series plant_manoeuvre(const Manoeuvre& m, const cvt::Scene& plant, const Series* reference,
                       PlantHold* hold = nullptr);

}  // namespace cvt::validation
