#pragma once
// Every plant of every scalar type, for the host tools (the CLI, the analysis
// toolkit, the SIL bridge): in double and float 33 feature masks, the 16 of
// the first four features, the 8 with wedging (which needs axial), the 8
// with tension and any of axial, road load and deformation, and tension with
// polygon (the link-passing ripple's scene); in q16.16 the 25 without
// wedging. Their code is compiled once, split
// over several translation units in lib/src/ so a build compiles them in
// parallel, and linked from the cvtplant::all_plants library; a caller of
// AllRomPlants<T>::build compiles none of it. Firmware uses a RomPlantSet of
// the masks it ships instead (scene/plant_set.hpp).
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "cvtplant/scalar/fixed.hpp"
#include "cvtplant/scene/plant_set.hpp"

namespace cvt {

namespace all_plants_detail {
template <class T>
constexpr bool kHasWedging = std::is_floating_point<T>::value;
// Every mask of scalar T; the storage size and alignment come from this set,
// the code from lib/src.
template <class T>
using Masks = std::conditional_t<kHasWedging<T>,
                                 RomPlantSet<T, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 17, 19, 21, 23,
                                             25, 27, 29, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40>,
                                 RomPlantSet<T, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 32, 33, 34, 35,
                                             36, 37, 38, 39, 40>>;
}  // namespace all_plants_detail

template <class T>
struct AllRomPlants {
  using Scalar = T;
  static constexpr std::size_t kSize = all_plants_detail::Masks<T>::kSize;
  static constexpr std::size_t kAlign = all_plants_detail::Masks<T>::kAlign;
  static constexpr bool contains(std::uint32_t features) { return all_plants_detail::Masks<T>::contains(features); }
  // Defined in lib/src/all_plants.cpp.
  static IRomSimulator<T>* build(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage);
  // RomPlantSet::visit over every mask: compiles f for each of them in the
  // caller (a copy or a byte image of the simulator, never its step).
  template <class Sim, class Fn>
  static bool visit(Sim& sim, Fn&& f) {
    return all_plants_detail::Masks<T>::visit(sim, static_cast<Fn&&>(f));
  }
};

extern template struct AllRomPlants<double>;
extern template struct AllRomPlants<float>;
extern template struct AllRomPlants<q16_16>;

}  // namespace cvt
