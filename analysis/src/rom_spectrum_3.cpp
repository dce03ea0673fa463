// The ROM spectrum and trajectory for the plants of state count
// kRomStateCounts[3] (rom_scenes_detail.hpp), one translation unit per count.
#include "rom_scenes_flow.hpp"

namespace cvt::analysis::rom_detail {
CVT_ROM_SCENES_INSTANTIATE(3)
}  // namespace cvt::analysis::rom_detail
