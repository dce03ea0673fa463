// Friction laws and sign functions (docs/physics.md#friction).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/autodiff/dual.hpp"
#include "cvtplant/friction/friction_law.hpp"

using cvt::FrictionLaw;
using cvt::FrictionParams;
using cvt::SignFunction;
namespace presets = cvt::friction_presets;

namespace {
FrictionParams<double> all_presets[] = {presets::oscillator_coulomb<double>(), presets::oscillator_stribeck<double>(),
                                        presets::table2_case1<double>(), presets::table2_case2<double>()};
}

TEST_CASE("case 1 rises from a to mu0 with velocity scale b (Eq. 6 case 1)") {
  const auto p = presets::table2_case1<double>();
  CHECK(cvt::friction_coefficient(p, 0.0) == doctest::Approx(0.003));
  // One velocity scale b covers 1 - 1/e of the rise.
  CHECK(cvt::friction_coefficient(p, 0.1) == doctest::Approx(0.003 + (0.25 - 0.003) * (1.0 - std::exp(-1.0))));
  CHECK(cvt::friction_coefficient(p, 10.0) == doctest::Approx(0.25).epsilon(1e-12));
}

TEST_CASE("case 2 (Stribeck) is zero at rest, peaks above mu0 and decays to mu0") {
  const auto p = presets::oscillator_stribeck<double>();
  CHECK(cvt::friction_coefficient(p, 0.0) == 0.0);
  double peak = 0.0;
  double v_peak = 0.0;
  for (double v = 0.0; v < 5.0; v += 1e-3) {
    const double mu = cvt::friction_coefficient(p, v);
    if (mu > peak) {
      peak = mu;
      v_peak = v;
    }
  }
  CHECK(peak > 0.25 * 2.0);  // sigma = 6.5 gives a large stiction hump
  CHECK(v_peak > 0.05);
  CHECK(v_peak < 1.0);
  CHECK(cvt::friction_coefficient(p, 50.0) == doctest::Approx(0.25).epsilon(1e-12));
  // Negative slope beyond the peak: the source of self-excitation.
  CHECK(cvt::friction_coefficient(p, 2.0) > cvt::friction_coefficient(p, 3.0));
}

TEST_CASE("sign functions are odd, bounded and have the documented slope at 0") {
  for (const SignFunction s : {SignFunction::exact, SignFunction::atan, SignFunction::tanh}) {
    FrictionParams<double> p = presets::oscillator_coulomb<double>();
    p.sign = s;
    p.lambda_s_m = 100.0;
    for (double v : {1e-4, 1e-3, 0.01, 0.1, 1.0, 10.0}) {
      CHECK(cvt::friction_sign(p, -v) == -cvt::friction_sign(p, v));
      CHECK(std::fabs(cvt::friction_sign(p, v)) <= 1.0);
      CHECK(cvt::friction_sign(p, v) > 0.0);
    }
    CHECK(cvt::friction_sign(p, 0.0) == 0.0);
  }
  FrictionParams<double> p = presets::oscillator_coulomb<double>();
  p.lambda_s_m = 1e4;
  // 2/pi atan(1) = 1/2 at lambda v = 1 (Eq. 9).
  CHECK(cvt::friction_sign(p, 1e-4) == doctest::Approx(0.5).epsilon(1e-12));
  p.sign = SignFunction::tanh;
  CHECK(cvt::friction_sign(p, 1e-4) == doctest::Approx(std::tanh(1.0)).epsilon(1e-12));
}

TEST_CASE("analytic slope of the friction characteristic matches central differences and duals") {
  for (FrictionParams<double> p : all_presets) {
    for (const SignFunction s : {SignFunction::atan, SignFunction::tanh}) {
      p.sign = s;
      p.lambda_s_m = 50.0;  // mild, so the central difference is accurate
      for (double v : {-3.0, -0.5, -0.02, -1e-3, 1e-3, 0.02, 0.5, 3.5}) {
        const double h = 1e-6;
        const double fd = (cvt::friction_characteristic(p, v + h) - cvt::friction_characteristic(p, v - h)) / (2 * h);
        const double an = cvt::friction_characteristic_slope(p, v);
        CHECK(an == doctest::Approx(fd).epsilon(1e-6).scale(1.0));
        using D = cvt::Dual<double, 1>;
        const D dv = cvt::friction_characteristic(p, D::variable(v, 0));
        CHECK(dv.d[0] == doctest::Approx(an).epsilon(1e-12));
      }
    }
  }
}
