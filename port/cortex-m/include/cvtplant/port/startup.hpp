#pragma once
// Image life cycle on Cortex-M (port/cortex-m/src/startup.cpp).
// Reset_Handler: FPU on, .data copied, .bss zeroed, SysTick icount started,
// static constructors run, then main(); main's return value becomes the QEMU
// process exit status. Static destructors never run.
// docs/build.md#startup

namespace cvt::port {

// Exit statuses used by the port itself. Tests use 0..kExitMaxFailures.
inline constexpr int kExitMaxFailures = 125;   // failure counts are capped here
inline constexpr int kExitFault = 126;         // unhandled exception / fault
inline constexpr int kExitAbort = 127;         // abort(), pure virtual call, assert

// Flushes the console and ends the image with `status`. Never returns.
[[noreturn]] void exit_image(int status);

}  // namespace cvt::port
