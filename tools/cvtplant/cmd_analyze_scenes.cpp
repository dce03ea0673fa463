// The scene, sweep and figure tools of `cvtplant analyze`
// (docs/analysis.md): trajectory, sweep, merge, figures, seed-section4,
// ripple.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cmd_analyze.hpp"
#include "cmd_seed_section4_reference.hpp"
#include "io_util.hpp"
#include "model_resolve.hpp"
#include "progress.hpp"
#include "scene_file.hpp"
#include "cvtplant/analysis/csv_writer.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/analysis/ripple.hpp"
#include "cvtplant/analysis/rom_scenes.hpp"
#include "cvtplant/analysis/section4.hpp"
#include "cvtplant/analysis/sweep.hpp"
#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace cvtcli::analyze {

using namespace cvt::analysis;
using nlohmann::json;

namespace {

// `analyze seed-section4`: one signal's summary (docs/analysis.md#seed-section4).
// `unit`: the signal's, named beside its statistics (docs/cli.md#json-output).
json section4_json(const Section4Result& r, const std::string& unit) {
  json j{{"signal", r.label},
         {"points", r.points},
         {"constant", r.constant},
         {"stats",
          {{"unit", unit}, {"mean", r.mean}, {"std", r.stddev}, {"min", r.min}, {"max", r.max},
           {"peak_to_peak", r.max - r.min}}},
         {"classification", r.classification},
         {"confidence", r.confidence},
         {"evidence", r.evidence},
         {"figures", r.figures}};
  if (r.constant) return j;
  const Classification& c = r.verdict;
  json v = classification_json(c);
  for (const char* k : {"tau", "m", "theiler", "deterministic", "test01", "spectrum", "amplitude_decay"}) j[k] = v[k];
  j["tau_method"] = c.ami.method;
  j["tau_ami_first_minimum"] = c.ami.tau_ami;
  j["fnn"] = {{"m", c.fnn.m}, {"fraction", c.fnn.fraction}, {"dimension", c.fnn.dimension}, {"reached", c.fnn.reached},
              {"rtol", 10.0}, {"atol", 2.0}};
  j["cao"] = {{"m", r.cao.m}, {"E1", r.cao.e1}, {"E2", r.cao.e2}, {"dimension", r.cao.dimension}, {"reached", r.cao.reached}};
  j["lle"] = {{"rosenstein", lle_json(c.lle, "rosenstein", c.m, c.tau)},
              {"kantz", r.kantz_error.empty() ? lle_json(r.kantz, "kantz", c.m, c.tau) : json{{"error", r.kantz_error}}}};
  j["rqa"] = rqa_json(c.rqa, c.m, c.tau, c.rqa_options);
  return j;
}

}  // namespace

