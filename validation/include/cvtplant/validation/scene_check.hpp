#pragma once
// One scene of `cvtplant validate` (docs/validation.md#method): the
// reference's inputs from the scene, the cached reference run, the plant on
// the same grid and the error measures; and the settings `validate` and
// `calibrate` share.
#include <optional>
#include <string>

#include "cvtplant/mbd/run.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/reference.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

struct RunSettings {
  SheaveChoice sheaves = SheaveChoice::scene;
  // The reference's parameter set (docs/validation.md#parameter-sets): the
  // caller sets each scene's own, or the one `--set` names.
  cvt::mbd::ParameterSet set = cvt::mbd::ParameterSet::seed;
  double t_end_s = 0;  // > 0: every run shortened to at most this [s]; 0: each scene's own length
  double rtol = 5e-7;  // the reference's BDF relative tolerance
  long long max_steps = 20000000;  // cap on the reference's integrator steps per scene
  std::string cache_dir;  // the reference cache (created by the caller)
};

// The simulated time a scene runs for under the settings [s].
double run_length_s(const cvt::Scene& s, const RunSettings& st);

// The reference's inputs and run options for scene s (1 ms samples: the
// scene's frame), or nothing with the reason in why_not.
struct ReferenceSetup {
  cvt::mbd::MbdParams params;
  cvt::mbd::RunOptions run;
};
std::optional<ReferenceSetup> reference_setup(const cvt::Scene& s, const RunSettings& st, std::string& why_not);

struct SceneResult {
  std::string name;
  std::string skipped;  // why the reference cannot run it (empty: it ran)
  double t_end_s = 0;
  Comparison cmp;
  ReferenceRun ref;
  Series plant;
  bool clamped = true;          // the reference's sheaves (reference_sheaves)
  double stop_s[2] = {-1, -1};  // first time each reference sheave is at its end stop (-1: never)
};

// `scene` as the reference runs it against `plant_scene`, the same scene
// whose plant may have other parameters (`validate --params`). A scene the
// reference cannot run comes back with `skipped` set. Throws RunError if the
// plant faults or the reference makes too few samples.
SceneResult check_scene(const std::string& name, const cvt::Scene& scene, const cvt::Scene& plant_scene,
                        const RunSettings& st, const cvt::mbd::ProgressSink& on_progress = {});

}  // namespace cvt::validation
