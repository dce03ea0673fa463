#pragma once
// Arm semihosting calls (the "bkpt 0xAB" interface). Under QEMU with
// `-semihosting-config enable=on,target=native` they reach the host; on real
// hardware they need a debugger attached, otherwise the bkpt faults.
// docs/build.md#semihosting
#include <cstdint>

namespace cvt::port {

// Writes a NUL-terminated string to the debug console (SYS_WRITE0).
void semihost_write0(const char* text);

// Ends the program; `status` becomes QEMU's process exit status
// (SYS_EXIT_EXTENDED with ADP_Stopped_ApplicationExit). Never returns.
[[noreturn]] void semihost_exit(int status);

}  // namespace cvt::port
