// AllRomPlants<T>::build: asks each part (all_plants_parts.hpp) in turn.
#include "all_plants_parts.hpp"

namespace cvt {

template <class T>
IRomSimulator<T>* AllRomPlants<T>::build(std::uint32_t features, const RomParams& p, const RomSimConfig& c,
                                         void* storage) {
  using namespace all_plants_detail;
  if (IRomSimulator<T>* s = build_plain<T>(features, p, c, storage)) return s;
  if (IRomSimulator<T>* s = build_tension<T>(features, p, c, storage)) return s;
  if constexpr (kHasWedging<T>) return build_wedging<T>(features, p, c, storage);
  return nullptr;
}

template struct AllRomPlants<double>;
template struct AllRomPlants<float>;
template struct AllRomPlants<q16_16>;

}  // namespace cvt
