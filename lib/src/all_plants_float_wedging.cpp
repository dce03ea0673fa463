// AllRomPlants<float>, part wedging (all_plants_parts.hpp).
#include "all_plants_parts.hpp"

namespace cvt::all_plants_detail {
template IRomSimulator<float>* build_wedging<float>(std::uint32_t, const RomParams&, const RomSimConfig&, void*);
}  // namespace cvt::all_plants_detail
