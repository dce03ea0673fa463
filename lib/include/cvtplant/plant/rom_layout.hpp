#pragma once
// Where each state of the reduced-order plant sits in its state vector, for a
// feature mask (docs/rom.md#state):
//
//   [w1 w2 x1 xd1 x2 xd2 | F_h delta delta_dot (axial) | rho rho_dot (wedging) | psi (polygon)]
//
// One function computes the layout, at compile time for a plant type
// (RomLayout<F>) and at run time for a plant behind the size-erased
// simulator interface (rom_state_index(features)), so both always agree.
#include <cstdint>

#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// Index of each state, or -1 where the feature mask has no such state.
struct RomStateIndex {
  int w1 = 0, w2 = 1, x1 = 2, xd1 = 3, x2 = 4, xd2 = 5;
  int F_h = -1, delta = -1, delta_dot = -1;  // axial
  int rho = -1, rho_dot = -1;                // wedging
  int psi = -1;                              // polygon
  int count = 6;
};

constexpr RomStateIndex rom_state_index(std::uint32_t features) {
  RomStateIndex s;
  int n = 6;
  if ((features & rom_feature::axial) != 0u) {
    s.F_h = n++;
    s.delta = n++;
    s.delta_dot = n++;
  }
  if ((features & rom_feature::wedging) != 0u) {
    s.rho = n++;
    s.rho_dot = n++;
  }
  if ((features & rom_feature::polygon) != 0u) s.psi = n++;
  s.count = n;
  return s;
}

// Name of state i as the logs write it (`cvtplant run --csv`, docs/cli.md#run).
constexpr const char* rom_state_name(std::uint32_t features, int i) {
  const RomStateIndex s = rom_state_index(features);
  constexpr const char* kCore[] = {"omega1", "omega2", "x1", "xd1", "x2", "xd2"};
  if (i >= 0 && i < 6) return kCore[i];
  if (i == s.F_h) return "F_h";
  if (i == s.delta) return "delta";
  if (i == s.delta_dot) return "delta_dot";
  if (i == s.rho) return "rho";
  if (i == s.rho_dot) return "rho_dot";
  if (i == s.psi) return "psi";
  return "?";
}

// Bit i of a state mask for state index i; nothing for an absent state (-1).
constexpr std::uint32_t rom_state_bit(int i) { return i < 0 ? 0u : 1u << i; }

// The layout of a plant type, as compile-time constants.
template <std::uint32_t F>
struct RomLayout {
  static constexpr bool kAxial = (F & rom_feature::axial) != 0;
  static constexpr bool kRoad = (F & rom_feature::road_load) != 0;
  static constexpr bool kDeform = (F & rom_feature::deformation) != 0;
  static constexpr bool kPolygon = (F & rom_feature::polygon) != 0;
  static constexpr bool kWedge = (F & rom_feature::wedging) != 0;
  // No states of its own: the chain's tension is a function of the state.
  static constexpr bool kTension = (F & rom_feature::tension) != 0;
  static_assert(!kWedge || kAxial, "the wedging feature needs the axial feature (docs/rom.md#wedging)");
  static constexpr RomStateIndex kIndex = rom_state_index(F);
  static constexpr int kW1 = kIndex.w1, kW2 = kIndex.w2, kX1 = kIndex.x1, kV1 = kIndex.xd1, kX2 = kIndex.x2,
                       kV2 = kIndex.xd2;
  // The indices of absent states are never used: every use sits under the
  // feature's `if constexpr`.
  static constexpr int kFh = kIndex.F_h, kDelta = kIndex.delta, kDeltaDot = kIndex.delta_dot;
  static constexpr int kRho = kIndex.rho, kRhoDot = kIndex.rho_dot;
  static constexpr int kPsi = kIndex.psi;
  static constexpr int kStates = kIndex.count;
  // Bit i set: state i is a position whose derivative is a velocity state
  // (semi-implicit Euler, integrate/semi_implicit_euler.hpp).
  static constexpr std::uint32_t kPositionMask = rom_state_bit(kX1) | rom_state_bit(kX2) | rom_state_bit(kDelta) |
                                                 rom_state_bit(kRho) | rom_state_bit(kPsi);
};

}  // namespace cvt
