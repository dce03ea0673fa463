#pragma once
// The reduced-order CVT plant (lib/include/cvtplant/plant/cvt_rom.hpp) seen by
// the analysis toolkit (docs/analysis.md#rom-scenes):
//  - output signals of a built-in ROM scene sampled every frame, exactly as
//    `cvtplant run` computes them (the scene's own integrator, double);
//  - the autonomous seed scenes registered for `cvtplant lyapunov`.
#include <map>
#include <string>
#include <vector>

#include "cvtplant/analysis/systems.hpp"

namespace cvt::analysis {

// Signals that rom_scene_series can sample (names as in `cvtplant run --csv`).
const std::vector<std::string>& rom_signal_names();

struct RomSeries {
  std::string scene;
  double frame_s = 0;                              // sample interval [s]
  std::vector<double> t;                           // t = 0, frame, 2 frame, ... [s]
  std::map<std::string, std::vector<double>> signal;  // one value per t
  std::string fault = "none";                      // the plant watchdog's verdict
};

// Runs the built-in ROM scene `scene` for `t_end` seconds (<= 0: the scene's
// own length). Throws InputError for an unknown scene or signal, or a scene
// whose feature set the toolkit does not instantiate.
RomSeries rom_scene_series(const std::string& scene, const std::vector<std::string>& signals, double t_end);

// Adds the ROM seed scenes (constant inputs: seed-case1, seed-case2) to the
// `lyapunov` scene table. Called by the table itself.
void add_rom_scenes(std::vector<Scene>& table);

}  // namespace cvt::analysis
