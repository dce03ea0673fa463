// The ROM spectrum and trajectory for plants of 12 states (rom_scenes_flow.hpp).
#include "rom_scenes_flow.hpp"

namespace cvt::analysis::rom_detail {
CVT_ROM_SCENES_INSTANTIATE(12)
}  // namespace cvt::analysis::rom_detail