Tool add_trajectory(CLI::App* an) {
  struct T {
    std::string scene, x0, out = "-";
    std::vector<std::string> params;
    double dt = -1, t_transient = 0, t_end = 10, sample_dt = 0.001;
    cvtcli::Caps caps;
  };
  auto a = std::make_shared<T>();
  auto* c = an->add_subcommand("trajectory", "simulate a scene (RK4) and write its states as CSV");
  c->add_option("--scene", a->scene, "model (see cvtplant lyapunov --list) or plant scene (built-in or TOML file) with constant inputs")->required();
  c->add_option("--x0", a->x0, "initial state, comma-separated");
  c->add_option("--param", a->params, "name=value (repeatable)");
  cvtcli::add_real(c, "--dt", a->dt, {1e-9, 1}, "RK4 step [s] (default: the scene's)");
  cvtcli::add_real(c, "--t-transient", a->t_transient, {0, 1e9}, "time not written [s] (maps: iterations)");
  cvtcli::add_real(c, "--t-end", a->t_end, {0, 1e9, true}, "time written [s] (maps: iterations)");
  cvtcli::add_real(c, "--sample-dt", a->sample_dt, {0, 1e9, true}, "output interval [s]");
  c->add_option("--out", a->out, "output CSV ('-' = stdout)");
  cvtcli::add_caps(c, a->caps, true, true);
  return {c, [a] {
    const auto model = cvtcli::resolve_model(a->scene);
    const Model& s = *model;
    const Params p = merge_params(s, cvtcli::parse_assignments(a->params, "--param"));
    const auto x0 = a->x0.empty() ? s.default_x0 : cvtcli::parse_list(a->x0, s.dim, "--x0");
    const double dt = a->dt > 0 ? a->dt : s.defaults.dt;
    // Work and memory before the run: every step, and the rows held until written.
    const double steps = s.is_map ? a->t_transient + a->t_end : (a->t_transient + a->t_end) / dt;
    const double rows_n = s.is_map ? a->t_end : a->t_end / std::max(a->sample_dt, dt);
    cvtcli::require_steps(steps, a->caps, s.is_map ? "--t-transient + --t-end iterations"
                                                    : "(--t-transient + --t-end) / --dt");
    cvtcli::require_memory(rows_n * s.dim * 8.0, a->caps,
                           cvtcli::fmt_count(rows_n) + " rows of " + std::to_string(s.dim) + " states");
    std::vector<std::string> inputs;
    if (!has_model(a->scene)) inputs.push_back(a->scene);
    std::FILE* f = cvtcli::open_output(a->out, "--out", inputs);
    std::vector<double> rows;
    {
      // No bar when the CSV goes to stdout: on a terminal the two would interleave.
      cvtcli::Progress progress("trajectory " + a->scene, f == stdout ? 0.0 : steps, "steps");
      rows = s.trajectory(p, x0, dt, a->t_transient, a->t_end, a->sample_dt,
                          [&](double done, double) { progress.update(done); });
    }
    {
      CsvWriter w(f);
      w.text("t");
      for (const auto& n : s.state_names) w.text(n);
      w.end_row();
      const std::size_t n = rows.size() / s.dim;
      const double step = s.is_map ? 1.0 : std::max(1L, std::lround(a->sample_dt / dt)) * dt;
      for (std::size_t i = 0; i < n; ++i) {
        w.num(a->t_transient + static_cast<double>(i + 1) * step);
        for (int k = 0; k < s.dim; ++k) w.num(rows[i * s.dim + k]);
        w.end_row();
        if ((i & 1023) == 0 && !cvtcli::output_ok(f)) break;  // reported by close_output
      }
    }
    cvtcli::close_output(f);
    return 0;
  }};
}

