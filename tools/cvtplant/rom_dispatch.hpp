#pragma once
// Maps a scene's run-time scalar kind and feature mask onto the compile-time
// plant type (docs/rom.md#features). Every valid combination of the feature
// bits is instantiated, so any scene file runs; firmware instantiates only
// the plant it ships.
#include <cstdint>
#include <type_traits>

#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvtcli {

// fn.template call<T, F>() for the scalar/features of the scene.
template <class T, class Fn>
decltype(auto) with_features(std::uint32_t features, Fn&& fn) {
  // Wedging (bit 4) comes with axial (bit 0) and floating point only
  // (validate_scene rejects the rest before a run): 8 more plants per scalar.
  if constexpr (std::is_floating_point_v<T>) {
    switch (features & cvt::rom_feature::all) {
#define CVT_ROM_CASE(N) \
  case N: return fn.template call<T, N>();
      CVT_ROM_CASE(17) CVT_ROM_CASE(19) CVT_ROM_CASE(21) CVT_ROM_CASE(23)
      CVT_ROM_CASE(25) CVT_ROM_CASE(27) CVT_ROM_CASE(29) CVT_ROM_CASE(31)
#undef CVT_ROM_CASE
      default: break;
    }
  }
  switch (features & cvt::rom_feature::basic) {
#define CVT_ROM_CASE(N) \
  case N: return fn.template call<T, N>();
    CVT_ROM_CASE(0) CVT_ROM_CASE(1) CVT_ROM_CASE(2) CVT_ROM_CASE(3)
    CVT_ROM_CASE(4) CVT_ROM_CASE(5) CVT_ROM_CASE(6) CVT_ROM_CASE(7)
    CVT_ROM_CASE(8) CVT_ROM_CASE(9) CVT_ROM_CASE(10) CVT_ROM_CASE(11)
    CVT_ROM_CASE(12) CVT_ROM_CASE(13) CVT_ROM_CASE(14)
#undef CVT_ROM_CASE
    default: return fn.template call<T, 15>();
  }
}

// Calls the entry point for `scalar`. Commands keep one entry point per
// scalar, each in its own translation unit (cmd_<name>_{double,float,fixed}.cpp,
// calling with_features<T>), so the 64 plant types compile in parallel.
template <class R, class Arg>
R by_scalar(cvt::ScalarKind scalar, Arg& arg, R (*f64)(Arg&), R (*f32)(Arg&), R (*q16)(Arg&)) {
  switch (scalar) {
    case cvt::ScalarKind::f32: return f32(arg);
    case cvt::ScalarKind::q16_16: return q16(arg);
    case cvt::ScalarKind::f64:
    default: return f64(arg);
  }
}

}  // namespace cvtcli
