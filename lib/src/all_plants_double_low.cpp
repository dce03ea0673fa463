// AllRomPlants<double>, part low (all_plants_parts.hpp).
#include "all_plants_parts.hpp"

namespace cvt::all_plants_detail {
template IRomSimulator<double>* build_low<double>(std::uint32_t, const RomParams&, const RomSimConfig&, void*);
}  // namespace cvt::all_plants_detail
