// `cvtplant run` with the fixed plants (cmd_run_runner.hpp): one translation
// unit per scalar so the build compiles them in parallel.
#include "cmd_run_runner.hpp"

namespace cvtcli::run_cmd {
Result run_fixed(Runner& runner) { return with_features<cvt::q16_16>(runner.scene.features, runner); }
}  // namespace cvtcli::run_cmd
