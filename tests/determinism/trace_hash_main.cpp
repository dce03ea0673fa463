// Prints the trace hashes of the reference scenario for every scalar type and
// a representative set of methods. The determinism tests compare this output
// between two runs, between -O0 and -O2 builds and between targets.
#include <cinttypes>
#include <cstdio>

#include "trace_hash.hpp"

namespace {
template <class T>
void print(cvt::Method m, double h, long steps) {
  std::printf("HASH %s %s %016" PRIx64 "\n", cvt::scalar_name<T>::value, cvt::method_name(m),
              cvt::testing::oscillator_trace_hash<T>(m, h, steps));
}
template <class T>
void print_rom() {
  cvt::testing::rom_trace_hashes<T>([](const char* label, std::uint64_t h) {
    std::printf("HASH %s %s %016" PRIx64 "\n", cvt::scalar_name<T>::value, label, h);
  });
}
}  // namespace

int main() {
  // 10 s of simulated time at the step each type is usually run with.
  print<double>(cvt::Method::rk4, 1e-4, 100000);
  print<double>(cvt::Method::ros2, 1e-3, 10000);
  print<float>(cvt::Method::rk4, 1e-4, 100000);
  print<float>(cvt::Method::ros2, 1e-3, 10000);
  print<cvt::q16_16>(cvt::Method::rk4, 1.0 / 1024, 10240);
  print<cvt::q16_16>(cvt::Method::ros2, 1.0 / 1024, 10240);
  // The reduced-order plant in every scalar type (docs/rom.md#determinism).
  print_rom<double>();
  print_rom<float>();
  print_rom<cvt::q16_16>();
  return 0;
}
