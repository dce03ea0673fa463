// The plant a SIL bridge runs: one built-in scene's ROM in double, with the
// scene's own integrator, substeps and frame (docs/sil.md#plant). Heap-free:
// the simulator lives in a std::variant over the feature masks the built-in
// scenes use, so only those three plants are compiled into the bridge.
#pragma once

#include <cstdint>
#include <type_traits>
#include <variant>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt::sil {

inline constexpr std::uint32_t kAxialRoadLoad = rom_feature::axial | rom_feature::road_load;

class ScenePlant {
 public:
  // False (and nothing loaded) when the scene needs a plant this bridge does
  // not instantiate, or its frame is not a whole number of microseconds
  // (sim_time_us must stay exact, docs/can.md#layout).
  bool load(const Scene& s) {
    const double us = s.frame_s * 1e6;
    const auto frame_us = static_cast<std::int64_t>(us + 0.5);
    if (frame_us < 1 || static_cast<double>(frame_us) != us) return false;
    const RomSimConfig cfg = sim_config_of(s);
    switch (s.features) {
      case 0: sim_.emplace<Sim<0>>(s.params, cfg); break;
      case rom_feature::axial: sim_.emplace<Sim<rom_feature::axial>>(s.params, cfg); break;
      case kAxialRoadLoad: sim_.emplace<Sim<kAxialRoadLoad>>(s.params, cfg); break;
      default: return false;
    }
    scene_ = &s;
    frame_ns_ = frame_us * 1000;
    reset();
    return true;
  }

  // Initial state of the scene; the axial equilibrium uses the scene's
  // inputs at t = 0 (docs/rom.md#axial).
  void reset() {
    if (scene_ == nullptr) return;
    const RomInputs<double> u0 = scene_inputs_at<double>(*scene_, 0.0);
    with_sim([&](auto& sim) { sim.reset(scene_->initial, u0); });
  }

  RomFault step(const RomInputs<double>& u) {
    RomFault f = RomFault::none;
    with_sim([&](auto& sim) { f = sim.step_frame(u); });
    return f;
  }

  RomOutputs<double> outputs() const {
    RomOutputs<double> o{};
    with_sim([&](const auto& sim) { o = sim.outputs(); });
    return o;
  }

  RomFault fault() const {
    RomFault f = RomFault::none;
    with_sim([&](const auto& sim) { f = sim.fault(); });
    return f;
  }

  long frames() const {
    long n = 0;
    with_sim([&](const auto& sim) { n = sim.frames(); });
    return n;
  }

  bool loaded() const { return scene_ != nullptr; }
  const Scene* scene() const { return scene_; }
  std::int64_t frame_ns() const { return frame_ns_; }

 private:
  template <std::uint32_t F>
  using Sim = RomSimulator<double, F>;

  template <class Fn>
  void with_sim(Fn&& fn) {
    if (auto* p = std::get_if<Sim<0>>(&sim_)) fn(*p);
    else if (auto* a = std::get_if<Sim<rom_feature::axial>>(&sim_)) fn(*a);
    else if (auto* r = std::get_if<Sim<kAxialRoadLoad>>(&sim_)) fn(*r);
  }
  template <class Fn>
  void with_sim(Fn&& fn) const {
    if (const auto* p = std::get_if<Sim<0>>(&sim_)) fn(*p);
    else if (const auto* a = std::get_if<Sim<rom_feature::axial>>(&sim_)) fn(*a);
    else if (const auto* r = std::get_if<Sim<kAxialRoadLoad>>(&sim_)) fn(*r);
  }

  std::variant<std::monostate, Sim<0>, Sim<rom_feature::axial>, Sim<kAxialRoadLoad>> sim_;
  const Scene* scene_ = nullptr;
  std::int64_t frame_ns_ = 1000000;
};

}  // namespace cvt::sil
