#pragma once
// The reduced-order CVT plant (lib/include/cvtplant/plant/) seen by the
// analysis toolkit (docs/analysis.md#rom-scenes), for any scene (built-in or
// read from a file by the caller) and any feature set, through the scene
// dispatch of lib/ (scene/all_plants.hpp):
//  - output signals of a scene sampled every frame, exactly as `cvtplant run`
//    computes them (the scene's own integrator, double);
//  - a scene with constant inputs as a Model for the spectrum tools.
#include <map>
#include <string>
#include <vector>

#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt::analysis {

// Signals that rom_scene_series can sample: every output signal of the
// plant's list (plant/rom_signals.hpp, the names of `cvtplant run --csv`)
// and the lumps' states x1, xd1, x2, xd2.
const std::vector<std::string>& rom_signal_names();
// A signal's SI unit as the plant's signal list writes it ("N", "N.m",
// "m/s", "rad/s"; "1" for slip, ratios and flags; "m", "m/s" for the lumps'
// states). InputError for an unknown name.
std::string rom_signal_unit(const std::string& name);

struct RomSeries {
  std::string scene;
  double frame_s = 0;                              // sample interval [s]
  std::vector<double> t;                           // t = 0, frame, 2 frame, ... [s]
  std::map<std::string, std::vector<double>> signal;  // one value per t
  std::string fault = "none";                      // the plant watchdog's verdict
};

// Runs `scene` (named `name` in messages) for `t_end` seconds (<= 0: the
// scene's own length). Throws InputError for an unknown signal or a scene the
// plants cannot run. `progress`, if set, gets (simulated s, t_end).
RomSeries rom_scene_series(const cvt::Scene& scene, const std::string& name, const std::vector<std::string>& signals,
                           double t_end, const ProgressFn& progress = {});

// A scene as a model for `lyapunov`, `analyze trajectory` and sweeps: its
// constant inputs and mu0 are the parameters. Throws InputError for a scene
// whose inputs vary in time (the spectrum is that of an autonomous system).
Model rom_model(const cvt::Scene& scene, const std::string& name);

// Adds the seed's section-4 scenes (seed-case1, seed-case2) to the model
// table, so that `lyapunov --list` shows them. Called by the table itself.
void add_rom_models(std::vector<Model>& table);

}  // namespace cvt::analysis
