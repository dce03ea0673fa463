#pragma once
// What an integrator needs from a plant (docs/numerics.md#integrators):
//
//   struct MySystem {
//     using Scalar = T;
//     static constexpr int kStates = N;
//     // bit i set: state i is a position whose derivative is a velocity state
//     // (used by semi-implicit Euler only)
//     static constexpr std::uint32_t kPositionMask = ...;
//     template <class S>
//     void derivative(const Eigen::Matrix<S, N, 1>& x, Eigen::Matrix<S, N, 1>& dxdt) const;
//     // optional; otherwise forward-mode dual numbers differentiate derivative()
//     void jacobian(const Eigen::Matrix<T, N, 1>& x, Eigen::Matrix<T, N, N>& J) const;
//   };
//
// Inputs are members of the system, set by the caller before each step and
// held constant over it (zero-order hold at the frame rate).
#include <Eigen/Core>
#include <type_traits>
#include <utility>

#include "cvtplant/autodiff/dual.hpp"

namespace cvt {

template <class Sys>
using StateOf = Eigen::Matrix<typename Sys::Scalar, Sys::kStates, 1>;
template <class Sys>
using JacobianOf = Eigen::Matrix<typename Sys::Scalar, Sys::kStates, Sys::kStates>;

namespace detail {
template <class Sys, class = void>
struct has_analytic_jacobian : std::false_type {};
template <class Sys>
struct has_analytic_jacobian<Sys, std::void_t<decltype(std::declval<const Sys&>().jacobian(
                                      std::declval<const StateOf<Sys>&>(), std::declval<JacobianOf<Sys>&>()))>>
    : std::true_type {};
}  // namespace detail

// J = df/dx by forward-mode dual numbers: one evaluation of derivative() in
// N-wide duals, a fixed cost (docs/numerics.md#jacobians).
template <class Sys>
void jacobian_by_duals(const Sys& sys, const StateOf<Sys>& x, JacobianOf<Sys>& J) {
  using T = typename Sys::Scalar;
  constexpr int N = Sys::kStates;
  using D = Dual<T, N>;
  Eigen::Matrix<D, N, 1> xd;
  Eigen::Matrix<D, N, 1> fd;
  for (int i = 0; i < N; ++i) xd(i) = D::variable(x(i), i);
  sys.derivative(xd, fd);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) J(i, j) = fd(i).d[j];
}

// The system's analytic Jacobian where it has one, else dual numbers.
template <class Sys>
void jacobian(const Sys& sys, const StateOf<Sys>& x, JacobianOf<Sys>& J) {
  if constexpr (detail::has_analytic_jacobian<Sys>::value) {
    sys.jacobian(x, J);
  } else {
    jacobian_by_duals(sys, x, J);
  }
}

}  // namespace cvt
