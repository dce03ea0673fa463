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
#include "registry.hpp"
#include "cmd_rom_accuracy_collector.hpp"
#include "scene_file.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

using cvtcli::rom_accuracy_cmd::Collector;
using cvtcli::rom_accuracy_cmd::Trace;

Trace collect(cvt::ScalarKind k, Collector& c) {
  namespace ra = cvtcli::rom_accuracy_cmd;
  return cvtcli::by_scalar(k, c, &ra::collect_double, &ra::collect_float, &ra::collect_fixed);
}

// RMS(a - ref) / RMS(ref) over the common frames; inf if the candidate stopped early.
double rel_rms(const std::vector<double>& a, const std::vector<double>& ref) {
  if (a.size() != ref.size()) return INFINITY;
  double se = 0, sr = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    se += (a[i] - ref[i]) * (a[i] - ref[i]);
    sr += ref[i] * ref[i];
  }
  if (sr == 0) return se == 0 ? 0.0 : INFINITY;
  return std::sqrt(se / sr);
}

cvtcli::Action register_rom_accuracy(CLI::App& app) {
  struct Opt {
    std::string scene, scalar = "double", candidates = "ros2:1,ros2:2,ros2:4,ros2:10,linear-implicit-euler:1,linear-implicit-euler:10,rk4:1,rk4:10";
    double t_end_s = 10, frame_s = 1e-3;
    int ref_substeps = 1000;
    bool json = false;
  };
  auto opt = std::make_shared<Opt>();
  CLI::App* sub = app.add_subcommand(
      "rom-accuracy", "Relative RMS error of integrator settings vs a converged reference (docs/rom.md)");
  sub->add_option("--scene", opt->scene, "Built-in scene or scene file")->required();
  sub->add_option("--t-end", opt->t_end_s, "Simulated time [s]");
  sub->add_option("--dt", opt->frame_s, "Frame step [s]");
  sub->add_option("--scalar", opt->scalar, "Scalar of the candidates: double | float | fixed")
      ->check(CLI::IsMember({"double", "float", "fixed"}));
  sub->add_option("--ref-substeps", opt->ref_substeps, "Reference: ros2 in double with this many substeps per frame")
      ->check(CLI::PositiveNumber);
  sub->add_option("--candidates", opt->candidates, "Comma-separated METHOD:SUBSTEPS list");
  sub->add_flag("--json", opt->json, "JSON output");
  return [opt]() -> int {
    auto loaded = cvtcli::resolve_scene(opt->scene);
    cvt::Scene s = loaded->scene;
    s.t_end_s = opt->t_end_s;
    if (!(opt->frame_s > 0) || !(opt->t_end_s > 0)) throw cvtcli::UsageError{"--dt/--t-end: must be > 0"};
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
      if (!cvt::parse_method(mn.c_str(), m)) throw cvtcli::UsageError{"--candidates: unknown method '" + mn + "'"};
      int n = 1;
      if (colon != std::string::npos) n = static_cast<int>(cvtcli::parse_finite(item.substr(colon + 1), "--candidates"));
      if (n < 1 || n > 100000) throw cvtcli::UsageError{"--candidates: substeps must be in 1..100000"};
      cands.push_back({m, n});
    }
    cvt::RomSimConfig rc = cvt::sim_config_of(s);
    rc.method = cvt::Method::ros2;
    rc.substeps = opt->ref_substeps;
    rc.watchdog_energy = false;
    Collector refc{s, rc};
    const Trace ref = collect(cvt::ScalarKind::f64, refc);
    if (ref.fault != cvt::RomFault::none) throw cvtcli::RunError{"the reference run faulted"};

    nlohmann::json rows = nlohmann::json::array();
    if (!opt->json)
      std::printf("%-24s %5s %-8s %11s %11s %11s %11s %11s %10s %s\n", "method", "sub", "scalar", "err_omega1",
                  "err_omega2", "err_F_ax", "err_xd1", "E_resid_rel", "ns/frame", "fault");
    for (const Cand& c : cands) {
      cvt::RomSimConfig cc = cvt::sim_config_of(s);
      cc.method = c.m;
      cc.substeps = c.substeps;
      Collector col{s, cc};
      const Trace tr = collect(sk, col);
      const double e1 = rel_rms(tr.w1, ref.w1), e2 = rel_rms(tr.w2, ref.w2), ef = rel_rms(tr.fax, ref.fax),
                   ex = rel_rms(tr.xd1, ref.xd1);
      const double ns = 1e9 * tr.wall_s / std::max<long>(1, tr.frames);
      auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
      rows.push_back({{"method", cvt::method_name(c.m)},
                      {"substeps", c.substeps},
                      {"scalar", opt->scalar},
                      {"err_omega1", num(e1)},
                      {"err_omega2", num(e2)},
                      {"err_F_ax", num(ef)},
                      {"err_xd1", num(ex)},
                      {"energy_residual_relative", tr.residual_rel},
                      {"ns_per_frame", ns},
                      {"fault", cvt::rom_fault_name(tr.fault)}});
      if (!opt->json)
        std::printf("%-24s %5d %-8s %11.3e %11.3e %11.3e %11.3e %11.3e %10.0f %s\n", cvt::method_name(c.m), c.substeps,
                    opt->scalar.c_str(), e1, e2, ef, ex, tr.residual_rel, ns, cvt::rom_fault_name(tr.fault));
    }
    if (opt->json) {
      nlohmann::json j;
      j["scene"] = loaded->name;
      j["t_end_s"] = s.t_end_s;
      j["frame_s"] = s.frame_s;
      j["reference"] = {{"method", "ros2"}, {"substeps", opt->ref_substeps}, {"scalar", "double"}};
      j["rows"] = rows;
      cvtcli::print_json(j);
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_rom_accuracy);

}  // namespace
