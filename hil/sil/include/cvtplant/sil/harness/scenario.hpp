// The SIL scenarios (docs/sil.md#scenarios): what the harness plays on the
// bus (driver demand, ratio set-point, load, injected faults) and the bounds
// its criteria judge. Host only: the harness, not the firmware.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cvtplant/can/messages.hpp"

namespace cvt::sil::harness {

// 10 ms control period = the CtrlCmd cycle, 1 ms plant frames.
inline constexpr int kFramesPerPeriod = 10;
inline constexpr double kPeriod_s = 0.01;

// Faults a scenario injects on purpose (docs/sil.md#fault-scenarios). Periods
// are 10 ms control periods; -1 = none.
struct Faults {
  std::vector<int> lost_cmd_periods;  // the controller's CtrlCmd lost on the wire
  int lost_step_period = -1;          // the harness's Step request lost on the wire
  int lost_status_period = -1;        // PlantStatus lost to the harness
  int lost_speeds_period = -1;        // PlantSpeeds lost to the harness (a partial group)
  double freeze_start_s = -1, freeze_end_s = -1;  // controller hung, its driver repeating the last frame
  double reboot_s = -1;                           // controller restarts, counter from 0
  double flood_start_s = -1, flood_end_s = -1;    // controller sends flood_frames CtrlCmd per period
  int flood_frames = 0;
  int lost_requests() const {
    return (lost_step_period >= 0) + (lost_status_period >= 0) + (lost_speeds_period >= 0);
  }
  // Faults of the controller's own link or software: only a controller the
  // harness runs itself can be made to show them.
  bool in_controller() const {
    return !lost_cmd_periods.empty() || freeze_start_s >= 0 || reboot_s >= 0 || flood_frames > 0;
  }
};

struct Scenario {
  const char* name;
  const char* what;
  double t_end_s;
  std::function<float(double)> demand_Nm;
  bool load_override = false;
  std::function<float(double)> load_Nm = [](double) { return 0.0f; };
  double link_loss_start_s = -1, link_loss_end_s = -1;  // controller silent in [start, end)
  Faults faults{};
  // Ratio control (docs/sil.md#ratio-scenarios): the variable-ratio scene,
  // the controller's RatioLaw on this set-point; empty = the ClampLaw alone.
  cvt::can::SceneId scene = cvt::can::SceneId::TipIn;
  std::function<float(double)> ratio_target{};
  double track_bound = 0;       // |ratio - set-point| once the set-point has held for settle_s
  double settle_s = 1.0;
  double slip_bound = 0.10;     // max |slip| outside the clamping drop
  double clamp_drop_start_s = -1, clamp_drop_end_s = -1;  // supply pressure at clamp_drop_factor
  float clamp_drop_factor = 1.0f;
  bool expect_end_stop = false;  // the sweep drives the chain onto the underdrive and overdrive stops
  double end_stops_by_s = 0;     // ... by this time
  // The shortest run (`--t-end`) whose criteria all have their data: the
  // events, a settled set-point, a recovery.
  double min_t_end_s = 0;
};

// a before t0, b after t1, linear between.
float ramp(double t, double t0, double t1, float a, float b);

// The clamping supply's fraction at t (HarnessLoad.clamp_supply_factor):
// the scenario's drop, else 1.
float clamp_supply(const Scenario& sc, double t);

// Every scenario, in the order `--scenario all` runs them.
std::vector<Scenario> scenarios();

// The scenarios of `list` (names separated by commas, or all) in the table's
// order, each cut at t_end_s when t_end_s > 0. A scenario `accept` refuses
// is left out of all (named in *left_out) and an error when named. Returns
// "" or the usage error: an unknown name, the refusal after `refusal_prefix`,
// or a cut below a scenario's shortest judged run (Scenario::min_t_end_s)
// unless `partial` (its first seconds only, docs/sil.md#cli: the criteria
// that need more are not judged, partial_criterion).
std::string select_scenarios(const std::string& list, double t_end_s, std::vector<Scenario>& out,
                             const std::function<bool(const Scenario&, std::string& why)>& accept = {},
                             std::vector<std::string>* left_out = nullptr, const std::string& refusal_prefix = "",
                             bool partial = false);

// A run cut below its scenario's shortest judged run (--allow-partial)
// judges only what any length judges: its answers and time, the frames, the
// slip and safety factor after the start-up, the watchdog and the command
// timeout. True for those criteria's names.
bool partial_criterion(const std::string& name);
// "ratio-sweep, kick-down, ... or all", for usage messages.
std::string scenario_names();

}  // namespace cvt::sil::harness
