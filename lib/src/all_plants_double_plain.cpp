// AllRomPlants<double>, part plain (all_plants_parts.hpp).
#include "all_plants_parts.hpp"

namespace cvt::all_plants_detail {
template IRomSimulator<double>* build_plain<double>(std::uint32_t, const RomParams&, const RomSimConfig&, void*);
}  // namespace cvt::all_plants_detail
