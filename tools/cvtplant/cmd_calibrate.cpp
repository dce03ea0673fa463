// `cvtplant calibrate`: the plant's lumped parameters fitted to multibody
// reference runs (docs/validation.md#calibration) or to a test rig's
// measured logs (docs/validation.md#measured-csv). The fit is the validation
// module's (validation/include/cvtplant/validation/calibration.hpp); this
// file parses the options, loads the scenes and prints.
#include <cmath>
#include <cstdio>
#include <filesystem>
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
#include "options.hpp"
#include "validation_options.hpp"
#include "cvtplant/files/paths.hpp"
#include "cvtplant/validation/calibration.hpp"
#include "cvtplant/validation/scene_check.hpp"
#include "cvtplant/validation/suite.hpp"
#include "cvtplant/validation/suite_check.hpp"

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
  std::string suite;  // a manoeuvre suite to fit on instead of scenes
  double max_t_end_s = 600;  // --suite: cap on its simulated seconds of reference
  std::vector<std::string> measured;  // test rig logs to fit on instead of reference runs
  double piston_area1_m2 = 0, piston_area2_m2 = 0;  // instead of the logs' own
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

// One argument as a POSIX shell reads it back: as it is when it holds only
// safe characters, else in single quotes. (Control characters never get
// here: paths with them are refused, docs/cli.md#files.)
std::string shell_word(const std::string& a) {
  bool plain = !a.empty();
  for (const char c : a)
    plain = plain && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string("-_./,:+=@%").find(c) != std::string::npos);
  if (plain) return a;
  std::string q = "'";
  for (const char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The command that reproduces a fit (the parameter file's header).
std::string command_line(const Options& o) {
  std::ostringstream s;
  s << "cvtplant calibrate";
  if (!o.suite.empty()) s << " --suite " << o.suite;
  for (const auto& m : o.measured) s << " --measured " << shell_word(m);
  s << " --scene " << shell_word(o.scenes) << " --fit " << shell_word(o.fit);
  if (!o.start.empty()) s << " --start " << shell_word(o.start);
  if (o.piston_area1_m2 > 0) s << " --piston-area1 " << exact_number(o.piston_area1_m2);
  if (o.piston_area2_m2 > 0) s << " --piston-area2 " << exact_number(o.piston_area2_m2);
  if (!o.ref.set.empty()) s << " --set " << o.ref.set;
  if (o.ref.sheaves != "scene") s << " --sheaves " << o.ref.sheaves;
  if (o.ref.t_end_s > 0) s << " --t-end " << exact_number(o.ref.t_end_s);
  if (o.measured.empty()) s << " --rtol " << exact_number(o.ref.rtol);
  s << " --every " << o.every << " --max-evals " << o.max_evals;
  if (!o.out.empty()) s << " --out " << shell_word(o.out);
  if (!o.header.empty()) s << " --header " << shell_word(o.header);
  if (o.function != "apply") s << " --function " << o.function;
  return s.str();
}

nlohmann::json to_json(const val::CalibrationResult& r, const std::vector<std::string>& names, const Options& o,
                       double ref_cpu_s) {
  nlohmann::json j;
  j["subcommand"] = "calibrate";
  j["scenes"] = names;
  if (!o.measured.empty()) j["measured"] = o.measured;
  if (o.measured.empty()) j["sheaves"] = o.ref.sheaves;
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
  j["reference_cpu_s"] = ref_cpu_s;  // of the runs made now (from the cache: none)
  if (!o.suite.empty()) {
    j["suite"] = o.suite;
    j["set"] = o.ref.set;
    j["held_out_faults"] = r.held_out_faults;
  }
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
    if (c.measured) {
      e["measured"] = true;
      const auto& v = c.start_speeds;
      e["start_speeds"] = {{"omega1_rad_s", v.omega1_rad_s}, {"omega2_rad_s", v.omega2_rad_s},
                           {"sigma1_rad_s", v.sigma1_rad_s}, {"sigma2_rad_s", v.sigma2_rad_s}};
    }
    if (!o.suite.empty()) e["held_out"] = c.held_out;
    for (std::size_t q = 0; q < c.quantities.size(); ++q)
      e[c.quantities[q]] = {{"rel_rms_start", c.rel_rms_start[q]}, {"rel_rms_end", c.rel_rms_end[q]}};
    cases.push_back(e);
  }
  j["cases"] = cases;
  return j;
}

void print_text(const val::CalibrationResult& r, const Options& o, const std::string& fitted_on) {
  std::printf("Calibration on %s: %ld plant runs, %d residuals, rms residual %.4g -> %.4g\n", fitted_on.c_str(),
              r.evaluations, r.residuals, r.rms_residual_start(), r.rms_residual_end());
  std::printf("| parameter | start | fitted | 1 sigma |\n|---|---|---|---|\n");
  for (const auto& p : r.params) {
    std::printf("| %s | %.6g | %.6g | ", p.name.c_str(), p.start, p.value);
    if (p.identifiable)
      std::printf("%.3g (%.2g %%) |\n", p.sigma, 100.0 * p.sigma_rel);
    else
      std::printf("not identifiable |\n");
  }
  std::printf("\n| %s | quantity | relative RMS error, start | after the fit |\n|---|---|---|---|\n",
              !o.measured.empty() ? "log" : !o.suite.empty() ? "manoeuvre" : "scene");
  for (const auto& c : r.cases)
    for (std::size_t q = 0; q < c.quantities.size(); ++q)
      std::printf("| %s%s | %s | %.2f %% | %.2f %% |\n", c.scene.c_str(), c.held_out ? " (held out)" : "",
                  c.quantities[q], 100.0 * c.rel_rms_start[q], 100.0 * c.rel_rms_end[q]);
  for (const auto& c : r.cases)
    if (c.measured)
      std::printf("\n%s: start speeds fitted to omega1 = %.6g +- %.2g rad/s, omega2 = %.6g +- %.2g rad/s\n",
                  c.scene.c_str(), c.start_speeds.omega1_rad_s, c.start_speeds.sigma1_rad_s,
                  c.start_speeds.omega2_rad_s, c.start_speeds.sigma2_rad_s);
}

// --max-evals against the fewest plant runs the fit can make.
void check_max_evals(const Options& o, const val::Calibration& cal) {
  if (o.max_evals >= cal.min_evaluations()) return;
  std::string what = std::to_string(split(o.fit).size()) + " parameter(s)";
  if (!o.measured.empty()) what += " and " + std::to_string(2 * o.measured.size()) + " start speed(s)";
  throw UsageError{"--max-evals: " + std::to_string(o.max_evals) + " is below the " +
                   std::to_string(cal.min_evaluations()) + " plant evaluations a fit of " + what +
                   " needs at the least (the start, and the residuals and the Jacobian at the result)"};
}

// The files --out and --header, and the result printed (a fit on logs or
// on a suite; `fitted_on` names what it was fitted on).
int report(const val::CalibrationResult& r, const Options& o, const CLI::App* sub, const std::string& fitted_on,
           const std::vector<std::string>& names, double ref_cpu_s) {
  if (sub->count("--out") > 0)
    write_generated_file(o.out, val::params_file_text(r, command_line(o), fitted_on), "--out");
  if (sub->count("--header") > 0)
    write_generated_file(o.header, val::header_text(r, command_line(o), o.function), "--header");
  if (o.json)
    print_json(to_json(r, names, o, ref_cpu_s));
  else
    print_text(r, o, fitted_on);
  return 0;
}

// The fit on test rig logs (docs/validation.md#measured-csv): the plant of
// the one --scene driven by each log's inputs, no reference run.
int run_measured(const Options& given, const CLI::App* sub, const std::vector<std::string>& fit) {
  // A log is fitted on every row unless --every says otherwise (a rig's
  // rate is its own, not the reference's 1 ms grid); the command written
  // into the files says which.
  Options o = given;
  if (sub->count("--every") == 0) o.every = 1;
  for (const char* flag : {"--set", "--sheaves", "--rtol", "--t-end", "--max-steps", "--out-dir"})
    if (sub->count(flag) > 0)
      throw UsageError{std::string(flag) + " is the reference's; a fit on --measured logs runs no reference"};
  if (sub->count("--scene") == 0)
    throw UsageError{"--measured needs --scene BASE: the plant (features, parameters) the logs drive"};
  const auto names = split(o.scenes);
  if (names.size() != 1)
    throw UsageError{"--scene: with --measured, one scene (the plant the logs drive), not " +
                     std::to_string(names.size())};
  const auto loaded = resolve_scene(names.front());
  cvt::files::CommandFiles files;
  if (loaded->source != "built-in") files.input("--scene", loaded->source);
  for (const auto& m : o.measured) files.input("--measured", m);
  // A log given twice would count twice and shrink the stated sigmas.
  for (std::size_t i = 0; i < o.measured.size(); ++i)
    for (std::size_t k = 0; k < i; ++k) {
      std::error_code ec;
      if (o.measured[i] == o.measured[k] || std::filesystem::equivalent(o.measured[i], o.measured[k], ec))
        throw UsageError{"--measured: " + cvtcli::quoted(o.measured[i]) + " is given twice (as " +
                         cvtcli::quoted(o.measured[k]) + ")"};
    }
  if (sub->count("--start") > 0) files.input("--start", o.start);
  if (sub->count("--out") > 0) files.output("--out", o.out);
  if (sub->count("--header") > 0) files.output("--header", o.header);
  cvt::Scene plant = loaded->scene;
  if (!o.start.empty()) apply_params_file(o.start, plant);
  std::unique_ptr<val::Calibration> cal;
  try {
    cal = std::make_unique<val::Calibration>(fit, plant.params);
  } catch (const val::InputError& e) {
    throw UsageError{std::string("--fit: ") + e.what()};
  }
  const val::PistonAreas areas{o.piston_area1_m2, o.piston_area2_m2};
  for (const auto& m : o.measured) {
    const val::MeasuredLog log = val::read_measured_csv(m, areas);
    cal->add_measured_case(m, plant, log, o.every);
  }
  check_max_evals(o, *cal);
  val::CalibrationResult r;
  {
    Progress progress("calibrate", o.max_evals, "plant runs");
    r = cal->run(o.max_evals, [&](long evals) { progress.update(static_cast<double>(evals)); });
  }
  std::string logs;
  for (const auto& m : o.measured) logs += (logs.empty() ? "" : ",") + m;
  const std::string fitted_on = logs + " (plant " + loaded->name + ")";
  return report(r, o, sub, fitted_on, names, 0.0);
}

// The fit on a manoeuvre suite (docs/validation.md#calibration-suite): the
// reference runs `validate --suite` makes (the same cache), the held-out
// manoeuvres reported, not fitted.
int run_suite(const Options& given, const CLI::App* sub, const std::vector<std::string>& fit) {
  for (const char* flag : {"--t-end", "--sheaves", "--piston-area1", "--piston-area2"})
    if (sub->count(flag) > 0)
      throw UsageError{std::string(flag) + " does not apply to --suite (its manoeuvres set the runs)"};
  Options o = given;
  // As validate --suite: the plant ratio-control, the production set, and
  // every 1 ms sample unless told otherwise (the ci suite's runs are 60 ms).
  if (sub->count("--scene") == 0) o.scenes = "ratio-control";
  if (o.ref.set.empty()) o.ref.set = "production";
  if (sub->count("--every") == 0) o.every = 1;
  const val::Suite suite = val::suite_by_name(o.suite);
  const auto names = split(o.scenes);
  if (names.size() != 1)
    throw UsageError{"--scene: with --suite, one scene (the plant), not " + std::to_string(names.size())};
  val::ReferenceConfig cfg;
  cfg.set = val::parameter_set(o.ref.set);
  cfg.rtol = o.ref.rtol;
  if (o.ref.max_steps_opt != nullptr && o.ref.max_steps_opt->count() > 0)
    cfg.max_steps_per_frame = std::min<long long>(o.ref.max_steps, cfg.max_steps_per_frame);
  const auto loaded = resolve_scene(names.front());
  cvt::files::CommandFiles files;
  if (loaded->source != "built-in") files.input("--scene", loaded->source);
  if (sub->count("--start") > 0) files.input("--start", o.start);
  if (sub->count("--out") > 0) files.output("--out", o.out);
  if (sub->count("--header") > 0) files.output("--header", o.header);
  cvt::Scene plant = loaded->scene;
  if (!o.start.empty()) apply_params_file(o.start, plant);
  if ((plant.features & cvt::rom_feature::wedging) == 0)
    throw UsageError{"--scene " + names.front() + ": a suite's plant needs the wedging feature (a variable ratio)"};
  std::unique_ptr<val::Calibration> cal;
  try {
    cal = std::make_unique<val::Calibration>(fit, plant.params);
  } catch (const val::InputError& e) {
    throw UsageError{std::string("--fit: ") + e.what()};
  }
  check_max_evals(o, *cal);
  val::SuiteOptions runs_only;
  runs_only.maps = false;
  runs_only.uncertainty = "none";
  const double total_s = val::suite_reference_s(suite, cfg, runs_only);
  if (total_s > o.max_t_end_s)
  {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.6g s of reference exceeds --max-t-end %.6g s", total_s, o.max_t_end_s);
    throw UsageError{"suite " + o.suite + ": " + buf};
  }
  prepare_out_dir(o.ref);
  std::vector<val::Manoeuvre> all = suite.fit;
  all.insert(all.end(), suite.held_out.begin(), suite.held_out.end());
  std::vector<val::ReferenceRun> refs;
  {
    Progress progress("calibrate --suite " + o.suite + ": reference", total_s);
    refs = val::reference_manoeuvres(all, cfg, o.ref.out_dir + "/reference-cache",
                                     [&](double t) { progress.update(t); });
  }
  double ref_cpu = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    report_cache_problem("calibrate", refs[i]);
    if (!refs[i].from_cache) ref_cpu += refs[i].cpu_s;
    cal->add_manoeuvre_case(all[i], plant, refs[i], o.every, i >= suite.fit.size());
  }
  val::CalibrationResult r;
  {
    Progress progress("calibrate", o.max_evals, "plant runs");
    r = cal->run(o.max_evals, [&](long evals) { progress.update(static_cast<double>(evals)); });
  }
  const std::string fitted_on = "suite " + o.suite + " (plant " + loaded->name + ", " + o.ref.set + " set)";
  std::vector<std::string> run_names;
  for (const auto& m : all) run_names.push_back(m.name);
  return report(r, o, sub, fitted_on, run_names, ref_cpu);
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
  add_int(sub, "--every", opt->every, 1, 1000, "Fit on every N-th sample (default 10)");
  add_int(sub, "--max-evals", opt->max_evals, 1, 100000,
          "Cap on plant evaluations of the fit, all counted: the start, the optimiser's and those at the result "
          "(default 400; at least the fitted parameters + 2)");
  sub->add_option("--suite", opt->suite,
                  "Fit on a manoeuvre suite's runs instead of scenes (" + joined(val::suite_names()) +
                      "; docs/validation.md#calibration-suite): its held-out runs are reported, not fitted; --scene "
                      "names the plant (default ratio-control), --set defaults to production");
  add_real(sub, "--max-t-end", opt->max_t_end_s, {0, 1e5, true},
           "--suite: refuse a suite above this many simulated seconds of reference, cached or not (default 600)");
  sub->add_option("--measured", opt->measured,
                  "Fit on a test rig's log instead of reference runs (repeatable; CSV, "
                  "docs/validation.md#measured-csv); --scene names the one plant the logs drive");
  add_real(sub, "--piston-area1", opt->piston_area1_m2, {1e-6, 1.0},
           "Driver piston area [m^2] turning a log's clamping pressure into a force (instead of the log's own)");
  add_real(sub, "--piston-area2", opt->piston_area2_m2, {1e-6, 1.0},
           "Driven piston area [m^2] turning a log's clamping pressure into a force (instead of the log's own)");
  sub->add_flag("--json", opt->json, "Print the result as JSON");
  return [opt, sub]() -> int {
    return guarded([&] {
      const Options& o = *opt;
      const val::RunSettings common = reference_settings(sub, o.ref);
      if (!val::is_cpp_identifier(o.function))
        throw UsageError{"--function: " + quoted(o.function) +
                         " is not a name for a C++ function (an identifier of at most 64 characters, not a keyword "
                         "nor reserved)"};
      const std::vector<std::string> fit = split(o.fit);
      if (!o.suite.empty() && !o.measured.empty()) throw UsageError{"--suite and --measured: one or the other"};
      if (sub->count("--max-t-end") > 0 && o.suite.empty()) throw UsageError{"--max-t-end caps a --suite; no --suite"};
      if (!o.suite.empty()) return run_suite(o, sub, fit);
      if (!o.measured.empty()) return run_measured(o, sub, fit);
      if (sub->count("--piston-area1") > 0 || sub->count("--piston-area2") > 0)
        throw UsageError{"--piston-area1/--piston-area2 turn a --measured log's pressures into forces; no --measured"};
      const auto names = split(o.scenes);
      if (names.empty()) throw UsageError{"--scene: no scene"};
      std::vector<std::shared_ptr<LoadedScene>> loaded;
      for (const auto& n : names) loaded.push_back(resolve_scene(n));
      // Every file read and written, before any work: the parameter file
      // and the header never over a scene, the start file or each other
      // (docs/cli.md#files).
      cvt::files::CommandFiles files;
      for (const auto& l : loaded)
        if (l->source != "built-in") files.input("--scene", l->source);
      if (sub->count("--start") > 0) files.input("--start", o.start);
      if (sub->count("--out") > 0) files.output("--out", o.out);
      if (sub->count("--header") > 0) files.output("--header", o.header);
      std::vector<cvt::Scene> plant_scenes;
      std::vector<val::RunSettings> settings;
      for (std::size_t i = 0; i < loaded.size(); ++i) {
        const auto& l = loaded[i];
        settings.push_back(settings_for(common, o.ref, *l));
        std::string why;
        if (!val::reference_setup(l->scene, settings.back(), why))
          throw UsageError{"--scene " + names[i] + ": the reference cannot run " + why};
        // --start moves the plant's parameters only; the reference runs the scene.
        plant_scenes.push_back(l->scene);
        if (!o.start.empty()) apply_params_file(o.start, plant_scenes.back());
        reference_step_cap(l->scene, settings.back(), o.ref, l->name);
      }
      // The fitted values are shared by every scene: they start from the first's.
      std::unique_ptr<val::Calibration> cal;
      try {
        cal = std::make_unique<val::Calibration>(fit, plant_scenes.front().params);
      } catch (const val::InputError& e) {
        throw UsageError{std::string("--fit: ") + e.what()};
      }
      check_max_evals(o, *cal);
      prepare_out_dir(o.ref);
      double ref_cpu = 0;
      for (std::size_t i = 0; i < loaded.size(); ++i) {
        cvt::Scene plant = plant_scenes[i];
        plant.t_end_s = val::run_length_s(plant, common);
        std::string why;
        auto setup = *val::reference_setup(loaded[i]->scene, settings[i], why);
        setup.run.t_end_s = plant.t_end_s;
        setup.run.max_steps = reference_step_cap(loaded[i]->scene, settings[i], o.ref, loaded[i]->name);
        Progress progress("calibrate " + loaded[i]->name + ": reference", setup.run.t_end_s);
        const val::ReferenceRun rr = val::reference_run(setup.params, setup.run, common.cache_dir,
                                                        [&](double t) { progress.update(t); });
        progress.finish();
        report_cache_problem("calibrate", rr);
        if (!rr.from_cache) ref_cpu += rr.cpu_s;
        cal->add_case(loaded[i]->name, plant, rr, o.every);
      }
      val::CalibrationResult r;
      {
        Progress progress("calibrate", o.max_evals, "plant runs");
        r = cal->run(o.max_evals, [&](long evals) { progress.update(static_cast<double>(evals)); });
      }
      if (sub->count("--out") > 0)
        write_generated_file(o.out, val::params_file_text(r, command_line(o), o.scenes), "--out");
      if (sub->count("--header") > 0)
        write_generated_file(o.header, val::header_text(r, command_line(o), o.function), "--header");
      if (o.json)
        print_json(to_json(r, names, o, ref_cpu));
      else
        print_text(r, o, o.scenes);
      return 0;
    });
  };
}

const bool registered = add_registrar(&register_calibrate);

}  // namespace

}  // namespace cvtcli
