#pragma once
// The frames of the ROM cost table (docs/rom.md#cost). One list, used by the
// Cortex-M4F instruction counts (tests/target/test_rom_cost.cpp) and by the
// host benchmark (bench/bench_rom.cpp), so both columns of the table measure
// the same frame from the same state. Heap-free.
#include <cstdint>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt::rom_cost {

// One row: a built-in scene run with the plant of the visited mask, at
// `substeps` per frame (0: the scene's own setting), with or without the
// energy ledger (Scene::energy_ledger) and with the scene's integrator or
// the one named in `integrator`; `edit` changes the scene's parameters
// (a scene file's [params], e.g. fixed sheaves).
struct Case {
  const char* label;
  const char* scene;
  int substeps;
  bool energy_ledger = true;
  const char* integrator = nullptr;
  void (*edit)(Scene&) = nullptr;
};

// The built-in seed-case1 runs the seed's fixed sheaves (docs/rom.md#tension);
// the rows that give it the axial feature hold its sheave by the clamping
// actuator instead (tools/scenes/seed-case1-clamped.toml and, with the
// tension state, its clamped regime).
inline void fixed_sheaves(Scene& s) { s.params.fixed_sheaves = true; }
inline void clamped_sheaves(Scene& s) { s.params.fixed_sheaves = false; }
// tools/scenes/seed-case1-ripple.toml: the same with the link-passing ripple
// (docs/rom.md#link-ripple), and with the ripple off (g = 0).
inline void fixed_sheaves_ripple(Scene& s) {
  s.params.fixed_sheaves = true;
  s.params.ripple_gain = 0.148;
}
// tools/scenes/ratio-control-tension.toml: ratio-control's primary clamping
// stepped from the 11.34 kN that holds its ratio to 1.1 times that at 2 s
// (an upshift, off the end stops), and the same with the link-passing ripple
// of tools/scenes/seed-case1-ripple.toml.
inline void primary_step(Scene& s) { s.clamp = step_profile(11342.279, 12476.507, 2.0); }
inline void primary_step_ripple(Scene& s) {
  primary_step(s);
  s.params.ripple_gain = 0.148;
}

