#pragma once
// The real-time plant's lumped parameters fitted to the multibody reference
// (docs/validation.md#calibration), written with the parameter file by:
//   cvtplant calibrate --scene tools/scenes/seed-case1-wedging.toml --fit wrap_tension_share --t-end 1 --rtol 5e-07 --every 10 --max-evals 400 --out tools/params/wrap-tension.toml --header lib/include/cvtplant/scene/calibrated_wrap_tension.hpp --function apply_wrap_tension
// rms residual 0.0304 -> 0.02007 over 404 residuals.
#include "cvtplant/plant/rom_params.hpp"

namespace cvt::calibrated {

constexpr void apply_wrap_tension(RomParams& p) {
  p.wrap_tension_share = 0.16856922773171393;
}

}  // namespace cvt::calibrated
