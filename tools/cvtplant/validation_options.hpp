#pragma once
// The options `validate` and `calibrate` share (docs/cli.md#validate,
// docs/validation.md): the reference's sheaves, its tolerance and step cap,
// and the output directory that holds the reference cache.
#include <CLI/CLI.hpp>

#include <string>

#include "cvtplant/validation/scene_check.hpp"

namespace cvtcli {

// The default output directory: under build/ of the working directory (the
// repository's root), never a source folder.
inline constexpr const char* kDefaultValidationDir = "build/validation";

struct ReferenceOptions {
  std::string out_dir = kDefaultValidationDir;
  std::string sheaves = "scene";
  double t_end_s = 0;  // 0: each scene's own
  double rtol = 5e-7;
  long long max_steps = 20000000;
};

// --out-dir (what it holds: `out_dir_what`), --sheaves, --rtol, --max-steps.
void add_reference_options(CLI::App* sub, ReferenceOptions& o, const std::string& out_dir_what);

// Checks --t-end (if given: > 0), --rtol, --max-steps and --out-dir and
// returns the module's settings; throws UsageError.
cvt::validation::RunSettings reference_settings(const CLI::App* sub, const ReferenceOptions& o);

// Creates the output directory and its reference-cache/ (with their
// parents); throws UsageError naming --out-dir.
void prepare_out_dir(const ReferenceOptions& o);

}  // namespace cvtcli
