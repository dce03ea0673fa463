// The plant step never allocates (docs/architecture.md#no-heap).
//
// Eigen's own runtime check: with EIGEN_RUNTIME_NO_MALLOC defined and asserts
// on, any Eigen heap allocation while set_is_malloc_allowed(false) is in force
// aborts. Global operator new is replaced to count allocations from anything
// else. A forked child proves the check is armed (it must abort).
#define EIGEN_RUNTIME_NO_MALLOC
#undef NDEBUG
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <new>

#include <Eigen/Dense>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"

namespace {
long g_news = 0;
}

void* operator new(std::size_t n) {
  ++g_news;
  if (void* p = std::malloc(n ? n : 1)) return p;
  std::abort();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

int failures = 0;
void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) ++failures;
}

template <class T>
void run_all_methods(double h) {
  const auto p = cvt::OscillatorParams<double>::seed_section3(cvt::friction_presets::oscillator_stribeck<double>());
  const cvt::StickSlipOscillator<T> sys(p.template cast<T>());
  for (const cvt::Method m : cvt::kAllMethods) {
    typename cvt::StickSlipOscillator<T>::State x;
    x << T(0.0), T(3.0), T(0.0), T(6.0);
    for (int i = 0; i < 200; ++i) cvt::step(m, sys, x, T(h));
  }
}

// 100 frames of the drive-train plant with the features of mask F, through
// the simulator (ledger, watchdog, the structured or the dense solve).
template <class T, std::uint32_t F>
void run_rom_frames(const char* scene) {
  cvt::Scene s = *cvt::find_builtin_scene(scene);
  s.features = F;
  s.t_end_s = 0.1;
  cvt::run_scene<T, F>(s, cvt::sim_config_of(s), [](long, double, const auto&) { return true; });
}

}  // namespace

int main() {
  // 1. The check is armed: a dynamic Eigen allocation must abort.
  const pid_t pid = fork();
  if (pid == 0) {
    Eigen::internal::set_is_malloc_allowed(false);
    Eigen::MatrixXd m(50, 50);  // heap: must trip eigen_assert -> abort
    m.setZero();
    std::_Exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  check(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT, "EIGEN_RUNTIME_NO_MALLOC aborts a heap allocation");

  // 2. Every method, every scalar type: no Eigen allocation, no operator new.
  const long news_before = g_news;
  Eigen::internal::set_is_malloc_allowed(false);
  run_all_methods<double>(1e-4);
  run_all_methods<float>(1e-4);
  run_all_methods<cvt::q16_16>(1.0 / 1024);
  Eigen::internal::set_is_malloc_allowed(true);
  check(g_news == news_before, "no operator new during plant steps");

  // 3. The drive-train plant: every feature (wedging: dense 11x11 LU and
  // dual-number Jacobian), and every fixed-point feature.
  namespace f = cvt::rom_feature;
  const long news_rom = g_news;
  Eigen::internal::set_is_malloc_allowed(false);
  run_rom_frames<double, f::all>("clamp-step");
  run_rom_frames<float, f::all>("clamp-step");
  run_rom_frames<cvt::q16_16, f::basic>("clamp-step");
  run_rom_frames<double, 0>("seed-case1");
  run_rom_frames<double, f::tension>("seed-case1");
  run_rom_frames<float, f::tension>("seed-case1");
  Eigen::internal::set_is_malloc_allowed(true);
  check(g_news == news_rom, "no operator new during drive-train plant frames");

  std::printf("%d passed, %d failed\n", 3 - failures, failures);
  return failures == 0 ? 0 : 1;
}
