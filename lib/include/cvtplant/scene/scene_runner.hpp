#pragma once
// Runs a scene frame by frame (docs/rom.md#frame-stepping). Heap-free: the
// caller's callback sees the simulator after every frame (and at t = 0).
#include <cstdint>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt {

inline RomSimConfig sim_config_of(const Scene& s) {
  RomSimConfig c;
  c.method = s.method;
  c.substeps = s.substeps;
  c.frame_s = s.frame_s;
  c.energy_ledger = s.energy_ledger;
  return c;
}

template <class T>
RomInputs<T> scene_inputs_at(const Scene& s, double t) {
  RomInputs<T> u;
  u.tau_in_Nm = T(s.tau_in.at(t));
  u.tau_load_Nm = T(s.tau_load.at(t));
  u.clamp_N = T(s.clamp.at(t));
  return u;
}

// Number of frames of a scene: t_end rounded to whole frames.
inline long scene_frames(const Scene& s) { return static_cast<long>(s.t_end_s / s.frame_s + 0.5); }

// Runs a scene on a simulator built with the scene's parameters: a
// RomSimulator<T, F> or the size-erased IRomSimulator<T> of a SceneSimulator
// (scene/plant_set.hpp). Resets it to the scene's start, then
// on_frame(long frame, double t_s, const Sim&) -> bool after every frame
// and at t = 0 (false stops the run). Returns the fault state at the end:
// scene-features, without running anything, if the simulator's features are
// not the scene's (a scene never runs with fewer features than it asks for,
// nor with others it did not ask for).
template <class Sim, class OnFrame>
RomFault run_frames(Sim& sim, const Scene& s, double frame_s, OnFrame&& on_frame) {
  using T = typename Sim::Scalar;
  if (sim.features() != s.features) return RomFault::scene_features;
  const Sim& view = sim;
  sim.reset(s.initial, scene_inputs_at<T>(s, 0.0));
  if (!on_frame(0L, 0.0, view)) return sim.fault();
  const long n = static_cast<long>(s.t_end_s / frame_s + 0.5);
  for (long i = 0; i < n; ++i) {
    // Inputs sampled at the start of the frame and held (zero-order hold).
    const double t0 = static_cast<double>(i) * frame_s;
    if (sim.step_frame(scene_inputs_at<T>(s, t0)) != RomFault::none) {
      on_frame(i + 1, t0 + frame_s, view);
      return sim.fault();
    }
    if (!on_frame(i + 1, static_cast<double>(i + 1) * frame_s, view)) break;
  }
  return sim.fault();
}

// The same with the plant of a compile-time feature mask F.
template <class T, std::uint32_t F, class OnFrame>
RomFault run_scene(const Scene& s, const RomSimConfig& cfg, OnFrame&& on_frame) {
  RomSimulator<T, F> sim(s.params, cfg);
  return run_frames(sim, s, cfg.frame_s, on_frame);
}

}  // namespace cvt
