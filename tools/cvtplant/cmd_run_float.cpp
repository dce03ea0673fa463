// `cvtplant run` with the float plants (cmd_run_runner.hpp): one translation
// unit per scalar so the build compiles them in parallel.
#include "cmd_run_runner.hpp"

namespace cvtcli::run_cmd {
Result run_float(Runner& runner) { return with_features<float>(runner.scene.features, runner); }
}  // namespace cvtcli::run_cmd
