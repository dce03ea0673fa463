// `cvtplant validate`: the real-time plant against the multibody reference,
// scene by scene, on the same inputs (docs/validation.md, docs/cli.md#validate).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "validation.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace cvtcli::validation {

namespace {

struct Options {
  std::string scene = "all";
  std::string out_dir = "validation";
  std::string params;  // a parameter file applied to every scene's plant
  std::string sheaves = "scene";  // the reference's sheaves: each scene's, or one mode for all
  std::string scene_dir = "tools/scenes";  // scene files that --scene all adds
  double t_end_s = 0;  // 0: each scene's own
  double rtol = 5e-7;
  long long max_steps = 20000000;
  double max_t_end_s = 60;
  bool json = false;
  bool figures = true;
};

struct SceneResult {
  std::string name;
  std::string skipped;  // why the reference cannot run it (empty: it ran)
  double t_end_s = 0;
  Comparison cmp;
  ReferenceRun ref;
  bool clamped = true;          // the reference's sheaves (reference_sheaves)
  double stop_s[2] = {-1, -1};  // first time each reference sheave is at its end stop (-1: never)
  std::string png, csv;
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

void write_overlay_csv(const std::string& path, const Series& p, const Series& r) {
  std::FILE* f = open_output(path);
  std::fprintf(f,
               "t_s,omega1_plant,omega1_ref,omega2_plant,omega2_ref,ratio_plant,ratio_ref,F_ax1_plant_N,F_ax1_ref_N,"
               "torque_plant_Nm,torque_ref_Nm,slip1_plant_m_s,slip1_ref_m_s,wrap_slip1_plant_m_s,wrap_slip1_ref_m_s\n");
  auto ratio = [](double w1, double w2) { return std::fabs(w2) >= 1.0 ? w1 / w2 : NAN; };
  for (std::size_t i = 0; i < std::min(p.size(), r.size()); ++i)
    std::fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", p.t_s[i],
                 p.omega1_rad_s[i], r.omega1_rad_s[i], p.omega2_rad_s[i], r.omega2_rad_s[i],
                 ratio(p.omega1_rad_s[i], p.omega2_rad_s[i]), ratio(r.omega1_rad_s[i], r.omega2_rad_s[i]),
                 p.F_ax1_N[i], r.F_ax1_N[i], p.torque_driver_Nm[i], r.torque_driver_Nm[i], p.slip1_m_s[i],
                 r.slip1_m_s[i], p.wrap_slip_m_s[i], r.wrap_slip_m_s[i]);
  close_output(f);
}

// Stacked panels, one per unit: speeds, ratio, force, torque, slip speed.
void write_overlay_png(const std::string& dir, const std::string& name, const std::string& csv,
                       const std::string& png, double compared_s, double t_end_s) {
  auto s = cvt::analysis::open_text_file(dir + "/" + name + ".gp");
  s << cvt::analysis::png_terminal(1000, 1300) << "set output '" << png << "'\n"
    << "set datafile separator ','\nset datafile missing 'nan'\nset grid\nset key outside right\n"
    << "set multiplot layout 5,1 title 'Scene " << name
    << ": real-time plant (lines) against the multibody reference (thin, grey and red)'\n"
    << "set lmargin 12\nset rmargin 26\nunset xlabel\n"
    // A fixed time axis: a short run whose ratio is undefined throughout (the
    // driven pulley below 1 rad/s) still draws an empty panel, not an error.
    << "set xrange [0:" << t_end_s << "]\n";
  // A dotted line where the comparison ends (a sheave at its end stop, or
  // the reference stopped).
  if (compared_s < t_end_s - 1e-9)
    s << "set arrow from " << compared_s << ", graph 0 to " << compared_s << ", graph 1 nohead dt 3 lc rgb '#000000'\n";
  const std::string src = "'" + csv + "' skip 1";
  s << "set ylabel 'pulley speed [rad/s]'\n"
    << "plot " << src << " using 1:3 with lines lw 1 lc rgb '#888888' title 'omega1 reference', " << src
    << " using 1:5 with lines lw 1 lc rgb '#e07b7b' title 'omega2 reference', " << src
    << " using 1:2 with lines lw 2 lc rgb '#1f4e9c' title 'omega1 plant', " << src
    << " using 1:4 with lines lw 2 dt 2 lc rgb '#c0392b' title 'omega2 plant'\n";
  // The ratio passes through infinity while a driven pulley starts: a fixed
  // range keeps the running values readable.
  s << "set ylabel 'speed ratio omega1/omega2 [-]'\nset yrange [0:6]\n"
    << "plot " << src << " using 1:7 with lines lw 1 lc rgb '#888888' title 'reference', " << src
    << " using 1:6 with lines lw 2 lc rgb '#1f4e9c' title 'plant'\n";
  s << "set autoscale y\nset ylabel 'driver axial force F_ax1 [kN]'\n"
    << "plot " << src << " using 1:($9/1000) with lines lw 1 lc rgb '#888888' title 'reference', " << src
    << " using 1:($8/1000) with lines lw 2 lc rgb '#1f4e9c' title 'plant'\n";
  s << "set ylabel 'torque on the driver [N m]'\n"
    << "plot " << src << " using 1:11 with lines lw 1 lc rgb '#888888' title 'reference', " << src
    << " using 1:10 with lines lw 2 lc rgb '#1f4e9c' title 'plant'\n";
  // The mean over the wrap, and (dashed) the slip the whole wrap shares,
  // whose crossing of the threshold is the time to gross slip.
  s << "set xlabel 't [s]'\nset ylabel 'driver slip speed [m/s]'\n"
    << "plot " << src << " using 1:13 with lines lw 1 lc rgb '#888888' title 'ref. mean', " << src
    << " using 1:15 with lines lw 1 dt 2 lc rgb '#e07b7b' title 'ref. whole wrap', " << src
    << " using 1:12 with lines lw 2 lc rgb '#1f4e9c' title 'plant mean', " << src
    << " using 1:14 with lines lw 2 dt 2 lc rgb '#c0392b' title 'plant whole wrap', " << kGrossSlip_m_s
    << " with lines lw 1 dt 3 lc rgb '#000000' title 'gross slip'\n"
    << "unset multiplot\n";
  s.close();
  cvt::analysis::run_gnuplot(dir + "/" + name + ".gp");
}

nlohmann::json jnum(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
nlohmann::json jtime(double t) { return t >= 0 ? nlohmann::json(t) : nlohmann::json(nullptr); }

nlohmann::json to_json(const SceneResult& r) {
  nlohmann::json j;
  j["scene"] = r.name;
  if (!r.skipped.empty()) {
    j["status"] = "not run";
    j["reason"] = r.skipped;
    return j;
  }
  j["status"] = "ok";
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
  j["gross_slip_s"] = {{"threshold_m_s", kGrossSlip_m_s},
                       {"plant", jtime(r.cmp.gross_slip_plant_s)},
                       {"reference", jtime(r.cmp.gross_slip_reference_s)}};
  j["csv"] = r.csv;
  j["png"] = r.png.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.png);
  return j;
}

std::string pct(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f %%", 100.0 * v);
  return b;
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

std::string tfmt(double t) { return t >= 0 ? fmt(t) + " s" : "never"; }

void print_text(const std::vector<SceneResult>& results) {
  for (const auto& r : results) {
    if (!r.skipped.empty()) {
      std::printf("## %s: not run (the reference cannot run %s)\n\n", r.name.c_str(), r.skipped.c_str());
      continue;
    }
    std::printf("## %s (%g s; compared over 0-%g s; steady state: the last %g s of it; reference on %s sheaves, %s)\n\n",
                r.name.c_str(), r.t_end_s, r.cmp.compared_s, r.cmp.window_s, r.clamped ? "clamped" : "fixed",
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
    std::printf("| time to gross slip (whole driver wrap > %g m/s) | s | | %s | %s | |\n\n", kGrossSlip_m_s,
                tfmt(r.cmp.gross_slip_plant_s).c_str(), tfmt(r.cmp.gross_slip_reference_s).c_str());
  }
}

Action register_validate(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "validate", "The real-time plant against the multibody reference on each drive-train scene (docs/validation.md)");
  sub->add_option("--scene", opt->scene, "A scene name, a scene file, or 'all' (every built-in drive-train scene)")
      ->capture_default_str();
  sub->add_option("--out-dir", opt->out_dir, "Directory for the overlays, CSVs and the reference cache")
      ->capture_default_str();
  sub->add_option("--t-end", opt->t_end_s, "Shorten every run to this simulated time [s] (default: each scene's)");
  sub->add_option("--max-t-end", opt->max_t_end_s, "Cap on a run's simulated time [s] (work); raise it for long scenes")
      ->capture_default_str();
  sub->add_option("--rtol", opt->rtol, "Reference's BDF relative tolerance, [1e-11, 1e-3]")->capture_default_str();
  sub->add_option("--max-steps", opt->max_steps, "Cap on the reference's integrator steps per scene, [1, 1e12]")
      ->capture_default_str();
  add_sheaves_option(sub, opt->sheaves);
  auto* dir_opt = sub->add_option("--scene-dir", opt->scene_dir,
                                  "Directory whose scene files (*.toml) --scene all adds to the built-in scenes")
                      ->capture_default_str();
  sub->add_option("--params", opt->params,
                  "Run the plant with a parameter file's [params] (e.g. calibrate --out); the reference is unchanged");
  sub->add_flag("--json", opt->json, "Print the results as JSON");
  sub->add_flag("!--no-figures", opt->figures, "Skip the overlay PNGs");
  return [opt, sub, dir_opt]() -> int {
    const Options& o = *opt;
    std::error_code ec;
    if (dir_opt->count() > 0 && !std::filesystem::is_directory(o.scene_dir, ec))
      throw UsageError{"--scene-dir: " + o.scene_dir + " is not a directory"};
    if (sub->count("--t-end") > 0 && !(o.t_end_s > 0 && std::isfinite(o.t_end_s)))
      throw UsageError{"--t-end: must be a positive number of seconds"};
    if (!(o.max_t_end_s > 0 && std::isfinite(o.max_t_end_s))) throw UsageError{"--max-t-end: must be > 0"};
    if (!(o.rtol >= 1e-11 && o.rtol <= 1e-3)) throw UsageError{"--rtol: outside [1e-11, 1e-3]"};
    if (!(o.max_steps >= 1 && o.max_steps <= 1000000000000LL)) throw UsageError{"--max-steps: outside [1, 1e12]"};
    if (o.out_dir.empty()) throw UsageError{"--out-dir: empty"};
    const auto scenes = scenes_for(o.scene, o.scene_dir);
    // Every scene's length and the parameter file are checked before any work.
    for (const auto& l : scenes) {
      if (!o.params.empty()) {
        cvt::Scene c = l->scene;
        apply_params_file(o.params, c);
      }
      const double t_end = o.t_end_s > 0 ? std::min(o.t_end_s, l->scene.t_end_s) : l->scene.t_end_s;
      if (t_end > o.max_t_end_s)
        throw UsageError{"scene " + l->name + ": " + fmt(t_end) + " s exceeds --max-t-end " + fmt(o.max_t_end_s) +
                         " s (raise it or shorten with --t-end)"};
    }
    try {
      cvt::analysis::ensure_dir(o.out_dir);
      cvt::analysis::ensure_dir(o.out_dir + "/reference-cache");
    } catch (const cvt::analysis::InputError& e) {
      throw UsageError{std::string("--out-dir: ") + e.what()};
    }
    std::vector<SceneResult> results;
    for (const auto& l : scenes) {
      SceneResult r;
      r.name = l->name;
      cvt::Scene s = l->scene;
      std::string why;
      const auto params = reference_params(s, sheave_choice(o.sheaves), why);
      if (!params) {
        r.skipped = why;
        results.push_back(r);
        continue;
      }
      if (o.t_end_s > 0) s.t_end_s = std::min(o.t_end_s, s.t_end_s);
      r.t_end_s = s.t_end_s;
      // After reference_params: the parameter file moves the plant only.
      if (!o.params.empty()) apply_params_file(o.params, s);
      cvt::mbd::RunOptions ro;
      ro.t_end_s = s.t_end_s;
      ro.rtol = o.rtol;
      ro.sample_s = s.frame_s;
      ro.max_steps = o.max_steps;
      r.ref = reference_run(*params, ro, o.out_dir + "/reference-cache", "validate " + r.name + ": reference");
      const Series plant = plant_run(s, s.frame_s);
      // A reference that stopped early is compared up to there.
      r.cmp = compare(plant, r.ref.series, std::min(plant.size(), r.ref.series.size()));
      r.clamped = params->sheaves == cvt::mbd::SheaveMode::clamped;
      if (r.clamped)
        for (int j = 0; j < 2; ++j) r.stop_s[j] = first_at_stop_s(r.ref, j, params->sheave_stop_m);
      r.csv = o.out_dir + "/" + r.name + ".csv";
      write_overlay_csv(r.csv, plant, r.ref.series);
      if (o.figures) {
        r.png = o.out_dir + "/" + r.name + ".png";
        write_overlay_png(o.out_dir, r.name, r.csv, r.png, r.cmp.compared_s, r.t_end_s);
      }
      results.push_back(r);
    }
    if (o.json) {
      nlohmann::json j;
      j["subcommand"] = "validate";
      j["out_dir"] = o.out_dir;
      j["sheaves"] = o.sheaves;
      j["scenes"] = nlohmann::json::array();
      for (const auto& r : results) j["scenes"].push_back(to_json(r));
      print_json(j);
    } else {
      std::printf("The reference's sheaves: %s.\n\n",
                  o.sheaves == "scene" ? "each scene's (fixed where the plant's are, else clamped)" : o.sheaves.c_str());
      print_text(results);
    }
    return 0;
  };
}

const bool registered = add_registrar(&register_validate);

}  // namespace

}  // namespace cvtcli::validation
