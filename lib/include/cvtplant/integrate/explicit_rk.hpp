#pragma once
// Explicit fixed-step methods: Euler, Heun (explicit trapezoid) and classical
// RK4 (docs/numerics.md#explicit-methods). Each costs a fixed number of
// right-hand-side evaluations per step: 1, 2 and 4.
#include "cvtplant/integrate/increment.hpp"
#include "cvtplant/integrate/system.hpp"

namespace cvt {

// The increments are as written for floating point; fixed point forms each
// weighted sum exactly and rounds it once (integrate/increment.hpp), carrying
// the remainder when the caller passes `carry`.

template <class Sys>
void step_explicit_euler(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, CarryOf<Sys>* carry = nullptr) {
  StateOf<Sys> k;
  sys.derivative(x, k);
  if constexpr (is_fixed_point_v<typename Sys::Scalar>) {
    fixed_increment<1>(x, h, {1}, {&k}, carry);
  } else {
    (void)carry;
    x += h * k;
  }
}

template <class Sys>
void step_heun(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, CarryOf<Sys>* carry = nullptr) {
  using T = typename Sys::Scalar;
  StateOf<Sys> k1, k2;
  sys.derivative(x, k1);
  const StateOf<Sys> xp = x + h * k1;
  sys.derivative(xp, k2);
  if constexpr (is_fixed_point_v<T>) {
    fixed_increment<2>(x, h, {1, 1}, {&k1, &k2}, carry);
  } else {
    (void)carry;
    x += (h * T(0.5)) * (k1 + k2);
  }
}

template <class Sys>
void step_rk4(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h, CarryOf<Sys>* carry = nullptr) {
  using T = typename Sys::Scalar;
  StateOf<Sys> k1, k2, k3, k4, xs;
  if constexpr (is_fixed_point_v<T>) {
    // Half steps as h k / 2 rounded once, not (h / 2) k.
    sys.derivative(x, k1);
    xs = x;
    fixed_increment<2>(xs, h, {1}, {&k1}, nullptr);
    sys.derivative(xs, k2);
    xs = x;
    fixed_increment<2>(xs, h, {1}, {&k2}, nullptr);
    sys.derivative(xs, k3);
    xs = x + h * k3;
    sys.derivative(xs, k4);
    fixed_increment<6>(x, h, {1, 2, 2, 1}, {&k1, &k2, &k3, &k4}, carry);
  } else {
    (void)carry;
    const T h2 = h * T(0.5);
    const T h6 = h / T(6);
    sys.derivative(x, k1);
    xs = x + h2 * k1;
    sys.derivative(xs, k2);
    xs = x + h2 * k2;
    sys.derivative(xs, k3);
    xs = x + h * k3;
    sys.derivative(xs, k4);
    // Summed in a fixed order so every scalar type rounds the same way each run.
    x += h6 * (k1 + T(2) * k2 + T(2) * k3 + k4);
  }
}

}  // namespace cvt
