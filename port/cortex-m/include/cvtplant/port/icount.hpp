#pragma once
// Instruction counting under QEMU (`-icount shift=0`), via SysTick.
// docs/build.md#icount
//
// With -icount shift=0 QEMU advances its virtual clock by exactly 1 ns per
// executed guest instruction. SysTick with CLKSOURCE=1 runs from the board's
// 25 MHz CPU clock, i.e. it decrements once per 40 ns = once per 40
// instructions. So
//     instructions = 40 * (SysTick decrements)          (kInstructionsPerTick)
// with a quantisation of +-40 instructions per measurement. Average over
// many repetitions (icount_total) to resolve single instructions.
//
// This is an instruction count, not a cycle count: a real Cortex-M4 spends
// more cycles than instructions (loads, divides, flash wait states).
// On real hardware these functions measure 40 x (core clock ticks)/40, i.e.
// core cycles rounded to 40 -- use DWT->CYCCNT there instead.
#include <cstdint>

namespace cvt::port {

inline constexpr std::uint32_t kInstructionsPerTick = 40;

// Starts SysTick as a free-running 24-bit down counter (no interrupt).
// Called by the startup code before main(); idempotent.
void icount_init();

// Raw counter snapshot, in instructions since an arbitrary origin, modulo
// 2^24 * 40 (= 671,088,640 instructions).
std::uint32_t icount_now();

// Instructions executed between two snapshots, for intervals shorter than
// 671 million instructions (the counter wraps once per that many).
std::uint32_t icount_between(std::uint32_t begin, std::uint32_t end);

// Convenience pair on a single global start mark (not reentrant). The
// result is quantised to 40 instructions and includes the few instructions
// of the calls themselves; use icount_per_call for exact figures.
void icount_begin();
std::uint32_t icount_end();

namespace detail {
using Thunk = void (*)(void*);
// Calls thunk(ctx) `reps` times through a volatile pointer, so the loop code
// is identical whatever the thunk is, and returns the instructions spent.
std::uint32_t icount_loop(Thunk thunk, void* ctx, std::uint32_t reps);
void icount_empty_thunk(void*);
}  // namespace detail

// Mean number of instructions one call of f() costs (call, return and any
// register saves included), measured over `reps` calls. The 40-instruction
// quantisation of the two counter reads and of the empty-loop calibration is
// spread over reps, so with reps >= 1000 the error is below 0.1 instruction
// and the rounded result is exact when every call takes the same path.
// reps * instructions must stay below 671 million (counter wrap).
template <class F>
std::uint32_t icount_per_call(F& f, std::uint32_t reps = 1000) {
  auto thunk = [](void* ctx) { (*static_cast<F*>(ctx))(); };
  const std::uint32_t with_f = detail::icount_loop(thunk, &f, reps);
  const std::uint32_t empty = detail::icount_loop(&detail::icount_empty_thunk, nullptr, reps);
  if (with_f <= empty) return 0;
  return (with_f - empty + reps / 2) / reps;
}

}  // namespace cvt::port
