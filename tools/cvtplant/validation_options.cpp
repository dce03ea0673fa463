// The options `validate` and `calibrate` share (docs/cli.md#validate).
#include "validation_options.hpp"

#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "options.hpp"
#include "reference_cost.hpp"
#include "cvtplant/files/paths.hpp"
#include "cvtplant/files/replace.hpp"

namespace cvtcli {

void add_reference_options(CLI::App* sub, ReferenceOptions& o, const std::string& out_dir_what) {
  sub->add_option("--out-dir", o.out_dir, out_dir_what + " (created with its parents)")->capture_default_str();
  sub->add_option("--sheaves", o.sheaves,
                  "The reference's sheaves: scene (fixed for a scene whose plant has fixed sheaves, else clamped), "
                  "clamped (pushed by the scene's clamping) or fixed (the seed's pulleys; the axial force is then "
                  "the reference's output)")
      ->capture_default_str()
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(cvt::validation::kSheaveChoiceNames),
                                                     std::end(cvt::validation::kSheaveChoiceNames))));
  add_real(sub, "--rtol", o.rtol, {1e-11, 1e-3}, "Reference's BDF relative tolerance (default 5e-7)");
  o.max_steps_opt = add_int(sub, "--max-steps", o.max_steps, 1, 1000000000000LL,
                            "Cap on each reference run's integrator steps (default: 20x its estimate, at most 1e8; "
                            "docs/cli.md#caps)");
  add_real(sub, "--t-end", o.t_end_s, {0, 3600, true},
           "Shorten every run to this simulated time [s] (default: each scene's)");
  sub->add_option("--set", o.set,
                  "The reference's parameter set for every scene: seed (Table 1) or production (the production-like "
                  "chain CVT, docs/mbd-production.md); default: each scene's own (a scene file's reference_set, its "
                  "base's, else seed; ratio-control's is production)")
      ->check(CLI::IsMember({"seed", "production"}));
}

cvt::validation::RunSettings reference_settings(const CLI::App* sub, const ReferenceOptions& o) {
  cvt::validation::RunSettings st;
  st.sheaves = cvt::validation::sheave_choice(o.sheaves);
  st.t_end_s = sub->count("--t-end") > 0 ? o.t_end_s : 0.0;
  st.rtol = o.rtol;
  st.cache_dir = o.out_dir + "/reference-cache";
  return st;
}

long long reference_step_cap(const cvt::Scene& s, const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                             const std::string& scene_name) {
  const bool given = o.max_steps_opt != nullptr && o.max_steps_opt->count() > 0;
  const double rate =
      st.set == cvt::mbd::ParameterSet::production ? kProductionBdfStepsPerSecond : kSeedBdfStepsPerSecond;
  return step_cap(bdf_work(cvt::validation::run_length_s(s, st), st.rtol, rate), given, static_cast<double>(o.max_steps),
                  "scene " + scene_name + "'s reference run");
}

cvt::validation::RunSettings settings_for(const cvt::validation::RunSettings& st, const ReferenceOptions& o,
                                          const LoadedScene& scene) {
  cvt::validation::RunSettings out = st;
  out.set = cvt::validation::parameter_set(!o.set.empty() ? o.set : scene.reference_set);
  return out;
}

std::string pct_text(double v) { return text_number(100.0 * v, "%.1f %%"); }

std::string num_text(double v) { return text_number(v, "%.4g"); }

void prepare_out_dir(const ReferenceOptions& o) {
  cvt::files::make_directories(o.out_dir + "/reference-cache", "--out-dir");
}

void report_cache_problem(const std::string& command, const std::string& problem) {
  if (problem.empty()) return;
  std::fprintf(stderr, "cvtplant %s: note: a cache entry failed its checks and was run again: %s\n", command.c_str(),
               cvt::files::shown_path(problem).c_str());
}

void report_cache_problem(const std::string& command, const cvt::validation::ReferenceRun& r) {
  report_cache_problem(command, r.cache_problem);
}

}  // namespace cvtcli
