// The real-time plant on the validation's sample grid (docs/validation.md#method).
#include "cvtplant/validation/plant.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cvtplant/plant/rom_signals.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "cvtplant/validation/errors.hpp"

namespace cvt::validation {

namespace {

using Holder = cvt::SceneSimulator<cvt::AllRomPlants<double>>;

// The plant in double through the scene dispatch (docs/architecture.md#scene-dispatch).
std::unique_ptr<Holder> load_plant(const cvt::Scene& s) {
  auto holder = std::make_unique<Holder>();
  const cvt::SceneIssue issue = holder->load(s, cvt::sim_config_of(s));
  if (!issue.ok) throw InputError(std::string(issue.field) + ": " + issue.message);
  return holder;
}

// One sample of the compared quantities, read through the plant's signal
// list; clamp1_N and clamp2_N are the clamping commands over the frame that
// starts at t.
void push_sample(Series& out, const cvt::Scene& s, double t, const cvt::IRomSimulator<double>& v, double clamp1_N,
                 double clamp2_N) {
  const bool wedging = (s.features & cvt::rom_feature::wedging) != 0;
  const cvt::RomOutputs<double> o = v.outputs();
  const auto signal = [&](cvt::RomSignal id) { return cvt::rom_signal(o, v.energy(), id); };
  out.t_s.push_back(t);
  out.omega1_rad_s.push_back(signal(cvt::RomSignal::omega1));
  out.omega2_rad_s.push_back(signal(cvt::RomSignal::omega2));
  out.F_ax1_N.push_back(signal(cvt::RomSignal::clamp_force));
  out.torque_driver_Nm.push_back(signal(cvt::RomSignal::torque_transmitted));
  // v_rel is the lump's speed over the sheave's; the driver's slip is the
  // sheave's over the chain's: the mean over the two lumps, and the slip
  // both lumps share (the whole wrap's).
  const double v1 = signal(cvt::RomSignal::v_rel1), v2 = signal(cvt::RomSignal::v_rel2);
  out.slip1_m_s.push_back(-0.5 * (v1 + v2));
  out.wrap_slip_m_s.push_back(whole_wrap_slip(std::min(-v1, -v2), std::max(-v1, -v2)));
  out.ratio_geom.push_back(signal(cvt::RomSignal::geometric_ratio));
  // Only the wedging plants have a driven pulley's axial force.
  out.F_ax2_N.push_back(wedging ? signal(cvt::RomSignal::driven_clamp_force) : std::nan(""));
  out.clamp1_N.push_back(clamp1_N);
  out.clamp2_N.push_back(wedging ? clamp2_N : std::nan(""));
  out.tau_in_Nm.push_back(signal(cvt::RomSignal::tau_in));
  out.tau_load_Nm.push_back(signal(cvt::RomSignal::tau_load));
}

[[noreturn]] void throw_fault(double t, cvt::RomFault fault) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "the plant faulted near t = %.6g s: ", t);
  throw RunError(buf + std::string(cvt::rom_fault_name(fault)));
}

}  // namespace

Series plant_run(const cvt::Scene& s, double sample_s) {
  const long every = std::max(1L, std::lround(sample_s / s.frame_s));
  Series out;
  out.reserve(static_cast<std::size_t>(s.t_end_s / sample_s) + 2);
  double last_t = 0;
  auto holder = load_plant(s);
  auto on_frame = [&](long i, double t, const cvt::IRomSimulator<double>& v) {
    if (i % every != 0) return true;
    push_sample(out, s, t, v, s.clamp.at(t), s.params.driven_clamp_N);
    last_t = t;
    return true;
  };
  const cvt::RomFault fault = cvt::run_frames(holder->sim(), s, s.frame_s, on_frame);
  if (fault != cvt::RomFault::none) throw_fault(last_t, fault);
  return out;
}

Series plant_run_driven(const cvt::Scene& s, long frames, const std::function<FrameInputs(double)>& drive,
                        const std::vector<char>* keep) {
  auto holder = load_plant(s);
  cvt::IRomSimulator<double>& sim = holder->sim();
  const bool wedging = (s.features & cvt::rom_feature::wedging) != 0;
  Series out;
  const auto kept = [&](long i) { return keep == nullptr || (*keep)[static_cast<std::size_t>(i)] != 0; };
  if (keep == nullptr) out.reserve(static_cast<std::size_t>(frames) + 1);
  const auto inputs = [&](const FrameInputs& f) {
    cvt::RomInputs<double> u;
    u.tau_in_Nm = f.tau_in_Nm;
    u.tau_load_Nm = f.tau_load_Nm;
    u.clamp_N = f.clamp1_N;
    return u;
  };
  const auto driven = [&](const FrameInputs& f) {
    return std::isnan(f.clamp2_N) ? s.params.driven_clamp_N : f.clamp2_N;
  };
  FrameInputs f = drive(0.0);
  // The driven actuator starts at its first command (reset settles it there).
  if (wedging) sim.set_driven_clamp_command(driven(f));
  sim.reset(s.initial, inputs(f));
  // Inputs sampled at the start of each frame and held (zero-order hold), as run_frames.
  for (long i = 0; i < frames; ++i) {
    const double t0 = static_cast<double>(i) * s.frame_s;
    if (kept(i)) push_sample(out, s, t0, sim, f.clamp1_N, driven(f));
    if (wedging) sim.set_driven_clamp_command(driven(f));
    if (sim.step_frame(inputs(f)) != cvt::RomFault::none) throw_fault(t0 + s.frame_s, sim.fault());
    f = drive(static_cast<double>(i + 1) * s.frame_s);
  }
  if (kept(frames)) push_sample(out, s, static_cast<double>(frames) * s.frame_s, sim, f.clamp1_N, driven(f));
  return out;
}

}  // namespace cvt::validation