// The feature mask is a template argument of the plant, so the rows are
// visited at compile time: v.template visit<Mask>(row) for every row.
// Feature rows use the gross-slip parameter set (no holds, every feature
// meaningful) and add one feature at a time to the core plant. Chordal action
// needs >= 4 substeps (docs/rom.md#polygon), hence the core x4 reference row.
template <class Visitor>
void for_each_case(Visitor&& v) {
  namespace f = rom_feature;
  v.template visit<0>(Case{"scene/oscillator-coulomb", "oscillator-coulomb", 0});
  v.template visit<0>(Case{"scene/oscillator-stribeck", "oscillator-stribeck", 0});
  // The seed case under its clamping actuator (seed-case1's inputs on the
  // axial plant, tools/scenes/seed-case1-clamped.toml): the default frame of
  // the cost goals.
  v.template visit<f::axial>(Case{"scene/seed-case1", "seed-case1", 0});
  // The default scene's own choices (docs/rom.md#cost): without the ledger,
  // and without it in linearly implicit Euler (its error against the
  // converged reference is in docs/rom.md#real-time-integrator).
  v.template visit<f::axial>(Case{"scene/seed-case1/no-ledger", "seed-case1", 0, false});
  v.template visit<f::axial>(Case{"scene/seed-case1/no-ledger/lin-impl-euler", "seed-case1", 0, false,
                                  "linear-implicit-euler"});
  v.template visit<f::axial>(Case{"scene/seed-case2", "seed-case2", 0});
  v.template visit<f::axial | f::road_load>(Case{"scene/clamp-step", "clamp-step", 0});
  v.template visit<f::axial | f::road_load>(Case{"scene/tip-in", "tip-in", 0});
  v.template visit<0>(Case{"scene/gross-slip", "gross-slip", 0});
  v.template visit<0>(Case{"feature/core", "gross-slip", 0});
  v.template visit<f::axial>(Case{"feature/+axial", "gross-slip", 0});
  v.template visit<f::road_load>(Case{"feature/+road_load", "gross-slip", 0});
  v.template visit<f::deformation>(Case{"feature/+deformation", "gross-slip", 0});
  v.template visit<0>(Case{"feature/core-x4", "gross-slip", 4});
  v.template visit<f::polygon>(Case{"feature/+polygon-x4", "gross-slip", 4});
  v.template visit<f::basic>(Case{"feature/all-but-wedging-x4", "gross-slip", 4});
  // Wedging is meaningful on a scene with the seed clamping (docs/rom.md#wedging).
  v.template visit<f::axial | f::wedging>(Case{"feature/seed-case1+wedging", "seed-case1", 0});
  // The plant of ratio control over CAN (docs/sil.md#ratio-control), off the
  // end stops, and clamp-step with wedging, whose 1.2 kN has driven the chain
  // onto the hub stop by 1 s: a frame in stop_substeps steps (docs/rom.md#end-stop).
  v.template visit<f::axial | f::road_load | f::wedging>(Case{"scene/ratio-control", "ratio-control", 0});
  v.template visit<f::axial | f::road_load | f::wedging>(
      Case{"scene/ratio-control/no-ledger", "ratio-control", 0, false});
  v.template visit<f::axial | f::road_load | f::wedging>(Case{"scene/clamp-step+wedging-on-stop", "clamp-step", 0});
  // The chain's tension state (docs/rom.md#tension): the seed case on fixed
  // sheaves (the built-in seed-case1's own plant), and with its clamping
  // actuator (the sheave held off its stop by the 3.3 kN).
  v.template visit<f::tension>(Case{"scene/seed-case1-tension", "seed-case1", 0, true, nullptr, &fixed_sheaves});
  v.template visit<f::axial | f::tension>(
      Case{"feature/seed-case1+tension", "seed-case1", 0, true, nullptr, &clamped_sheaves});
  // Chordal action with the tension feature at the scene's 4 substeps, with
  // and without the ripple: the ripple's own cost (docs/rom.md#link-ripple).
  v.template visit<f::tension | f::polygon>(
      Case{"scene/seed-case1-ripple", "seed-case1", 4, true, nullptr, &fixed_sheaves_ripple});
  v.template visit<f::tension | f::polygon>(
      Case{"scene/seed-case1-ripple/off", "seed-case1", 4, true, nullptr, &fixed_sheaves});
  // Every feature of the variable-ratio plant at once (docs/rom.md#tension-radial):
  // ratio-control with the chain's tension state off the end stops, and
  // clamp-step with the same features on the hub stop (its 1.2 kN has driven
  // the chain there by 1 s: two substeps of one W, docs/rom.md#end-stop);
  // with chordal action and the link ripple at 4 substeps, the ripple's cost.
  constexpr std::uint32_t full = f::axial | f::road_load | f::wedging | f::tension;
  v.template visit<full>(Case{"scene/ratio-control-tension", "ratio-control", 0, true, nullptr, &primary_step});
  v.template visit<full>(
      Case{"scene/ratio-control-tension/no-ledger", "ratio-control", 0, false, nullptr, &primary_step});
  v.template visit<full>(Case{"scene/clamp-step+wedging+tension-on-stop", "clamp-step", 0});
  v.template visit<full | f::polygon>(
      Case{"scene/ratio-control-tension/ripple-x4", "ratio-control", 4, true, nullptr, &primary_step_ripple});
}

// Where the measured frame starts: the scene run on its own input profiles
// for this long, so the cost is that of normal running, not of the start.
inline constexpr double kWarmup_s = 1.0;

// A simulator of row `c` at t = kWarmup_s and the inputs of the next frame.
// The caller copies `sim` before each measured frame so every measured call
// takes the same path.
template <class T, std::uint32_t F>
struct Frame {
  RomSimulator<T, F> sim;
  RomInputs<T> next;

  static Scene scene_of(const Case& c) {
    Scene s = *find_builtin_scene(c.scene);
    if (c.substeps > 0) s.substeps = c.substeps;
    s.energy_ledger = c.energy_ledger;
    if (!c.energy_ledger) s.log &= ~rom_log::energy;
    if (c.integrator != nullptr) parse_method(c.integrator, s.method);
    if (c.edit != nullptr) c.edit(s);
    return s;
  }

  explicit Frame(const Case& c) : Frame(scene_of(c)) {}

  explicit Frame(const Scene& s) : sim(s.params, sim_config_of(s)) {
    sim.reset(s.initial, scene_inputs_at<T>(s, 0.0));
    const long n = static_cast<long>(kWarmup_s / s.frame_s + 0.5);
    for (long i = 0; i < n; ++i) sim.step_frame(scene_inputs_at<T>(s, static_cast<double>(i) * s.frame_s));
    next = scene_inputs_at<T>(s, static_cast<double>(n) * s.frame_s);
  }
};

}  // namespace cvt::rom_cost
