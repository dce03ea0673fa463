#pragma once
// Linearly implicit one-step methods with a fixed cost per step: one Jacobian,
// one fixed-size LU (partial pivoting: same operation count whatever the
// pivots) and a fixed number of solves. No Newton iteration, so the cost never
// depends on the state (docs/numerics.md#rosenbrock).
//
//   linearly implicit Euler (order 1, L-stable):
//     (I - h J) k = f(x_n);                 x_{n+1} = x_n + h k
//   ROS2 of Verwer et al. (order 2, L-stable, gamma = 1 + 1/sqrt(2)):
//     (I - gamma h J) k1 = f(x_n)
//     (I - gamma h J) k2 = f(x_n + h k1) - 2 k1
//     x_{n+1} = x_n + 3/2 h k1 + 1/2 h k2
#include <Eigen/LU>

#include "cvtplant/integrate/system.hpp"

namespace cvt {

// The steps with a given matrix J in W = I - a J: the system's Jacobian at
// x_n for the methods as written, or an approximation of it (both methods
// keep their order for any J: ROS2 is a W-method, linearly implicit Euler is
// first order anyway; docs/numerics.md#rosenbrock).
template <class Sys>
void step_linear_implicit_euler_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h,
                                     const JacobianOf<Sys>& J) {
  const JacobianOf<Sys> W = JacobianOf<Sys>::Identity() - h * J;
  const Eigen::PartialPivLU<JacobianOf<Sys>> lu(W);
  StateOf<Sys> f;
  sys.derivative(x, f);
  const StateOf<Sys> k = lu.solve(f);
  x += h * k;
}

template <class Sys>
void step_ros2_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, const JacobianOf<Sys>& J) {
  using T = typename Sys::Scalar;
  // gamma = 1 + 1/sqrt(2), written out so float/fixed round it once at set-up.
  const T gamma = T(1.70710678118654752440);
  const JacobianOf<Sys> W = JacobianOf<Sys>::Identity() - (gamma * h) * J;
  const Eigen::PartialPivLU<JacobianOf<Sys>> lu(W);
  StateOf<Sys> f, k1, k2;
  sys.derivative(x, f);
  k1 = lu.solve(f);
  const StateOf<Sys> x1 = x + h * k1;
  sys.derivative(x1, f);
  f -= T(2) * k1;
  k2 = lu.solve(f);
  x += (h * T(1.5)) * k1 + (h * T(0.5)) * k2;
}

template <class Sys>
void step_linear_implicit_euler(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  JacobianOf<Sys> J;
  jacobian(sys, x, J);
  step_linear_implicit_euler_with(sys, x, h, J);
}

template <class Sys>
void step_ros2(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  JacobianOf<Sys> J;
  jacobian(sys, x, J);
  step_ros2_with(sys, x, h, J);
}

}  // namespace cvt
