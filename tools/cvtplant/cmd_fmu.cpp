// `cvtplant fmu`: a co-simulation FMU (FMI 3.0 or 2.0) of a scene's plant
// (docs/fmu.md, docs/cli.md#fmu). The packaging is fmu/; this parses and
// prints.
#include <sys/stat.h>

#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "cvtplant/fmu/packager.hpp"
#include "io_util.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "scene_simulator.hpp"

namespace {

struct Options {
  std::string scene, out;
  int fmi = 3;
  bool json = false;
};

cvtcli::Action register_fmu(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "fmu", "Write a co-simulation FMU (FMI 3.0 or 2.0) of a scene's plant (docs/fmu.md)");
  sub->add_option("--scene", opt->scene, "Built-in scene name (see `cvtplant scenes`) or a TOML scene file")
      ->required();
  sub->add_option("--fmi", opt->fmi, "FMI version: 3 (default) or 2")->check(CLI::IsMember({2, 3}));
  sub->add_option("--out", opt->out, "The FMU file to write (a zip, conventionally NAME.fmu)")->required();
  sub->add_flag("--json", opt->json, "Print a JSON summary instead of the text one");
  return [opt]() -> int {
    const Options& o = *opt;
    auto loaded = cvtcli::resolve_scene(o.scene);
    const cvt::Scene& s = loaded->scene;
    // The plant must exist for the scene's scalar (wedging: floating point only).
    cvtcli::check_scene_simulator(s, s.scalar);
    if (o.out == "-") throw cvtcli::UsageError{"--out: an FMU is a zip file; give a path"};
    if (o.out.empty()) throw cvtcli::UsageError{"--out: empty file name"};
    if (loaded->source != "built-in" && cvtcli::same_file(o.out, loaded->source))
      throw cvtcli::UsageError{"--out: " + o.out + " is the scene file; writing would destroy it"};
    struct stat st {};
    if (::stat(o.out.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      throw cvtcli::UsageError{"--out: " + o.out + " is a directory"};

    cvt::fmu::PackageRequest req;
    req.scene = s;
    req.name = loaded->name;
    req.summary = loaded->summary.empty() ? std::string(s.summary) : loaded->summary;
    req.fmi_version = o.fmi;
    cvt::fmu::PackageSummary sum;
    try {
      sum = cvt::fmu::write_fmu(req, o.out);
    } catch (const cvt::fmu::PackageError& e) {
      throw cvtcli::RunError{e.what()};
    }
    const char* version = o.fmi == 3 ? "3.0" : "2.0";
    if (o.json) {
      nlohmann::json j;
      j["subcommand"] = "fmu";
      j["scene"] = loaded->name;
      j["source"] = loaded->source;
      j["fmi_version"] = version;
      j["out"] = o.out;
      j["model_identifier"] = sum.model_identifier;
      j["instantiation_token"] = sum.token;
      j["binary"] = sum.binary_path;
      j["features"] = cvtcli::feature_names(s.features);
      j["scalar"] = cvt::scalar_kind_name(s.scalar);
      j["frame_s"] = s.frame_s;
      j["variable_count"] = sum.variables;
      j["input_count"] = sum.inputs;
      j["output_count"] = sum.outputs;
      j["parameter_count"] = sum.parameters;
      cvtcli::print_json(j);
    } else {
      std::printf("FMU %s: FMI %s co-simulation of scene %s (%s): features %s, %s, frames of %g s\n", o.out.c_str(),
                  version, loaded->name.c_str(), loaded->source.c_str(), cvtcli::feature_names(s.features).c_str(),
                  cvt::scalar_kind_name(s.scalar), s.frame_s);
      std::printf("  %d variables: the time, %d inputs, %d outputs (the fault code one of them), %d parameters\n", sum.variables,
                  sum.inputs, sum.outputs, sum.parameters);
      std::printf("  %s, sources/, documentation/; %zu bytes\n", sum.binary_path.c_str(), sum.bytes);
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_fmu);

}  // namespace
