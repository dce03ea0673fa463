// `cvtplant run`: a scene of the reduced-order CVT plant, frame by frame,
// in double, float or q16.16 (docs/cli.md#run, docs/rom.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "registry.hpp"
#include "cmd_run_runner.hpp"
#include "scene_file.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

using cvtcli::run_cmd::Result;
using cvtcli::run_cmd::Runner;

struct Options {
  std::string scene;
  double t_end_s = -1, dt_s = -1;
  int substeps = -1;
  std::string integrator, scalar, csv;
  int every = 1;
  bool json = false;
};

cvtcli::Action register_run(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("run", "Run a scene of the reduced-order CVT plant (docs/rom.md)");
  sub->add_option("--scene", opt->scene, "Built-in scene name (see `cvtplant scenes`) or a TOML scene file")
      ->required();
  sub->add_option("--t-end", opt->t_end_s, "Simulated time [s] (default: the scene's)");
  sub->add_option("--dt", opt->dt_s, "Frame step [s] (default: the scene's, 1e-3)");
  sub->add_option("--substeps", opt->substeps, "Integrator steps per frame (default: the scene's)");
  sub->add_option("--integrator", opt->integrator,
                  "euler | semi-implicit-euler | heun | rk4 | linear-implicit-euler | ros2 (default: the scene's)");
  sub->add_option("--scalar", opt->scalar, "double | float | fixed (q16.16) (default: the scene's)")
      ->check(CLI::IsMember({"double", "float", "fixed"}));
  sub->add_option("--csv", opt->csv, "Write the frames as CSV ('-' for stdout)");
  sub->add_option("--every", opt->every, "Write every N-th frame to the CSV")->check(CLI::PositiveNumber);
  sub->add_flag("--json", opt->json, "Print a JSON summary instead of the text one");

  return [opt, sub]() -> int {
    const Options& o = *opt;
    auto loaded = cvtcli::resolve_scene(o.scene);
    cvt::Scene s = loaded->scene;
    if (sub->count("--t-end") > 0) {
      if (!(o.t_end_s > 0) || !std::isfinite(o.t_end_s)) throw cvtcli::UsageError{"--t-end: must be > 0"};
      s.t_end_s = o.t_end_s;
    }
    if (sub->count("--dt") > 0) {
      if (!(o.dt_s > 0) || !std::isfinite(o.dt_s)) throw cvtcli::UsageError{"--dt: must be > 0"};
      s.frame_s = o.dt_s;
    }
    if (sub->count("--substeps") > 0) s.substeps = o.substeps;
    if (!o.integrator.empty() && !cvt::parse_method(o.integrator.c_str(), s.method))
      throw cvtcli::UsageError{"--integrator: unknown method '" + o.integrator + "'"};
    if (o.scalar == "double") s.scalar = cvt::ScalarKind::f64;
    if (o.scalar == "float") s.scalar = cvt::ScalarKind::f32;
    if (o.scalar == "fixed") s.scalar = cvt::ScalarKind::q16_16;
    const cvt::SceneIssue issue = cvt::validate_scene(s);
    if (!issue.ok) throw cvtcli::UsageError{std::string(issue.field) + ": " + issue.message};
    if (s.t_end_s / s.frame_s > 1e9) throw cvtcli::UsageError{"--t-end/--dt: more than 1e9 frames"};
    // q16.16 steps in units of 2^-10 s (docs/rom.md#fixed-point); 32 LSB of
    // that unit keep the rounding of the substep under 2 %.
    if (s.scalar == cvt::ScalarKind::q16_16 && s.frame_s / s.substeps / cvt::RomUnits<cvt::q16_16>::time_s < 32.0 / 65536.0)
      throw cvtcli::UsageError{"--dt: q16.16 cannot represent substeps below 4.8e-7 s to 2 %"};

    std::FILE* csv = o.csv.empty() ? nullptr : cvtcli::open_output(o.csv);
    Runner runner{s, csv, o.every};
    namespace rc = cvtcli::run_cmd;
    const Result r = cvtcli::by_scalar(s.scalar, runner, &rc::run_double, &rc::run_float, &rc::run_fixed);
    cvtcli::close_output(csv);

    const double frames = static_cast<double>(std::max<long>(1, r.frames));
    const double ns_frame = 1e9 * r.wall_s / frames;
    const double rel = r.scale > 0 ? r.residual / r.scale : 0.0;
    if (o.json) {
      nlohmann::json j;
      j["subcommand"] = "run";
      j["scene"] = loaded->name;
      j["source"] = loaded->source;
      j["features"] = cvtcli::feature_names(s.features);
      j["scalar"] = cvt::scalar_kind_name(s.scalar);
      j["integrator"] = cvt::method_name(s.method);
      j["dt_s"] = s.frame_s;
      j["substeps"] = s.substeps;
      j["frames"] = r.frames;
      j["t_end_s"] = r.t_end_s;
      j["fault"] = cvt::rom_fault_name(r.fault);
      j["energy"] = {{"stored_initial_J", r.stored0},  {"stored_final_J", r.stored}, {"input_J", r.input},
                     {"actuator_J", r.actuator},       {"load_J", r.load},           {"friction_loss_J", r.friction},
                     {"damping_loss_J", r.damping},    {"residual_J", r.residual},   {"flow_scale_J", r.scale},
                     {"residual_relative", rel}};
      j["mean"] = {{"omega1_rad_s", r.mean_w1}, {"omega2_rad_s", r.mean_w2}, {"F_ax_N", r.mean_fax}};
      j["max_abs_slip"] = r.max_abs_slip;
      j["final"] = {{"omega1_rad_s", r.final_w1},
                    {"omega2_rad_s", r.final_w2},
                    {"F_ax_N", r.final_fax},
                    {"slip", r.final_slip},
                    {"torque_transmitted_Nm", r.final_torque}};
      j["run_time_s"] = r.wall_s;
      j["ns_per_frame"] = ns_frame;
      j["ns_per_step"] = ns_frame / s.substeps;
      cvtcli::print_json(j);
    } else {
      std::printf("Scene %s (%s): features %s, %s, %s, dt = %g s x %d substeps\n", loaded->name.c_str(),
                  loaded->source.c_str(), cvtcli::feature_names(s.features).c_str(), cvt::scalar_kind_name(s.scalar),
                  cvt::method_name(s.method), s.frame_s, s.substeps);
      std::printf("  %ld frames to t = %g s, fault: %s\n", r.frames, r.t_end_s, cvt::rom_fault_name(r.fault));
      std::printf("  final: omega1 = %.4f rad/s, omega2 = %.4f rad/s, F_ax = %.1f N, slip = %.5f\n", r.final_w1,
                  r.final_w2, r.final_fax, r.final_slip);
      std::printf("  energy: in %.4g J, actuator %.4g J, load %.4g J, friction %.4g J, damping %.4g J, "
                  "stored %.4g -> %.4g J, residual %.3g J (%.2e of the flows)\n",
                  r.input, r.actuator, r.load, r.friction, r.damping, r.stored0, r.stored, r.residual, rel);
      std::printf("  %.0f ns/frame (%.3f s wall)\n", ns_frame, r.wall_s);
    }
    return r.fault == cvt::RomFault::none ? 0 : 1;
  };
}

const bool registered = cvtcli::add_registrar(&register_run);

}  // namespace
