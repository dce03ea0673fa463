#pragma once
// The parts of AllRomPlants<T>::build. Each part is explicitly instantiated
// per scalar type in its own translation unit (all_plants_<scalar>_<part>.cpp),
// so that a two-core build compiles the 91 plants in parallel.
#include <cstdint>

#include "cvtplant/scene/all_plants.hpp"

namespace cvt::all_plants_detail {

// Each part builds the plants of its set (all_plants.hpp).
template <class T>
IRomSimulator<T>* build_low(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return LowPlants<T>::build(features, p, c, storage);
}
template <class T>
IRomSimulator<T>* build_polygon(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return PolygonPlants<T>::build(features, p, c, storage);
}
template <class T>
IRomSimulator<T>* build_wedging(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return WedgingPlants<T>::build(features, p, c, storage);
}
template <class T>
IRomSimulator<T>* build_tension(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
  return TensionPlants<T>::build(features, p, c, storage);
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
