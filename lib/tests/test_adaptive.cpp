// The adaptive solver (docs/numerics.md#adaptive): RODAS4 against closed
// forms, and the scene runner against the frame stepper run with many
// substeps (an independent reference: another method, fixed steps).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/integrate/rodas4.hpp"
#include "cvtplant/integrate/rosenbrock.hpp"
#include "cvtplant/scene/adaptive_runner.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

namespace f = cvt::rom_feature;

// x'' + 2 zeta w x' + w^2 x = 0 with a stiff decaying third state
// y' = -k (y - x): linear, so its solution is known in closed form for x, v.
struct Linear {
  using Scalar = double;
  static constexpr int kStates = 3;
  static constexpr std::uint32_t kPositionMask = 0;
  double w = 2.0, zeta = 0.1, k = 1e4;
  template <class S>
  void derivative(const Eigen::Matrix<S, 3, 1>& x, Eigen::Matrix<S, 3, 1>& d) const {
    d(0) = x(1);
    d(1) = -S(w * w) * x(0) - S(2 * zeta * w) * x(1);
    d(2) = -S(k) * (x(2) - x(0));
  }
  void jacobian(const Eigen::Matrix<double, 3, 1>&, Eigen::Matrix<double, 3, 3>& J) const {
    J << 0, 1, 0, -w * w, -2 * zeta * w, 0, k, 0, -k;
  }
  // x(t) from x(0) = 1, v(0) = 0 (underdamped).
  double x_exact(double t) const {
    const double wd = w * std::sqrt(1 - zeta * zeta);
    return std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
  }
};

// Fixed steps of h over [0, 1]: the error of x(1) and of the dense output
// at the middle of every step.
void linear_errors(double h, double& end_err, double& dense_err) {
  const Linear sys;
  Eigen::Vector3d x(1, 0, 1), f, x_new, atol(1, 1, 1);
  Eigen::Matrix3d J;
  sys.jacobian(x, J);
  cvt::DenseWSolver<Linear> w;
  cvt::Rodas4Work work;
  cvt::Rodas4Dense<Linear> dense;
  const int n = static_cast<int>(std::lround(1.0 / h));
  dense_err = 0;
  for (int i = 0; i < n; ++i) {
    sys.derivative(x, f);
    (void)cvt::rodas4_step(sys, x, f, J, h, w, atol, 1e-6, x_new, &dense, work);
    dense_err = std::max(dense_err, std::fabs(dense.at(0.5)(0) - sys.x_exact((i + 0.5) * h)));
    x = x_new;
  }
  end_err = std::fabs(x(0) - sys.x_exact(1.0));
  CHECK(work.solves == 6L * n);
  CHECK(work.rhs == 5L * n);
}

TEST_CASE("RODAS4: order 4 on a linear system with a stiff mode, dense output of order 3 or better") {
  double e1, d1, e2, d2;
  linear_errors(0.02, e1, d1);
  linear_errors(0.01, e2, d2);
  CAPTURE(e1);
  CAPTURE(e2);
  CAPTURE(d1);
  CAPTURE(d2);
  // Halving h divides the error by 2^4 = 16 for order 4 (stiff mode with
  // k h = 100..200 included: L-stability damps it, no order reduction here).
  CHECK(e1 / e2 > 12.0);
  CHECK(e1 / e2 < 22.0);
  // Continuous output: local error O(h^4), so at least 8x per halving.
  CHECK(d1 / d2 > 7.0);
  CHECK(e2 < 1e-8);
}

TEST_CASE("RODAS4: L-stable, a step far beyond the stiff time scale damps the stiff mode") {
  const Linear sys;
  Eigen::Vector3d x(0, 0, 1), f, x_new, atol(1, 1, 1);  // only y displaced from equilibrium
  Eigen::Matrix3d J;
  sys.jacobian(x, J);
  sys.derivative(x, f);
  cvt::DenseWSolver<Linear> w;
  cvt::Rodas4Work work;
  (void)cvt::rodas4_step(sys, x, f, J, 1.0, w, atol, 1e-6, x_new, nullptr, work);
  // k h = 1e4: the exact factor exp(-1e4) is 0; an A- but not L-stable
  // method would leave a factor near 1 in magnitude.
  CHECK(std::fabs(x_new(2)) < 1e-3);
}

// Frames of a run, row-major, RomLayout<F>::kStates states per frame in SI units.
using Trace = std::vector<double>;
template <std::uint32_t F>
long frames_of(const Trace& t) {
  return static_cast<long>(t.size()) / cvt::RomLayout<F>::kStates;
}

template <std::uint32_t F>
Trace fixed_reference(const cvt::Scene& s, int substeps) {
  cvt::RomSimConfig c = cvt::sim_config_of(s);
  c.method = cvt::Method::ros2;
  c.substeps = substeps;
  c.w_slope_floor = false;
  Trace t;
  cvt::run_scene<double, F>(s, c, [&](long, double, const cvt::RomSimulator<double, F>& sim) {
    const auto x = sim.state_si();
    t.insert(t.end(), x.data(), x.data() + x.size());
    return true;
  });
  return t;
}

