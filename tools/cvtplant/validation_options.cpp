// The options `validate` and `calibrate` share (docs/cli.md#validate).
#include "validation_options.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "commands.hpp"

namespace cvtcli {

namespace {

void make_dir(const std::string& d) {
  std::error_code ec;
  if (std::filesystem::is_directory(d, ec)) return;
  if (std::filesystem::exists(d, ec)) throw UsageError{"--out-dir: '" + d + "' exists and is not a directory"};
  std::filesystem::create_directories(d, ec);
  if (ec || !std::filesystem::is_directory(d, ec))
    throw UsageError{"--out-dir: cannot create directory '" + d + "'"};
}

}  // namespace

void add_reference_options(CLI::App* sub, ReferenceOptions& o, const std::string& out_dir_what) {
  sub->add_option("--out-dir", o.out_dir, out_dir_what + " (created with its parents)")->capture_default_str();
  sub->add_option("--sheaves", o.sheaves,
                  "The reference's sheaves: scene (fixed for a scene whose plant has fixed sheaves, else clamped), "
                  "clamped (pushed by the scene's clamping) or fixed (the seed's pulleys; the axial force is then "
                  "the reference's output)")
      ->capture_default_str()
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(cvt::validation::kSheaveChoiceNames),
                                                     std::end(cvt::validation::kSheaveChoiceNames))));
  sub->add_option("--set", o.set,
                  "The reference's parameter set for every scene: seed (Table 1) or production (the production-like "
                  "chain CVT, docs/mbd-production.md); default: each scene's own (a scene file's reference_set, "
                  "else seed)")
      ->check(CLI::IsMember({"seed", "production"}));
  sub->add_option("--rtol", o.rtol, "Reference's BDF relative tolerance, [1e-11, 1e-3]")->capture_default_str();
  sub->add_option("--max-steps", o.max_steps, "Cap on the reference's integrator steps per scene, [1, 1e12]")
      ->capture_default_str();
}

cvt::validation::RunSettings reference_settings(const CLI::App* sub, const ReferenceOptions& o) {
  if (sub->count("--t-end") > 0 && !(o.t_end_s > 0 && std::isfinite(o.t_end_s)))
    throw UsageError{"--t-end: must be a positive number of seconds"};
  if (!(o.rtol >= 1e-11 && o.rtol <= 1e-3)) throw UsageError{"--rtol: outside [1e-11, 1e-3]"};
  if (!(o.max_steps >= 1 && o.max_steps <= 1000000000000LL)) throw UsageError{"--max-steps: outside [1, 1e12]"};
  if (o.out_dir.empty()) throw UsageError{"--out-dir: empty"};
  cvt::validation::RunSettings st;
  st.sheaves = cvt::validation::sheave_choice(o.sheaves);
  st.t_end_s = o.t_end_s;
  st.rtol = o.rtol;
  st.max_steps = o.max_steps;
  st.cache_dir = o.out_dir + "/reference-cache";
  return st;
}

cvt::validation::RunSettings settings_for(const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                                          const LoadedScene& scene) {
  cvt::validation::RunSettings out = st;
  out.set = cvt::validation::parameter_set(!o.set.empty() ? o.set : scene.reference_set);
  return out;
}

std::string pct_text(double v) {
  if (!std::isfinite(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.1f %%", 100.0 * v);
  return b;
}

std::string num_text(double v) {
  if (!std::isfinite(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void prepare_out_dir(const ReferenceOptions& o) {
  make_dir(o.out_dir);
  make_dir(o.out_dir + "/reference-cache");
}

}  // namespace cvtcli
