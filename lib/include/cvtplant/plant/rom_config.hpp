#pragma once
// What every piece of the plant (plant/feature/*.hpp) knows about the plant
// type it is part of: the scalar, the state layout, the internal units and
// which features the type carries (docs/rom.md#features).
//
// A feature bit of a plant type is either compiled in (its states and code
// always there: F), carried but switched at set-up (its code compiled in, a
// run-time flag: D, only for the stateless features of
// rom_feature::runtime_capable, which the host tools' dispatch uses to
// compile fewer plant types, docs/rom.md#build-time), or absent (neither
// states nor code).
#include <cstdint>

#include <Eigen/Core>

#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_features.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/plant/rom_units.hpp"

namespace cvt {

template <class T, std::uint32_t F, std::uint32_t D = 0>
struct RomConfig {
  static_assert((D & ~rom_feature::runtime_capable) == 0u,
                "only features without states can be switched at run time (rom_feature::runtime_capable)");
  static_assert((F & D) == 0u, "a feature is either compiled in or switched at run time");
  static_assert(rom_feature_conflict(F) == nullptr, "the feature mask is not a plant (rom_feature_conflict)");

  using Scalar = T;
  using Layout = RomLayout<F>;
  using U = RomUnits<T>;
  using Acc = RomAcc<T>;
  static constexpr int N = Layout::kStates;
  static constexpr std::uint32_t kStatic = F, kRuntime = D;
  // Compiled in (always on).
  static constexpr bool on(std::uint32_t bit) { return (F & bit) != 0u; }
  // Its code compiled in: always on, or on when the plant's run-time mask says so.
  static constexpr bool carried(std::uint32_t bit) { return ((F | D) & bit) != 0u; }

  static constexpr bool kAxial = on(rom_feature::axial);
  static constexpr bool kRadial = on(rom_feature::wedging);
  static constexpr bool kPolygon = on(rom_feature::polygon);
  static constexpr bool kTension = on(rom_feature::tension);

  template <class S>
  using Vec = Eigen::Matrix<S, N, 1>;
  using State = Vec<T>;
  using Jacobian = Eigen::Matrix<T, N, N>;

  // One time unit in the plant's type (RomUnits; 1 except fixed point).
  static constexpr T kTimeUnit = T(U::time_s);
  // A rate per second as a rate per time unit (docs/rom.md#fixed-point). The
  // factor is applied to each equation's SI result, before anything large
  // multiplies it, so no intermediate leaves the fixed-point range.
  template <class S>
  static S per_tau(const S& v) {
    if constexpr (U::kScaled) return v * S(kTimeUnit);
    return v;
  }
};

// The names a feature's class (plant/feature/*.hpp) works in, from its
// plant configuration Cfg: the scalar T, layout L, units U, accumulator Acc,
// State and Vec<S>. One list for every feature: a class template cannot take
// member type names from a dependent base without restating them.
#define CVT_ROM_FEATURE_TYPES(Cfg)   \
  using T = typename Cfg::Scalar;    \
  using L = typename Cfg::Layout;    \
  using U = typename Cfg::U;         \
  using Acc = typename Cfg::Acc;     \
  using State = typename Cfg::State; \
  template <class S>                 \
  using Vec = typename Cfg::template Vec<S>

// A feature of a plant whose scene asked for it: compiled in, or carried and
// switched on at set-up (`features`, the plant's run-time mask).
template <class Cfg>
constexpr bool rom_feature_on(std::uint32_t features, std::uint32_t bit) {
  return Cfg::on(bit) || (Cfg::carried(bit) && (features & bit) != 0u);
}

}  // namespace cvt
