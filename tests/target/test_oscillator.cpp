// The seed's oscillator on the target (docs/build.md#target-tests):
//  * the section-3 behaviours the host suite checks, in float (the M4F's
//    hardware type) and in fixed point, at a reduced horizon;
//  * instruction counts of one oscillator step per scalar type and method
//    (ICOUNT lines; quoted in docs/build.md#icount);
//  * the determinism trace hashes (HASH lines) of the oscillator and of the
//    reduced-order plant, which ctest saves to trace_hash.log for
//    tests/cross/compare-trace-hashes.sh to compare with the x86-64 and
//    aarch64 builds.
#include "../determinism/trace_hash.hpp"
#include "cvtplant/port/icount.hpp"
#include "harness.hpp"

using namespace cvt;
using cvt::port::console;
using cvt::target::abs_diff;

namespace {

template <class T>
StickSlipOscillator<T> seed_oscillator(const FrictionParams<double>& f) {
  return StickSlipOscillator<T>(OscillatorParams<double>::seed_section3(f).template cast<T>());
}

template <class T>
void print_hash_line(const char* label, std::uint64_t hash) {
  auto& c = console();
  c << "HASH " << scalar_name<T>::value << ' ' << label << ' ';
  // Lower-case, no prefix: the host prints with PRIx64.
  char buf[24];
  const std::size_t n = cvt::port::format_hex(buf, sizeof buf, hash, 16);
  for (std::size_t i = 2; i < n; ++i) {
    const char ch = buf[i];
    c << static_cast<char>(ch >= 'A' && ch <= 'F' ? ch - 'A' + 'a' : ch);
  }
  c << '\n';
}

template <class T>
void print_hash(Method m, double h_s, long steps) {
  print_hash_line<T>(method_name(m), testing::oscillator_trace_hash<T>(m, h_s, steps));
}

template <class T>
void print_step_icount(Method m, const char* label) {
  const auto sys = seed_oscillator<T>(friction_presets::oscillator_stribeck<double>());
  typename StickSlipOscillator<T>::State x;
  // A sliding state: both masses slower than the belt, so every call takes
  // the same branch of the friction law and the count is exact.
  x << T(0.05), T(1.0), T(0.02), T(2.0);
  const T h(1.0 / 1024);
  const typename StickSlipOscillator<T>::State x0 = x;
  auto one_step = [&] {
    x = x0;
    step(m, sys, x, h);
  };
  auto reset_only = [&] { x = x0; };
  const std::uint32_t with_step = cvt::port::icount_per_call(one_step);
  const std::uint32_t reset = cvt::port::icount_per_call(reset_only);
  const std::uint32_t n = with_step > reset ? with_step - reset : 0;
  console() << "ICOUNT oscillator_step " << label << ' ' << method_name(m) << ' ' << n << '\n';
  CHECK_GT(n, 0u);
}

}  // namespace

CVT_TARGET_TEST(oscillator_coulomb_converges_float) {
  const auto sys = seed_oscillator<float>(friction_presets::oscillator_coulomb<double>());
  const float x_star = sys.sliding_equilibrium_m();
  StickSlipOscillator<float>::State x;
  x << 0.0f, 3.0f, 0.0f, 6.0f;
  for (int i = 0; i < 40000; ++i) step(Method::ros2, sys, x, 1e-3f);  // 40 s
  CHECK_LE(abs_diff(x(0), x_star), 1e-4);
  CHECK_LE(abs_diff(x(2), x_star), 1e-4);
  CHECK_LE(abs_diff(x(1), 0.0), 1e-3);
  CHECK_LE(abs_diff(x(3), 0.0), 1e-3);
}

CVT_TARGET_TEST(oscillator_stribeck_rest_and_cycle_fixed) {
  const auto sys = seed_oscillator<q16_16>(friction_presets::oscillator_stribeck<double>());
  const double x_star = static_cast<double>(sys.sliding_equilibrium_m());
  const q16_16 h(1.0 / 1024);
  // From rest: settles on the sliding equilibrium (seed Fig. 10, bottom).
  StickSlipOscillator<q16_16>::State x = StickSlipOscillator<q16_16>::State::Zero();
  for (int i = 0; i < 40 * 1024; ++i) step(Method::ros2, sys, x, h);
  CHECK_LE(abs_diff(static_cast<double>(x(0)), x_star), 2e-3);
  // The q16.16 velocity LSB (1.5e-5 m/s) times the steep smoothed sign
  // (lambda = 1e4 s/m) leaves a bounded chatter of a few mm/s around rest.
  CHECK_LE(abs_diff(static_cast<double>(x(1)), 0.0), 1e-2);
  // From [0 3 0 6]: a large stick-slip cycle survives 40 s (seed Fig. 10, top).
  x << q16_16(0.0), q16_16(3.0), q16_16(0.0), q16_16(6.0);
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 40 * 1024; ++i) {
    step(Method::ros2, sys, x, h);
    if (i >= 30 * 1024) {
      const double x1 = static_cast<double>(x(0));
      lo = x1 < lo ? x1 : lo;
      hi = x1 > hi ? x1 : hi;
    }
  }
  CHECK_GT(hi - lo, 0.5);
}

CVT_TARGET_TEST(oscillator_step_instruction_counts) {
  print_step_icount<float>(Method::rk4, "float");
  print_step_icount<float>(Method::ros2, "float");
  print_step_icount<q16_16>(Method::rk4, "q16_16");
  print_step_icount<q16_16>(Method::ros2, "q16_16");
  print_step_icount<double>(Method::ros2, "double");
}

// Same scenarios and steps as tests/determinism/trace_hash_main.cpp, minus
// double RK4 (soft-float double at 1e-4 s steps takes minutes under QEMU).
CVT_TARGET_TEST(oscillator_trace_hashes) {
  print_hash<double>(Method::ros2, 1e-3, 10000);
  print_hash<float>(Method::rk4, 1e-4, 100000);
  print_hash<float>(Method::ros2, 1e-3, 10000);
  print_hash<q16_16>(Method::rk4, 1.0 / 1024, 10240);
  print_hash<q16_16>(Method::ros2, 1.0 / 1024, 10240);
}

// The reduced-order plant's hashes (tests/determinism/trace_hash.hpp), in
// the two types the M4F runs natively or in integers; double is soft-float
// here and is compared between the host and aarch64 only.
CVT_TARGET_TEST(rom_trace_hashes) {
  testing::rom_trace_hashes<float>([](const char* label, std::uint64_t h) { print_hash_line<float>(label, h); });
  testing::rom_trace_hashes<q16_16>([](const char* label, std::uint64_t h) { print_hash_line<q16_16>(label, h); });
}
