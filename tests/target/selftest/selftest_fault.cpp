// Harness self-test: an undefined instruction escalates to HardFault
// (exception 3); the port's Default_Handler must report it and end the image
// with kExitFault (126) instead of hanging until the ctest timeout.
#include "harness.hpp"

CVT_TARGET_TEST(selftest_fault) {
  asm volatile("udf #0");
  CHECK(false);  // not reached
}
