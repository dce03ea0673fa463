// `cvtplant calibrate`: the plant's lumped parameters fitted to multibody
// reference runs (docs/validation.md#calibration). The fit is the validation
// module's (validation/include/cvtplant/validation/calibration.hpp); this
// file parses the options, loads the scenes and prints.
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "guarded.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "validation_options.hpp"
#include "cvtplant/validation/calibration.hpp"
#include "cvtplant/validation/scene_check.hpp"

namespace cvtcli {

namespace {

namespace val = cvt::validation;

struct Options {
  ReferenceOptions ref;
  std::string scenes = "seed-case1,seed-case2,gross-slip";
  std::string fit = "k1_N_m,c1_Ns_m,k2_N_m,c2_Ns_m,lump_mass_kg,r1_m,r2_m";
  std::string out;
  std::string header;  // the same values as a C++ header for the built-in scenes
  std::string function = "apply";  // the header's function, cvt::calibrated::NAME(RomParams&)
  std::string start;  // parameter file to start from
  int every = 10;
  int max_evals = 400;
  bool json = false;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// The command that reproduces a fit (the parameter file's header).
std::string command_line(const Options& o) {
  std::ostringstream s;
  s << "cvtplant calibrate --scene " << o.scenes << " --fit " << o.fit;
  if (!o.start.empty()) s << " --start " << o.start;
  if (!o.ref.set.empty()) s << " --set " << o.ref.set;
  if (o.ref.sheaves != "scene") s << " --sheaves " << o.ref.sheaves;
  if (o.ref.t_end_s > 0) s << " --t-end " << o.ref.t_end_s;
  s << " --rtol " << o.ref.rtol << " --every " << o.every << " --max-evals " << o.max_evals << " --out " << o.out;
  if (!o.header.empty()) s << " --header " << o.header;
  if (o.function != "apply") s << " --function " << o.function;
  return s.str();
}

nlohmann::json to_json(const val::CalibrationResult& r, const std::vector<std::string>& names, const Options& o,
                       double ref_cpu_s) {
  nlohmann::json j;
  j["subcommand"] = "calibrate";
  j["scenes"] = names;
  j["sheaves"] = o.ref.sheaves;
  j["optimiser"] = "Eigen LevenbergMarquardt (forward-difference Jacobian)";
  j["status"] = r.status;
  j["plant_evaluations"] = r.evaluations;
  j["plant_faults"] = r.faults;
  j["iterations"] = r.iterations;
  j["residuals"] = r.residuals;
  j["cost_start"] = r.cost_start;
  j["cost_end"] = r.cost_end;
  j["rms_residual_start"] = r.rms_residual_start();
  j["rms_residual_end"] = r.rms_residual_end();
  j["reference_cpu_s"] = ref_cpu_s;
  nlohmann::json params = nlohmann::json::array();
  for (const auto& p : r.params)
    params.push_back({{"name", p.name},
                      {"start", p.start},
                      {"value", p.value},
                      {"sigma", p.identifiable ? nlohmann::json(p.sigma) : nlohmann::json(nullptr)},
                      {"sigma_rel", p.identifiable ? nlohmann::json(p.sigma_rel) : nlohmann::json(nullptr)},
                      {"identifiable", p.identifiable}});
  j["parameters"] = params;
  // The relative RMS errors of each case at the start and the end.
  nlohmann::json cases = nlohmann::json::array();
  for (const auto& c : r.cases) {
    nlohmann::json e;
    e["scene"] = c.scene;
    for (int q = 0; q < val::kFitQuantityCount; ++q)
      e[val::kFitQuantities[q].name] = {{"rel_rms_start", c.rel_rms_start[q]}, {"rel_rms_end", c.rel_rms_end[q]}};
    cases.push_back(e);
  }
  j["cases"] = cases;
  return j;
}

void print_text(const val::CalibrationResult& r, const Options& o) {
  std::printf("Calibration on %s: %ld plant runs, %d residuals, rms residual %.4g -> %.4g\n", o.scenes.c_str(),
              r.evaluations, r.residuals, r.rms_residual_start(), r.rms_residual_end());
  std::printf("| parameter | start | fitted | 1 sigma |\n|---|---|---|---|\n");
  for (const auto& p : r.params) {
    std::printf("| %s | %.6g | %.6g | ", p.name.c_str(), p.start, p.value);
    if (p.identifiable)
      std::printf("%.3g (%.2g %%) |\n", p.sigma, 100.0 * p.sigma_rel);
    else
      std::printf("not identifiable |\n");
  }
  std::printf("\n| scene | quantity | relative RMS error, start | after the fit |\n|---|---|---|---|\n");
  for (const auto& c : r.cases)
    for (int q = 0; q < val::kFitQuantityCount; ++q)
      std::printf("| %s | %s | %.2f %% | %.2f %% |\n", c.scene.c_str(), val::kFitQuantities[q].name,
                  100.0 * c.rel_rms_start[q], 100.0 * c.rel_rms_end[q]);
}

void write_text_file(const std::string& path, const std::string& text) {
  std::FILE* f = open_output(path);
  std::fputs(text.c_str(), f);
  close_output(f);
}

Action register_calibrate(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "Fit the plant's lumped parameters to multibody reference runs (docs/validation.md#calibration)");
  sub->add_option("--scene", opt->scenes, "Scenes to fit on, comma-separated (each one the reference can run)")
      ->capture_default_str();
  sub->add_option("--fit", opt->fit, "Parameters to fit, comma-separated: " + joined(val::fittable_names()))
      ->capture_default_str();
  sub->add_option("--out", opt->out, "Write the fitted parameters as a parameter file (TOML [params])");
  sub->add_option("--header", opt->header,
                  "Also write them as a C++ header with cvt::calibrated::apply(RomParams&) (the built-in scenes')");
  add_reference_options(sub, opt->ref, "Directory of the reference cache (shared with validate)");
  sub->add_option("--function", opt->function,
                  "The header's function name, cvt::calibrated::NAME(RomParams&) (one header per fitted set)")
      ->capture_default_str();
  sub->add_option("--start", opt->start, "Start from a parameter file's values (default: the scenes' own)");
  sub->add_option("--t-end", opt->ref.t_end_s, "Shorten every run to this simulated time [s]");
  sub->add_option("--every", opt->every, "Fit on every N-th sample, [1, 1000]")->capture_default_str();
  sub->add_option("--max-evals", opt->max_evals, "Cap on plant evaluations of the optimiser, [1, 100000]")
      ->capture_default_str();
  sub->add_flag("--json", opt->json, "Print the result as JSON");
  return [opt, sub]() -> int {
    return guarded([&] {
      const Options& o = *opt;
      if (sub->count("--t-end") > 0 && !(o.ref.t_end_s > 0 && o.ref.t_end_s <= 3600))
        throw UsageError{"--t-end: must be in (0, 3600] s"};
      const val::RunSettings common = reference_settings(sub, o.ref);
      if (!(o.every >= 1 && o.every <= 1000)) throw UsageError{"--every: outside [1, 1000]"};
      if (!(o.max_evals >= 1 && o.max_evals <= 100000)) throw UsageError{"--max-evals: outside [1, 100000]"};
      if (!val::is_cpp_identifier(o.function))
        throw UsageError{"--function: not a C++ identifier: '" + o.function + "'"};
      const std::vector<std::string> fit = split(o.fit);
      const auto names = split(o.scenes);
      if (names.empty()) throw UsageError{"--scene: no scene"};
      std::vector<std::shared_ptr<LoadedScene>> loaded;
      std::vector<cvt::Scene> plant_scenes;
      std::vector<val::RunSettings> settings;
      for (const auto& n : names) {
        auto l = resolve_scene(n);
        settings.push_back(settings_for(common, o.ref, *l));
        std::string why;
        if (!val::reference_setup(l->scene, settings.back(), why))
          throw UsageError{"--scene " + n + ": the reference cannot run " + why};
        loaded.push_back(l);
        // --start moves the plant's parameters only; the reference runs the scene.
        plant_scenes.push_back(l->scene);
        if (!o.start.empty()) apply_params_file(o.start, plant_scenes.back());
      }
      // The fitted values are shared by every scene: they start from the first's.
      std::unique_ptr<val::Calibration> cal;
      try {
        cal = std::make_unique<val::Calibration>(fit, plant_scenes.front().params);
      } catch (const val::InputError& e) {
        throw UsageError{std::string("--fit: ") + e.what()};
      }
      prepare_out_dir(o.ref);
      double ref_cpu = 0;
      for (std::size_t i = 0; i < loaded.size(); ++i) {
        cvt::Scene plant = plant_scenes[i];
        plant.t_end_s = val::run_length_s(plant, common);
        std::string why;
        auto setup = *val::reference_setup(loaded[i]->scene, settings[i], why);
        setup.run.t_end_s = plant.t_end_s;
        Progress progress("calibrate " + loaded[i]->name + ": reference", setup.run.t_end_s);
        const val::ReferenceRun rr = val::reference_run(setup.params, setup.run, common.cache_dir,
                                                        [&](double t) { progress.update(t); });
        progress.finish();
        ref_cpu += rr.cpu_s;
        cal->add_case(loaded[i]->name, plant, rr, o.every);
      }
      val::CalibrationResult r;
      {
        Progress progress("calibrate", o.max_evals, "plant runs");
        r = cal->run(o.max_evals, [&](long evals) { progress.update(static_cast<double>(evals)); });
      }
      if (!o.out.empty()) write_text_file(o.out, val::params_file_text(r, command_line(o), o.scenes));
      if (!o.header.empty()) write_text_file(o.header, val::header_text(r, command_line(o), o.function));
      if (o.json)
        print_json(to_json(r, names, o, ref_cpu));
      else
        print_text(r, o);
      return 0;
    });
  };
}

const bool registered = add_registrar(&register_calibrate);

}  // namespace

}  // namespace cvtcli
