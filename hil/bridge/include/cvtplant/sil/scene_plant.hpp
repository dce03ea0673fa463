// The plant a SIL bridge runs: a scene's ROM in double, with the scene's own
// integrator, substeps and frame (docs/sil.md#plant). Any feature set: the
// plant is built by the scene dispatch of lib/ (scene/all_plants.hpp) into
// storage this object owns, without the heap.
#pragma once

#include <cmath>
#include <cstdint>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/cvt_rom.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt::sil {

// What the bridge publishes about its plant (PlantParams, PlantRatioMap,
// PlantThrustMap; docs/sil.md#published-parameters): the values a controller
// calibrates from, taken from the loaded scene's parameters, so a new
// parameter set needs no new controller constants.
struct PublishedParams {
  bool variable_ratio = false;
  double capacity_coeff = 0.0;  // tau_cap / (F_ax r1) = 2 f mu0 / cos(beta0)
  double radius_driver_m = 0.0;
  double clamp_max_N = 0.0;
  // Variable ratio: at the overdrive stop, set-up, the underdrive stop.
  double ratio[3] = {};
  double thrust_ratio[3] = {};
};

// docs/sil.md#published-parameters: the torque capacity per clamping force
// and driver radius is mu0 times the two lumps' normal load per axial force
// at the set-up half angle (docs/rom.md#contact, #lump-load-split); the ratio
// map is the chain's radial travel through the plant's own driven-radius
// cubic (docs/rom.md#wedging), r(rho) = (r2 + dr2(rho)) / (r1 + rho), and the
// thrust ratio at rest kappa(rho) = -dr2/drho (no-load: the wrap-tension
// share left out, docs/rom.md#wrap-tension).
inline PublishedParams published_params(const Scene& s) {
  const RomParams& p = s.params;
  PublishedParams q;
  q.variable_ratio = (s.features & rom_feature::wedging) != 0;
  const double cos_b0 = dm::cos(p.beta0_rad);
  q.capacity_coeff = p.friction.mu0 * (lump_load_per_axial(p.entry_load_share, p.normal_load_factor, cos_b0) +
                                       lump_load_per_axial(1.0 - p.entry_load_share, p.normal_load_factor, cos_b0));
  q.radius_driver_m = p.r1_m;
  q.clamp_max_N = p.clamp_max_N;
  if (q.variable_ratio) {
    const CvtRom<double, rom_feature::axial | rom_feature::wedging> rom(p);
    const double rho[3] = {p.radial_travel_m, 0.0, -p.radial_travel_m};
    for (int i = 0; i < 3; ++i) {
      q.ratio[i] = (p.r2_m + rom.radial().driven_radius_change(rho[i])) / (p.r1_m + rho[i]);
      q.thrust_ratio[i] = rom.ratio_slope(rho[i]);
    }
  }
  return q;
}

// PlantShift's end-stop flags (docs/can.md#layout).
struct EndStops {
  bool underdrive = false, overdrive = false;
};

// PlantDiag.plant_fault for the real-time plant's watchdog reasons
// (docs/rom.md#watchdog, docs/sil.md#plant-faults).
constexpr can::PlantFault plant_fault_code(RomFault f) {
  switch (f) {
    case RomFault::none: return can::PlantFault::None;
    case RomFault::input_non_finite:
    case RomFault::input_saturated: return can::PlantFault::Input;
    case RomFault::state_non_finite: return can::PlantFault::StateNonFinite;
    case RomFault::state_saturated: return can::PlantFault::StateSaturated;
    case RomFault::energy_growth: return can::PlantFault::EnergyCheck;
    case RomFault::radius_out_of_range: return can::PlantFault::RadiusOutOfRange;
    case RomFault::speed_out_of_range: return can::PlantFault::SpeedOutOfRange;
    case RomFault::step_unresolved: return can::PlantFault::StepUnresolved;
    case RomFault::scene_features: return can::PlantFault::SceneFeatures;
    case RomFault::tension_out_of_range: return can::PlantFault::TensionOutOfRange;
  }
  return can::PlantFault::StateInvalid;
}

