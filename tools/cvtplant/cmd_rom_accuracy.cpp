// `cvtplant rom-accuracy`: error of fixed-frame integrator settings against a
// converged reference of the same equations, and their host cost
// (docs/rom.md#real-time-integrator). This is the measurement behind the
// real-time default; it regenerates the table in docs/rom.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "scene_simulator.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

struct Trace {
  std::vector<double> w1, w2, fax, xd1;
  cvt::RomFault fault = cvt::RomFault::none;
  long frames = 0;
  double wall_s = 0;
  double residual_rel = std::nan("");
};

// Samples the speeds, the axial force and the first lump's velocity every
// frame, on the scene's plant in any scalar type.
struct Collector {
  const cvt::Scene& scene;
  cvt::RomSimConfig cfg;
  // The command's bar, in substeps: this run's start and its substeps per frame.
  cvtcli::Progress* progress = nullptr;
  double progress_base = 0;

  template <class T>
  Trace operator()(cvt::IRomSimulator<T>& sim_run) {
    Trace tr;
    const long n = static_cast<long>(scene.t_end_s / cfg.frame_s + 0.5);
    tr.w1.reserve(n + 1);
    tr.w2.reserve(n + 1);
    tr.fax.reserve(n + 1);
    tr.xd1.reserve(n + 1);
    const int kV1 = cvt::rom_state_index(sim_run.features()).xd1;
    auto on_frame = [&](long i, double, const cvt::IRomSimulator<T>& sim) {
      if (sim.fault() != cvt::RomFault::none) return false;
      if (progress != nullptr && (i & 255) == 0)
        progress->update(progress_base + static_cast<double>(i) * cfg.substeps);
      const auto o = sim.outputs();
      tr.w1.push_back(cvt::to_double(o.omega1_rad_s));
      tr.w2.push_back(cvt::to_double(o.omega2_rad_s));
      tr.fax.push_back(cvt::to_double(o.clamp_force_N));
      T x[cvt::kRomMaxStates];
      sim.state(x);
      tr.xd1.push_back(cvt::to_double(x[kV1]));
      tr.frames = i;
      const auto& e = sim.energy();
      // Relative to the energy that flowed: none flowed, not computed (docs/cli.md#nulls).
      tr.residual_rel = e.scale_J() > 0 ? double(e.residual_J() / e.scale_J()) : std::nan("");
      return true;
    };
    const auto t0 = std::chrono::steady_clock::now();
    tr.fault = cvt::run_frames(sim_run, scene, cfg.frame_s, on_frame);
    tr.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return tr;
  }
};

// The trace of `s` in scalar k with the settings c; a plant the scalar type
// does not have is refused (exit 2), never run with fewer features.
Trace collect(const cvt::Scene& s, cvt::ScalarKind k, const cvt::RomSimConfig& c, cvtcli::Progress* progress,
              double& progress_base) {
  const double base = progress_base;
  progress_base += static_cast<double>(cvt::scene_frames(s)) * c.substeps;
  return cvtcli::with_scene_simulator(s, k, c, Collector{s, c, progress, base},
                                      std::string("--scalar ") + cvt::scalar_kind_name(k) + ": ");
}

// RMS(a - ref) / RMS(ref) over the common frames; NaN (not computed: null,
// n/a) if the candidate stopped early or the reference is 0 throughout while
// the candidate is not.
double rel_rms(const std::vector<double>& a, const std::vector<double>& ref) {
  if (a.size() != ref.size()) return std::nan("");
  double se = 0, sr = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    se += (a[i] - ref[i]) * (a[i] - ref[i]);
    sr += ref[i] * ref[i];
  }
  if (sr == 0) return se == 0 ? 0.0 : std::nan("");
  return std::sqrt(se / sr);
}

