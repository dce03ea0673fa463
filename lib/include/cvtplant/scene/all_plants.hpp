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

// The parts of the set, each compiled in translation units of its own
// (lib/src/all_plants_<scalar>_<part>.cpp); the one place their masks are
// written.
// The core plant with axial, road load and deformation.
template <class T>
using LowPlants = RomPlantSet<T, 0, 1, 2, 3, 4, 5, 6, 7>;
// The same with polygon.
template <class T>
using PolygonPlants = RomPlantSet<T, 8, 9, 10, 11, 12, 13, 14, 15>;
// Wedging (which needs axial), with any of road load, deformation and
// polygon; floating point only.
template <class T>
using WedgingPlants = RomPlantSet<T, 17, 19, 21, 23, 25, 27, 29, 31>;
// Tension with any of axial, road load and deformation (docs/rom.md#tension),
// and tension with polygon, for the link-passing ripple's scene
// (tools/scenes/seed-case1-ripple.toml, docs/rom.md#link-ripple).
template <class T>
using TensionPlants = RomPlantSet<T, 32, 33, 34, 35, 36, 37, 38, 39, 40>;

// The plant set of the masks of several sets.
template <class... Sets>
struct Joined;
template <class Set>
struct Joined<Set> {
  using type = Set;
};
template <class T, std::uint32_t... A, std::uint32_t... B, class... Rest>
struct Joined<RomPlantSet<T, A...>, RomPlantSet<T, B...>, Rest...> : Joined<RomPlantSet<T, A..., B...>, Rest...> {};

// Every mask of scalar T; the storage size and alignment come from this set,
// the code from lib/src.
template <class T>
using Masks = std::conditional_t<kHasWedging<T>,
                                 typename Joined<LowPlants<T>, PolygonPlants<T>, WedgingPlants<T>, TensionPlants<T>>::type,
                                 typename Joined<LowPlants<T>, PolygonPlants<T>, TensionPlants<T>>::type>;
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
