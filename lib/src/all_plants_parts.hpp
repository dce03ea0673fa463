#pragma once
// The parts of AllRomPlants<T>::build (scene/all_plants.hpp). Each part is
// explicitly instantiated per scalar type in its own translation unit
// (all_plants_<scalar>_<part>.cpp), so that a two-core build compiles the 32
// plant types in parallel.
#include <cstdint>

#include "cvtplant/scene/all_plants.hpp"

namespace cvt::all_plants_detail {

// The core plant with axial and polygon (road load and deformation at set-up).
template <class T>
IRomSimulator<T>* build_plain(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return Plain<T>::build(features, p, c, storage);
}
// The same with the chain's tension state (docs/rom.md#tension).
template <class T>
IRomSimulator<T>* build_tension(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return Tension<T>::build(features, p, c, storage);
}
// The variable-ratio plants (wedging needs axial), with polygon and tension;
// floating point only (docs/rom.md#wedging).
template <class T>
IRomSimulator<T>* build_wedging(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return Wedging<T>::build(features, p, c, storage);
}

// Instantiated in the part translation units only.
#define CVT_ALL_PLANTS_PART(part, T) \
  extern template IRomSimulator<T>* part<T>(std::uint32_t, const RomParams&, const RomSimConfig&, void*);
CVT_ALL_PLANTS_PART(build_plain, double)
CVT_ALL_PLANTS_PART(build_tension, double)
CVT_ALL_PLANTS_PART(build_wedging, double)
CVT_ALL_PLANTS_PART(build_plain, float)
CVT_ALL_PLANTS_PART(build_tension, float)
CVT_ALL_PLANTS_PART(build_wedging, float)
CVT_ALL_PLANTS_PART(build_plain, q16_16)
CVT_ALL_PLANTS_PART(build_tension, q16_16)
#undef CVT_ALL_PLANTS_PART

}  // namespace cvt::all_plants_detail
