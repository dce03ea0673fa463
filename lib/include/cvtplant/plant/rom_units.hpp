#pragma once
// Internal units of the reduced-order plant (docs/rom.md#fixed-point).
#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

// Internal units of the plant (docs/rom.md#fixed-point). Floating point runs
// in SI: every factor is 1 and folds away at compile time, so float and
// double results are those of the plain SI equations, bit for bit. Fixed point
// measures time in units of 2^-10 s and the lump and sheave displacements in
// 2^-10 m: the stick stiffness per time unit (1.2e4 at 3.3 kN) and the bolt
// stiffness per length unit (1483 N) then fit q16.16, and the step is 0.512
// units instead of 33 LSB of seconds. Velocities stay in m/s and rad/s, since
// 2^-10 m per 2^-10 s is 1 m/s: position rows need no factor at all.
// Scaling and overflow, per scalar type (as CMSIS-DSP documents its q formats):
//   double, float  SI units; overflow gives +-inf or NaN, which the
//                  simulator's watchdog reports (state-non-finite).
//   Fixed<F>       time in 2^-10 s, x1, x2 and delta in 2^-10 m, the creep
//                  strain's denominator in 1024 N, everything else in SI. Every operation saturates at lowest()/max()
//                  instead of wrapping (scalar/fixed.hpp); a state at a rail
//                  is reported by the watchdog (state-saturated). Rates are
//                  scaled by per_tau() before anything large multiplies them,
//                  so no intermediate leaves the q16.16 range in the built-in
//                  scenes (docs/rom.md#fixed-point has the ranges).
template <class T>
struct RomUnits {
  static constexpr bool kScaled = false;
  static constexpr double time_s = 1.0;    // one time unit [s]
  static constexpr double length_m = 1.0;  // one unit of x1, x2, delta [m]
  static constexpr double tension_N = 1.0;  // unit of the creep strain's denominator kL + T_s (docs/rom.md#tension) [N]
};
template <int FracBits>
struct RomUnits<Fixed<FracBits>> {
  static constexpr bool kScaled = true;
  static constexpr double time_s = 1.0 / 1024.0;
  static constexpr double length_m = time_s;  // = time unit x 1 m/s
  // kL + T_s is a few kN: its inverse in 1/N would be 20 LSB, in 1/(1024 N) 2e4.
  static constexpr double tension_N = 1024.0;
};

}  // namespace cvt
