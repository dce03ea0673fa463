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

Series plant_run(const cvt::Scene& s, double sample_s) {
  const long every = std::max(1L, std::lround(sample_s / s.frame_s));
  Series out;
  out.reserve(static_cast<std::size_t>(s.t_end_s / sample_s) + 2);
  double last_t = 0;
  // The plant in double through the scene dispatch (docs/architecture.md#scene-dispatch).
  auto holder = std::make_unique<cvt::SceneSimulator<cvt::AllRomPlants<double>>>();
  const cvt::SceneIssue issue = holder->load(s, cvt::sim_config_of(s));
  if (!issue.ok) throw InputError(std::string(issue.field) + ": " + issue.message);
  const bool wedging = (s.features & cvt::rom_feature::wedging) != 0;
  auto on_frame = [&](long i, double t, const cvt::IRomSimulator<double>& v) {
    if (i % every != 0) return true;
    // The compared quantities, read through the plant's signal list.
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
    out.clamp1_N.push_back(s.clamp.at(t));
    out.clamp2_N.push_back(wedging ? s.params.driven_clamp_N : std::nan(""));
    out.tau_in_Nm.push_back(signal(cvt::RomSignal::tau_in));
    out.tau_load_Nm.push_back(signal(cvt::RomSignal::tau_load));
    last_t = t;
    return true;
  };
  const cvt::RomFault fault = cvt::run_frames(holder->sim(), s, s.frame_s, on_frame);
  if (fault != cvt::RomFault::none) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "the plant faulted near t = %.6g s: ", last_t);
    throw RunError(buf + std::string(cvt::rom_fault_name(fault)));
  }
  return out;
}

}  // namespace cvt::validation
