#pragma once
// Scalar-type glue: the core is written once as templates over T and
// instantiated for double, float and fixed point (docs/numerics.md#scalars).
// Everything here is constexpr and heap-free.
#include <cstdint>

#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

// Conversion from a double literal/parameter. Only used at set-up time, never
// per step on the embedded path (double is soft-float on a Cortex-M4F).
template <class T>
constexpr T from_double(double v) { return T(v); }

template <class T>
constexpr double to_double(T v) { return static_cast<double>(v); }
template <int F>
constexpr double to_double(Fixed<F> v) { return v.to_double(); }

template <class T> struct scalar_name;
template <> struct scalar_name<double> { static constexpr const char* value = "double"; };
template <> struct scalar_name<float> { static constexpr const char* value = "float"; };
template <int F> struct scalar_name<Fixed<F>> { static constexpr const char* value = Fixed<F>::kName; };

}  // namespace cvt
