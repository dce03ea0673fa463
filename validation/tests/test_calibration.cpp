// The calibration problem (docs/validation.md#calibration): a fit against a
// reference made by the plant itself with a known parameter must find that
// parameter, its cost is validate's relative RMS errors squared, and the
// files it writes carry the values to the last digit.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/validation/calibration.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/plant.hpp"

using namespace cvt::validation;

namespace {

// gross-slip over 0.3 s: the chain slides on the driver, so the torque it
// carries is the friction on the wrap, proportional to the normal load.
cvt::Scene short_gross_slip() {
  cvt::Scene s = *cvt::find_builtin_scene("gross-slip");
  s.t_end_s = 0.3;
  return s;
}

// The plant's own run as the "reference".
ReferenceRun plant_as_reference(const cvt::Scene& s) {
  ReferenceRun r;
  r.series = plant_run(s, s.frame_s);
  r.sheave1_m.assign(r.series.size(), 0.0);
  r.sheave2_m.assign(r.series.size(), 0.0);
  return r;
}

}  // namespace

TEST_SUITE("calibration") {
  TEST_CASE("a known normal-load factor is found again, with a small uncertainty") {
    const cvt::Scene start = short_gross_slip();
    cvt::Scene truth = start;
    truth.params.normal_load_factor = 0.8 * start.params.normal_load_factor;
    Calibration cal({"normal_load_factor"}, start.params);
    cal.add_case("gross-slip", start, plant_as_reference(truth), 10);
    const CalibrationResult r = cal.run(100);
    REQUIRE(r.params.size() == 1u);
    CHECK(r.params[0].start == start.params.normal_load_factor);
    CHECK(r.params[0].value == doctest::Approx(truth.params.normal_load_factor).epsilon(1e-5));
    CHECK(r.params[0].identifiable);
    CHECK(r.cost_start > 1e-4);
    CHECK(r.cost_end < 1e-10 * r.cost_start);
    CHECK(r.fitted.normal_load_factor == r.params[0].value);
    CHECK(r.faults == 0);
    CHECK(r.residuals == 4 * 31);  // 301 frames, every 10th
  }

  TEST_CASE("each case's cost is the sum of validate's squared relative RMS errors") {
    const cvt::Scene start = short_gross_slip();
    cvt::Scene truth = start;
    truth.params.normal_load_factor = 0.9 * start.params.normal_load_factor;
    const ReferenceRun ref = plant_as_reference(truth);
    Calibration cal({"normal_load_factor"}, start.params);
    cal.add_case("gross-slip", start, ref, 1);
    const std::vector<double> f = cal.start_residuals();
    const Series plant = plant_run(start, start.frame_s);
    double expected = 0;
    for (const auto& q : kFitQuantities) expected += std::pow(rel_rms(plant.*q.column, ref.series.*q.column), 2);
    double cost = 0;
    for (double x : f) cost += x * x;
    CHECK(expected > 1e-4);
    CHECK(cost == doctest::Approx(expected).epsilon(1e-12));
  }

  TEST_CASE("unknown, repeated or no parameters are refused; shares at an end start from the middle") {
    const cvt::RomParams p;
    CHECK_THROWS_AS(Calibration({"J1_kgm2"}, p), InputError);  // physical: shared with the reference
    CHECK_THROWS_AS(Calibration({"no_such"}, p), InputError);
    CHECK_THROWS_AS(Calibration({"k1_N_m", "k1_N_m"}, p), InputError);
    CHECK_THROWS_AS(Calibration({}, p), InputError);
    cvt::RomParams q;
    q.wrap_tension_share = 0.0;  // the term switched off
    Calibration cal({"wrap_tension_share"}, q);
    CHECK_THROWS_AS(cal.run(1), InputError);  // no case to fit on
  }

  TEST_CASE("the parameter file and the header carry every value to the last digit") {
    CalibrationResult r;
    r.residuals = 8;
    r.cost_start = 2.0;
    r.cost_end = 0.5;
    r.params = {{"k1_N_m", 2707.8729961981267, 3141.5926535897931, 12.5, 12.5 / 3141.5926535897931, true},
                {"entry_load_share", 0.5, 0.123456789012345678, 0, 0, false}};
    const std::string file = params_file_text(r, "cvtplant calibrate --fit k1_N_m,entry_load_share", "a,b");
    CHECK(file.find("# (rms residual 0.5 -> 0.25)") != std::string::npos);
    const auto value_after = [&](const std::string& text, const std::string& key) {
      const std::size_t at = text.find(key);
      REQUIRE(at != std::string::npos);
      return std::strtod(text.c_str() + at + key.size(), nullptr);
    };
    CHECK(value_after(file, "\nk1_N_m = ") == 3141.5926535897931);
    CHECK(value_after(file, "\nentry_load_share = ") == 0.123456789012345678);
    CHECK(file.find("not identifiable") != std::string::npos);
    const std::string header = header_text(r, "cvtplant calibrate", "apply_case");
    CHECK(header.find("constexpr void apply_case(RomParams& p) {") != std::string::npos);
    CHECK(value_after(header, "p.k1_N_m = ") == 3141.5926535897931);
    CHECK(value_after(header, "p.entry_load_share = ") == 0.123456789012345678);
    CHECK_THROWS_AS(header_text(r, "", "1st"), InputError);
    CHECK(is_cpp_identifier("apply_2"));
    CHECK_FALSE(is_cpp_identifier("apply-2"));
    CHECK_FALSE(is_cpp_identifier(""));
  }
}
