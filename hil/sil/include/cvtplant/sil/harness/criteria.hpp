// The pass/fail criteria of the SIL scenarios (docs/sil.md#criteria): the
// trace a run records, and the checks judged on it and on the plant's
// diagnostics. Host only.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/sil/harness/scenario.hpp"

namespace cvt::sil::harness {

struct Check {
  std::string name;
  bool pass;
  std::string detail;
  // false: reported, not judged (a real-time run whose plant did not keep
  // time, docs/sil.md#ratio-realtime); JUnit <skipped>, never a failure.
  bool judged = true;
  // A criterion on the motion: the measured value and the bound it is held
  // to (NaN for the functional criteria), what a comparison of two plants
  // sets side by side (docs/sil.md#compare).
  double value = NAN, limit = NAN;
};

// A criterion with its measured value and its bound.
Check measured(std::string name, bool pass, std::string detail, double value, double limit);

struct Sample {
  double t_s;
  float demand_Nm, clamp_cmd_N, axial_N, torque_Nm, slip, omega1, omega2, safety;
  bool cmd_timeout, watchdog;
  float ratio_target, geometric_ratio, driven_cmd_N, driven_axial_N, radius1_m;
  bool stop_under, stop_over;
};

struct ScenarioResult {
  std::string name;
  std::string what;  // the scenario in one line (JUnit property "description")
  double wall_s = 0;
  std::vector<Check> checks;
  std::vector<Sample> trace;  // what the CSV holds
  bool pass() const {
    for (const Check& c : checks)
      if (c.judged && !c.pass) return false;
    return true;
  }
};

// The clamping commands a controller put on the bus in a period.
struct Commands {
  float clamp_cmd_N = 0.0f;   // CtrlCmd.clamp_force_cmd_N (driver, primary)
  float driven_cmd_N = 0.0f;  // CtrlShiftCmd.driven_clamp_force_cmd_N (driven, secondary)
};

// The plant's latest output group as a node on the bus sees it.
struct GroupView {
  const cvt::can::PlantSpeeds& speeds;
  const cvt::can::PlantRatio& ratio;
  const cvt::can::PlantForces& forces;
  const cvt::can::PlantShift& shift;
};

// printf into a string, up to three numbers.
std::string fmt(const char* f, double a, double b = 0, double c = 0);

// t in [start, end) of a window that exists (start >= 0).
bool in_window(double t, double start, double end);

// Counter growth between two PlantDiag-family readings, modulo 2^16.
double grew(std::uint16_t now, std::uint16_t then);

// slip-recovery: the time after the supply is back within which the slip
// must be small again; the common slip criteria skip the drop and this time.
inline constexpr double kRecovery_s = 1.0;

// The plant's torque capacity, from its published parameters (PlantParams,
// docs/sil.md#published-parameters): tau_cap = coeff F_ax r1 at the driver's
// running radius r1, the set-up radius when the plant's ratio is fixed.
struct Capacity {
  float coeff = 0.0f;     // PlantParams.capacity_coeff = 2 f mu0 / cos(beta0)
  float radius_m = 0.0f;  // PlantParams.radius_driver_m
  float at_Nm(float axial_force_N, float r1_m) const { return coeff * axial_force_N * r1_m; }
};

// One trace sample from the plant's latest group and the controller's last
// commands; the torque-capacity safety factor (docs/sil.md#criteria) with
// the plant's `capacity`.
Sample sample_of(const Scenario& sc, const Capacity& capacity, double t_s, double t_cmd,
                 const cvt::can::PlantStatus& st, const GroupView& g, const Commands& cmd);

bool any_watchdog(const std::vector<Sample>& trace);

// docs/sil.md#ratio-scenarios: settled tracking, the slip excursion of a
// clamping drop and its recovery, the end stops.
void ratio_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c);

// Criteria on the motion (docs/sil.md#criteria), after the first 50 ms
// start-up: slip, the ratio criteria, the torque-capacity safety factor.
void motion_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c);

// What a lock-step run counted, for its criteria (docs/sil.md#criteria,
// #fault-scenarios). Counter growths are taken against the diagnostics
// answered to the scenario's Reset.
struct LockstepCounts {
  int periods = 0;
  std::uint32_t no_reply = 0, bad_time = 0, bad_mode = 0;
  double resends = 0;            // requests the harness sent again
  double harness_rejected = 0;   // plant frames the harness rejected (over its lifetime)
  double controller_rejected = 0;  // < 0: not observable (a controller in another process)
  double cmd_timeouts = 0;       // PlantDiag.cmd_timeouts growth
  double rejected_frames = 0;    // PlantDiag.rejected_frames growth
  double cmd_lost = 0, resyncs = 0, superseded = 0;  // PlantCmdDiag growth
  double harness_lost = 0;       // frames the harness's fault injector lost on purpose
  double controller_lost = 0;    // commands lost on purpose on the controller's link
  double max_recovery_ms = 0;    // slowest recovery of a lost request, wall time
  // The plant stopped (PlantStatus Fault, docs/sil.md#plant-faults): the
  // time of the group that first showed it and the reason, else -1 and "".
  double plant_fault_s = -1;
  std::string plant_fault;
};

// The reason of a plant fault for the criteria: its kind as PlantDiag
// carries it and, when the harness can see it (a plant in this process),
// the plant's own words.
std::string plant_fault_reason(const cvt::can::PlantDiag& diag, const std::string& message);

// Every criterion of a lock-step run after trace_written, in report order:
// the bridge's answers and time, valid frames, the motion, the watchdog, the
// command timeout (or its outage criteria) and the injected faults'.
void lockstep_checks(const Scenario& sc, const std::vector<Sample>& trace, const LockstepCounts& n,
                     std::vector<Check>& c);

// A plant that overran more than this fraction of its frames did not keep
// time: only the functional criteria are judged (docs/sil.md#ratio-realtime).
// At 9.3 % overruns on a loaded VM a late clamping command let the slip reach
// 0.13: the motion criteria measure the controller only on a punctual bus.
inline constexpr double kMaxOverrunFraction = 0.01;

// Marks the checks from `from` on as not judged: the plant did not keep time.
void not_judged_from(std::vector<Check>& c, std::size_t from);

// A run cut below its scenario's shortest judged run (--allow-partial):
// what needs the rest of the scenario is reported, not judged.
void partial_not_judged(const Scenario& sc, std::vector<Check>& c);

}  // namespace cvt::sil::harness
