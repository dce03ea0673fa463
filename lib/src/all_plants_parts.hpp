#pragma once
// The parts of AllRomPlants<T>::build. Each part is explicitly instantiated
// per scalar type in its own translation unit (all_plants_<scalar>_<part>.cpp),
// so that a two-core build compiles the 91 plants in parallel.
#include <cstdint>

#include "cvtplant/scene/all_plants.hpp"

namespace cvt::all_plants_detail {

// Masks 0..7: the core plant with axial, road load and deformation.
template <class T>
IRomSimulator<T>* build_low(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return RomPlantSet<T, 0, 1, 2, 3, 4, 5, 6, 7>::build(features, p, c, storage);
}
// Masks 8..15: the same with polygon.
template <class T>
IRomSimulator<T>* build_polygon(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return RomPlantSet<T, 8, 9, 10, 11, 12, 13, 14, 15>::build(features, p, c, storage);
}
// Masks 17..31 (odd): wedging, floating point only.
template <class T>
IRomSimulator<T>* build_wedging(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return RomPlantSet<T, 17, 19, 21, 23, 25, 27, 29, 31>::build(features, p, c, storage);
}

// Masks 32..39: tension with axial, road load and deformation (docs/rom.md#tension);
// mask 40, tension with polygon, for the link-passing ripple's scene
// (tools/scenes/seed-case1-ripple.toml, docs/rom.md#link-ripple).
template <class T>
IRomSimulator<T>* build_tension(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return RomPlantSet<T, 32, 33, 34, 35, 36, 37, 38, 39, 40>::build(features, p, c, storage);
}

// Instantiated in the part translation units only.
extern template IRomSimulator<double>* build_low<double>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                void*);
extern template IRomSimulator<double>* build_polygon<double>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                    void*);
extern template IRomSimulator<double>* build_wedging<double>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                    void*);
extern template IRomSimulator<float>* build_low<float>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                              void*);
extern template IRomSimulator<float>* build_polygon<float>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                  void*);
extern template IRomSimulator<float>* build_wedging<float>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                  void*);
extern template IRomSimulator<q16_16>* build_low<q16_16>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                void*);
extern template IRomSimulator<q16_16>* build_polygon<q16_16>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                    void*);
extern template IRomSimulator<double>* build_tension<double>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                    void*);
extern template IRomSimulator<float>* build_tension<float>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                  void*);
extern template IRomSimulator<q16_16>* build_tension<q16_16>(std::uint32_t, const RomParams&, const RomSimConfig&,
                                                    void*);

}  // namespace cvt::all_plants_detail