Tool add_sweep(CLI::App* an) {
  struct S {
    std::string scene, a1, a2, x0, shard = "0/1", out = "-";
    std::vector<std::string> params;
    double dt = -1, t_transient = -1, t_end = -1, t_peaks = 20;
    int jobs = 0, state = 0;
    cvtcli::Caps caps;
  };
  auto a = std::make_shared<S>();
  auto* c = an->add_subcommand("sweep", "parameter sweep: spectrum + bifurcation data, parallel and shardable");
  c->add_option("--scene", a->scene, "model (see cvtplant lyapunov --list) or plant scene (built-in or TOML file) with constant inputs")->required();
  c->add_option("--axis", a->a1, "first axis name=lo:hi:n")->required();
  c->add_option("--axis2", a->a2, "optional second axis name=lo:hi:n");
  c->add_option("--param", a->params, "fixed override name=value (repeatable)");
  c->add_option("--x0", a->x0, "initial state");
  cvtcli::add_real(c, "--dt", a->dt, {1e-9, 1}, "RK4 step [s]");
  cvtcli::add_real(c, "--t-transient", a->t_transient, {0, 1e9}, "discarded time [s]");
  cvtcli::add_real(c, "--t-end", a->t_end, {0, 1e9, true}, "accumulation time [s]");
  cvtcli::add_real(c, "--t-peaks", a->t_peaks, {0, 1e9}, "time after the spectrum run for bifurcation peaks [s]");
  cvtcli::add_int(c, "--state", a->state, 0, 1000, "state index whose local maxima are recorded");
  c->add_option("--shard", a->shard, "i/N: run points k with k % N == i (for array jobs)");
  cvtcli::add_int(c, "--jobs", a->jobs, 0, 1024, "threads (default 0: all cores)");
  c->add_option("--out", a->out, "output CSV ('-' = stdout)");
  cvtcli::add_caps(c, a->caps, true, true);
  return {c, [a] {
    SweepSpec sp;
    sp.scene = a->scene;
    const auto model = cvtcli::resolve_model(a->scene);
    const Model& s = *model;
    sp.model = model.get();
    sp.overrides = cvtcli::parse_assignments(a->params, "--param");
    sp.a1 = parse_axis(a->a1);
    if (!a->a2.empty()) {
      sp.has_a2 = true;
      sp.a2 = parse_axis(a->a2);
    }
    if (!a->x0.empty()) sp.x0 = cvtcli::parse_list(a->x0, s.dim, "--x0");
    sp.benettin = s.defaults;
    if (a->dt > 0) sp.benettin.dt = a->dt;
    if (a->t_transient >= 0) sp.benettin.t_transient = a->t_transient;
    if (a->t_end > 0) sp.benettin.t_end = a->t_end;
    sp.t_peaks = a->t_peaks;
    sp.bif_state = a->state;
    if (a->state >= s.dim)
      throw cvtcli::UsageError{"--state: " + std::to_string(a->state) + " is not a state index of " +
                               s.name + " (0.." + std::to_string(s.dim - 1) + ")"};
    long long si = 0, sn = 1;
    {
      const std::size_t slash = a->shard.find('/');
      std::string why = slash == std::string::npos ? "must look like i/N" : "";
      if (why.empty()) why = cvtcli::check_int(a->shard.substr(slash + 1), 1, 1000000, &sn);
      if (why.empty()) why = cvtcli::check_int(a->shard.substr(0, slash), 0, sn - 1, &si);
      if (!why.empty()) throw cvtcli::UsageError{"--shard " + cvtcli::quoted(a->shard) + ": " + why};
    }
    // Work and memory of this shard before it runs: every point's
    // transient, warm-up, accumulation and peak search; its row.
    const double points = std::ceil(static_cast<double>(sp.total()) / static_cast<double>(sn));
    const BenettinOptions& bo = sp.benettin;
    const double span = bo.t_transient + bo.t_warmup + bo.t_end + sp.t_peaks;
    cvtcli::require_steps(points * (s.is_map ? span : span / bo.dt), a->caps,
                          cvtcli::fmt_count(points) + " points x " +
                              (s.is_map ? "(transient + warm-up + accumulation + peaks) iterations"
                                        : "(transient + warm-up + accumulation + peaks) / dt"));
    cvtcli::require_memory(points * (2.0 * s.dim + sp.max_peaks + 8) * 8.0, a->caps,
                           cvtcli::fmt_count(points) + " points");
    sp.benettin.max_steps = a->caps.max_steps;
    std::vector<std::string> inputs;
    if (!has_model(a->scene)) inputs.push_back(a->scene);
    std::FILE* f = cvtcli::open_output(a->out, "--out", inputs);
    cvtcli::Progress progress("sweep " + s.name, points, "points");
    const auto pts = run_sweep(sp, static_cast<int>(si), static_cast<int>(sn), a->jobs,
                               [&](long done, long) { progress.update(static_cast<double>(done)); });
    progress.finish();
    write_sweep_csv(f, sp, s.dim, pts);
    cvtcli::close_output(f);
    long failed = 0;
    for (const auto& p : pts) failed += !p.error.empty();
    if (!pts.empty() && failed == static_cast<long>(pts.size()))
      throw cvtcli::RunError{"every point (" + std::to_string(failed) + ") failed; first error: " +
                             cvtcli::quoted(pts.front().error, 200)};
    if (failed > 0)
      std::fprintf(stderr, "cvtplant analyze sweep: %ld of %zu point(s) failed (see the error column)\n",
                   failed, pts.size());
    return 0;
  }};
}

Tool add_merge(CLI::App* an) {
  auto shards = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>("-");
  auto* c = an->add_subcommand("merge", "merge sweep shards; refuses mixed sweeps and missing points");
  c->add_option("shards", *shards, "shard CSV files")->required();
  c->add_option("--out", *out, "merged CSV ('-' = stdout)");
  return {c, [shards, out] {
    std::FILE* f = cvtcli::open_output(*out, "--out", *shards);
    merge_sweep_csv(*shards, f);
    cvtcli::close_output(f);
    return 0;
  }};
}

