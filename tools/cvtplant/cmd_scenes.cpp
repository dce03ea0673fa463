// `cvtplant scenes`: the built-in scenes of the reduced-order plant, one per
// line (docs/cli.md#scenes, docs/rom.md#built-in-scenes).
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "io_util.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace {

cvtcli::Action register_scenes(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("scenes", "List the built-in scenes of the reduced-order plant");
  sub->add_flag("--json", *json, "Print the list as JSON");
  return [json]() -> int {
    if (*json) {
      nlohmann::json arr = nlohmann::json::array();
      for (const cvt::Scene& s : cvt::kBuiltinScenes) {
        arr.push_back({{"scene", s.name},
                       {"summary", s.summary},
                       {"features", cvtcli::feature_names(s.features)},
                       {"t_end_s", s.t_end_s},
                       {"frame_s", s.frame_s},
                       {"substeps", s.substeps},
                       {"integrator", cvt::method_name(s.method)},
                       {"scalar", cvt::scalar_kind_name(s.scalar)}});
      }
      cvtcli::print_json(arr);
    } else {
      for (const cvt::Scene& s : cvt::kBuiltinScenes) std::printf("%-20s %s\n", s.name, s.summary);
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_scenes);

}  // namespace
