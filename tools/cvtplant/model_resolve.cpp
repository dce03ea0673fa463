#include "model_resolve.hpp"

#include <sys/stat.h>

#include "commands.hpp"
#include "options.hpp"
#include "scene_file.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/rom_scenes.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace cvtcli {

std::shared_ptr<const cvt::analysis::Model> resolve_model(const std::string& name_or_path) {
  namespace an = cvt::analysis;
  if (an::has_model(name_or_path)) return std::make_shared<an::Model>(an::find_model(name_or_path));
  struct stat st {};
  if (cvt::find_builtin_scene(name_or_path.c_str()) == nullptr && ::stat(name_or_path.c_str(), &st) != 0) {
    std::string known;
    for (const an::Model& m : an::models()) known += (known.empty() ? "" : ", ") + m.name;
    throw UsageError{"unknown scene " + quoted(name_or_path, 200) + ": not a model (" + known +
                     "), a built-in plant scene (see `cvtplant scenes`) or a readable scene file"};
  }
  // A file that exists but is no scene says why: a directory, a syntax
  // error, or the scene's own refusal (FILE:LINE: field: why).
  const std::shared_ptr<LoadedScene> scene = resolve_scene(name_or_path);
  try {
    return std::make_shared<an::Model>(an::rom_model(scene->scene, scene->name));
  } catch (const an::InputError& e) {
    throw UsageError{e.what()};
  }
}

}  // namespace cvtcli