Tool add_figures(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto dir = std::make_shared<std::string>();
  auto sweep = std::make_shared<std::string>();
  auto scene = std::make_shared<std::string>();
  auto t_end = std::make_shared<double>(20.0);
  auto caps = std::make_shared<cvtcli::Caps>();
  auto* c = an->add_subcommand("figures", "PNG figures via gnuplot: series (--csv), scene (--scene) or sweep (--sweep)");
  c->add_option("--csv", a->csv, "input CSV");
  c->add_option("--column", a->column, "column name");
  cvtcli::add_real(c, "--dt", a->dt, {0, 1e6, true}, "sample interval [s]");
  cvtcli::add_int(c, "--discard", a->discard, 0, 1000000000000LL, "leading samples dropped");
  cvtcli::add_int(c, "--tau", a->tau, 1, 100000, "delay [samples]");
  cvtcli::add_int(c, "--m", a->m, 1, 30, "embedding dimension");
  c->add_option("--scene", *scene, "scene for time histories and phase portraits");
  cvtcli::add_real(c, "--t-end", *t_end, {0, 1e5, true}, "scene simulation time [s] (maps: iterations)");
  cvtcli::add_caps(c, *caps, true, true);
  c->add_option("--sweep", *sweep, "merged sweep CSV for bifurcation and exponent maps");
  c->add_option("--out-dir", *dir, "output directory")->required();
  c->add_flag("--json", a->json, "print the written files as JSON");
  return {c, [a, dir, sweep, scene, t_end, caps] {
    std::vector<std::string> files;
    if (a->csv.empty() && sweep->empty() && scene->empty())
      throw cvtcli::UsageError{"give --csv/--column, --scene or --sweep"};
    if (!a->csv.empty()) {
      if (a->column.empty()) throw cvtcli::UsageError{"--column is required with --csv"};
      CsvColumn col = read_column(a->csv, a->column, *caps);
      if (a->discard < 0 || static_cast<std::size_t>(a->discard) >= col.values.size())
        throw cvtcli::UsageError{"--discard must be in 0..N-1"};
      cvtcli::require_memory(kSeriesBytesPerSample * static_cast<double>(col.values.size()), *caps,
                             cvtcli::fmt_count(static_cast<double>(col.values.size())) + " samples");
      std::vector<double> x(col.values.begin() + a->discard, col.values.end());
      auto f = series_figures(x, a->dt, a->column, *dir, a->tau, a->m);
      files.insert(files.end(), f.begin(), f.end());
    }
    const bool plant_scene =
        !scene->empty() && (cvt::find_builtin_scene(scene->c_str()) != nullptr || !has_model(*scene));
    if (plant_scene) {
      // A plant scene (built-in or a file): the frames `run` computes.
      const auto loaded = cvtcli::resolve_scene(*scene);
      const cvt::Scene& sc = loaded->scene;
      const double frames = *t_end / sc.frame_s;
      cvtcli::require_steps(frames * sc.substeps, *caps,
                            cvtcli::fmt_count(frames) + " frames x " + std::to_string(sc.substeps) +
                                " substeps");
      cvtcli::require_memory(frames * 8.0 * 16, *caps, cvtcli::fmt_count(frames) + " frames of 15 signals");
      cvtcli::Progress progress("figures " + loaded->name, *t_end);
      auto f = rom_scene_figures(sc, loaded->name, *t_end, *dir,
                                 [&](double t, double) { progress.update(t); });
      files.insert(files.end(), f.begin(), f.end());
    } else if (!scene->empty()) {
      const auto model = cvtcli::resolve_model(*scene);
      const Model& s = *model;
      const double steps = s.is_map ? *t_end : *t_end / s.defaults.dt;
      cvtcli::require_steps(steps, *caps, s.is_map ? "--t-end iterations" : "--t-end / the scene's dt");
      cvtcli::require_memory(steps * s.dim * 8.0, *caps, cvtcli::fmt_count(steps) + " states");
      cvtcli::Progress progress("figures " + *scene, steps, "steps");
      auto f = model_figures(s, s.default_params, s.default_x0, s.defaults.dt, *t_end, *dir,
                             [&](double done, double) { progress.update(done); });
      files.insert(files.end(), f.begin(), f.end());
    }
    if (!sweep->empty()) {
      auto f = sweep_figures(*sweep, *dir);
      files.insert(files.end(), f.begin(), f.end());
    }
    if (a->json)
      cvtcli::print_json(json{{"files", files}});
    else
      for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
    return 0;
  }};
}

