// calibrate on a manoeuvre suite (docs/validation.md#calibration-suite): the
// manoeuvre cases run the plant as validate --suite does, and a held-out
// manoeuvre is reported at the start and the result but never fitted.
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/calibration.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/manoeuvre.hpp"
#include "cvtplant/validation/suite.hpp"

using namespace cvt::validation;

namespace {

// A variable-ratio plant built here (not a built-in scene, whose values move).
cvt::Scene wedging_plant() {
  cvt::Scene s;
  s.features = cvt::rom_feature::axial | cvt::rom_feature::road_load | cvt::rom_feature::wedging;
  s.params.friction = cvt::friction_presets::table2_case1<double>();
  return s;
}

// The plant's own run of a manoeuvre as its "reference".
ReferenceRun plant_reference(const Manoeuvre& m, const cvt::Scene& plant) {
  ReferenceRun r;
  r.series = plant_manoeuvre(m, plant, nullptr);
  return r;
}

}  // namespace

TEST_SUITE("calibration") {
  // Cost: about 1 s (host release): two plant holds to settle, then a
  // few short manoeuvre runs.
  TEST_CASE("a suite's held-out manoeuvre is reported at the start and the result, never fitted") {
    const cvt::Scene truth = wedging_plant();
    const OperatingPoint op = controller_point(150, 1.5, 60);
    const Manoeuvre fitted = clamp_step_manoeuvre(op, 0.1, 0.01, 0.06);
    const Manoeuvre held = clamp_step_manoeuvre(op, -0.1, 0.01, 0.06);
    const ReferenceRun ref_fit = plant_reference(fitted, truth), ref_held = plant_reference(held, truth);
    cvt::Scene start = truth;
    start.params.normal_load_factor *= 1.2;

    Calibration cal({"normal_load_factor"}, start.params);
    cal.add_manoeuvre_case(fitted, start, ref_fit, 1, false);
    cal.add_manoeuvre_case(held, start, ref_held, 1, true);
    const CalibrationResult r = cal.run(12);
    // Only the fitted run's samples are residuals: five quantities.
    CHECK(r.residuals == 5 * static_cast<int>(ref_fit.series.size()));
    REQUIRE(r.cases.size() == 2u);
    CHECK_FALSE(r.cases[0].held_out);
    CHECK(r.cases[1].held_out);
    CHECK(r.cases[1].quantities.size() == 5u);
    CHECK(r.cases[1].quantities.back() == std::string("ratio"));

    // The held-out errors at the start are those the same run has as a
    // fitted case at the start.
    Calibration alone({"normal_load_factor"}, start.params);
    alone.add_manoeuvre_case(held, start, ref_held, 1, false);
    const std::vector<double> f = alone.start_residuals();
    const std::size_t n = ref_held.series.size();
    for (std::size_t q = 0; q < 5; ++q) {
      double ss = 0;
      for (std::size_t i = 0; i < n; ++i) ss += f[q * n + i] * f[q * n + i];
      CHECK(r.cases[1].rel_rms_start[q] == doctest::Approx(std::sqrt(ss)).epsilon(1e-12));
    }
    // The fit moves the shared value towards the truth, and the held-out
    // run, made with the same truth, follows.
    CHECK(std::fabs(r.params[0].value - truth.params.normal_load_factor) <
          0.5 * std::fabs(r.params[0].start - truth.params.normal_load_factor));
    double held_start = 0, held_end = 0;
    for (std::size_t q = 0; q < 5; ++q) {
      held_start += r.cases[1].rel_rms_start[q] * r.cases[1].rel_rms_start[q];
      held_end += r.cases[1].rel_rms_end[q] * r.cases[1].rel_rms_end[q];
    }
    CHECK(held_end < held_start);
    CHECK(r.evaluations <= 12);
    CHECK(r.held_out_faults == 0);

    // A plant without a variable ratio cannot run a manoeuvre.
    cvt::Scene fixed = truth;
    fixed.features = cvt::rom_feature::axial;
    CHECK_THROWS_AS(cal.add_manoeuvre_case(fitted, fixed, ref_fit, 1, false), InputError);
  }
}
