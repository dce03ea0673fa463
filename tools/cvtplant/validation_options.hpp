#pragma once
// The options `validate` and `calibrate` share (docs/cli.md#validate,
// docs/validation.md): the reference's sheaves, its tolerance and step cap,
// and the output directory that holds the reference cache.
#include <CLI/CLI.hpp>

#include <string>

#include <nlohmann/json.hpp>

#include "scene_file.hpp"
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
  long long max_steps = 20000000;
};

// --out-dir (what it holds: `out_dir_what`), --set, --sheaves, --rtol, --max-steps.
void add_reference_options(CLI::App* sub, ReferenceOptions& o, const std::string& out_dir_what);

// Checks --t-end (if given: > 0), --rtol, --max-steps and --out-dir and
// returns the module's settings; throws UsageError.
cvt::validation::RunSettings reference_settings(const CLI::App* sub, const ReferenceOptions& o);

// The settings for one scene: the parameter set --set names, or the
// scene's own (a scene file's `reference_set`; the built-in scenes' seed).
cvt::validation::RunSettings settings_for(const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                                          const LoadedScene& scene);

// A relative error as "12.3 %", a value to four digits, and a value as
// JSON; a value one model lacks (NaN: no common sample) reads "n/a" / null.
std::string pct_text(double v);
std::string num_text(double v);
nlohmann::json json_number(double v);

// Creates the output directory and its reference-cache/ (with their
// parents); throws UsageError naming --out-dir.
void prepare_out_dir(const ReferenceOptions& o);

}  // namespace cvtcli
