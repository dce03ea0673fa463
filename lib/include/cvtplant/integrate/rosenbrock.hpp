#pragma once
// Linearly implicit one-step methods with a fixed cost per step: one Jacobian,
// one factorisation of W = I - a J and a fixed number of solves. No Newton
// iteration, so the cost never depends on the state (docs/numerics.md#rosenbrock).
//
//   linearly implicit Euler (order 1, L-stable):
//     (I - h J) k = f(x_n);                 x_{n+1} = x_n + h k
//   ROS2 of Verwer et al. (order 2, L-stable, gamma = 1 + 1/sqrt(2)):
//     (I - gamma h J) k1 = f(x_n)
//     (I - gamma h J) k2 = f(x_n + h k1) - 2 k1
//     x_{n+1} = x_n + 3/2 h k1 + 1/2 h k2
//
// One implementation of each method, with the linear solve pluggable: a W
// solver has
//   void factor(const JacobianOf<Sys>& J, const T& a);   // W = I - a J
//   StateOf<Sys> solve(const StateOf<Sys>& f) const;     // W^-1 f
// DenseWSolver is a fixed-size LU with partial pivoting (the same operation
// count whatever the pivots); the real-time plant plugs in its
// block-eliminated solver (plant/rom_step.hpp).
#include <Eigen/LU>

#include "cvtplant/integrate/increment.hpp"
#include "cvtplant/integrate/system.hpp"

namespace cvt {

// gamma = 1 + 1/sqrt(2), written out so float and fixed round it once.
inline constexpr double kRos2Gamma = 1.70710678118654752440;

template <class Sys>
class DenseWSolver {
 public:
  using T = typename Sys::Scalar;
  void factor(const JacobianOf<Sys>& J, const T& a) { lu_.compute(JacobianOf<Sys>::Identity() - a * J); }
  StateOf<Sys> solve(const StateOf<Sys>& f) const { return lu_.solve(f); }

 private:
  Eigen::PartialPivLU<JacobianOf<Sys>> lu_;
};

// The steps with a given matrix J in W = I - a J: the system's Jacobian at
// x_n for the methods as written, or an approximation of it (both methods
// keep their order for any J: ROS2 is a W-method, linearly implicit Euler is
// first order anyway; docs/numerics.md#rosenbrock). `f` holds f(x_n) on
// entry and is used as scratch.
// The final increment is as written for floating point; fixed point forms
// h (3 k1 + k2) / 2 exactly and rounds it once, with the remainder carried
// to the next step when `carry` is given (integrate/increment.hpp).
template <class Sys, class WSolver>
void step_linear_implicit_euler_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h,
                                     const JacobianOf<Sys>& J, WSolver& w, StateOf<Sys>& f,
                                     CarryOf<Sys>* carry = nullptr) {
  (void)sys;
  w.factor(J, h);
  if constexpr (is_fixed_point_v<typename Sys::Scalar>) {
    const StateOf<Sys> k = w.solve(f);
    fixed_increment<1>(x, h, {1}, {&k}, carry);
  } else {
    (void)carry;
    x += h * w.solve(f);
  }
}

template <class Sys, class WSolver>
void step_ros2_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, const JacobianOf<Sys>& J, WSolver& w,
                    StateOf<Sys>& f, CarryOf<Sys>* carry = nullptr) {
  using T = typename Sys::Scalar;
  w.factor(J, T(kRos2Gamma) * h);
  const StateOf<Sys> k1 = w.solve(f);
  const StateOf<Sys> x1 = x + h * k1;
  sys.derivative(x1, f);
  f -= T(2) * k1;
  const StateOf<Sys> k2 = w.solve(f);
  if constexpr (is_fixed_point_v<T>) {
    fixed_increment<2>(x, h, {3, 1}, {&k1, &k2}, carry);
  } else {
    (void)carry;
    x += (h * T(1.5)) * k1 + (h * T(0.5)) * k2;
  }
}

// The same with the dense LU.
template <class Sys>
void step_linear_implicit_euler_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h,
                                     const JacobianOf<Sys>& J, CarryOf<Sys>* carry = nullptr) {
  DenseWSolver<Sys> w;
  StateOf<Sys> f;
  sys.derivative(x, f);
  step_linear_implicit_euler_with(sys, x, h, J, w, f, carry);
}

template <class Sys>
void step_ros2_with(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, const JacobianOf<Sys>& J,
                    CarryOf<Sys>* carry = nullptr) {
  DenseWSolver<Sys> w;
  StateOf<Sys> f;
  sys.derivative(x, f);
  step_ros2_with(sys, x, h, J, w, f, carry);
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
