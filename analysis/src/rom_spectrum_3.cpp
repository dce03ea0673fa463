// The ROM spectrum and trajectory for plants of 10 states (rom_scenes_flow.hpp).
#include "rom_scenes_flow.hpp"

namespace cvt::analysis::rom_detail {
CVT_ROM_SCENES_INSTANTIATE(10)
}  // namespace cvt::analysis::rom_detail
