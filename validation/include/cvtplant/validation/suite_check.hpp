#pragma once
// A manoeuvre suite against the reference (docs/validation.md#suite): each
// manoeuvre's comparison, the maps cell by cell, the reference's own
// uncertainty in the manner of ASME V&V 20 (docs/validation.md#uncertainty)
// and the goals with the error beside it.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cvtplant/mbd/run.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/manoeuvre.hpp"
#include "cvtplant/validation/maps.hpp"
#include "cvtplant/validation/suite.hpp"

namespace cvt::validation {

struct ManoeuvreCheck {
  Manoeuvre m;
  bool held_out = false;
  ReferenceRun ref;
  Series plant;
  PlantHold hold;
  Comparison cmp;
};

// What the reference's answer could be off by: numerical (the change when
// its tolerance is tightened 10x and 100x), input (the spread over the
// choices its sources leave open: the spread of the answer between each
// range's two ends, a uniform distribution over it, input_share), combined u_val = sqrt(u_num^2 +
// u_input^2), u_num the 100x change. In the error's units (relative).
struct Uncertainty {
  double u_num10 = 0, u_num100 = 0, u_input = 0;
  std::vector<std::pair<std::string, double>> inputs;  // each open choice's share
  double u_num() const { return u_num100; }
  double u_val() const;
};

// An open choice's share of the input uncertainty: a uniform distribution
// over a range whose two ends differ by `spread`, half-width / sqrt(3).
double input_share(double spread);

// One open choice of the reference's inputs: a field (visit_mbd_params'
// name) and the range its sources leave.
struct OpenChoice {
  std::string field;
  double lo, hi;
  std::string why;
};
// The production set's (docs/validation.md#uncertainty): the friction
// coefficient and the articulation damper, which its docs call assumptions.
std::vector<OpenChoice> open_choices(cvt::mbd::ParameterSet set);

// The goals (docs/validation.md#goals) and one row of their table.
struct GoalRow {
  std::string goal;    // "ratio RMS", "omega1 RMS", "thrust-ratio cell", ...
  std::string where;   // the manoeuvre or the map's cell
  bool held_out = false;
  double error = 0;    // relative (signed for steady-state and map errors)
  double limit = 0;
  bool has_u = false;  // the reference's uncertainty was measured for this row's kind
  Uncertainty u;
  std::string u_from;  // the run the uncertainty was measured on
  bool met() const { return std::fabs(error) <= limit; }
};

struct SuiteOptions {
  bool maps = true;
  // Uncertainty runs: none; subset (the suite's uncertainty_runs and, with
  // the maps, one cell of each: the hold at ratio 1.5 and 90 N m, the shift
  // rate at 100 rad/s and ratio 1.5, the onset at 120 N m); all (every run
  // of the suite besides).
  std::string uncertainty = "subset";
};

struct SuiteResult {
  Suite suite;
  std::vector<ManoeuvreCheck> runs;
  bool has_maps = false;
  Maps maps;
  // Uncertainty per measured run and goal quantity ("ratio RMS" ...), and
  // per map goal.
  struct Measured {
    std::string where, goal;
    Uncertainty u;
  };
  std::vector<Measured> uncertainty;
  std::vector<GoalRow> goals;
  double reference_cpu_s = 0;
  int reference_runs = 0, from_cache = 0;
};

// Runs the suite's manoeuvres on the reference (cached) and the plant,
// compares them, makes the maps and the uncertainty runs the options ask
// for, and fills the goal table. Throws InputError for a bad plant or
// option, RunError if the plant faults.
SuiteResult check_suite(const Suite& suite, const cvt::Scene& plant, const ReferenceConfig& c,
                        const std::string& cache_dir, const SuiteOptions& o,
                        const cvt::mbd::ProgressSink& on_progress = {});

// The simulated seconds of reference the suite asks for (its runs, the
// maps' and the uncertainty runs'), cached or not: a progress bar's total
// and the size a caller caps.
double suite_reference_s(const Suite& suite, const ReferenceConfig& c, const SuiteOptions& o);

// The goals' limits: ratio 3 % RMS, pulley speeds 2 % RMS, mean axial forces
// 5 %, thrust-ratio map 5 % in every cell, shift rate 10 %, clamping at
// gross-slip onset 5 %.
struct GoalLimits {
  static constexpr double ratio = 0.03, speed = 0.02, axial = 0.05, thrust = 0.05, shift = 0.10, onset = 0.05;
};

}  // namespace cvt::validation
