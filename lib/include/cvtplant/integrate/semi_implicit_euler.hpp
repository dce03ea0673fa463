#pragma once
// Semi-implicit (symplectic) Euler: velocities first with f(x_n), then the
// positions with the updated velocities (docs/numerics.md#semi-implicit-euler).
// Two right-hand-side evaluations per step; needs Sys::kPositionMask. With no
// position states it degenerates to explicit Euler (plus one wasted evaluation).
#include <cstdint>

#include "cvtplant/integrate/system.hpp"

namespace cvt {

template <class Sys>
void step_semi_implicit_euler(const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  constexpr std::uint32_t kPos = Sys::kPositionMask;
  StateOf<Sys> k;
  sys.derivative(x, k);
  for (int i = 0; i < Sys::kStates; ++i)
    if (((kPos >> i) & 1u) == 0u) x(i) += h * k(i);
  // Position derivatives re-evaluated at (q_n, v_{n+1}).
  sys.derivative(x, k);
  for (int i = 0; i < Sys::kStates; ++i)
    if (((kPos >> i) & 1u) != 0u) x(i) += h * k(i);
}

}  // namespace cvt
