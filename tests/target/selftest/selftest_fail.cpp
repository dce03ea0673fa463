// Harness self-test (not part of cvt_target_tests): exactly two of the three
// checks below fail, so the image must exit with status 2 and print both
// failures with file:line and values (checked by the ctest regex).
#include "harness.hpp"

CVT_TARGET_TEST(selftest_two_failures) {
  CHECK_EQ(1 + 1, 3);                 // fails: lhs = 2, rhs = 3
  CHECK_NEAR(1.0, 1.0 + 1e-12, 1e-9);  // passes
  CHECK(2 < 1);                        // fails
}
