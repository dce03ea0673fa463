#pragma once
// Scene files (TOML) for the offline tool (docs/rom.md#scene-files). Errors
// name the file, the line and the field; every value is checked by
// cvt::validate_scene before a run.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/scene/scene.hpp"

namespace cvtcli {

// A scene plus the storage its name/summary point into.
struct LoadedScene {
  cvt::Scene scene;
  std::string name, summary, source;  // source: "built-in" or the file path
  // The multibody reference's parameter set the scene is validated against
  // (docs/validation.md#parameter-sets): a scene file's `reference_set`, else
  // its base scene's (cvt::Scene::reference_set: ratio-control's production).
  std::string reference_set = "seed";
};

// Scene files are a few kB (three profiles of at most 16 points); a larger
// input is refused before it is parsed.
inline constexpr std::size_t kMaxSceneFileBytes = 1 << 20;

// Reads and validates a scene file; throws UsageError("FILE:LINE: FIELD: why").
std::shared_ptr<LoadedScene> load_scene_file(const std::string& path);
// The same on a document already read; `path` names it in messages.
std::shared_ptr<LoadedScene> parse_scene_text(const std::string& text, const std::string& path);

// Applies a parameter file (a TOML file with a [params] table of RomParams
// fields, as `cvtplant calibrate --out` writes) to s; throws UsageError like
// load_scene_file, also if the result fails cvt::validate_scene.
void apply_params_file(const std::string& path, cvt::Scene& s);

// A built-in scene name or a path to a scene file.
std::shared_ptr<LoadedScene> resolve_scene(const std::string& name_or_path);

// A scene field that a flag of the command sets (run's --dt sets frame_s).
struct SceneFlag {
  const char* field;  // as cvt::validate_scene names it
  const char* flag;   // "--dt"
  double value;       // the value given (shown in full in a refusal)
  bool given;         // whether the flag was given
};
// cvt::validate_scene on a scene some flags changed; throws UsageError. A
// refusal of a field a given flag set names the flag and its value
// (`--dt: 0.1 s is above --t-end 0.05 s`), any other names the scene.
void check_scene(const cvt::Scene& s, const LoadedScene& loaded, const std::vector<SceneFlag>& flags);

// "axial,road_load" for a feature mask ("none" if 0).
std::string feature_names(std::uint32_t features);

}  // namespace cvtcli
