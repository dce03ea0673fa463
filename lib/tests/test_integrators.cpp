// Fixed-step integrators: order of accuracy, fixed cost, stiff stability and
// Jacobians (docs/numerics.md#integrators).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"

namespace {

// q'' + 2 zeta w q' + w^2 q = 0, state [q v]; has an exact solution.
struct DampedOscillator {
  using Scalar = double;
  static constexpr int kStates = 2;
  static constexpr std::uint32_t kPositionMask = 0b01u;
  double w = 2.0, zeta = 0.1;
  mutable int rhs_calls = 0;
  template <class S>
  void derivative(const Eigen::Matrix<S, 2, 1>& x, Eigen::Matrix<S, 2, 1>& dx) const {
    ++rhs_calls;
    dx(0) = x(1);
    dx(1) = -S(w * w) * x(0) - S(2.0 * zeta * w) * x(1);
  }
  Eigen::Vector2d exact(double t) const {  // from q(0)=1, v(0)=0
    const double wd = w * std::sqrt(1 - zeta * zeta);
    const double s = zeta * w;
    const double e = std::exp(-s * t);
    const double q = e * (std::cos(wd * t) + s / wd * std::sin(wd * t));
    const double v = -e * (w * w / wd) * std::sin(wd * t);
    return {q, v};
  }
};

// y' = lambda (y - cos t) - sin t, solution y = cos t; stiff for lambda << 0.
// Autonomised with t as a state (t' = 1), so a linearly implicit method sees
// the whole Jacobian.
struct StiffProthero {
  using Scalar = double;
  static constexpr int kStates = 2;
  static constexpr std::uint32_t kPositionMask = 0;
  double lambda = -1e4;
  template <class S>
  void derivative(const Eigen::Matrix<S, 2, 1>& x, Eigen::Matrix<S, 2, 1>& dx) const {
    // Generic code outside namespace cvt names the math once; the dual
    // overloads are found by argument-dependent lookup (detmath.hpp).
    using cvt::cos;
    using cvt::sin;
    dx(0) = S(lambda) * (x(0) - cos(x(1))) - sin(x(1));
    dx(1) = S(1.0);
  }
};

double error_at(cvt::Method m, double h, double t_end) {
  DampedOscillator sys;
  Eigen::Vector2d x(1.0, 0.0);
  const int n = static_cast<int>(std::lround(t_end / h));
  for (int i = 0; i < n; ++i) cvt::step(m, sys, x, h);
  return (x - sys.exact(t_end)).norm();
}

}  // namespace

TEST_CASE("each method converges at its stated order") {
  for (const cvt::Method m : cvt::kAllMethods) {
    CAPTURE(cvt::method_name(m));
    // Steps small enough to be in the asymptotic range for every method, yet
    // large enough that round-off does not hide the error of RK4.
    const double h = cvt::method_order(m) == 4 ? 0.02 : 0.002;
    const double e1 = error_at(m, h, 2.0);
    const double e2 = error_at(m, h / 2, 2.0);
    const double observed = std::log2(e1 / e2);
    CHECK(observed == doctest::Approx(cvt::method_order(m)).epsilon(0.1));
  }
}

TEST_CASE("the cost per step is fixed: right-hand-side evaluations do not depend on the state") {
  const int expected[] = {1, 2, 2, 4, 1, 2};  // euler, semi-implicit, heun, rk4, lin-impl (+jac), ros2 (+jac)
  int k = 0;
  for (const cvt::Method m : cvt::kAllMethods) {
    CAPTURE(cvt::method_name(m));
    for (const double q0 : {0.0, 1.0, -1e3}) {
      DampedOscillator sys;
      Eigen::Vector2d x(q0, 0.5);
      sys.rhs_calls = 0;
      cvt::step(m, sys, x, 0.01);
      // Rosenbrock methods also differentiate the system once with duals.
      const bool implicit = m == cvt::Method::linear_implicit_euler || m == cvt::Method::ros2;
      CHECK(sys.rhs_calls == expected[k] + (implicit ? 1 : 0));
    }
    ++k;
  }
}

TEST_CASE("linearly implicit methods stay stable and accurate where RK4 explodes (h*lambda = -10)") {
  const double h = 1e-3;
  for (const cvt::Method m : cvt::kAllMethods) {
    CAPTURE(cvt::method_name(m));
    StiffProthero sys;
    Eigen::Vector2d x(1.5, 0.0);  // off the slow manifold: a fast transient first
    for (int i = 0; i < 2000; ++i) cvt::step(m, sys, x, h);
    const double err = std::fabs(x(0) - std::cos(x(1)));
    if (m == cvt::Method::linear_implicit_euler || m == cvt::Method::ros2) {
      // L-stable: the transient is gone and the slow solution is followed to O(h/|lambda|).
      CHECK(err < 1e-6);
    } else {
      CHECK(!(err < 1.0));  // explicit methods are unstable here (or NaN)
    }
  }
}

TEST_CASE("semi-implicit Euler keeps the energy of an undamped oscillator bounded; explicit Euler does not") {
  auto energy_growth = [](cvt::Method m) {
    DampedOscillator sys;
    sys.zeta = 0.0;
    Eigen::Vector2d x(1.0, 0.0);
    const double e0 = 0.5 * (x(1) * x(1) + sys.w * sys.w * x(0) * x(0));
    for (int i = 0; i < 100000; ++i) cvt::step(m, sys, x, 0.01);
    return 0.5 * (x(1) * x(1) + sys.w * sys.w * x(0) * x(0)) / e0;
  };
  const double symplectic = energy_growth(cvt::Method::semi_implicit_euler);
  CHECK(symplectic < 1.03);
  CHECK(symplectic > 0.97);
  CHECK(energy_growth(cvt::Method::explicit_euler) > 10.0);
}

TEST_CASE("oscillator Jacobian: analytic == dual numbers == finite differences") {
  for (const auto& fr : {cvt::friction_presets::oscillator_coulomb<double>(),
                         cvt::friction_presets::oscillator_stribeck<double>()}) {
    auto p = cvt::OscillatorParams<double>::seed_section3(fr);
    p.friction.lambda_s_m = 30.0;  // smooth enough for a clean central difference
    const cvt::StickSlipOscillator<double> sys(p);
    for (const Eigen::Vector4d& x : {Eigen::Vector4d(0, 3, 0, 6), Eigen::Vector4d(0.1, 3.49, -0.2, 3.52),
                                    Eigen::Vector4d(-0.3, 0, 0.4, 1)}) {
      Eigen::Matrix4d Ja, Jd, Jf;
      sys.jacobian(x, Ja);
      cvt::jacobian_by_duals(sys, x, Jd);
      for (int j = 0; j < 4; ++j) {
        const double h = 1e-6;
        Eigen::Vector4d xp = x, xm = x, fp, fm;
        xp(j) += h;
        xm(j) -= h;
        sys.derivative(xp, fp);
        sys.derivative(xm, fm);
        Jf.col(j) = (fp - fm) / (2 * h);
      }
      CHECK((Ja - Jd).cwiseAbs().maxCoeff() <= 1e-12 * (1 + Ja.cwiseAbs().maxCoeff()));
      CHECK((Ja - Jf).cwiseAbs().maxCoeff() <= 1e-6 * (1 + Ja.cwiseAbs().maxCoeff()));
    }
  }
}
