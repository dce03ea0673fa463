#pragma once
// The options `validate` and `calibrate` share (docs/cli.md#validate,
// docs/validation.md): the reference's sheaves, its tolerance and step cap,
// and the output directory that holds the reference cache.
#include <CLI/CLI.hpp>

#include <string>

#include <nlohmann/json.hpp>

#include "io_util.hpp"
#include "scene_file.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/scene_check.hpp"

namespace cvtcli {

// The default output directory: under build/ of the working directory (the
// repository's root), never a source folder.
inline constexpr const char* kDefaultValidationDir = "build/validation";

struct ReferenceOptions {
  std::string out_dir = kDefaultValidationDir;
  std::string sheaves = "scene";
  std::string set;      // --set: the reference's parameter set for every scene; empty: each scene's own
  double t_end_s = 0;  // 0: each scene's own
  double rtol = 5e-7;
  long long max_steps = 0;  // given: the cap of every reference run; else automatic per run
  CLI::Option* max_steps_opt = nullptr;
};

// --out-dir (what it holds: `out_dir_what`), --set, --sheaves, --rtol,
// --max-steps and --t-end (each with its range).
void add_reference_options(CLI::App* sub, ReferenceOptions& o, const std::string& out_dir_what);

// The module's settings from the options (the step cap is set per run by
// reference_step_cap).
cvt::validation::RunSettings reference_settings(const CLI::App* sub, const ReferenceOptions& o);

// The step cap of one scene's reference run: --max-steps if given, else
// automatic from its estimated work (reference_cost.hpp); throws
// UsageError naming the scene when the estimate is above it.
long long reference_step_cap(const cvt::Scene& s, const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                             const std::string& scene_name);

// The settings for one scene: the parameter set --set names, or the
// scene's own (a scene file's `reference_set`, else its base's; ratio-control's
// production, the other built-in scenes' seed).
cvt::validation::RunSettings settings_for(const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                                          const LoadedScene& scene);

// A relative error as "12.3 %" and a value to four digits; a value one
// model lacks (NaN: no common sample) reads "n/a" (json_number: null).
std::string pct_text(double v);
std::string num_text(double v);

// Creates the output directory and its reference-cache/ (with their
// parents; one that another run creates at the same moment is fine);
// throws UsageError naming --out-dir.
void prepare_out_dir(const ReferenceOptions& o);

// A note on stderr when a cache entry failed its checks and the reference
// was run again (docs/validation.md#cache).
void report_cache_problem(const std::string& command, const std::string& problem);
void report_cache_problem(const std::string& command, const cvt::validation::ReferenceRun& r);

}  // namespace cvtcli
