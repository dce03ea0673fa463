// The seed's stick-slip oscillator (docs/physics.md#oscillator):
//  * host cost of one fixed step per scalar type and method;
//  * work-precision: run time of 2 s of the Stribeck cycle from [0 3 0 6]
//    against the error of the end state, for every fixed-step method at
//    several steps and for Boost.Odeint's adaptive Dormand-Prince at several
//    tolerances (an established solver for comparison).
// Table and command: docs/numerics.md#work-precision.
#include <benchmark/benchmark.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"

namespace {

namespace odeint = boost::numeric::odeint;

template <class T>
cvt::StickSlipOscillator<T> stribeck() {
  return cvt::StickSlipOscillator<T>(
      cvt::OscillatorParams<double>::seed_section3(cvt::friction_presets::oscillator_stribeck<double>())
          .template cast<T>());
}

// ---- cost of one step --------------------------------------------------------

template <class T>
void BM_step(benchmark::State& st, cvt::Method m) {
  const auto sys = stribeck<T>();
  typename cvt::StickSlipOscillator<T>::State x;
  x << T(0.05), T(1.0), T(0.02), T(2.0);  // sliding: the common branch
  const typename cvt::StickSlipOscillator<T>::State x0 = x;
  const T h(1.0 / 1024);
  for (auto _ : st) {
    x = x0;
    cvt::step(m, sys, x, h);
    benchmark::DoNotOptimize(x);
  }
}

// ---- work-precision ------------------------------------------------------------

constexpr double kHorizon_s = 2.0;
using Vec4 = std::array<double, 4>;

struct OdeintRhs {
  cvt::StickSlipOscillator<double> sys = stribeck<double>();
  void operator()(const Vec4& x, Vec4& dxdt, double /*t*/) const {
    const Eigen::Vector4d xe(x[0], x[1], x[2], x[3]);
    Eigen::Vector4d f;
    sys.derivative(xe, f);
    for (int i = 0; i < 4; ++i) dxdt[i] = f(i);
  }
};

Vec4 odeint_solution(double tol) {
  Vec4 x{0.0, 3.0, 0.0, 6.0};
  odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_dopri5<Vec4>>(tol, tol), OdeintRhs{}, x,
                             0.0, kHorizon_s, 1e-5);
  return x;
}

// Dormand-Prince at a tolerance far below every method's error, computed once.
const Vec4& reference() {
  static const Vec4 ref = odeint_solution(1e-13);
  return ref;
}

double error_of(const Vec4& x) {
  double e = 0.0;
  for (int i = 0; i < 4; ++i) e = std::fmax(e, std::fabs(x[i] - reference()[i]));
  return e;
}

void BM_fixed_step(benchmark::State& st, cvt::Method m) {
  const double h = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kHorizon_s / h);
  const auto sys = stribeck<double>();
  Eigen::Vector4d x;
  reference();
  for (auto _ : st) {
    x << 0.0, 3.0, 0.0, 6.0;
    for (long i = 0; i < n; ++i) cvt::step(m, sys, x, h);
    benchmark::DoNotOptimize(x);
  }
  st.counters["h_s"] = h;
  st.counters["max_abs_error"] = error_of({x(0), x(1), x(2), x(3)});
}

void BM_odeint_dopri5(benchmark::State& st) {
  const double tol = std::pow(10.0, -static_cast<double>(st.range(0)));
  reference();
  Vec4 x{};
  for (auto _ : st) {
    x = odeint_solution(tol);
    benchmark::DoNotOptimize(x);
  }
  st.counters["tol"] = tol;
  st.counters["max_abs_error"] = error_of(x);
}

}  // namespace

void BM_step_double(benchmark::State& st, cvt::Method m) { BM_step<double>(st, m); }
void BM_step_float(benchmark::State& st, cvt::Method m) { BM_step<float>(st, m); }
void BM_step_q16_16(benchmark::State& st, cvt::Method m) { BM_step<cvt::q16_16>(st, m); }
BENCHMARK_CAPTURE(BM_step_double, rk4, cvt::Method::rk4);
BENCHMARK_CAPTURE(BM_step_double, ros2, cvt::Method::ros2);
BENCHMARK_CAPTURE(BM_step_double, linear_implicit_euler, cvt::Method::linear_implicit_euler);
BENCHMARK_CAPTURE(BM_step_double, semi_implicit_euler, cvt::Method::semi_implicit_euler);
BENCHMARK_CAPTURE(BM_step_float, rk4, cvt::Method::rk4);
BENCHMARK_CAPTURE(BM_step_float, ros2, cvt::Method::ros2);
BENCHMARK_CAPTURE(BM_step_q16_16, rk4, cvt::Method::rk4);
BENCHMARK_CAPTURE(BM_step_q16_16, ros2, cvt::Method::ros2);

// Steps per second: 1000 .. 32000 (h = 1 ms .. 31 us).
#define CVT_WP(name, method) \
  BENCHMARK_CAPTURE(BM_fixed_step, name, method)->RangeMultiplier(2)->Range(1000, 32000)->Unit(benchmark::kMillisecond)
CVT_WP(rk4, cvt::Method::rk4);
CVT_WP(heun, cvt::Method::heun);
CVT_WP(ros2, cvt::Method::ros2);
CVT_WP(linear_implicit_euler, cvt::Method::linear_implicit_euler);
CVT_WP(semi_implicit_euler, cvt::Method::semi_implicit_euler);
#undef CVT_WP
BENCHMARK(BM_odeint_dopri5)->DenseRange(4, 10, 2)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
