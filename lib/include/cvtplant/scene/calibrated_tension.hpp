#pragma once
// The real-time plant's lumped parameters fitted to the multibody reference
// (docs/validation.md#calibration), written with the parameter file by:
//   cvtplant calibrate --scene seed-case1 --fit centrifugal_gain,stop_tension_share --start tools/params/tension-uncalibrated.toml --rtol 5e-07 --every 10 --max-evals 400 --out tools/params/tension.toml --header lib/include/cvtplant/scene/calibrated_tension.hpp --function apply_tension
// rms residual 0.007102 -> 0.005005 over 4004 residuals.
#include "cvtplant/plant/rom_params.hpp"

namespace cvt::calibrated {

constexpr void apply_tension(RomParams& p) {
  p.centrifugal_gain = 1.7354691179494748;
  p.stop_tension_share = 0.11228898872804133;
}

}  // namespace cvt::calibrated
