#pragma once
// The analytic Jacobian of a reduced-order plant at a state against the
// dual-number Jacobian of the same right-hand side (docs/rom.md#jacobian),
// and optionally against its central differences: shared by the plant's
// tests (test_rom_core.cpp, test_rom_tension.cpp, ...).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cvtplant/integrate/system.hpp"
#include "cvtplant/plant/cvt_rom.hpp"

namespace rom_test {

// Table 1 parameters with the built-in road load (docs/rom.md#road-load).
inline cvt::RomParams road_load_params() {
  cvt::RomParams p;
  p.road_T0_Nm = 10.0;
  p.road_cv_Nms_rad = 0.05;
  p.road_ca_Nms2_rad2 = 0.002;
  return p;
}

// A plant at the tests' torques (80 / 40 N m) and clamping force.
template <std::uint32_t F>
cvt::CvtRom<double, F> loaded_plant(const cvt::RomParams& p, double clamp_N) {
  cvt::CvtRom<double, F> rom(p);
  rom.inputs.tau_in_Nm = 80.0;
  rom.inputs.tau_load_Nm = 40.0;
  rom.inputs.clamp_N = clamp_N;
  return rom;
}

// x0's state with every component moved off its symmetric value, so each
// partial is exercised.
template <class Rom>
typename Rom::State offset_state(const Rom& rom, const cvt::RomInitial& x0) {
  typename Rom::State x = rom.initial_state(x0);
  for (int i = 0; i < Rom::kStates; ++i) x(i) += 1e-3 * (i + 1);
  return x;
}

template <class Rom>
void check_jacobian_at(const Rom& rom, const typename Rom::State& x, bool central_differences) {
  using L = typename Rom::Layout;
  const cvt::RomParams& p = rom.params();
  // A held pulley's column is zero by design (docs/rom.md#jacobian): it
  // multiplies an increment that is always zero.
  auto held = [&](int j) { return (j == L::kW1 && p.hold_driver_speed) || (j == L::kW2 && p.hold_driven_speed); };
  typename Rom::Jacobian Ja, Jd;
  rom.jacobian(x, Ja);
  cvt::jacobian_by_duals(rom, x, Jd);
  for (int i = 0; i < Rom::kStates; ++i)
    for (int j = 0; j < Rom::kStates; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      // Both are exact derivatives of the same expression: only rounding differs.
      CHECK(Ja(i, j) == doctest::Approx(held(j) ? 0.0 : Jd(i, j)).epsilon(1e-10).scale(1.0));
    }
  if (!central_differences) return;
  // Step 1e-6 of each state's size: away from stick, where the atan sign's
  // curvature would need a finer one.
  double worst = 0;
  for (int j = 0; j < Rom::kStates; ++j) {
    if (held(j)) continue;
    const double h = 1e-6 * std::max(1.0, std::fabs(x(j)));
    typename Rom::State xp = x, xm = x, fp, fm;
    xp(j) += h;
    xm(j) -= h;
    rom.derivative(xp, fp);
    rom.derivative(xm, fm);
    for (int i = 0; i < Rom::kStates; ++i) {
      const double cd = (fp(i) - fm(i)) / (2 * h);
      worst = std::max(worst, std::fabs(Ja(i, j) - cd) / (1e-4 * std::fabs(cd) + 1e-3));
    }
  }
  CHECK(worst < 1.0);
}

}  // namespace rom_test
