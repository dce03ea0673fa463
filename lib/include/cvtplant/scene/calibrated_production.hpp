#pragma once
// The production lumps' values fitted to the multibody reference's production
// set on the controller suite's fit manoeuvres (docs/validation.md#calibrated-production),
// with their parameter file tools/params/production.toml: the radial damping,
// which sets the shift rate per unit of thrust imbalance (the derived 555.5 N s/m
// shifted 2-4 times faster than the reference), and the wrap-tension share,
// which sets the thrust ratio that holds a ratio under torque
// (docs/rom.md#wrap-tension; 0 held it 1-7 % below the reference's).
#include "cvtplant/plant/rom_params.hpp"

namespace cvt::calibrated {

constexpr void apply_production(RomParams& p) {
  p.radial_damping_Ns_m = 75000.0;
  p.wrap_tension_share = 0.125;
}

}  // namespace cvt::calibrated
