// SysTick as an instruction counter under QEMU -icount shift=0.
// docs/build.md#icount
#include "cvtplant/port/icount.hpp"

namespace cvt::port {
namespace {

// ARMv7-M SysTick registers (ARMv7-M ARM, B3.3).
volatile std::uint32_t& syst_csr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000E010u); }
volatile std::uint32_t& syst_rvr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000E014u); }
volatile std::uint32_t& syst_cvr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000E018u); }

constexpr std::uint32_t kCsrEnable = 1u << 0;
constexpr std::uint32_t kCsrClkSourceCpu = 1u << 2;
constexpr std::uint32_t kReload = 0x00FFFFFFu;  // full 24-bit range
constexpr std::uint32_t kPeriod = kReload + 1u;

std::uint32_t g_mark = 0;

}  // namespace

std::uint32_t icount_now() {
  // The counter counts down; turn it into an up-counting tick number.
  const std::uint32_t down = syst_cvr() & kReload;
  return (kReload - down) * kInstructionsPerTick;
}

std::uint32_t icount_between(std::uint32_t begin, std::uint32_t end) {
  constexpr std::uint32_t kWrap = kPeriod * kInstructionsPerTick;  // 671,088,640
  return (end >= begin) ? end - begin : kWrap - begin + end;
}

void icount_begin() { g_mark = icount_now(); }
std::uint32_t icount_end() { return icount_between(g_mark, icount_now()); }

void icount_init() {
  if ((syst_csr() & kCsrEnable) != 0) return;
  syst_rvr() = kReload;
  syst_cvr() = 0;  // any write clears the counter; it reloads on the next tick
  syst_csr() = kCsrClkSourceCpu | kCsrEnable;
}

namespace detail {

void icount_empty_thunk(void*) {}

std::uint32_t icount_loop(Thunk thunk, void* ctx, std::uint32_t reps) {
  // volatile: the compiler must not inline or specialise the call, so the
  // loop is the same instructions for the real thunk and the empty one.
  Thunk volatile call = thunk;
  const std::uint32_t t0 = icount_now();
  for (std::uint32_t i = 0; i < reps; ++i) call(ctx);
  return icount_between(t0, icount_now());
}

}  // namespace detail
}  // namespace cvt::port
