#pragma once
// Every scene key under [params] (docs/rom.md#scene-files): each feature's
// file lists its own (plant/feature/*.hpp); this gathers the lists, so a
// set-up value a feature adds is read from scene files and parameter files
// where the feature declares it.
#include "cvtplant/plant/feature/axial.hpp"
#include "cvtplant/plant/feature/deformation.hpp"
#include "cvtplant/plant/feature/drive_train.hpp"
#include "cvtplant/plant/feature/polygon.hpp"
#include "cvtplant/plant/feature/radial.hpp"
#include "cvtplant/plant/feature/road_load.hpp"
#include "cvtplant/plant/feature/tension.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// f(const RomParamKey&) for every key, the core's first, then the
// features' in the order of their bits.
template <class F>
void for_each_rom_param_key(F&& f) {
  for (const RomParamKey& k : kRomDriveTrainKeys) f(k);
  for (const RomParamKey& k : kRomAxialKeys) f(k);
  for (const RomParamKey& k : kRomRoadLoadKeys) f(k);
  for (const RomParamKey& k : kRomDeformationKeys) f(k);
  for (const RomParamKey& k : kRomPolygonKeys) f(k);
  for (const RomParamKey& k : kRomRadialKeys) f(k);
  for (const RomParamKey& k : kRomTensionKeys) f(k);
}

}  // namespace cvt