Tool add_seed_section4(CLI::App* an) {
  struct A {
    std::string scene, out_dir, signals = "F_ax,torque_transmitted";
    double t_end = -1, t_transient = 2.0;
    int tau = -1, m = -1;
    bool json = false;
    cvtcli::Caps caps;
  };
  auto a = std::make_shared<A>();
  auto* c = an->add_subcommand("seed-section4",
                               "the seed's section 4 pipeline on ROM plant signals (1 ms samples, transient removed, "
                               "normalised, AMI delay, FNN/Cao dimension, Rosenstein/Kantz exponent, recurrence "
                               "plot + RQA, 0-1 test, verdict) with figures and a JSON summary");
  c->add_option("--scene", a->scene, "plant scene: built-in (seed-case1, seed-case2, ...; see cvtplant scenes) or a TOML scene file");
  const auto reference = cvtcli::add_section4_reference(c);
  c->add_option("--out-dir", a->out_dir, "output directory: <signal>/*.png and summary.json")->required();
  c->add_option("--signals", a->signals, "comma-separated plant outputs (F_ax, torque_transmitted, slip, v_rel1, ...)");
  cvtcli::add_real(c, "--t-end", a->t_end, {0, 1e5, true}, "simulated time [s] (default: the scene's)");
  cvtcli::add_real(c, "--t-transient", a->t_transient, {0, 1e5}, "removed from the start before the analysis [s]");
  cvtcli::add_int(c, "--tau", a->tau, 1, 100000, "delay [samples] (default: first AMI minimum)");
  cvtcli::add_int(c, "--m", a->m, 1, 30, "embedding dimension (default: FNN)");
  c->add_flag("--json", a->json, "print the summary as JSON");
  cvtcli::add_caps(c, a->caps, true, true);
  return {c, [a, reference] {
    if (cvtcli::section4_reference_selected(*reference)) return cvtcli::run_section4_reference(*reference);
    if (a->scene.empty()) throw cvtcli::UsageError{"--scene or --reference is required"};
    std::vector<std::string> names;
    {
      std::stringstream ss(a->signals);
      std::string n;
      while (std::getline(ss, n, ','))
        if (!n.empty()) names.push_back(n);
    }
    if (names.empty()) throw cvtcli::UsageError{"--signals is empty"};
    const auto scene = cvtcli::resolve_scene(a->scene);
    {
      // Work and memory before the run: the frames and their substeps;
      // the time and every signal stored, then one signal's analysis.
      const cvt::Scene& sc = scene->scene;
      const double frames = (a->t_end > 0 ? a->t_end : sc.t_end_s) / sc.frame_s;
      cvtcli::require_steps(frames * sc.substeps, a->caps,
                            cvtcli::fmt_count(frames) + " frames x " + std::to_string(sc.substeps) +
                                " substeps");
      cvtcli::require_memory(frames * (8.0 * (1 + names.size()) + kSeriesBytesPerSample), a->caps,
                             cvtcli::fmt_count(frames) + " samples of " +
                                 std::to_string(names.size()) + " signal(s) and their analysis");
    }
    // One bar: the plant run counts as one stage, then each signal's five.
    const double stages = 1.0 + 5.0 * static_cast<double>(names.size());
    cvtcli::Progress progress("seed-section4 " + scene->name, stages, "stages");
    progress.update(0);
    const RomSeries run = rom_scene_series(scene->scene, scene->name, names, a->t_end);
    progress.update(1);
    ensure_dir(a->out_dir);
    if (run.fault != "none")
      throw cvtcli::RunError{"the plant faulted (" + run.fault + ") in scene " + a->scene};
    Section4Options so;
    so.dt = run.frame_s;
    so.discard = std::lround(a->t_transient / run.frame_s);
    so.tau = a->tau;
    so.m = a->m;
    json out{{"scene", a->scene},
             {"sample_s", run.frame_s},
             {"t_end_s", run.t.empty() ? 0.0 : run.t.back()},
             {"t_transient_s", so.discard * run.frame_s},
             {"plant_fault", run.fault},
             {"normalisation", "z-score after the transient"},
             {"signals", json::array()}};
    if (a->scene == "seed-case1")
      out["seed_claim"] = "chaotic driver axial force (seed Figs. 18 and 21)";
    if (a->scene == "seed-case2")
      out["seed_claim"] = "mildly chaotic driver axial force (seed Figs. 19, 20 and 22)";
    double stages_before = 1;
    for (const auto& n : names) {
      so.on_stage = [&](int done, int) { progress.update(stages_before + done); };
      const Section4Result r =
          section4_pipeline(run.signal.at(n), so, a->scene + " " + n, a->out_dir + "/" + n);
      out["signals"].push_back(section4_json(r, rom_signal_unit(n)));
      stages_before += 5;
    }
    progress.finish();
    const std::string summary = a->out_dir + "/summary.json";
    {
      std::FILE* f = cvtcli::open_output(summary, "--out-dir");
      const std::string text = out.dump(2) + "\n";
      std::fwrite(text.data(), 1, text.size(), f);
      cvtcli::close_output(f);
    }
    if (a->json) {
      cvtcli::print_json(out);
      return 0;
    }
    for (const auto& j : out["signals"]) {
      std::printf("%s: %s (%s)\n", j["signal"].get<std::string>().c_str(),
                  j["classification"].get<std::string>().c_str(),
                  j["confidence"].get<std::string>().c_str());
      for (const auto& e : j["evidence"]) std::printf("  - %s\n", e.get<std::string>().c_str());
    }
    std::printf("wrote %s\n", summary.c_str());
    return 0;
  }};
}

