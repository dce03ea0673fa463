// Proof that cvt::dm calls no libm transcendental (docs/numerics.md#detmath).
//
// 1. Compile time: every libm name that cvt::dm does not itself define is
//    poisoned BEFORE detmath.hpp is read, so any use of it inside the header
//    (or inside anything the header pulls in afterwards) is a hard error. The
//    headers detmath.hpp depends on are included first: their own mentions of
//    these names are lexed before the poison and are harmless.
// 2. Link level: the double names (sin, cos, exp, atan, tanh) cannot be
//    poisoned because cvt::dm defines functions with those names. For them,
//    ctest `lib.detmath_no_libm` runs nm on this object file and fails on any
//    undefined reference to a libm function (lib/tests/check_no_libm.cmake).
//    This TU instantiates every dm function for every scalar type, so the
//    object contains every call the header can make.
#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#pragma GCC poison sinf cosf tanf expf exp2f expm1f atanf atan2f tanhf sinhf coshf logf log1pf powf asinf acosf
#pragma GCC poison sinl cosl tanl expl exp2l expm1l atanl atan2l tanhl sinhl coshl logl log1pl powl asinl acosl
#pragma GCC poison tan exp2 expm1 atan2 sinh cosh log log1p log2 log10 pow asin acos fmod remainder sincos sincosf
#pragma GCC poison __builtin_sin __builtin_cos __builtin_tan __builtin_exp __builtin_atan __builtin_tanh
#pragma GCC poison __builtin_sinf __builtin_cosf __builtin_tanf __builtin_expf __builtin_atanf __builtin_tanhf
#pragma GCC poison __builtin_log __builtin_logf __builtin_pow __builtin_powf __builtin_atan2 __builtin_atan2f

#include "cvtplant/math/detmath.hpp"

namespace {

// volatile inputs keep the compiler from folding the calls away, so the
// object file really contains each code path.
template <class T>
T exercise(T x) {
  return cvt::abs(x) + cvt::sqrt(cvt::abs(x)) + cvt::atan(x) + cvt::exp(x) + cvt::tanh(x) + cvt::sin(x) + cvt::cos(x) +
         cvt::sign(x);
}

}  // namespace

TEST_CASE("detmath poison TU: every function for every type compiles without libm names") {
  volatile double d = 0.5;
  volatile float f = 0.5f;
  volatile std::int32_t r = 32768;
  const double yd = exercise<double>(d);
  const float yf = exercise<float>(f);
  const auto yq = exercise<cvt::q16_16>(cvt::q16_16::from_raw(r));
  // abs+sqrt+atan+exp+tanh+sin+cos+sign at 0.5 = 0.5+0.70711+0.46365+1.64872+0.46212+0.47943+0.87758+1
  const double expect = 6.138603;
  CHECK(yd == doctest::Approx(expect).epsilon(1e-6));
  CHECK(static_cast<double>(yf) == doctest::Approx(expect).epsilon(1e-6));
  CHECK(yq.to_double() == doctest::Approx(expect).epsilon(1e-4));
}
