// `cvtplant rom-accuracy` with the double plants (cmd_rom_accuracy_collector.hpp):
// one translation unit per scalar so the build compiles them in parallel.
#include "cmd_rom_accuracy_collector.hpp"

namespace cvtcli::rom_accuracy_cmd {
Trace collect_double(Collector& c) { return with_features<double>(c.scene.features, c); }
}  // namespace cvtcli::rom_accuracy_cmd
