#pragma once
// The frame loop of `cvtplant run` for one plant type (docs/cli.md#run),
// shared by cmd_run.cpp and the per-scalar translation units
// cmd_run_{double,float,fixed}.cpp: each of those instantiates the
// feature masks of one scalar, so the build compiles the three in parallel.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>

#include "rom_dispatch.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvtcli::run_cmd {

struct Result {
  cvt::RomFault fault = cvt::RomFault::none;
  long frames = 0;
  double t_end_s = 0;
  double wall_s = 0;
  double stored0 = 0, stored = 0, input = 0, actuator = 0, load = 0, friction = 0, damping = 0, residual = 0,
         scale = 0;
  double mean_w1 = 0, mean_w2 = 0, mean_fax = 0, max_abs_slip = 0;
  double final_w1 = 0, final_w2 = 0, final_fax = 0, final_slip = 0, final_torque = 0;
};

inline const char* kStateNames[] = {"omega1", "omega2", "x1", "xd1", "x2", "xd2"};

struct Runner {
  const cvt::Scene& scene;
  std::FILE* csv;
  int every;

  template <class T, std::uint32_t F>
  Result call() {
    using Sim = cvt::RomSimulator<T, F>;
    using L = cvt::RomLayout<F>;
    const std::uint32_t log = scene.log;
    if (csv != nullptr) {
      std::fprintf(csv, "t,omega1,omega2,F_ax,slip");
      if (log & cvt::rom_log::torques) std::fprintf(csv, ",tau_in,tau_load,torque_transmitted");
      if (log & cvt::rom_log::friction) std::fprintf(csv, ",F1,F2,v_rel1,v_rel2,stick1,stick2");
      if (log & cvt::rom_log::ratios) std::fprintf(csv, ",speed_ratio,geometric_ratio,r1,r2");
      if (log & cvt::rom_log::energy)
        std::fprintf(csv, ",E_stored,W_in,W_actuator,W_load,W_friction,W_damping,E_residual");
      if (log & cvt::rom_log::states) {
        for (const char* n : kStateNames) std::fprintf(csv, ",%s", n);
        if (L::kAxial) std::fprintf(csv, ",F_h,delta,delta_dot");
        if (L::kWedge) std::fprintf(csv, ",rho,rho_dot");
        if (L::kPolygon) std::fprintf(csv, ",psi");
      }
      std::fprintf(csv, ",fault\n");
    }
    Result r;
    double sum_w1 = 0, sum_w2 = 0, sum_fax = 0;
    auto d = [](const T& v) { return cvt::to_double(v); };
    auto on_frame = [&](long i, double t, const Sim& sim) {
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
      if (csv != nullptr && (i % every == 0 || sim.fault() != cvt::RomFault::none)) {
        std::fprintf(csv, "%.9g,%.10g,%.10g,%.10g,%.10g", t, d(o.omega1_rad_s), d(o.omega2_rad_s), d(o.clamp_force_N),
                     d(o.slip));
        if (log & cvt::rom_log::torques)
          std::fprintf(csv, ",%.10g,%.10g,%.10g", d(o.tau_in_Nm), d(o.tau_load_Nm), d(o.torque_transmitted_Nm));
        if (log & cvt::rom_log::friction)
          std::fprintf(csv, ",%.10g,%.10g,%.10g,%.10g,%d,%d", d(o.friction1_N), d(o.friction2_N), d(o.v_rel1_m_s),
                       d(o.v_rel2_m_s), o.stick1 ? 1 : 0, o.stick2 ? 1 : 0);
        if (log & cvt::rom_log::ratios)
          std::fprintf(csv, ",%.10g,%.10g,%.10g,%.10g", d(o.speed_ratio), d(o.geometric_ratio), d(o.radius1_m),
                       d(o.radius2_m));
        if (log & cvt::rom_log::energy)
          std::fprintf(csv, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.6g", double(e.stored_J), double(e.input_J),
                       double(e.actuator_J), double(e.load_J), double(e.friction_loss_J), double(e.damping_loss_J),
                       double(e.residual_J()));
        if (log & cvt::rom_log::states) {
          const auto xs = sim.state_si();  // displacements in m whatever the scalar's internal units
          for (int k = 0; k < Sim::Plant::kStates; ++k) std::fprintf(csv, ",%.12g", xs(k));
        }
        std::fprintf(csv, ",%s\n", cvt::rom_fault_name(sim.fault()));
      }
      if (sim.fault() != cvt::RomFault::none || i == cvt::scene_frames(scene)) {
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
      }
      return true;
    };
    const auto t0 = std::chrono::steady_clock::now();
    r.fault = cvt::run_scene<T, F>(scene, cvt::sim_config_of(scene), on_frame);
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double n = static_cast<double>(std::max<long>(1, r.frames));
    r.mean_w1 = sum_w1 / n;
    r.mean_w2 = sum_w2 / n;
    r.mean_fax = sum_fax / n;
    return r;
  }
};

Result run_double(Runner& runner);
Result run_float(Runner& runner);
Result run_fixed(Runner& runner);

}  // namespace cvtcli::run_cmd
