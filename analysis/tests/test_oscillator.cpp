// The seed's section 3 oscillator (docs/analysis.md#seed-oscillator).
#include <doctest/doctest.h>

#include <algorithm>

#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/analysis/test01.hpp"

using namespace cvt::analysis;

TEST_CASE("trajectory sampler returns one row per sample interval") {
  for (const char* name : {"oscillator-coulomb", "oscillator-stribeck"}) {
    const Model& s = find_model(name);
    const auto rows = s.trajectory(s.default_params, s.default_x0, 1e-4, 0, 0.2, 0.05);
    CHECK(rows.size() == 16);
  }
}

TEST_CASE("Coulomb friction from [0 3 0 6]: all exponents negative, equal to the equilibrium's eigenvalue real parts") {
  const Model& s = find_model("oscillator-coulomb");
  BenettinOptions o;
  o.dt = 1e-4;
  o.t_transient = 0;
  o.t_warmup = 5;
  o.t_end = 200;
  const SpectrumResult r = s.spectrum(s.default_params, {0, 3, 0, 6}, o);
  for (double e : r.exponents) CHECK(e < 0);
  // At the sliding equilibrium (v1 = v2 = 0, slip -3.5 m/s) the atan is
  // saturated, so J is the linear spring-damper chain: eigenvalues have real
  // parts -c1/(2m) = -0.5 (twice) and -(c1+2c2)/(2m) = -1.5 (twice). The
  // seed's (-0.49791 -0.56974 -1.4286 -1.5038) is a finite-time split of these.
  CHECK(r.exponents[0] == doctest::Approx(-0.5).epsilon(0.04));
  CHECK(r.exponents[1] == doctest::Approx(-0.5).epsilon(0.04));
  CHECK(r.exponents[2] == doctest::Approx(-1.5).epsilon(0.03));
  CHECK(r.exponents[3] == doctest::Approx(-1.5).epsilon(0.03));
  CHECK(r.sum == doctest::Approx(-4.0).epsilon(1e-4));
  CHECK(r.final_speed < 1e-9);
}

TEST_CASE("Stribeck friction from [0 3 0 6]: a limit cycle, not chaos") {
  const Model& s = find_model("oscillator-stribeck");
  BenettinOptions o;
  o.dt = 1e-3;  // dt/2 changes the exponents by < 1e-8 (docs: dt check)
  o.t_transient = 200;
  o.t_warmup = 20;
  o.t_end = 1000;
  const SpectrumResult r = s.spectrum(s.default_params, {0, 3, 0, 6}, o);
  // lambda_1 is the neutral flow-direction exponent: its CI covers 0 and it
  // equals the growth rate of |f| (exactly, for a closed orbit).
  CHECK(std::abs(r.exponents[0]) <= r.ci95[0]);
  CHECK(std::abs(r.exponents[0]) < 5e-3);
  CHECK(std::abs(r.exponents[0] - r.flow_direction_rate) < 1e-6);
  for (int i = 1; i < 4; ++i) CHECK(r.exponents[i] + r.ci95[i] < -1.0);
  CHECK(r.final_speed > 1.0);  // still moving: not the fixed point
  CHECK(std::abs(r.sum - r.trace_mean) < 1e-6);
  // The finite-time estimate shrinks like 1/t: the extrapolation is ~0.
  CHECK(std::abs(r.lambda1_extrapolated) < 3 * r.lambda1_extrapolated_se + 2e-3);

  // Independent cross-checks on the sampled displacement x1 (10 ms).
  const auto rows = s.trajectory(s.default_params, r.x_final, 1e-3, 0, 200, 0.01);
  std::vector<double> x1;
  for (std::size_t i = 0; i < rows.size(); i += 4) x1.push_back(rows[i]);
  ClassifyOptions co;
  co.dt = 0.01;
  const Classification c = classify(x1, co);
  CHECK(c.classification == "periodic");
  CHECK(std::abs(c.t01.k_median) < 0.1);
  CHECK(c.rqa.det > 0.95);
  // The attractor lies in the invariant plane x1 = x2, v1 = v2 (equal masses
  // and friction): a 2-D autonomous flow, where Poincare-Bendixson rules out chaos.
  double asym = 0;
  for (std::size_t i = 0; i < rows.size(); i += 4)
    asym = std::max({asym, std::abs(rows[i] - rows[i + 2]), std::abs(rows[i + 1] - rows[i + 3])});
  CHECK(asym < 1e-9);
}
