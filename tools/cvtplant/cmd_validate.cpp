// `cvtplant validate`: the real-time plant against the multibody reference,
// scene by scene, on the same inputs (docs/validation.md, docs/cli.md#validate).
// The comparison is the validation module's (validation/); this file parses
// the options, chooses the scenes and prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "guarded.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "validate_suite.hpp"
#include "validation_options.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/validation/report.hpp"
#include "cvtplant/validation/scene_check.hpp"
#include "cvtplant/validation/suite.hpp"

namespace cvtcli {

namespace {

namespace val = cvt::validation;

struct Options {
  ReferenceOptions ref;
  std::string scene = "all";
  std::string params;  // a parameter file applied to every scene's plant
  std::string scene_dir = "tools/scenes";  // scene files that --scene all adds
  double max_t_end_s = 60;
  bool json = false;
  bool figures = true;
  // --suite (docs/validation.md#suite): the scene is the plant's, default ratio-control.
  std::string suite, uncertainty = "subset";
  bool maps = true;
};

struct SceneOutput {
  val::SceneResult r;
  std::string png, csv;
  const char* set = "seed";  // the reference's parameter set
};

bool holds_a_pulley(const cvt::Scene& s) { return s.params.hold_driver_speed || s.params.hold_driven_speed; }

// The scene files (*.toml, by name) in dir; none if dir does not exist.
std::vector<std::string> scene_files(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.is_regular_file(ec) && e.path().extension() == ".toml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// `all`: the built-in drive-train scenes (the oscillators hold both pulleys)
// and the drive-train scene files of scene_dir.
std::vector<std::shared_ptr<LoadedScene>> scenes_for(const std::string& which, const std::string& scene_dir) {
  std::vector<std::shared_ptr<LoadedScene>> out;
  if (which != "all") {
    out.push_back(resolve_scene(which));
    return out;
  }
  for (const cvt::Scene& s : cvt::kBuiltinScenes)
    if (!holds_a_pulley(s)) out.push_back(resolve_scene(s.name));
  for (const std::string& f : scene_files(scene_dir)) {
    auto l = resolve_scene(f);
    if (!holds_a_pulley(l->scene)) out.push_back(l);
  }
  return out;
}

nlohmann::json jnum(double v) { return json_number(v); }
nlohmann::json jtime(double t) { return t >= 0 ? nlohmann::json(t) : nlohmann::json(nullptr); }

nlohmann::json to_json(const SceneOutput& o) {
  const val::SceneResult& r = o.r;
  nlohmann::json j;
  j["scene"] = r.name;
  if (!r.skipped.empty()) {
    j["status"] = "not run";
    j["reason"] = r.skipped;
    return j;
  }
  j["status"] = "ok";
  j["set"] = o.set;
  j["sheaves"] = r.clamped ? "clamped" : "fixed";
  j["t_end_s"] = r.t_end_s;
  j["compared_s"] = r.cmp.compared_s;
  j["sheave_at_stop_s"] = {{"driver", jtime(r.stop_s[0])}, {"driven", jtime(r.stop_s[1])}};
  j["window_s"] = r.cmp.window_s;
  j["reference"] = {{"from_cache", r.ref.from_cache},
                    {"cpu_s", r.ref.cpu_s},
                    {"wall_s", r.ref.wall_s},
                    {"steps", r.ref.steps},
                    {"energy_residual_rel", r.ref.ledger_residual_rel},
                    {"failure", r.ref.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.ref.failure)}};
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& e : r.cmp.rows)
    rows.push_back({{"quantity", e.quantity},
                    {"unit", e.unit},
                    {"rel_rms", jnum(e.rel_rms)},
                    {"plant_ss", jnum(e.plant_ss)},
                    {"reference_ss", jnum(e.reference_ss)},
                    {"ss_rel", jnum(e.ss_rel)}});
  j["errors"] = rows;
  j["F_ax1_ripple_N"] = {{"plant", r.cmp.ripple_plant_N}, {"reference", r.cmp.ripple_reference_N}};
  j["gross_slip_s"] = {{"threshold_m_s", val::kGrossSlip_m_s},
                       {"plant", jtime(r.cmp.gross_slip_plant_s)},
                       {"reference", jtime(r.cmp.gross_slip_reference_s)}};
  j["csv"] = o.csv;
  j["png"] = o.png.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.png);
  return j;
}

