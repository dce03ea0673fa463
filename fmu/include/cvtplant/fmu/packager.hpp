#pragma once
// `cvtplant fmu`: an FMU of a scene's plant (docs/fmu.md). The model
// description comes from the same variable list the FMU serves
// (variables.hpp); the shared object and the sources come from the payload
// built with this program (fmu/CMakeLists.txt). Heap and exceptions allowed.
#include <stdexcept>
#include <string>
#include <vector>

#include "cvtplant/scene/scene.hpp"

namespace cvt::fmu {

// A problem with the request (bad name, output path) or the write; the
// message is one line.
struct PackageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct PackageRequest {
  Scene scene;
  std::string name;     // the scene's name: the model name
  std::string summary;  // one line for the description
  int fmi_version = 3;  // 3 or 2
};

// "cvtplant_" and the name with every character outside [A-Za-z0-9_] as '_'.
std::string model_identifier(const std::string& scene_name);

// The files of the FMU, by their path inside it.
struct FmuFile {
  std::string path;
  std::string text;
};
// resources/scene.txt, modelDescription.xml, documentation/index.html and
// (FMI 3.0) sources/buildDescription.xml, sources/CMakeLists.txt.
std::vector<FmuFile> generated_files(const PackageRequest& r);

// What `cvtplant fmu` reports.
struct PackageSummary {
  std::string model_identifier, token, binary_path;
  int variables = 0, inputs = 0, outputs = 0, parameters = 0;
  std::size_t bytes = 0;
};

// Writes the FMU to `out` (replaced whole, or left as it was on an error).
PackageSummary write_fmu(const PackageRequest& r, const std::string& out);

}  // namespace cvt::fmu
