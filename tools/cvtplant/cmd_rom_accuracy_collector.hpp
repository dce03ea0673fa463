#pragma once
// The trace collector of `cvtplant rom-accuracy` for one plant type
// (docs/rom.md#real-time-integrator), shared by cmd_rom_accuracy.cpp and the
// per-scalar translation units cmd_rom_accuracy_{double,float,fixed}.cpp:
// each instantiates the feature masks of one scalar, so the build
// compiles the three in parallel.
#include <chrono>
#include <cstdint>
#include <vector>

#include "rom_dispatch.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvtcli::rom_accuracy_cmd {

struct Trace {
  std::vector<double> w1, w2, fax, xd1;
  cvt::RomFault fault = cvt::RomFault::none;
  long frames = 0;
  double wall_s = 0;
  double residual_rel = 0;
};

struct Collector {
  const cvt::Scene& scene;
  cvt::RomSimConfig cfg;

  template <class T, std::uint32_t F>
  Trace call() {
    Trace tr;
    const long n = static_cast<long>(scene.t_end_s / cfg.frame_s + 0.5);
    tr.w1.reserve(n + 1);
    tr.w2.reserve(n + 1);
    tr.fax.reserve(n + 1);
    tr.xd1.reserve(n + 1);
    auto on_frame = [&](long i, double, const cvt::RomSimulator<T, F>& sim) {
      if (sim.fault() != cvt::RomFault::none) return false;
      const auto o = sim.outputs();
      tr.w1.push_back(cvt::to_double(o.omega1_rad_s));
      tr.w2.push_back(cvt::to_double(o.omega2_rad_s));
      tr.fax.push_back(cvt::to_double(o.clamp_force_N));
      tr.xd1.push_back(cvt::to_double(sim.state()(cvt::RomLayout<F>::kV1)));
      tr.frames = i;
      const auto& e = sim.energy();
      tr.residual_rel = e.scale_J() > 0 ? double(e.residual_J() / e.scale_J()) : 0.0;
      return true;
    };
    const auto t0 = std::chrono::steady_clock::now();
    tr.fault = cvt::run_scene<T, F>(scene, cfg, on_frame);
    tr.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return tr;
  }
};

Trace collect_double(Collector& c);
Trace collect_float(Collector& c);
Trace collect_fixed(Collector& c);

}  // namespace cvtcli::rom_accuracy_cmd
