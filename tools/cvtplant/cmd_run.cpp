// `cvtplant run`: a scene of the reduced-order CVT plant, frame by frame,
// in double, float or q16.16 (docs/cli.md#run, docs/rom.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "cvtplant/analysis/csv_writer.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "scene_simulator.hpp"
#include "cvtplant/scene/adaptive_runner.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "cvtplant/files/interrupt.hpp"
#include "cvtplant/files/paths.hpp"

namespace {

struct Result {
  cvt::RomFault fault = cvt::RomFault::none;
  long frames = 0;
  double t_end_s = 0;
  double wall_s = 0;    // the frame loop, CSV included
  double output_s = 0;  // of which: formatting and writing the CSV
  double stored0 = 0, stored = 0, input = 0, actuator = 0, load = 0, friction = 0, damping = 0, residual = 0,
         scale = 0;
  double mean_w1 = 0, mean_w2 = 0, mean_fax = 0, max_abs_slip = 0;
  double final_w1 = 0, final_w2 = 0, final_fax = 0, final_slip = 0, final_torque = 0;
  // The chain's tension state at the end (feature tension, docs/rom.md#tension).
  double final_T_tight = 0, final_T_slack = 0, final_T_c = 0, final_creep = 0;
  bool final_on_stop = false;
  // SIGINT or SIGTERM stopped the run after the frame at t_end_s; its row
  // is written whole (docs/cli.md#interruption).
  bool interrupted = false;
};

// The frame loop on the scene's plant (any scalar, any feature set), on the
// frame stepper or the adaptive solver: both show each frame through the same
// view (outputs, energy, fault, state_si), so the rows are written once. The
// CSV is written through a buffered shortest-round-trip writer and its cost
// is timed apart from the plant's (docs/cli.md#run).
struct Runner {
  // The CSV's numeric columns at most: time, every signal, the states.
  static constexpr int kMaxColumns = 1 + cvt::kRomSignalCount + cvt::kRomMaxStates;
  // The output groups written before the state vector, in column order.
  static constexpr std::uint32_t kGroupsBeforeStates[] = {cvt::rom_log::base, cvt::rom_log::torques,
                                                          cvt::rom_log::friction, cvt::rom_log::ratios,
                                                          cvt::rom_log::energy};
  const cvt::Scene& scene;
  std::FILE* csv;
  int every;

  // The frame stepper.
  template <class T>
  Result operator()(cvt::IRomSimulator<T>& simulator) {
    return frames<T>(simulator.features(), simulator.state_count(),
                     [&](auto& on_frame) { return cvt::run_frames(simulator, scene, scene.frame_s, on_frame); });
  }

