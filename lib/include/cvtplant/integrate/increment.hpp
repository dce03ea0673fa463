#pragma once
// The increment of a one-step method in fixed point (docs/numerics.md#fixed-point-steps):
//
//   x += h (c_1 k_1 + ... + c_n k_n) / D        (integer weights c_i, D = 1, 2 or 6)
//
// Floating point keeps each method's own expression (rounding differs only
// in the last bits, and the trace hashes are kept). In Fixed<F> the step h is
// a few hundred LSB or fewer, and rounding h/2 or h/6 first changed the
// method's weights: at h = 7 LSB (1e-4 s in seconds) h/6 is 1 LSB and h/2 is
// 4, so RK4 advanced 6/7 of the step and the seed oscillator's period came out
// 17 % long. Here the weighted sum is formed exactly in 64-bit integers and
// rounded once.
//
// With a carry (IncrementCarry), the rounding remainder of each state is added
// to its next increment (first-order error feedback): the increments applied
// over a run sum to the computed ones within half an LSB. Without it, a rate
// that stays constant rounds the same way every step, and the error grows
// linearly with the run (and a small increment that rounds to zero every
// step stalls a state short of its equilibrium).
//
// Scaling and overflow: the exact sum needs |h| |sum c_i k_i| < 2^62 raw^2,
// i.e. |h| below 2^31 / (6 |k|_max) LSB; beyond that the increment saturates
// (the state goes to its rail, which the ROM watchdog reports as
// state-saturated). Integer arithmetic only: the same bits on every target.
#include <cstdint>

#include "cvtplant/scalar/fixed.hpp"

namespace cvt {

// Rounding remainders of the last increments, one per state, in units of
// 1 / (D 2^F) LSB (|r| <= D 2^(F-1)); one carry serves one method (its D).
// Floating point carries nothing.
template <class T, int N>
struct IncrementCarry {
  void clear() {}
};
template <int F, int N>
struct IncrementCarry<Fixed<F>, N> {
  std::int64_t r[N] = {};
  void clear() {
    for (std::int64_t& v : r) v = 0;
  }
};

// The carry of a system's state.
template <class Sys>
using CarryOf = IncrementCarry<typename Sys::Scalar, Sys::kStates>;

namespace increment_detail {
template <class T>
struct same {
  using type = T;
};
}  // namespace increment_detail

// x += h (sum_i c[i] k[i]) / D with one rounding per state (ties away from
// zero), carrying the remainder in `carry` if it is not null.
template <int D, int NK, int F, class Vec>
void fixed_increment(Vec& x, Fixed<F> h, const int (&c)[NK], const Vec* const (&k)[NK],
                     typename increment_detail::same<IncrementCarry<Fixed<F>, Vec::RowsAtCompileTime>>::type* carry) {
  static_assert(D == 1 || D == 2 || D == 6, "the methods' denominators");
  constexpr std::int64_t kDen = std::int64_t{D} << F;
  constexpr std::int64_t kLimit = std::int64_t{1} << 62;
  const std::int64_t hr = h.raw();
  const std::int64_t ah = hr < 0 ? -hr : hr;
  for (int i = 0; i < Vec::RowsAtCompileTime; ++i) {
    std::int64_t s = 0;
    for (int j = 0; j < NK; ++j) s += std::int64_t{c[j]} * (*k[j])(i).raw();
    const std::int64_t as = s < 0 ? -s : s;
    std::int64_t q;
    if (ah != 0 && as > kLimit / ah) {
      // Beyond 64 bits: saturate the state in the increment's direction.
      q = ((hr < 0) != (s < 0)) ? fixed_detail::kRawMin * 2 : fixed_detail::kRawMax * 2;
      if (carry != nullptr) carry->r[i] = 0;
    } else {
      std::int64_t num = hr * s;
      if (carry != nullptr) num += carry->r[i];
      q = num >= 0 ? (num + kDen / 2) / kDen : -((-num + kDen / 2) / kDen);
      if (carry != nullptr) carry->r[i] = num - q * kDen;
    }
    x(i) = Fixed<F>::from_raw(fixed_detail::saturate(std::int64_t{x(i).raw()} + q));
  }
}

}  // namespace cvt
