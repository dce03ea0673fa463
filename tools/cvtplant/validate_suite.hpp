#pragma once
// `cvtplant validate --suite`: a manoeuvre suite against the reference, its
// goal table, the maps and the reference's uncertainty
// (docs/validation.md#suite, docs/cli.md#validate).
#include <string>

#include "validation_options.hpp"

namespace cvtcli {

struct SuiteCliOptions {
  ReferenceOptions ref;           // --out-dir, --set (empty: production), --rtol, --max-steps
  std::string suite;              // controller, ci
  std::string plant = "ratio-control";  // the plant's scene: its features (with wedging), parameters, numerics
  std::string params;             // a parameter file applied to the plant
  std::string uncertainty = "subset";  // none, subset, all
  double max_sim_s = 600;         // cap on the suite's simulated seconds of reference (cached or not)
  bool maps = true, figures = true, json = false;
};

// Runs the suite and prints its table (or JSON); throws UsageError for bad
// options before any run. Returns the exit code.
int run_validate_suite(const SuiteCliOptions& o);

}  // namespace cvtcli
