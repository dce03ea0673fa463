#pragma once
// Every plant of every scalar type, for the host tools (the CLI, the analysis
// toolkit, the SIL bridge): every feature combination a scene can ask for
// (rom_feature_conflict), in double and float, and every one without
// wedging in q16.16. The stateless features road load and deformation are
// carried by every plant and switched at set-up (CvtRom's run-time bits), so
// the combinations of the others are the plant types: in double and float
// the 8 of axial, polygon and tension and the 4 with wedging (which needs
// axial) with polygon and tension, in q16.16 the 8 without wedging; 32 types
// for the 128 combinations (docs/rom.md#build-time). Their code is compiled
// once, split over several translation units in lib/src/ so a build
// compiles them in parallel, and linked from the cvtplant::all_plants
// library; a caller of AllRomPlants<T>::build compiles none of it. Firmware
// uses a RomPlantSet of the masks it ships instead (scene/plant_set.hpp),
// every bit compiled in.
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "cvtplant/scalar/fixed.hpp"
#include "cvtplant/scene/plant_set.hpp"

namespace cvt {

namespace all_plants_detail {
namespace f = rom_feature;
// The bits every host plant carries and switches at set-up.
inline constexpr std::uint32_t kRuntime = rom_feature::runtime_capable;
template <class T>
constexpr bool kHasWedging = std::is_floating_point<T>::value;
// The parts of the set, each compiled in translation units of its own
// (lib/src/all_plants_<scalar>_<part>.cpp); the one place their masks are
// written.
// The core plant with axial and polygon (road load and deformation at set-up).
template <class T>
using Plain = RomPlantSetRt<T, kRuntime, 0, f::axial, f::polygon, f::axial | f::polygon>;
// The same with the chain's tension state (docs/rom.md#tension).
template <class T>
using Tension = RomPlantSetRt<T, kRuntime, f::tension, f::tension | f::axial, f::tension | f::polygon,
                              f::tension | f::axial | f::polygon>;
// The variable-ratio plants (wedging needs axial), with polygon and tension;
// floating point only (docs/rom.md#wedging, #tension-radial).
template <class T>
using Wedging = RomPlantSetRt<T, kRuntime, f::axial | f::wedging, f::axial | f::wedging | f::polygon,
                              f::axial | f::wedging | f::tension, f::axial | f::wedging | f::polygon | f::tension>;

// The plant set of the masks of several sets.
template <class... Sets>
struct Joined;
template <class Set>
struct Joined<Set> {
  using type = Set;
};
template <class T, std::uint32_t R, std::uint32_t... A, std::uint32_t... B, class... Rest>
struct Joined<RomPlantSetRt<T, R, A...>, RomPlantSetRt<T, R, B...>, Rest...>
    : Joined<RomPlantSetRt<T, R, A..., B...>, Rest...> {};

// Every mask of scalar T; the storage size and alignment come from this set,
// the code from lib/src.
template <class T>
using Masks = std::conditional_t<kHasWedging<T>, typename Joined<Plain<T>, Tension<T>, Wedging<T>>::type,
                                 typename Joined<Plain<T>, Tension<T>>::type>;
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
