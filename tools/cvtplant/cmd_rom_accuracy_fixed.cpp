// `cvtplant rom-accuracy` with the fixed plants (cmd_rom_accuracy_collector.hpp):
// one translation unit per scalar so the build compiles them in parallel.
#include "cmd_rom_accuracy_collector.hpp"

namespace cvtcli::rom_accuracy_cmd {
Trace collect_fixed(Collector& c) { return with_features<cvt::q16_16>(c.scene.features, c); }
}  // namespace cvtcli::rom_accuracy_cmd