  // drive(on_frame) runs the frames and returns the fault at the end.
  template <class T, class Drive>
  Result frames(std::uint32_t features, int n_states, Drive&& drive) {
    using clock = std::chrono::steady_clock;
    const std::uint32_t log = scene.log;
    cvt::analysis::CsvWriter w(csv);
    clock::duration output_time{};
    if (csv != nullptr) {
      const auto t0 = clock::now();
      w.text("t");
      // The plant's signals in their groups (rom_signals.hpp); the state
      // vector sits between the energy and the tension groups.
      const auto header = [&](std::uint32_t group) {
        for (const auto& s : cvt::kRomSignals)
          if (s.log == group) w.text(s.name);
      };
      for (std::uint32_t group : kGroupsBeforeStates)
        if (group == cvt::rom_log::base || (log & group)) header(group);
      if (log & cvt::rom_log::states)
        for (int k = 0; k < n_states; ++k) w.text(cvt::rom_state_name(features, k));
      if (log & cvt::rom_log::tension) header(cvt::rom_log::tension);
      w.text("fault");
      w.end_row();
      output_time += clock::now() - t0;
    }
    Result r;
    double sum_w1 = 0, sum_w2 = 0, sum_fax = 0;
    auto d = [](const T& v) { return cvt::to_double(v); };
    const long n_frames = cvt::scene_frames(scene);
    // No bar when the CSV itself goes to stdout: on a terminal the two would
    // interleave. The loop polls the interruption flag itself, between rows.
    cvtcli::Progress progress(std::string("run ") + scene.name, csv == stdout ? 0.0 : scene.t_end_s, "s", stderr,
                              cvtcli::Progress::Interrupts::polled_by_caller);
    auto on_frame = [&](long i, double t, const auto& sim) {
      // A signal: this frame is the last one, written and summarised whole.
      const bool stop = cvt::files::interrupted();
      r.interrupted = stop;
      const cvt::RomOutputs<T> o = sim.outputs();
      const auto& e = sim.energy();
      if (i > 0) {
        sum_w1 += d(o.omega1_rad_s);
        sum_w2 += d(o.omega2_rad_s);
        sum_fax += d(o.clamp_force_N);
        r.max_abs_slip = std::max(r.max_abs_slip, std::fabs(d(o.slip)));
      }
      r.frames = i;
      r.t_end_s = t;
      if (csv != nullptr && (i % every == 0 || sim.fault() != cvt::RomFault::none || stop)) {
        const auto t0 = clock::now();
        // The row's numbers gathered first and written in one call
        // (docs/cli.md#csv-numbers); the flags as 0/1.
        double row[kMaxColumns];
        int k = 0;
        row[k++] = t;
        const auto values = [&](std::uint32_t group) {
          for (const auto& s : cvt::kRomSignals)
            if (s.log == group) row[k++] = cvt::rom_signal(o, e, s.id);
        };
        for (std::uint32_t group : kGroupsBeforeStates)
          if (group == cvt::rom_log::base || (log & group)) values(group);
        if (log & cvt::rom_log::states) {
          sim.state_si(row + k);  // displacements in m whatever the scalar's internal units
          k += n_states;
        }
        if (log & cvt::rom_log::tension) values(cvt::rom_log::tension);
        w.nums(row, static_cast<std::size_t>(k));
        w.text(cvt::rom_fault_name(sim.fault()));
        w.end_row();
        output_time += clock::now() - t0;
      }
      if (sim.fault() != cvt::RomFault::none || i == n_frames || stop) {
        r.stored0 = double(e.stored0_J);
        r.stored = double(e.stored_J);
        r.input = double(e.input_J);
        r.actuator = double(e.actuator_J);
        r.load = double(e.load_J);
        r.friction = double(e.friction_loss_J);
        r.damping = double(e.damping_loss_J);
        r.residual = double(e.residual_J());
        r.scale = double(e.scale_J());
        r.final_w1 = d(o.omega1_rad_s);
        r.final_w2 = d(o.omega2_rad_s);
        r.final_fax = d(o.clamp_force_N);
        r.final_slip = d(o.slip);
        r.final_torque = d(o.torque_transmitted_Nm);
        r.final_T_tight = d(o.tension_tight_N);
        r.final_T_slack = d(o.tension_slack_N);
        r.final_T_c = d(o.centrifugal_tension_N);
        r.final_creep = d(o.creep_strain);
        r.final_on_stop = o.sheave_on_stop;
      }
      if ((i & 4095) == 0) progress.update(t);
      // A failed write (closed pipe, full disk) stops the run; the caller reports it.
      return cvtcli::output_ok(csv) && !stop;
    };
    const auto t0 = clock::now();
    r.fault = drive(on_frame);
    if (csv != nullptr) {
      const auto t1 = clock::now();
      w.flush();
      output_time += clock::now() - t1;
    }
    r.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
    r.output_s = std::chrono::duration<double>(output_time).count();
    progress.finish();
    // Means over the frames after t = 0; none when the run stopped at t = 0.
    const double n = r.frames > 0 ? static_cast<double>(r.frames) : std::nan("");
    r.mean_w1 = sum_w1 / n;
    r.mean_w2 = sum_w2 / n;
    r.mean_fax = sum_fax / n;
    return r;
  }
};
// The adaptive solver (docs/numerics.md#adaptive) on the scene's plant: double
// precision, the feature sets without wedging (masks 0..15).
struct AdaptiveOutcome {
  cvt::AdaptiveStatus status = cvt::AdaptiveStatus::ok;
  cvt::Rodas4Work work;
  double t_s = 0;
};

template <std::uint32_t F, class OnFrame>
cvt::RomFault run_adaptive_mask(const cvt::Scene& s, const cvt::AdaptiveConfig& c, OnFrame& on_frame,
                                AdaptiveOutcome& out) {
  cvt::AdaptiveRun<F> run(s.params, c);
  cvt::RomFault fault = cvt::RomFault::none;
  out.status = run.run(s, s.frame_s, [&](long i, double t, const cvt::AdaptiveFrame<F>& frame) {
    fault = frame.fault();
    return on_frame(i, t, frame);
  });
  out.work = run.work();
  out.t_s = run.time_s();
  return fault;
}

template <class OnFrame, std::uint32_t... Fs>
cvt::RomFault run_adaptive(const cvt::Scene& s, const cvt::AdaptiveConfig& c, OnFrame& on_frame, AdaptiveOutcome& out,
                           std::integer_sequence<std::uint32_t, Fs...>) {
  cvt::RomFault fault = cvt::RomFault::none;
  (void)((s.features == Fs ? (fault = run_adaptive_mask<Fs>(s, c, on_frame, out), true) : false) || ...);
  return fault;
}

struct Options {
  std::string scene;
  double t_end_s = -1, dt_s = -1;
  int substeps = -1;
  std::string integrator, scalar, csv, solver = "fixed";
  double rtol = 1e-6, atol = -1;
  int every = 1;
  bool json = false;
  cvtcli::Caps caps;
};

cvtcli::Action register_run(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("run", "Run a scene of the reduced-order CVT plant (docs/rom.md)");
  sub->add_option("--scene", opt->scene, "Built-in scene name (see `cvtplant scenes`) or a TOML scene file")
      ->required();
  cvtcli::add_real(sub, "--t-end", opt->t_end_s, {0, 1e5, true}, "Simulated time [s] (default: the scene's)");
  cvtcli::add_real(sub, "--dt", opt->dt_s, {1e-7, 1}, "Frame step [s] (default: the scene's, 1e-3)");
  cvtcli::add_int(sub, "--substeps", opt->substeps, 1, 10000, "Integrator steps per frame (default: the scene's)");
  sub->add_option("--integrator", opt->integrator,
                  "euler | semi-implicit-euler | heun | rk4 | linear-implicit-euler | ros2 (default: the scene's)");
  sub->add_option("--scalar", opt->scalar, "double | float | fixed (q16.16) (default: the scene's)")
      ->check(CLI::IsMember({"double", "float", "fixed"}));
  sub->add_option("--solver", opt->solver,
                  "fixed: the real-time frame stepper (default) | adaptive: RODAS4 with error control, frames from "
                  "its dense output (double, no wedging; docs/numerics.md#adaptive)")
      ->check(CLI::IsMember({"fixed", "adaptive"}));
  cvtcli::add_real(sub, "--rtol", opt->rtol, {1e-14, 1, true}, "Adaptive solver: relative tolerance (default 1e-6)");
  cvtcli::add_real(sub, "--atol", opt->atol, {1e-14, 1, true},
                   "Adaptive solver: absolute tolerance per unit of each state's floor (1 rad/s, 1 um, 1 mm/s, 1 N, "
                   "1 mrad; default: --rtol)");
  sub->add_option("--csv", opt->csv, "Write the frames as CSV ('-' for stdout)");
  cvtcli::add_int(sub, "--every", opt->every, 1, 1000000000, "Write every N-th frame to the CSV");
  sub->add_flag("--json", opt->json, "Print a JSON summary instead of the text one");
  cvtcli::add_caps(sub, opt->caps, true, false);

  return [opt, sub]() -> int {
    const Options& o = *opt;
    auto loaded = cvtcli::resolve_scene(o.scene);
    cvt::Scene s = loaded->scene;
    if (sub->count("--t-end") > 0) s.t_end_s = o.t_end_s;
    if (sub->count("--dt") > 0) s.frame_s = o.dt_s;
    if (sub->count("--substeps") > 0) s.substeps = o.substeps;
    if (!o.integrator.empty() && !cvt::parse_method(o.integrator.c_str(), s.method))
      throw cvtcli::UsageError{"--integrator: unknown method '" + o.integrator + "'"};
    if (o.scalar == "double") s.scalar = cvt::ScalarKind::f64;
    if (o.scalar == "float") s.scalar = cvt::ScalarKind::f32;
    if (o.scalar == "fixed") s.scalar = cvt::ScalarKind::q16_16;
    cvtcli::check_scene(s, *loaded,
                        {{"t_end_s", "--t-end", o.t_end_s, sub->count("--t-end") > 0},
                         {"frame_s", "--dt", o.dt_s, sub->count("--dt") > 0},
                         {"substeps", "--substeps", static_cast<double>(o.substeps), sub->count("--substeps") > 0}});
    if (o.json && o.csv == "-") throw cvtcli::UsageError{"--json and --csv - both write to stdout; give --csv a file"};
    // The scene file is read, the CSV written: never the one over the other
    // (docs/cli.md#files).
    cvt::files::CommandFiles files;
    if (loaded->source != "built-in") files.input("--scene", loaded->source);
    if (sub->count("--csv") > 0) files.output("--csv", o.csv);
    const bool adaptive = o.solver == "adaptive";
    if (adaptive) {
      // The frame stepper's settings have no meaning for the adaptive solver:
      // refused rather than ignored.
      for (const char* flag : {"--substeps", "--integrator"})
        if (sub->count(flag) > 0) throw cvtcli::UsageError{std::string(flag) + " sets the frame stepper; --solver adaptive chooses its own steps"};
      if (s.scalar != cvt::ScalarKind::f64)
        throw cvtcli::UsageError{"--solver adaptive runs in double only (the scene asks for " +
                                 std::string(cvt::scalar_kind_name(s.scalar)) + ")"};
      if ((s.features & cvt::rom_feature::wedging) != 0u)
        throw cvtcli::UsageError{"--solver adaptive: the wedging plant keeps the frame stepper (its driven actuator "
                                 "and end stops act per frame; docs/numerics.md#adaptive)"};
      if ((s.features & cvt::rom_feature::tension) != 0u)
        throw cvtcli::UsageError{"--solver adaptive: the tension plants run on the frame stepper only (the adaptive "
                                 "solver is compiled for the masks without tension; docs/numerics.md#adaptive)"};
    } else {
      for (const char* flag : {"--rtol", "--atol"})
        if (sub->count(flag) > 0) throw cvtcli::UsageError{std::string(flag) + " needs --solver adaptive"};
    }
    const double frames = static_cast<double>(cvt::scene_frames(s));
    if (!adaptive)
      cvtcli::require_steps(frames * s.substeps, o.caps,
                            cvtcli::fmt_count(frames) + " frames x " + std::to_string(s.substeps) + " substeps");
    // q16.16 steps in units of 2^-10 s (docs/rom.md#fixed-point); 32 LSB of
    // that unit keep the rounding of the substep under 2 %.
    if (s.scalar == cvt::ScalarKind::q16_16 && s.frame_s / s.substeps / cvt::RomUnits<cvt::q16_16>::time_s < 32.0 / 65536.0)
      throw cvtcli::UsageError{"--dt: q16.16 cannot represent substeps below 4.8e-7 s to 2 %"};

    std::FILE* csv = sub->count("--csv") == 0 ? nullptr : cvtcli::open_output(o.csv, "--csv");
    cvt::AdaptiveConfig acfg;
    acfg.rtol = o.rtol;
    acfg.atol = o.atol > 0 ? o.atol : o.rtol;
    acfg.energy = s.energy_ledger;
    acfg.max_steps = static_cast<long>(std::min(o.caps.max_steps, 9e18));
    AdaptiveOutcome ad;
    Runner runner{s, csv, o.every};
    const Result r =
        adaptive ? runner.frames<double>(s.features, cvt::rom_state_index(s.features).count,
                                         [&](auto& on_frame) {
                                           return run_adaptive(s, acfg, on_frame, ad,
                                                               std::make_integer_sequence<std::uint32_t, 16>{});
                                         })
                 : cvtcli::with_scene_simulator(s, s.scalar, cvt::sim_config_of(s), runner);
    cvtcli::close_output(csv);
    // An adaptive run stopped between frames has no final frame to summarise:
    // the CSV keeps the frames written, the error says where it stopped.
    if (adaptive && ad.status == cvt::AdaptiveStatus::step_cap)
      throw cvtcli::RunError{"the adaptive solver reached the cap of " + cvtcli::fmt_count(o.caps.max_steps) +
                             " steps at t = " + std::to_string(ad.t_s) + " s; raise it with --max-steps"};
    if (adaptive && ad.status == cvt::AdaptiveStatus::step_too_small)
      throw cvtcli::RunError{"the adaptive solver's step fell below 1e-14 of the time at t = " +
                             std::to_string(ad.t_s) + " s: the tolerances cannot be met in double"};
    // With the CSV on stdout the text summary goes to stderr: stdout holds data only.
    std::FILE* info = csv == stdout ? stderr : stdout;

    // The plant's cost and the output's, apart: the CSV's formatting would
    // otherwise be read as the plant's (docs/cli.md#run).
    const double per_frame = 1e9 / static_cast<double>(std::max<long>(1, r.frames));
    const double ns_frame = r.wall_s * per_frame;
    const double output_ns = r.output_s * per_frame;
    const double plant_ns = ns_frame - output_ns;
    // Relative to the energy that flowed; none flowed: not computed.
    const double rel = r.scale > 0 ? r.residual / r.scale : std::nan("");
    const char* status = r.interrupted ? "interrupted" : r.fault != cvt::RomFault::none ? "failed" : "ok";
    char at[64];
    std::snprintf(at, sizeof at, "t = %.6g s", r.t_end_s);
    if (o.json) {
      nlohmann::json j;
      j["subcommand"] = "run";
      j["status"] = status;
      j["scene"] = loaded->name;
      j["source"] = loaded->source;
      j["features"] = cvtcli::feature_names(s.features);
      j["scalar"] = cvt::scalar_kind_name(s.scalar);
      j["solver"] = o.solver;
      if (adaptive) {
        j["integrator"] = "rodas4";
        j["rtol"] = acfg.rtol;
        j["atol"] = acfg.atol;
        j["work"] = {{"steps", ad.work.accepted},      {"rejected", ad.work.rejected},
                     {"rhs", ad.work.rhs},             {"jacobians", ad.work.jacobians},
                     {"factorizations", ad.work.factorizations}, {"solves", ad.work.solves}};
      } else {
        j["integrator"] = cvt::method_name(s.method);
      }
      j["frame_s"] = s.frame_s;
      if (!adaptive) j["substeps"] = s.substeps;
      j["frames"] = r.frames;
      j["t_end_s"] = r.t_end_s;
      j["fault"] = cvt::rom_fault_name(r.fault);
      j["energy_ledger"] = s.energy_ledger;
      if (s.energy_ledger) j["energy"] = {{"stored_initial_J", r.stored0},  {"stored_final_J", r.stored}, {"input_J", r.input},
                     {"actuator_J", r.actuator},       {"load_J", r.load},           {"friction_loss_J", r.friction},
                     {"damping_loss_J", r.damping},    {"residual_J", r.residual},   {"flow_scale_J", r.scale},
                     {"residual_rel", cvtcli::json_number(rel)}};
      j["mean"] = {{"omega1_rad_s", cvtcli::json_number(r.mean_w1)},
                   {"omega2_rad_s", cvtcli::json_number(r.mean_w2)},
                   {"F_ax_N", cvtcli::json_number(r.mean_fax)}};
      j["max_abs_slip"] = r.max_abs_slip;
      j["final"] = {{"omega1_rad_s", r.final_w1},
                    {"omega2_rad_s", r.final_w2},
                    {"F_ax_N", r.final_fax},
                    {"slip", r.final_slip},
                    {"torque_transmitted_Nm", r.final_torque}};
      if ((s.features & cvt::rom_feature::tension) != 0u)
        j["final"]["tension"] = {{"T_tight_N", r.final_T_tight},
                                 {"T_slack_N", r.final_T_slack},
                                 {"T_centrifugal_N", r.final_T_c},
                                 {"creep_strain", r.final_creep},
                                 {"sheave_on_stop", r.final_on_stop}};
      j["wall_s"] = r.wall_s;
      j["output_wall_s"] = r.output_s;
      j["ns_per_frame"] = ns_frame;
      j["plant_ns_per_frame"] = plant_ns;
      j["output_ns_per_frame"] = output_ns;
      j["ns_per_step"] = adaptive ? 1e9 * (r.wall_s - r.output_s) /
                                        static_cast<double>(std::max<long>(1, ad.work.accepted + ad.work.rejected))
                                  : plant_ns / s.substeps;
      cvtcli::print_json(j);
    } else {
      if (adaptive)
        std::fprintf(info, "Scene %s (%s): features %s, double, adaptive rodas4 (rtol %g, atol %g), frames of %g s\n",
                     loaded->name.c_str(), loaded->source.c_str(), cvtcli::feature_names(s.features).c_str(), acfg.rtol,
                     acfg.atol, s.frame_s);
      else
        std::fprintf(info, "Scene %s (%s): features %s, %s, %s, dt = %g s x %d substeps\n", loaded->name.c_str(),
                     loaded->source.c_str(), cvtcli::feature_names(s.features).c_str(),
                     cvt::scalar_kind_name(s.scalar), cvt::method_name(s.method), s.frame_s, s.substeps);
      std::fprintf(info, "  %ld frames to t = %g s, fault: %s%s\n", r.frames, r.t_end_s, cvt::rom_fault_name(r.fault),
                   r.interrupted ? " (interrupted)" : "");
      std::fprintf(info, "  final: omega1 = %.4f rad/s, omega2 = %.4f rad/s, F_ax = %.1f N, slip = %.5f\n", r.final_w1,
                  r.final_w2, r.final_fax, r.final_slip);
      if (s.energy_ledger) std::fprintf(info, "  energy: in %.4g J, actuator %.4g J, load %.4g J, friction %.4g J, damping %.4g J, "
                  "stored %.4g -> %.4g J, residual %.3g J (%s of the flows)\n",
                  r.input, r.actuator, r.load, r.friction, r.damping, r.stored0, r.stored, r.residual,
                  cvtcli::text_number(rel, "%.2e").c_str());
      if (adaptive)
        std::fprintf(info, "  %ld steps (%ld rejected), %ld right-hand sides, %ld Jacobians, %ld factorisations\n",
                     ad.work.accepted, ad.work.rejected, ad.work.rhs, ad.work.jacobians, ad.work.factorizations);
      if (csv != nullptr)
        std::fprintf(info, "  plant %.0f ns/frame, CSV output %.0f ns/frame (%.3f s wall)\n", plant_ns, output_ns,
                     r.wall_s);
      else
        std::fprintf(info, "  plant %.0f ns/frame (%.3f s wall)\n", plant_ns, r.wall_s);
    }
    if (r.interrupted) throw cvtcli::Interrupted{at, true};
    if (r.fault != cvt::RomFault::none) {
      char buf[96];
      std::snprintf(buf, sizeof buf, " at t = %g s (frame %ld)", r.t_end_s, r.frames);
      throw cvtcli::RunError{std::string("the plant faulted: ") + cvt::rom_fault_name(r.fault) + buf};
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_run);

}  // namespace
