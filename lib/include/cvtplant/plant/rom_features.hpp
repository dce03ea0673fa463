#pragma once
// The plant's optional physics as feature bits (docs/rom.md#features): one
// list of the bits, their names, what each needs and which combinations
// mean nothing. Each feature's physics is one file under plant/feature/;
// CvtRom (cvt_rom.hpp) composes the ones a plant type names.
#include <cstdint>

namespace cvt {

namespace rom_feature {
inline constexpr std::uint32_t axial = 1u << 0;        // driver clamping actuator lag + sheave axial DOF, F_ax = bolt force
inline constexpr std::uint32_t road_load = 1u << 1;    // tau_load += T0 tanh(w2/w_eps) + c_v w2 + c_a w2|w2|
inline constexpr std::uint32_t deformation = 1u << 2;  // seed Eq. 3-4 flank angle per lump
inline constexpr std::uint32_t polygon = 1u << 3;      // chordal action of the driver wrap and the link ripple (phase psi)
inline constexpr std::uint32_t wedging = 1u << 4;      // radial chain DOF, seed Eq. 7, variable ratio, driven clamping (needs axial)
inline constexpr std::uint32_t tension = 1u << 5;      // chain tension: creep, centrifugal tension, sheave stops
// The first four features, each of which every scalar type supports.
inline constexpr std::uint32_t basic = axial | road_load | deformation | polygon;
// The first five: every state a plant can have (wedging is floating point only).
inline constexpr std::uint32_t all = basic | wedging;
// Every defined bit; every combination of them is a plant (rom_feature_conflict).
inline constexpr std::uint32_t known = all | tension;
// Features without states of their own whose code a plant type can carry
// and switch at set-up instead of at compile time (CvtRom's run-time bits):
// the host tools' scene dispatch compiles one plant for each combination of
// the others (docs/rom.md#build-time). Firmware names every bit at compile
// time and carries none of these branches.
inline constexpr std::uint32_t runtime_capable = road_load | deformation;
}  // namespace rom_feature

// A feature's name as scene files spell it (docs/rom.md#scene-files).
struct RomFeatureName {
  const char* name;
  std::uint32_t bit;
};
inline constexpr RomFeatureName kRomFeatureNames[] = {
    {"axial", rom_feature::axial},     {"road_load", rom_feature::road_load}, {"deformation", rom_feature::deformation},
    {"polygon", rom_feature::polygon}, {"wedging", rom_feature::wedging},     {"tension", rom_feature::tension}};

// Why a feature mask is not a plant, or nullptr: an unknown bit, or a
// feature without one it needs. Every other combination composes.
constexpr const char* rom_feature_conflict(std::uint32_t features) {
  if ((features & ~rom_feature::known) != 0u) return "unknown feature bit";
  if ((features & rom_feature::wedging) != 0u && (features & rom_feature::axial) == 0u)
    return "wedging needs the axial feature (the bolt force depends on the chain's radial position)";
  return nullptr;
}

}  // namespace cvt