Tool add_ripple(CLI::App* an) {
  struct R {
    std::string csv, column, time_column, windows, unit;
    RippleOptions o;
    bool json = false;
    cvtcli::Caps caps;
  };
  auto a = std::make_shared<R>();
  auto* c = an->add_subcommand("ripple", "detrended spread and dominant frequency of a column over time windows");
  c->add_option("--csv", a->csv, "input CSV with a header row and a time column")->required();
  c->add_option("--column", a->column, "column name")->required();
  c->add_option("--time-column", a->time_column, "time column [s] (default: t_s if present, else t)");
  c->add_option("--windows", a->windows, "windows [t0, t1) in s: T0:T1,T0:T1,...")->required();
  cvtcli::add_real(c, "--min-hz", a->o.min_hz, {0, 1e9},
                   "search the dominant frequency at or above this [Hz] (default 20)");
  cvtcli::add_real(c, "--band", a->o.band, {0, 10, true},
                   "the line's band around it, relative: f/(1+b)..f(1+b) (default 0.2)");
  c->add_option("--unit", a->unit, "the column's unit, reported beside its values (default: '-')");
  c->add_flag("--json", a->json, "machine-readable output");
  cvtcli::add_caps(c, a->caps, false, true);
  return {c, [a] {
    std::vector<std::pair<double, double>> wins;
    std::size_t from = 0;
    while (from <= a->windows.size()) {
      const std::size_t comma = std::min(a->windows.find(',', from), a->windows.size());
      const std::string w = a->windows.substr(from, comma - from);
      const std::size_t colon = w.find(':');
      if (colon == std::string::npos)
        throw cvtcli::UsageError{"--windows: '" + w + "' is not T0:T1"};
      const double t0 = cvtcli::parse_finite(w.substr(0, colon), "--windows");
      const double t1 = cvtcli::parse_finite(w.substr(colon + 1), "--windows");
      if (!(t1 > t0)) throw cvtcli::UsageError{"--windows: '" + w + "' must end after it begins"};
      wins.emplace_back(t0, t1);
      from = comma + 1;
    }
    std::string tcol = a->time_column;
    if (tcol.empty()) {
      const auto head = read_csv_header(a->csv);
      tcol = std::find(head.begin(), head.end(), "t_s") != head.end() ? "t_s" : "t";
    }
    const CsvColumn t = read_column(a->csv, tcol, a->caps);
    const CsvColumn y = read_column(a->csv, a->column, a->caps);
    const std::string unit = a->unit.empty() ? "-" : a->unit;
    json rows = json::array();
    if (!a->json)
      std::printf("%-12s %8s %12s %10s %10s %10s %10s\n", "window_s", "samples", "mean", "std",
                  "p-p", "peak_Hz", "line_amp");
    for (const auto& [t0, t1] : wins) {
      const RippleWindow r = ripple_window(t.values, y.values, t0, t1, a->o);
      rows.push_back({{"t_begin_s", r.t_begin_s}, {"t_end_s", r.t_end_s}, {"samples", r.samples},
                      {"mean", r.mean}, {"std", r.std}, {"peak_to_peak", r.peak_to_peak},
                      {"line_amplitude", r.line_amplitude}, {"unit", unit},
                      {"peak_Hz", r.peak_hz}});
      if (!a->json)
        std::printf("%5g-%-6g %8zu %12.6g %10.4g %10.4g %10.4g %10.4g\n", t0, t1, r.samples, r.mean,
                    r.std, r.peak_to_peak, r.peak_hz, r.line_amplitude);
    }
    if (a->json)
      cvtcli::print_json({{"column", a->column}, {"time_column", tcol}, {"min_Hz", a->o.min_hz},
                          {"band_rel", a->o.band}, {"windows", rows}});
    return 0;
  }};
}

}  // namespace cvtcli::analyze
