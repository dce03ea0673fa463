// AllRomPlants<q16_16>, part plain (all_plants_parts.hpp).
#include "all_plants_parts.hpp"

namespace cvt::all_plants_detail {
template IRomSimulator<q16_16>* build_plain<q16_16>(std::uint32_t, const RomParams&, const RomSimConfig&, void*);
}  // namespace cvt::all_plants_detail
