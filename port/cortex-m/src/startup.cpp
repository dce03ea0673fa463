// Reset and exception entry for Cortex-M4F/M7 images on QEMU's MPS2 boards.
// docs/build.md#startup
//
// Not newlib's crt0: rdimon's _start takes a data abort on mps2-an386
// (docs/build.md#startup), and we want no libc start-up code anyway.
#include <cstdint>

#include "cvtplant/port/console.hpp"
#include "cvtplant/port/icount.hpp"
#include "cvtplant/port/semihosting.hpp"
#include "cvtplant/port/startup.hpp"

// Symbols provided by port/cortex-m/ld/mps2-common.ld.
extern "C" {
extern std::uint32_t __data_load_start[];
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern std::uint32_t __stack_top[];
using InitFn = void (*)();
extern InitFn __preinit_array_start[];
extern InitFn __preinit_array_end[];
extern InitFn __init_array_start[];
extern InitFn __init_array_end[];

int main();
[[noreturn]] void Reset_Handler();
void Default_Handler();
}

namespace {

volatile std::uint32_t& scb_cpacr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000ED88u); }
volatile std::uint32_t& scb_cfsr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000ED28u); }
volatile std::uint32_t& scb_hfsr() { return *reinterpret_cast<volatile std::uint32_t*>(0xE000ED2Cu); }

// Kept out of line so that nothing in Reset_Handler itself can be scheduled
// before the FPU is on (an FP instruction with CP10/CP11 off is a UsageFault).
__attribute__((noinline)) void run_static_constructors() {
  for (InitFn* f = __preinit_array_start; f != __preinit_array_end; ++f) (*f)();
  for (InitFn* f = __init_array_start; f != __init_array_end; ++f) (*f)();
}

__attribute__((noinline)) int run_main() { return main(); }

}  // namespace

extern "C" void Reset_Handler() {
  // CP10 and CP11 full access (ARMv7-M ARM B3.2.20), then barriers so the
  // next instruction sees the FPU enabled.
  scb_cpacr() = scb_cpacr() | (0xFu << 20);
  asm volatile("dsb\n\tisb" ::: "memory");

  // Word-wise copy/zero: the linker script aligns both ends to 4 bytes.
  // Plain loops, not memcpy/memset, because the C library is not set up
  // (and -ftree-loop-distribute-patterns could turn these into calls to it:
  // the volatile pointers prevent that).
  volatile std::uint32_t* dst = __data_start;
  for (const std::uint32_t* src = __data_load_start; dst < __data_end;) *dst++ = *src++;
  for (volatile std::uint32_t* p = __bss_start; p < __bss_end;) *p++ = 0u;

  cvt::port::icount_init();
  run_static_constructors();
  cvt::port::exit_image(run_main());
}

namespace cvt::port {

void exit_image(int status) {
  console().flush();
  semihost_exit(status);
}

}  // namespace cvt::port

// Any exception without a handler of its own: report it and stop the image
// with kExitFault, so a test run fails loudly instead of hanging until the
// ctest timeout.
extern "C" void Default_Handler() {
  std::uint32_t ipsr;
  asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  auto& out = cvt::port::console();
  out.flush();
  out << "FATAL: unhandled exception " << static_cast<std::uint32_t>(ipsr & 0x1FFu)
      << " CFSR=";
  out.hex(scb_cfsr(), 8) << " HFSR=";
  out.hex(scb_hfsr(), 8) << '\n';
  cvt::port::exit_image(cvt::port::kExitFault);
}

// Weak aliases: an image overrides a handler by defining a function with the
// same name (e.g. `extern "C" void SysTick_Handler()`).
#define CVT_WEAK_HANDLER(name) extern "C" void name() __attribute__((weak, alias("Default_Handler")))
CVT_WEAK_HANDLER(NMI_Handler);
CVT_WEAK_HANDLER(HardFault_Handler);
CVT_WEAK_HANDLER(MemManage_Handler);
CVT_WEAK_HANDLER(BusFault_Handler);
CVT_WEAK_HANDLER(UsageFault_Handler);
CVT_WEAK_HANDLER(SVC_Handler);
CVT_WEAK_HANDLER(DebugMon_Handler);
CVT_WEAK_HANDLER(PendSV_Handler);
CVT_WEAK_HANDLER(SysTick_Handler);
#undef CVT_WEAK_HANDLER

namespace {
using Vector = void (*)();
// 16 system exceptions + 32 external interrupts (the MPS2 CMSDK images use
// 32). All external interrupts go to Default_Handler.
constexpr int kExternalIrqs = 32;
}  // namespace

// Referenced by EXTERN() in the linker script, so it is pulled out of the
// port archive and kept by --gc-sections.
extern "C" __attribute__((section(".isr_vector"), used))
const Vector cvt_vector_table[16 + kExternalIrqs] = {
    reinterpret_cast<Vector>(__stack_top),
    Reset_Handler,
    NMI_Handler,
    HardFault_Handler,
    MemManage_Handler,
    BusFault_Handler,
    UsageFault_Handler,
    nullptr,
    nullptr,
    nullptr,
    nullptr,
    SVC_Handler,
    DebugMon_Handler,
    nullptr,
    PendSV_Handler,
    SysTick_Handler,
#define CVT_IRQ4 Default_Handler, Default_Handler, Default_Handler, Default_Handler
    CVT_IRQ4, CVT_IRQ4, CVT_IRQ4, CVT_IRQ4, CVT_IRQ4, CVT_IRQ4, CVT_IRQ4, CVT_IRQ4,
#undef CVT_IRQ4
};
