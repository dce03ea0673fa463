#pragma once
// Forward-mode dual numbers with a fixed number N of directional derivatives,
// for Jacobians of the plant right-hand side (docs/numerics.md#jacobians).
// Heap-free: the derivative part is a plain array. The deterministic math is
// extended to duals by the chain rule (below).
#include <Eigen/Core>

#include "cvtplant/math/detmath.hpp"

namespace cvt {

template <class T, int N>
struct Dual {
  T v{};      // value
  T d[N]{};   // partial derivatives

  constexpr Dual() = default;
  constexpr Dual(const T& value) : v(value) {}  // NOLINT: implicit, so constants mix in
  template <class U, class = std::enable_if_t<std::is_arithmetic<U>::value && !std::is_same<U, T>::value>>
  constexpr explicit Dual(U value) : v(T(value)) {}

  // The i-th independent variable: value x, derivative e_i.
  static constexpr Dual variable(const T& x, int i) {
    Dual r(x);
    r.d[i] = T(1);
    return r;
  }

  Dual& operator+=(const Dual& o) {
    v += o.v;
    for (int i = 0; i < N; ++i) d[i] += o.d[i];
    return *this;
  }
  Dual& operator-=(const Dual& o) {
    v -= o.v;
    for (int i = 0; i < N; ++i) d[i] -= o.d[i];
    return *this;
  }
  Dual& operator*=(const Dual& o) {
    for (int i = 0; i < N; ++i) d[i] = d[i] * o.v + v * o.d[i];
    v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    const T inv = T(1) / o.v;
    const T q = v * inv;
    for (int i = 0; i < N; ++i) d[i] = (d[i] - q * o.d[i]) * inv;
    v = q;
    return *this;
  }
};

template <class T, int N> Dual<T, N> operator+(Dual<T, N> a, const Dual<T, N>& b) { return a += b; }
template <class T, int N> Dual<T, N> operator-(Dual<T, N> a, const Dual<T, N>& b) { return a -= b; }
template <class T, int N> Dual<T, N> operator*(Dual<T, N> a, const Dual<T, N>& b) { return a *= b; }
template <class T, int N> Dual<T, N> operator/(Dual<T, N> a, const Dual<T, N>& b) { return a /= b; }
// Mixed dual/scalar arithmetic (template deduction would not convert T).
template <class T, int N> Dual<T, N> operator+(Dual<T, N> a, const T& b) { a.v += b; return a; }
template <class T, int N> Dual<T, N> operator+(const T& b, Dual<T, N> a) { a.v += b; return a; }
template <class T, int N> Dual<T, N> operator-(Dual<T, N> a, const T& b) { a.v -= b; return a; }
template <class T, int N> Dual<T, N> operator-(const T& b, const Dual<T, N>& a) { return Dual<T, N>(b) - a; }
template <class T, int N> Dual<T, N> operator*(Dual<T, N> a, const T& b) {
  a.v *= b;
  for (int i = 0; i < N; ++i) a.d[i] *= b;
  return a;
}
template <class T, int N> Dual<T, N> operator*(const T& b, Dual<T, N> a) { return a * b; }
template <class T, int N> Dual<T, N> operator/(Dual<T, N> a, const T& b) { return a / Dual<T, N>(b); }
template <class T, int N> Dual<T, N> operator/(const T& b, const Dual<T, N>& a) { return Dual<T, N>(b) / a; }
template <class T, int N> Dual<T, N> operator-(Dual<T, N> a) {
  a.v = -a.v;
  for (int i = 0; i < N; ++i) a.d[i] = -a.d[i];
  return a;
}
template <class T, int N> Dual<T, N> operator+(const Dual<T, N>& a) { return a; }
template <class T, int N> bool operator<(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v < b.v; }
template <class T, int N> bool operator>(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v > b.v; }
template <class T, int N> bool operator<=(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v <= b.v; }
template <class T, int N> bool operator>=(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v >= b.v; }
template <class T, int N> bool operator==(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v == b.v; }
template <class T, int N> bool operator!=(const Dual<T, N>& a, const Dual<T, N>& b) { return a.v != b.v; }

// The math of dual numbers, next to the type and found by argument-dependent
// lookup (docs/numerics.md#scalar-math): each function by the chain rule on
// the deterministic math of T, so a Jacobian by duals rounds like the plant.
namespace dual_detail {
// f(a) with f'(a.v) = slope.
template <class T, int N>
Dual<T, N> chain(const Dual<T, N>& a, const T& value, const T& slope) {
  Dual<T, N> r(value);
  for (int i = 0; i < N; ++i) r.d[i] = slope * a.d[i];
  return r;
}
}  // namespace dual_detail

template <class T, int N> Dual<T, N> abs(const Dual<T, N>& a) {
  // Subgradient 0 at the kink: the friction laws multiply |v| terms by s(0) = 0.
  return dual_detail::chain(a, abs(a.v), sign(a.v));
}
template <class T, int N> Dual<T, N> sign(const Dual<T, N>& a) { return Dual<T, N>(sign(a.v)); }
template <class T, int N> Dual<T, N> sqrt(const Dual<T, N>& a) {
  const T s = sqrt(a.v);
  return dual_detail::chain(a, s, T(0.5) / s);
}
template <class T, int N> Dual<T, N> exp(const Dual<T, N>& a) {
  const T e = exp(a.v);
  return dual_detail::chain(a, e, e);
}
template <class T, int N> Dual<T, N> atan(const Dual<T, N>& a) {
  return dual_detail::chain(a, atan(a.v), T(1) / (T(1) + a.v * a.v));
}
template <class T, int N> Dual<T, N> tanh(const Dual<T, N>& a) {
  const T t = tanh(a.v);
  return dual_detail::chain(a, t, T(1) - t * t);
}
template <class T, int N> Dual<T, N> sin(const Dual<T, N>& a) { return dual_detail::chain(a, sin(a.v), cos(a.v)); }
template <class T, int N> Dual<T, N> cos(const Dual<T, N>& a) { return dual_detail::chain(a, cos(a.v), -sin(a.v)); }

}  // namespace cvt

namespace Eigen {
// Lets Eigen hold duals in fixed-size vectors (we only use coefficient-wise
// access and simple arithmetic on them, never decompositions).
template <class T, int N>
struct NumTraits<cvt::Dual<T, N>> : NumTraits<T> {
  using Real = cvt::Dual<T, N>;
  using NonInteger = cvt::Dual<T, N>;
  using Nested = cvt::Dual<T, N>;
  using Literal = cvt::Dual<T, N>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = N + 1,
    AddCost = N + 1,
    MulCost = 3 * N + 1
  };
};
}  // namespace Eigen
