// Arm semihosting, AArch32 Thumb flavour: operation in r0, parameter in r1,
// then `bkpt 0xAB`; the result comes back in r0.
// docs/build.md#semihosting
#include "cvtplant/port/semihosting.hpp"

namespace cvt::port {
namespace {

constexpr std::uint32_t kSysWrite0 = 0x04;
constexpr std::uint32_t kSysExit = 0x18;
constexpr std::uint32_t kSysExitExtended = 0x20;
constexpr std::uint32_t kAdpStoppedApplicationExit = 0x20026;

std::uint32_t semihost_call(std::uint32_t op, const void* arg) {
  register std::uint32_t r0 asm("r0") = op;
  register const void* r1 asm("r1") = arg;
  // "memory": the host reads (and for some calls writes) the argument block.
  asm volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

}  // namespace

void semihost_write0(const char* text) { semihost_call(kSysWrite0, text); }

void semihost_exit(int status) {
  // On AArch32 plain SYS_EXIT takes the reason code by value and cannot carry
  // a status (QEMU maps ApplicationExit to 0, everything else to 1).
  // SYS_EXIT_EXTENDED takes {reason, subcode} and QEMU exits with subcode.
  const std::uint32_t block[2] = {kAdpStoppedApplicationExit,
                                  static_cast<std::uint32_t>(status)};
  semihost_call(kSysExitExtended, block);
  // A host without SYS_EXIT_EXTENDED returns here: fall back to the
  // two-valued SYS_EXIT so that failure is at least still failure.
  semihost_call(kSysExit, reinterpret_cast<const void*>(
                              status == 0 ? kAdpStoppedApplicationExit : 0x20023u /* RunTimeErrorUnknown */));
  for (;;) {
  }
}

}  // namespace cvt::port
