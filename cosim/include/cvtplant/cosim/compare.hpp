#pragma once
// The closed-loop comparison (docs/sil.md#compare): each SIL scenario run in
// lock-step against the scene's real-time plant and against the multibody
// reference, the same controller (the example controller) reacting to what
// each plant does, each plant behind its bridge on its own loopback bus.
// Per scenario: every criterion on each plant, whether the verdicts agree,
// the difference against the criterion's bound, and the traces of both
// overlaid with the RMS difference of each. Host only.
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/cosim/reference_plant.hpp"
#include "cvtplant/sil/harness/criteria.hpp"
#include "cvtplant/sil/harness/scenario.hpp"

namespace cvt::cosim {

struct CompareOptions {
  std::vector<cvt::sil::harness::Scenario> scenarios;
  std::string out_dir = ".";
  // The reference's tolerances and caps; its release states are kept in
  // out_dir/reference-cache unless release_cache_dir says otherwise.
  ReferenceOptions reference;
  // Progress: the plant ("rom", "reference"), the scenario and the simulated
  // time reached, every period; empty for none.
  std::function<void(const char* plant, const char* scenario, double t_s, double t_end_s)> progress;
};

// One criterion side by side.
struct CriterionPair {
  std::string name;
  const cvt::sil::harness::Check* rom = nullptr;  // null: not in that run (a run that stopped early)
  const cvt::sil::harness::Check* ref = nullptr;
  bool agree = false;         // the same verdict: both judged and equal, or both not judged
  double difference = NAN;    // value on the reference minus on the plant (criteria with a value)
  // |difference| > 20 % of |limit|: docs/sil.md#compare says why for each.
  bool beyond_fifth_of_limit = false;
};

// One trace of both runs: the RMS of the difference over the samples both
// have, and the RMS of the plant's trace beside it for scale.
struct TraceDifference {
  const char* name;  // ratio, slip, clamp_cmd, axial, ...
  const char* unit;
  double rms_difference = 0, rms_rom = 0;
  int samples = 0;
};

struct ScenarioComparison {
  cvt::sil::harness::ScenarioResult rom, ref;
  std::vector<CriterionPair> criteria;
  std::vector<TraceDifference> traces;
  bool verdicts_agree = false;  // every criterion agrees
  // The reference's cost: CPU seconds of its steps and of its release state
  // (the start-up, or 0 from the cache), and the simulated time it ran.
  double ref_step_cpu_s = 0, ref_reset_cpu_s = 0, ref_sim_s = 0;
  bool ref_release_cached = false;
  const char* name() const { return rom.name.c_str(); }
};

// Runs every scenario of `o` on both plants and writes, in o.out_dir,
// rom/ and reference/ (each run's CSV trace and JUnit file),
// compare-<scenario>.csv (the overlaid traces), compare-criteria.csv (one
// row per scenario and criterion), compare-traces.csv (the RMS differences)
// and compare-scenarios.csv (verdicts, the reference's CPU). Throws
// std::runtime_error when a plant does not answer or a file cannot be written.
std::vector<ScenarioComparison> compare_scenarios(const CompareOptions& o);

// The console table: per scenario the verdicts, then each criterion's value
// on both plants, the difference against its bound and the RMS differences.
std::string comparison_table(const std::vector<ScenarioComparison>& c);

}  // namespace cvt::cosim