template <std::uint32_t F>
Trace adaptive(const cvt::Scene& s, double tol, cvt::AdaptiveStatus& st, cvt::Rodas4Work* work = nullptr) {
  cvt::AdaptiveConfig c;
  c.rtol = c.atol = tol;
  cvt::AdaptiveRun<F> run(s.params, c);
  Trace t;
  st = run.run(s, s.frame_s, [&](long i, double time, const cvt::AdaptiveFrame<F>& fr) {
    CHECK(i == frames_of<F>(t));
    CHECK(time == static_cast<double>(i) * s.frame_s);
    double x[32];
    fr.state_si(x);
    t.insert(t.end(), x, x + fr.state_count());
    return true;
  });
  if (work != nullptr) *work = run.work();
  return t;
}

// docs/performance.md#error; the runs must have the same frames.
template <std::uint32_t F>
double rel_rms(const Trace& ref, const Trace& out) {
  REQUIRE(ref.size() == out.size());
  return cvt::trajectory_relative_rms(ref.data(), out.data(), frames_of<F>(ref), cvt::RomLayout<F>::kStates, F);
}

template <std::uint32_t F>
void check_against_reference(const char* name, double t_end) {
  cvt::Scene s = *cvt::find_builtin_scene(name);
  // The scene's inputs on the plant of mask F (seed-case1: under its clamping
  // actuator; the adaptive runner has no tension plant, docs/numerics.md#adaptive).
  s.features = F;
  s.t_end_s = t_end;
  CAPTURE(name);
  // ROS2 (order 2) with 256 substeps per frame: about 1e-9 relative here.
  const Trace ref = fixed_reference<F>(s, 256);
  cvt::AdaptiveStatus st{};
  cvt::Rodas4Work loose, tight;
  const double e4 = rel_rms<F>(ref, adaptive<F>(s, 1e-4, st, &loose));
  CHECK(st == cvt::AdaptiveStatus::ok);
  const double e7 = rel_rms<F>(ref, adaptive<F>(s, 1e-7, st, &tight));
  CHECK(st == cvt::AdaptiveStatus::ok);
  CAPTURE(e4);
  CAPTURE(e7);
  CHECK(e4 < 3e-4);
  CHECK(e7 < 3e-7);
  CHECK(e7 < e4 / 100.0);
  // It steps over frames: fewer steps than frames at the loose tolerance.
  CHECK(loose.accepted < frames_of<F>(ref));
  CHECK(tight.accepted > loose.accepted);
}

TEST_CASE("Adaptive scene runner: matches the frame stepper at 256 substeps, error follows the tolerance") {
  check_against_reference<f::axial>("seed-case1", 0.5);
  check_against_reference<f::axial>("seed-case2", 0.5);
  check_against_reference<0>("gross-slip", 0.5);
  check_against_reference<0>("oscillator-stribeck", 5.0);
}

TEST_CASE("Adaptive scene runner: held inputs change at a step and every frame of a ramp") {
  // clamp-step: the command steps at 2 s; tip-in: the torque ramps over
  // 1.0 .. 1.2 s, so the held input changes every frame there.
  check_against_reference<f::axial | f::road_load>("tip-in", 1.4);
  cvt::Scene s = *cvt::find_builtin_scene("clamp-step");
  s.t_end_s = 2.3;
  const Trace ref = fixed_reference<f::axial | f::road_load>(s, 256);
  cvt::AdaptiveStatus st{};
  const double e = rel_rms<f::axial | f::road_load>(ref, adaptive<f::axial | f::road_load>(s, 1e-7, st));
  CHECK(st == cvt::AdaptiveStatus::ok);
  CHECK(e < 3e-7);
}

TEST_CASE("Adaptive scene runner: bit-for-bit the same on a second run") {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case2");
  s.t_end_s = 0.5;
  cvt::AdaptiveStatus st{};
  const Trace a = adaptive<f::axial>(s, 1e-6, st);
  const Trace b = adaptive<f::axial>(s, 1e-6, st);
  REQUIRE(a.size() == b.size());
  const bool same = std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  CHECK(same);
}

TEST_CASE("Adaptive scene runner: energy ledger closes, step cap stops the run") {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  s.features = f::axial;  // under its clamping actuator
  s.t_end_s = 0.5;
  cvt::AdaptiveConfig c;
  c.rtol = c.atol = 1e-7;
  cvt::AdaptiveRun<f::axial> run(s.params, c);
  double residual = 1, scale = 0;
  const cvt::AdaptiveStatus st = run.run(s, s.frame_s, [&](long, double, const cvt::AdaptiveFrame<f::axial>& fr) {
    residual = fr.energy().residual_J();
    scale = fr.energy().scale_J();
    return true;
  });
  CHECK(st == cvt::AdaptiveStatus::ok);
  // The trapezoid over 1 ms frames on an accurate solution: the residual is
  // the quadrature's error, far below the watchdog's 5 %.
  CHECK(scale > 0);
  CHECK(std::fabs(residual) < 1e-3 * scale);

  c.max_steps = 10;
  cvt::AdaptiveRun<f::axial> capped(s.params, c);
  long last = -1;
  const cvt::AdaptiveStatus st2 = capped.run(s, s.frame_s, [&](long i, double, const cvt::AdaptiveFrame<f::axial>&) {
    last = i;
    return true;
  });
  CHECK(st2 == cvt::AdaptiveStatus::step_cap);
  CHECK(capped.work().accepted + capped.work().rejected == 10);
  CHECK(last < cvt::scene_frames(s));
}

}  // namespace
