#pragma once
// The stability watchdog of the reduced-order plant (docs/rom.md#watchdog):
// the faults a frame can latch and the per-state checks. The energy check
// lives with the ledger (rom_energy.hpp) and the simulator (rom_sim.hpp).
#include <cstdint>
#include <type_traits>

#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

enum class RomFault : std::uint8_t {
  none = 0,
  input_non_finite,   // an input was NaN/inf: the frame was not integrated
  state_non_finite,   // the step produced NaN/inf (floating point)
  state_saturated,    // a state hit the rail of the fixed-point range
  energy_growth,      // stored energy exceeds what the inputs supplied (docs/rom.md#watchdog)
  radius_out_of_range,  // wedging: the chain left the pulleys' radial travel (docs/rom.md#wedging)
  input_saturated,    // fixed point: an input at the rail of the Q range (it was clipped)
  speed_out_of_range,  // a pulley beyond RomParams::speed_limit_rad_s
  step_unresolved,    // polygon: links pass the driver faster than the step resolves (docs/rom.md#polygon)
  scene_features,     // run_frames: the simulator's features are not the scene's
  tension_out_of_range,  // tension: m' v_c^2 beyond the fixed-point range (docs/rom.md#tension)
};

inline constexpr const char* rom_fault_name(RomFault f) {
  switch (f) {
    case RomFault::none: return "none";
    case RomFault::input_non_finite: return "input-non-finite";
    case RomFault::state_non_finite: return "state-non-finite";
    case RomFault::state_saturated: return "state-saturated";
    case RomFault::radius_out_of_range: return "radius-out-of-range";
    case RomFault::energy_growth: return "energy-growth";
    case RomFault::input_saturated: return "input-saturated";
    case RomFault::speed_out_of_range: return "speed-out-of-range";
    case RomFault::step_unresolved: return "step-unresolved";
    case RomFault::scene_features: return "scene-features";
    case RomFault::tension_out_of_range: return "tension-out-of-range";
  }
  return "?";
}

// What a fault means and what the simulator did (docs/rom.md#watchdog), one
// line for messages (the FMU's log, docs/fmu.md#faults).
inline constexpr const char* rom_fault_description(RomFault f) {
  switch (f) {
    case RomFault::none: return "no fault";
    case RomFault::input_non_finite: return "an input was NaN or infinite; the frame was not integrated";
    case RomFault::state_non_finite: return "a substep produced NaN or infinity; the state was rolled back to the frame start";
    case RomFault::state_saturated: return "a fixed-point state hit the rail of the Q range; rolled back";
    case RomFault::radius_out_of_range:
      return "the chain went more than twice the radial travel from its set-up radius (the end stop could not hold it); rolled back";
    case RomFault::energy_growth:
      return "the energy ledger's residual exceeded 5 % of the flows plus 1 J (unexplained energy growth); rolled back";
    case RomFault::input_saturated: return "a fixed-point input was at the rail of the Q range (it was clipped); the frame was not integrated";
    case RomFault::speed_out_of_range: return "a pulley was faster than speed_limit_rad_s (outside the model); rolled back";
    case RomFault::step_unresolved:
      return "links passed the driver faster than the step resolves with 8 steps per link; rolled back";
    case RomFault::scene_features: return "the simulator's features are not the scene's; nothing ran";
    case RomFault::tension_out_of_range:
      return "the chain's centrifugal tension left the fixed-point range; rolled back";
  }
  return "?";
}

// x - x is +0 for every finite x and NaN for NaN and +-inf, and NaN stays NaN
// through a sum: the sum of x_i - x_i over a vector is 0 exactly when every
// x_i is finite. One comparison for the whole vector instead of two per
// component (the frame's checks, docs/rom.md#cost); needs the arithmetic done
// as written (no -ffast-math, which would fold x - x to 0).
template <class T>
inline bool rom_all_finite_zero(const T& sum_of_differences) {
  return sum_of_differences == T(0);
}

// False for NaN and +-inf; fixed point has neither.
template <class T>
inline bool rom_finite(const T& v) {
  if constexpr (std::is_floating_point_v<T>) {
    return v == v && v - v == v - v;  // NaN fails the first, +-inf the second
  } else {
    (void)v;
    return true;
  }
}

// The fault of a frame's inputs: non-finite (floating point) or at the rail
// of the Q range (fixed point: the value did not fit and was clipped when it
// was converted), else none.
template <class T>
inline RomFault rom_input_fault(const T& tau_in, const T& tau_load, const T& clamp) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!rom_all_finite_zero((tau_in - tau_in) + (tau_load - tau_load) + (clamp - clamp)))
      return RomFault::input_non_finite;
  } else {
    auto rail = [](const T& v) { return v == T::max() || v == T::lowest(); };
    if (rail(tau_in) || rail(tau_load) || rail(clamp)) return RomFault::input_saturated;
  }
  return RomFault::none;
}

// The first fault a state shows: a non-finite component (floating point) or
// one at the rail of the fixed-point range (saturated), else none.
template <class State>
inline RomFault rom_state_fault(const State& x) {
  using T = typename State::Scalar;
  if constexpr (std::is_floating_point_v<T>) {
    T z = x(0) - x(0);
    #pragma GCC unroll 16
    for (int i = 1; i < State::RowsAtCompileTime; ++i) z += x(i) - x(i);
    return rom_all_finite_zero(z) ? RomFault::none : RomFault::state_non_finite;
  } else {
    for (int i = 0; i < x.size(); ++i)
      if (x(i) == T::max() || x(i) == T::lowest()) return RomFault::state_saturated;
    return RomFault::none;
  }
}

}  // namespace cvt