cvtcli::Action register_rom_accuracy(CLI::App& app) {
  struct Opt {
    std::string scene, scalar = "double", candidates = "ros2:1,ros2:2,ros2:4,ros2:10,linear-implicit-euler:1,linear-implicit-euler:10,rk4:1,rk4:10";
    double t_end_s = 10, frame_s = 1e-3;
    int ref_substeps = 1000;
    bool json = false;
    cvtcli::Caps caps;
  };
  auto opt = std::make_shared<Opt>();
  CLI::App* sub = app.add_subcommand(
      "rom-accuracy", "Relative RMS error of integrator settings vs a converged reference (docs/rom.md)");
  sub->add_option("--scene", opt->scene, "Built-in scene or scene file")->required();
  cvtcli::add_real(sub, "--t-end", opt->t_end_s, {0, 1e5, true}, "Simulated time [s]");
  cvtcli::add_real(sub, "--dt", opt->frame_s, {1e-7, 1}, "Frame step [s], at most --t-end");
  sub->add_option("--scalar", opt->scalar, "Scalar of the candidates: double | float | fixed")
      ->check(CLI::IsMember({"double", "float", "fixed"}));
  cvtcli::add_int(sub, "--ref-substeps", opt->ref_substeps, 1, 100000,
                  "Reference: ros2 in double with this many substeps per frame");
  sub->add_option("--candidates", opt->candidates, "Comma-separated METHOD:SUBSTEPS list (substeps 1..100000)");
  sub->add_flag("--json", opt->json, "JSON output");
  cvtcli::add_caps(sub, opt->caps, true, true);
  return [opt]() -> int {
    auto loaded = cvtcli::resolve_scene(opt->scene);
    cvt::Scene s = loaded->scene;
    s.t_end_s = opt->t_end_s;
    // A frame longer than the run would compare nothing.
    if (opt->frame_s > opt->t_end_s) throw cvtcli::UsageError{"--dt: must be <= --t-end"};
    s.frame_s = opt->frame_s;
    const cvt::ScalarKind sk = opt->scalar == "double" ? cvt::ScalarKind::f64
                               : opt->scalar == "float" ? cvt::ScalarKind::f32
                                                        : cvt::ScalarKind::q16_16;
    struct Cand {
      cvt::Method m;
      int substeps;
    };
    std::vector<Cand> cands;
    std::stringstream ss(opt->candidates);
    std::string item;
    while (std::getline(ss, item, ',')) {
      const auto colon = item.find(':');
      cvt::Method m{};
      const std::string mn = item.substr(0, colon);
      if (!cvt::parse_method(mn.c_str(), m))
        throw cvtcli::UsageError{"--candidates: unknown method " + cvtcli::quoted(mn)};
      long long n = 1;
      if (colon != std::string::npos) {
        const std::string why = cvtcli::check_int(item.substr(colon + 1), 1, 100000, &n);
        if (!why.empty()) throw cvtcli::UsageError{"--candidates: substeps " + why};
      }
      cands.push_back({m, static_cast<int>(n)});
    }
    if (cands.empty()) throw cvtcli::UsageError{"--candidates: empty list"};
    // Work and memory, estimated before anything runs: the reference and every
    // candidate step every frame; the reference's trace and one candidate's
    // (4 signals of 8 bytes per frame each) are held at once.
    const double frames = static_cast<double>(cvt::scene_frames(s));
    double substeps = opt->ref_substeps;
    for (const Cand& c : cands) substeps += c.substeps;
    cvtcli::require_steps(frames * substeps, opt->caps,
                          cvtcli::fmt_count(frames) + " frames x " + cvtcli::fmt_count(substeps) +
                              " substeps of the reference and the candidates");
    cvtcli::require_memory(2 * 4 * 8 * (frames + 1), opt->caps,
                           "two traces of 4 signals x " + cvtcli::fmt_count(frames) + " frames");
    cvtcli::check_scene_simulator(s, cvt::ScalarKind::f64);
    cvtcli::check_scene_simulator(s, sk, std::string("--scalar ") + opt->scalar + ": ");
    cvt::RomSimConfig rc = cvt::sim_config_of(s);
    rc.method = cvt::Method::ros2;
    rc.substeps = opt->ref_substeps;
    rc.watchdog_energy = false;
    cvtcli::Progress progress("rom-accuracy " + std::string(s.name), frames * substeps, "");
    double done_substeps = 0;
    const Trace ref = collect(s, cvt::ScalarKind::f64, rc, &progress, done_substeps);
    if (ref.fault != cvt::RomFault::none)
      throw cvtcli::RunError{std::string("the reference run faulted: ") + cvt::rom_fault_name(ref.fault)};

    nlohmann::json rows = nlohmann::json::array();
    if (!opt->json)
      std::printf("%-24s %5s %-8s %11s %11s %11s %11s %11s %10s %s\n", "method", "sub", "scalar", "err_omega1",
                  "err_omega2", "err_F_ax", "err_xd1", "E_resid_rel", "ns/frame", "fault");
    for (const Cand& c : cands) {
      cvt::RomSimConfig cc = cvt::sim_config_of(s);
      cc.method = c.m;
      cc.substeps = c.substeps;
      const Trace tr = collect(s, sk, cc, &progress, done_substeps);
      const double e1 = rel_rms(tr.w1, ref.w1), e2 = rel_rms(tr.w2, ref.w2), ef = rel_rms(tr.fax, ref.fax),
                   ex = rel_rms(tr.xd1, ref.xd1);
      const double ns = 1e9 * tr.wall_s / std::max<long>(1, tr.frames);
      auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
      rows.push_back({{"integrator", cvt::method_name(c.m)},
                      {"substeps", c.substeps},
                      {"scalar", opt->scalar},
                      {"err_omega1_rel", num(e1)},
                      {"err_omega2_rel", num(e2)},
                      {"err_F_ax_rel", num(ef)},
                      {"err_xd1_rel", num(ex)},
                      {"energy_residual_rel", num(tr.residual_rel)},
                      {"ns_per_frame", ns},
                      {"fault", cvt::rom_fault_name(tr.fault)}});
      progress.finish();  // the row goes where the bar was; the next update redraws it below
      if (!opt->json) {
        const auto e = [](double v) { return cvtcli::text_number(v, "%.3e"); };
        std::printf("%-24s %5d %-8s %11s %11s %11s %11s %11s %10.0f %s\n", cvt::method_name(c.m), c.substeps,
                    opt->scalar.c_str(), e(e1).c_str(), e(e2).c_str(), e(ef).c_str(), e(ex).c_str(),
                    e(tr.residual_rel).c_str(), ns, cvt::rom_fault_name(tr.fault));
      }
    }
    if (opt->json) {
      nlohmann::json j;
      j["subcommand"] = "rom-accuracy";
      j["scene"] = loaded->name;
      j["t_end_s"] = s.t_end_s;
      j["frame_s"] = s.frame_s;
      j["reference"] = {{"integrator", "ros2"}, {"substeps", opt->ref_substeps}, {"scalar", "double"}};
      j["rows"] = rows;
      cvtcli::print_json(j);
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_rom_accuracy);

}  // namespace
