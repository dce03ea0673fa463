// The FMU tests (docs/fmu.md#tests). `cvt_fmu_tests resume ...` is the
// second process of the serialised-state test (test_fmu_calls.cpp).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstring>
#include <exception>
#include <cstdio>

int resume_in_new_process(int argc, char** argv);

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "resume") == 0) {
    try {
      return resume_in_new_process(argc, argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "resume: %s\n", e.what());
      return 1;
    }
  }
  doctest::Context ctx(argc, argv);
  return ctx.run();
}
