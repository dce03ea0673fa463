// The ROM spectrum and trajectory for the plants of state count
// kRomStateCounts[5] (rom_scenes_detail.hpp), one translation unit per count.
#include "rom_scenes_flow.hpp"

namespace cvt::analysis::rom_detail {
CVT_ROM_SCENES_INSTANTIATE(5)
}  // namespace cvt::analysis::rom_detail