// The plant behind the bridge (docs/sil.md#plant-interface): what BasicBridge
// asks of its plant. This one is the scene's real-time plant, heap-free.
class ScenePlant {
 public:
  // False, with the previous scene kept, when the plants cannot run the
  // scene (check_scene_plant) or its frame is not a whole number of
  // microseconds (sim_time_us must stay exact, docs/can.md#layout).
  bool load(const Scene& s) {
    const double us = s.frame_s * 1e6;
    const auto frame_us = static_cast<std::int64_t>(us + 0.5);
    if (frame_us < 1 || static_cast<double>(frame_us) != us) return false;
    if (!check_scene_plant<AllRomPlants<double>>(s).ok) return false;
    sim_.load(s);
    scene_ = &s;
    frame_ns_ = frame_us * 1000;
    return true;
  }

  // Initial state of the scene; the axial equilibrium uses the scene's
  // inputs at t = 0 (docs/rom.md#axial).
  void reset() {
    if (scene_ == nullptr) return;
    // A new run starts the driven actuator at the scene's set-up value.
    sim_.sim().set_driven_clamp_command(scene_->params.driven_clamp_N);
    sim_.sim().reset(scene_->initial, scene_inputs_at<double>(*scene_, 0.0));
  }

  RomFault step(const RomInputs<double>& u) { return loaded() ? sim_.sim().step_frame(u) : RomFault::none; }
  RomOutputs<double> outputs() const { return loaded() ? sim_.sim().outputs() : RomOutputs<double>{}; }
  RomFault fault() const { return loaded() ? sim_.sim().fault() : RomFault::none; }
  bool faulted() const { return fault() != RomFault::none; }
  can::PlantFault fault_code() const { return plant_fault_code(fault()); }
  // The watchdog's reason (docs/rom.md#watchdog): the JSON summary's
  // plant_fault, and the whole of what is known about it.
  const char* fault_detail() const { return rom_fault_name(fault()); }
  const char* fault_message() const { return rom_fault_name(fault()); }
  const char* load_refusal() const { return "this bridge has no plant for its features/frame"; }
  const char* realtime_refusal() const { return ""; }
  long frames() const { return loaded() ? sim_.sim().frames() : 0; }
  // A frame of the real-time plant costs microseconds (docs/rom.md#cost).
  bool keeps_time() const { return true; }
  PublishedParams published() const { return loaded() ? published_params(*scene_) : PublishedParams{}; }

  // PlantForces.driven_axial_force_N: without wedging the ROM has one lumped
  // clamping force (docs/rom.md#axial), which both signals carry; with it the
  // driven actuator's own force.
  double driven_axial_N() const { return variable_ratio() ? driven_clamp_N() : outputs().clamp_force_N; }
  // The chain beyond the radial travel of the driver (docs/rom.md#wedging).
  EndStops end_stops() const {
    if (!variable_ratio()) return {};
    const double rho = outputs().radius1_m - scene_->params.r1_m;
    return {rho < -scene_->params.radial_travel_m, rho > scene_->params.radial_travel_m};
  }

  // Wedging: the driven (secondary) clamping command, the force the driven
  // actuator applies, frames taken with the end stop's finer steps
  // (docs/rom.md#driven-clamping, #end-stop); the set-up value before the first.
  void set_driven_clamp_command(double f_N) {
    if (loaded()) sim_.sim().set_driven_clamp_command(f_N);
  }
  double driven_clamp_N() const { return loaded() ? sim_.sim().driven_clamp_N() : 0.0; }
  long stop_refined_frames() const { return loaded() ? sim_.sim().stop_refined_frames() : 0; }
  // The energy ledger's residual over its flows (docs/rom.md#energy-balance).
  double energy_residual_rel() const {
    if (!loaded()) return 0.0;
    const auto& e = sim_.sim().energy();
    return e.scale_J() > 0.0 ? std::fabs(e.residual_J()) / e.scale_J() : 0.0;
  }
  bool variable_ratio() const { return loaded() && (scene_->features & rom_feature::wedging) != 0; }

  bool loaded() const { return scene_ != nullptr; }
  const Scene* scene() const { return scene_; }
  std::int64_t frame_ns() const { return frame_ns_; }

 private:
  SceneSimulator<AllRomPlants<double>> sim_;
  const Scene* scene_ = nullptr;
  std::int64_t frame_ns_ = 1000000;
};

}  // namespace cvt::sil
