#pragma once
// The real-time plant's lumped parameters fitted to the multibody reference
// (docs/validation.md#calibration), written with the parameter file by:
//   cvtplant calibrate --scene gross-slip --fit normal_load_factor --rtol 5e-07 --every 10 --max-evals 400 --out tools/params/calibrated.toml --header lib/include/cvtplant/scene/calibrated_params.hpp
// rms residual 0.2449 -> 0.006126 over 4004 residuals.
#include "cvtplant/plant/rom_params.hpp"

namespace cvt::calibrated {

constexpr void apply(RomParams& p) {
  p.normal_load_factor = 0.85415113819893507;
}

}  // namespace cvt::calibrated
