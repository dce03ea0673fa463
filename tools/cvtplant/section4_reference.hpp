#pragma once
// The multibody reference's runs for the seed's section-4 analysis
// (docs/seed-section4.md): the seed's run-up from rest and steady operating
// points (a start at speed against a road load that the input torque
// balances), integrated by BDF at a tolerance or by the seed's RK4, sampled
// every millisecond with the links' passages through the middle of each
// wrap, and cached on disk by their inputs and the reference's version.
#include <string>
#include <vector>

#include "cvtplant/analysis/two_trajectory.hpp"
#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"

namespace cvtcli::section4ref {

// One scenario of the reference (docs/seed-section4.md#runs).
struct Scenario {
  int friction_case = 1;
  bool steady = false;       // false: the seed's run-up from rest (100 / 50 N m)
  double omega1_rad_s = 0;   // steady: the driver speed the chain is brought to
  double omega2_rad_s = 0;   // steady: the driven speed of the spin-up (the hold finds the chain's own)
  double load_Nm = 90;       // steady: the road load's torque at the driven speed of the spin-up
  double hold_s = 2.0;       // steady: the hold before the release (docs/mbd.md#start-at-speed)
  double t_end_s = 10;       // simulated time after the release
};

// How the reference is integrated.
struct Numerics {
  cvt::mbd::Method method = cvt::mbd::Method::bdf;
  double rtol = 5e-7;   // bdf
  double dt_s = 1e-6;   // rk4
  double t_end_s = -1;  // < 0: the scenario's; else a shorter run (RK4 over its first seconds)
  std::string label() const;  // "BDF rtol 5e-07", "RK4 dt 1e-06 s"
};

// The load of a steady point, an absorber on the driven shaft:
// c_a w2 |w2| - 2 load with c_a = 3 load / w2s^2, w2s the spin-up's driven
// speed: `load` at w2s, rising there with the slope 6 load / w2s, three
// times a quadratic law's, so a drift of the speeds dies out within about a
// second (the constant part is the road load's tau_load, the quadratic its
// c_a; docs/seed-section4.md#runs).
cvt::mbd::RoadLoad steady_road_load(const Scenario& s);
double steady_constant_load_Nm(const Scenario& s);

// The reference's inputs: the seed's case with the scenario's start, loads
// and input torque tau_in_Nm (steady points: the hold's holding torque).
cvt::mbd::MbdParams scenario_params(const Scenario& s, double tau_in_Nm);

// One run, sampled every millisecond from the release (t = 0).
struct Run {
  std::vector<double> t_s, omega1_rad_s, omega2_rad_s, F_ax1_N, F_ax2_N, torque1_Nm, torque2_Nm, slip1_m_s,
      slip2_m_s, wrap1, wrap2;
  // Times at which a link's front pin passes the middle of each wrap (the
  // driver's leftmost point, the driven's rightmost), interpolated between
  // samples [s].
  std::vector<double> passages1_s, passages2_s;
  double tau_in_Nm = 0;  // the input torque after the release
  // Steady points: the hold's driver holding torque (mean over its last
  // 0.2 s), driven speed at the release, and how steady the hold ended
  // (docs/mbd.md#start-at-speed).
  double holding_torque_Nm = 0, omega2_release_rad_s = 0, hold_omega2_range_rel = 0, hold_torque_change_rel = 0;
  double cpu_s = 0, ledger_residual_rel = 0;
  long long steps = 0;
  bool from_cache = false;
  std::string cache_file;
  std::string failure;  // a run that stopped early: why (the samples before stay)
  std::size_t size() const { return t_s.size(); }
  // The named signal (F_ax1_N, F_ax2_N, omega1_rad_s, omega2_rad_s); throws UsageError for another name.
  const std::vector<double>& signal(const std::string& name) const;
};

// A speed for a scenario's name: "30", "12.5".
std::string format_speed(double omega_rad_s);

// The signals the command analyses by name, with their units.
const std::vector<std::string>& signal_names();
std::string signal_unit(const std::string& name);

// Runs (or reads from cache_dir, "" for no cache) one scenario. Steady points
// first run the start alone to read the hold's holding torque, then release
// with it. A run that fails keeps its samples and names the failure.
Run reference_run(const Scenario& s, const Numerics& n, const std::string& cache_dir, const std::string& label);

// The largest Lyapunov exponent of a scenario from the reference's own
// equations (docs/seed-section4.md#benettin): two trajectories
// (docs/analysis.md#two-trajectory) on cvt::mbd::Stepper, which saves and
// restores the state; the deviation is measured in the tolerance-scaled
// norm of the link and pulley-speed states (the pulley angles and the
// energy ledger feed nothing back and are left out). The stepper runs from
// the release to t_start_s, then o.warmup intervals align the deviation and
// o.intervals are accumulated. Cached like the runs.
struct ExponentRun {
  cvt::analysis::TwoTrajectoryResult result;
  double t_start_s = 0, rtol = 0, cpu_s = 0;
  cvt::analysis::TwoTrajectoryOptions options;
  bool from_cache = false;
  std::string failure;  // the stepper faulted: why (no estimate then)
};
ExponentRun equation_exponent(const Scenario& s, double tau_in_Nm, double t_start_s, double rtol,
                              const cvt::analysis::TwoTrajectoryOptions& o, const std::string& cache_dir,
                              const std::string& label);

}  // namespace cvtcli::section4ref
