#pragma once
// Explicit fixed-step methods: Euler, Heun (explicit trapezoid) and classical
// RK4 (docs/numerics.md#explicit-methods). Each costs a fixed number of
// right-hand-side evaluations per step: 1, 2 and 4.
#include "cvtplant/integrate/system.hpp"

namespace cvt {

template <class Sys>
void step_explicit_euler(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  StateOf<Sys> k;
  sys.derivative(x, k);
  x += h * k;
}

template <class Sys>
void step_heun(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  using T = typename Sys::Scalar;
  StateOf<Sys> k1, k2;
  sys.derivative(x, k1);
  const StateOf<Sys> xp = x + h * k1;
  sys.derivative(xp, k2);
  x += (h * T(0.5)) * (k1 + k2);
}

template <class Sys>
void step_rk4(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  using T = typename Sys::Scalar;
  const T h2 = h * T(0.5);
  const T h6 = h / T(6);
  StateOf<Sys> k1, k2, k3, k4, xs;
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

}  // namespace cvt
