// Image runner of the C codec's Cortex-M4F self-test (hil/codegen/c/target/selftest.c).
#include "cvtplant/port/console.hpp"

extern "C" int cvt_can_c_selftest(void);

int main() {
  const int failures = cvt_can_c_selftest();
  cvt::port::console() << "C codec self-test: " << failures << " failed checks\n"
                       << (failures == 0 ? "RESULT PASS\n" : "RESULT FAIL\n");
  return failures > 125 ? 125 : failures;
}
