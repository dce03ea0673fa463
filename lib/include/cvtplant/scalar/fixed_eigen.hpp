#pragma once
// Eigen support for cvt::Fixed<F>: NumTraits plus the functions Eigen finds by
// argument-dependent lookup (abs, sqrt, ...). With this,
// Eigen::Matrix<q16_16, N, N> arithmetic and partialPivLu().solve() work,
// heap-free for fixed sizes (docs/numerics.md#fixed-point, Eigen section).
//
// Saturation still applies inside Eigen's kernels: an LU of a badly scaled or
// ill-conditioned matrix saturates instead of overflowing. Keep systems scaled
// to O(1) entries when solving in fixed point.
#include <Eigen/Core>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

// Found by ADL from Eigen's numext:: helpers (abs and sqrt are fixed.hpp's).
template <int F>
constexpr Fixed<F> abs2(Fixed<F> x) { return x * x; }
template <int F>
constexpr const Fixed<F>& conj(const Fixed<F>& x) { return x; }
template <int F>
constexpr const Fixed<F>& real(const Fixed<F>& x) { return x; }
template <int F>
constexpr Fixed<F> imag(const Fixed<F>&) { return Fixed<F>{}; }
template <int F>
constexpr bool isfinite(Fixed<F>) { return true; }  // no inf/NaN encodings
template <int F>
constexpr bool isnan(Fixed<F>) { return false; }
template <int F>
constexpr bool isinf(Fixed<F>) { return false; }

}  // namespace cvt

namespace Eigen {

template <int F>
struct NumTraits<cvt::Fixed<F>> : GenericNumTraits<cvt::Fixed<F>> {
  using Real = cvt::Fixed<F>;
  using NonInteger = cvt::Fixed<F>;
  using Nested = cvt::Fixed<F>;
  using Literal = cvt::Fixed<F>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1,
    AddCost = 2,   // add + saturate
    MulCost = 6,   // 32x32->64 multiply, round, saturate
  };
  static constexpr Real epsilon() { return Real::epsilon(); }
  // "Negligible" threshold for Eigen's rank/zero tests: 2^(F/2) LSB.
  static constexpr Real dummy_precision() { return Real::from_raw(std::int32_t{1} << (F / 2)); }
  static constexpr Real highest() { return Real::max(); }
  static constexpr Real lowest() { return Real::lowest(); }
  static constexpr Real infinity() { return Real::max(); }   // saturation value stands in
  static constexpr Real quiet_NaN() { return Real{}; }       // NaN converts to 0
  static constexpr int digits10() { return (31 * 301) / 1000; }
  static constexpr int digits() { return 31; }
  static constexpr int min_exponent() { return 0; }
  static constexpr int max_exponent() { return 0; }
};

}  // namespace Eigen
