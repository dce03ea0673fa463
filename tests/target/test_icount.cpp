// Calibration of the SysTick instruction counter (docs/build.md#icount).
// A Thumb loop of `subs; bne` runs exactly 2 instructions per iteration, so
// 1000 iterations cost 1800 instructions more than 100 iterations. That
// difference only comes out right if QEMU counts 1 ns per instruction and
// SysTick ticks every 40 ns (kInstructionsPerTick).
#include "cvtplant/port/icount.hpp"
#include "harness.hpp"

using namespace cvt::port;

namespace {
void spin_100() { asm volatile("movw r0, #100\n1:\n\tsubs r0, #1\n\tbne 1b" ::: "r0", "cc"); }
void spin_1000() { asm volatile("movw r0, #1000\n1:\n\tsubs r0, #1\n\tbne 1b" ::: "r0", "cc"); }
}  // namespace

CVT_TARGET_TEST(icount_calibration) {
  auto f100 = [] { spin_100(); };
  auto f1000 = [] { spin_1000(); };
  const std::uint32_t n100 = icount_per_call(f100);
  const std::uint32_t n1000 = icount_per_call(f1000);
  console() << "ICOUNT calibration_spin_100 " << n100 << '\n';
  console() << "ICOUNT calibration_spin_1000 " << n1000 << '\n';
  CHECK_EQ(n1000 - n100, 1800u);
  // The loop itself is 1 + 200 instructions; a call/return adds a few.
  CHECK_GE(n100, 201u);
  CHECK_LE(n100, 201u + 8u);
  // Measuring twice gives the same answer: the count is deterministic.
  CHECK_EQ(icount_per_call(f1000), n1000);
}

CVT_TARGET_TEST(icount_raw_pair_is_quantised_to_40) {
  icount_begin();
  spin_1000();
  const std::uint32_t n = icount_end();
  console() << "ICOUNT raw_begin_end_spin_1000 " << n << '\n';
  CHECK_EQ(n % kInstructionsPerTick, 0u);
  CHECK_GE(n, 2000u - kInstructionsPerTick);
  CHECK_LE(n, 2001u + 40u + kInstructionsPerTick);
}