std::string pct(double v) { return pct_text(v); }
std::string fmt(double v) { return num_text(v); }

std::string tfmt(double t) { return t >= 0 ? fmt(t) + " s" : "never"; }

void print_text(const std::vector<SceneOutput>& results) {
  for (const auto& o : results) {
    const val::SceneResult& r = o.r;
    if (!r.skipped.empty()) {
      std::printf("## %s: not run (the reference cannot run %s)\n\n", r.name.c_str(), r.skipped.c_str());
      continue;
    }
    std::printf(
        "## %s (%g s; compared over 0-%g s; steady state: the last %g s of it; reference: %s set on %s sheaves, %s)\n\n",
        r.name.c_str(), r.t_end_s, r.cmp.compared_s, r.cmp.window_s, o.set, r.clamped ? "clamped" : "fixed",
        r.ref.from_cache ? "from the cache" : "run now");
    if (!r.ref.failure.empty()) std::printf("The comparison ends there: %s.\n\n", r.ref.failure.c_str());
    if (r.clamped)
      std::printf("Reference's movable sheaves at their end stops (a ratio limit) from: driver %s, driven %s.\n\n",
                  tfmt(r.stop_s[0]).c_str(), tfmt(r.stop_s[1]).c_str());
    std::printf("| quantity | unit | relative RMS error | plant (steady) | reference (steady) | steady-state error |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (const auto& e : r.cmp.rows)
      std::printf("| %s | %s | %s | %s | %s | %s |\n", e.quantity.c_str(), e.unit.c_str(), pct(e.rel_rms).c_str(),
                  fmt(e.plant_ss).c_str(), fmt(e.reference_ss).c_str(), pct(e.ss_rel).c_str());
    std::printf("| F_ax1 ripple (peak to peak) | N | | %s | %s | |\n", fmt(r.cmp.ripple_plant_N).c_str(),
                fmt(r.cmp.ripple_reference_N).c_str());
    std::printf("| time to gross slip (whole driver wrap > %g m/s) | s | | %s | %s | |\n\n", val::kGrossSlip_m_s,
                tfmt(r.cmp.gross_slip_plant_s).c_str(), tfmt(r.cmp.gross_slip_reference_s).c_str());
  }
}

Action register_validate(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "validate", "The real-time plant against the multibody reference on each drive-train scene (docs/validation.md)");
  sub->add_option("--scene", opt->scene, "A scene name, a scene file, or 'all' (every built-in drive-train scene)")
      ->capture_default_str();
  add_reference_options(sub, opt->ref, "Directory for the overlays, CSVs and the reference cache");
  sub->add_option("--t-end", opt->ref.t_end_s, "Shorten every run to this simulated time [s] (default: each scene's)");
  sub->add_option("--max-t-end", opt->max_t_end_s, "Cap on a run's simulated time [s] (work); raise it for long scenes")
      ->capture_default_str();
  auto* dir_opt = sub->add_option("--scene-dir", opt->scene_dir,
                                  "Directory whose scene files (*.toml) --scene all adds to the built-in scenes")
                      ->capture_default_str();
  sub->add_option("--params", opt->params,
                  "Run the plant with a parameter file's [params] (e.g. calibrate --out); the reference is unchanged");
  sub->add_flag("--json", opt->json, "Print the results as JSON");
  sub->add_flag("!--no-figures", opt->figures, "Skip the overlay PNGs");
  sub->add_option("--suite", opt->suite,
                  "Run a manoeuvre suite against the reference instead of scenes (docs/validation.md#suite): "
                  "controller or ci; --scene then names the plant (default ratio-control), --set the reference's "
                  "set (default production), --max-t-end caps the suite's simulated seconds of reference")
      ->check(CLI::IsMember(val::suite_names()));
  sub->add_option("--uncertainty", opt->uncertainty,
                  "With --suite: the reference's uncertainty runs: none, subset (one run of each kind and one "
                  "cell of each map) or all")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "subset", "all"}));
  sub->add_flag("!--no-maps", opt->maps, "With --suite: skip the maps (thrust ratio, shift rate, traction, onset)");
  return [opt, sub, dir_opt]() -> int {
    return guarded([&] {
      const Options& o = *opt;
      if (!o.suite.empty()) {
        if (sub->count("--t-end") > 0) throw UsageError{"--t-end: a suite's manoeuvres have their own lengths"};
        if (dir_opt->count() > 0) throw UsageError{"--scene-dir: not with --suite (--scene names the plant)"};
        if (sub->count("--sheaves") > 0) throw UsageError{"--sheaves: a suite runs clamped sheaves"};
        SuiteCliOptions so;
        so.ref = o.ref;
        so.suite = o.suite;
        if (sub->count("--scene") > 0) so.plant = o.scene;
        so.params = o.params;
        so.uncertainty = o.uncertainty;
        so.max_sim_s = sub->count("--max-t-end") > 0 ? o.max_t_end_s : so.max_sim_s;
        so.maps = o.maps;
        so.figures = o.figures;
        so.json = o.json;
        return run_validate_suite(so);
      }
      if (sub->count("--uncertainty") > 0 || sub->count("--no-maps") > 0)
        throw UsageError{"--uncertainty and --no-maps go with --suite"};
      std::error_code ec;
      if (dir_opt->count() > 0 && !std::filesystem::is_directory(o.scene_dir, ec))
        throw UsageError{"--scene-dir: " + o.scene_dir + " is not a directory"};
      if (!(o.max_t_end_s > 0 && std::isfinite(o.max_t_end_s))) throw UsageError{"--max-t-end: must be > 0"};
      const val::RunSettings common = reference_settings(sub, o.ref);
      const auto scenes = scenes_for(o.scene, o.scene_dir);
      // Every scene's length and the parameter file are checked before any work.
      std::vector<cvt::Scene> plant_scenes;
      std::vector<val::RunSettings> settings;
      for (const auto& l : scenes) {
        settings.push_back(settings_for(common, o.ref, *l));
        plant_scenes.push_back(l->scene);
        if (!o.params.empty()) apply_params_file(o.params, plant_scenes.back());
        const double t_end = val::run_length_s(l->scene, common);
        if (t_end > o.max_t_end_s)
          throw UsageError{"scene " + l->name + ": " + fmt(t_end) + " s exceeds --max-t-end " + fmt(o.max_t_end_s) +
                           " s (raise it or shorten with --t-end)"};
      }
      prepare_out_dir(o.ref);
      std::vector<SceneOutput> results;
      for (std::size_t i = 0; i < scenes.size(); ++i) {
        const auto& l = scenes[i];
        SceneOutput out;
        {
          Progress progress("validate " + l->name + ": reference", val::run_length_s(l->scene, common));
          out.r = val::check_scene(l->name, l->scene, plant_scenes[i], settings[i],
                                   [&](double t) { progress.update(t); });
          out.set = cvt::mbd::parameter_set_name(settings[i].set);
        }
        if (out.r.skipped.empty()) {
          out.csv = o.ref.out_dir + "/" + l->name + ".csv";
          std::FILE* f = open_output(out.csv);
          val::write_overlay_csv(f, out.r.plant, out.r.ref.series);
          close_output(f);
          if (o.figures) {
            out.png = o.ref.out_dir + "/" + l->name + ".png";
            val::write_overlay_png(o.ref.out_dir, l->name, out.csv, out.png, out.r.cmp.compared_s, out.r.t_end_s);
          }
        }
        results.push_back(std::move(out));
      }
      if (o.json) {
        nlohmann::json j;
        j["subcommand"] = "validate";
        j["out_dir"] = o.ref.out_dir;
        j["sheaves"] = o.ref.sheaves;
        j["scenes"] = nlohmann::json::array();
        for (const auto& r : results) j["scenes"].push_back(to_json(r));
        print_json(j);
      } else {
        std::printf("The reference's sheaves: %s.\n\n", o.ref.sheaves == "scene"
                                                            ? "each scene's (fixed where the plant's are, else clamped)"
                                                            : o.ref.sheaves.c_str());
        print_text(results);
      }
      return 0;
    });
  };
}

const bool registered = add_registrar(&register_validate);

}  // namespace

}  // namespace cvtcli
