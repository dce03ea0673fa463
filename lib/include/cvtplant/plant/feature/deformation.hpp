#pragma once
// Feature `deformation` (docs/rom.md#deformation): the sheave's elastic
// deformation tilts the flank each lump presses on, seed Eq. 3-4,
//   beta_i = beta0 + Delta/2 sin(zeta_i - theta_c + pi/2).
// The lumps sit at fixed wrap angles, so the feature is a set-up choice of
// the flank angles: no state, no per-step cost, and every plant type can
// switch it at set-up (rom_feature::runtime_capable).
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// The flank half angles the two lumps press on [rad] and their tangents.
struct RomFlankAngles {
  double beta1_rad = 0.0, beta2_rad = 0.0;
  double tan_beta[2] = {0.0, 0.0};
};

// beta0 for both lumps, or seed Eq. 3-4 at their wrap angles zeta_i with
// Delta and theta_c from the set-up ratio r1/r2.
inline RomFlankAngles rom_flank_angles(const RomParams& p, bool deformation) {
  RomFlankAngles b;
  b.beta1_rad = b.beta2_rad = p.beta0_rad;
  if (deformation) {
    const double ratio = p.r1_m / p.r2_m;
    const double Delta = seed::deformation_amplitude_rad(ratio);
    const double theta_c = seed::deformation_centre_rad(ratio);
    b.beta1_rad = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta1_rad);
    b.beta2_rad = seed::flank_angle_rad(p.beta0_rad, Delta, theta_c, p.zeta2_rad);
  }
  b.tan_beta[0] = dm::sin(b.beta1_rad) / dm::cos(b.beta1_rad);
  b.tan_beta[1] = dm::sin(b.beta2_rad) / dm::cos(b.beta2_rad);
  return b;
}

}  // namespace cvt
