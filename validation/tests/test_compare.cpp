// The error measures (docs/validation.md#measures): closed forms on
// constructed series, and the one relative RMS definition that validate's
// tables and calibrate's residuals share.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/errors.hpp"

using namespace cvt::validation;

namespace {

double sum_of_squares(const std::vector<double>& v) {
  return std::inner_product(v.begin(), v.end(), v.begin(), 0.0);
}

// A grid of n samples 1 ms apart with every column set by f(t).
template <class F>
Series series(std::size_t n, F&& f) {
  Series s;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 1e-3 * static_cast<double>(i);
    s.t_s.push_back(t);
    f(t, s);
  }
  return s;
}

}  // namespace

TEST_SUITE("compare") {
  TEST_CASE("rel_rms of a plant off by a constant factor is that factor") {
    std::vector<double> ref, plant;
    for (int i = 0; i < 100; ++i) {
      ref.push_back(std::sin(0.1 * i) + 2.0);
      plant.push_back(1.03 * ref.back());
    }
    CHECK(rel_rms(plant, ref) == doctest::Approx(0.03).epsilon(1e-12));
    CHECK(rel_rms(ref, ref) == 0.0);
  }

  TEST_CASE("a sample where either model is not finite is left out") {
    std::vector<double> ref = {1.0, 2.0, 3.0}, plant = {1.1, 2.2, 3.3};
    const double clean = rel_rms(plant, ref);
    ref.insert(ref.begin() + 1, NAN);
    plant.insert(plant.begin() + 1, 100.0);
    plant.push_back(NAN);
    ref.push_back(5.0);
    CHECK(rel_rms(plant, ref) == clean);
    CHECK(clean == doctest::Approx(0.1).epsilon(1e-12));
  }

  TEST_CASE("a reference that is 0 throughout gives the absolute RMS of the difference") {
    const std::vector<double> ref = {0.0, 0.0, 0.0, 0.0}, plant = {1.0, -1.0, 1.0, -1.0};
    CHECK(rel_rms(plant, ref) == 1.0);
    std::vector<double> r(4);
    relative_residuals(plant, ref, reference_scale(ref), r.data());
    CHECK(sum_of_squares(r) == doctest::Approx(1.0).epsilon(1e-15));
  }

  TEST_CASE("calibrate's residuals square-sum to validate's rel_rms squared, missing reference samples included") {
    // The plant is finite (a plant that faults is not compared); the
    // reference misses samples.
    std::vector<double> ref, plant;
    for (int i = 0; i < 500; ++i) {
      ref.push_back(i % 37 == 5 ? NAN : 50.0 + 10.0 * std::cos(0.05 * i));
      plant.push_back((std::isnan(ref.back()) ? 50.0 : ref.back()) * (1.0 + 0.02 * std::sin(0.3 * i)) + 0.5);
    }
    const ReferenceScale scale = reference_scale(ref);
    CHECK(scale.used == 500u - 14u);  // i % 37 == 5: 14 of 500
    std::vector<double> r(ref.size());
    relative_residuals(plant, ref, scale, r.data());
    const double e = rel_rms(plant, ref);
    CHECK(e > 0.01);
    CHECK(sum_of_squares(r) == doctest::Approx(e * e).epsilon(1e-13));
    // The missing samples contribute nothing.
    CHECK(r[5] == 0.0);
    CHECK(r[42] == 0.0);
    CHECK(r[7] != 0.0);
  }

  TEST_CASE("the whole wrap's slip: the smallest forward, the largest backward, else 0") {
    CHECK(whole_wrap_slip(0.2, 0.5) == 0.2);
    CHECK(whole_wrap_slip(-0.5, -0.2) == -0.2);
    CHECK(whole_wrap_slip(-0.1, 0.3) == 0.0);
    CHECK(std::isnan(whole_wrap_slip(0.3, -0.1)));
    CHECK(std::isnan(whole_wrap_slip(NAN, 0.1)));
  }

  TEST_CASE("compare: steady-state means over the last second, ripple, ratio where omega2 turns, gross slip") {
    // 3 s: omega2 starts below 1 rad/s (no ratio there), the plant's force
    // is 1 % high and carries a 20 N peak-to-peak ripple in the last second,
    // its wrap slides from 2.5 s, the reference's never.
    const auto fill = [](bool plant) {
      return series(3001, [plant](double t, Series& s) {
        s.omega1_rad_s.push_back(100.0);
        s.omega2_rad_s.push_back(t < 0.5 ? 0.5 : (plant ? 50.0 : 40.0));
        s.F_ax1_N.push_back(plant ? 1010.0 + (t >= 2.0 - 1e-9 ? 10.0 * std::cos(2e3 * t) : 0.0) : 1000.0);
        s.torque_driver_Nm.push_back(plant ? 99.0 : 100.0);
        s.slip1_m_s.push_back(0.01);
        s.wrap_slip_m_s.push_back(plant && t >= 2.5 - 1e-9 ? 2.0 : 0.0);
        s.ratio_geom.push_back(plant ? 1.5 : 1.2);
        // The plant has no driven axial force (no wedging): NaN throughout.
        s.F_ax2_N.push_back(plant ? std::nan("") : 1100.0);
      });
    };
    const Series p = fill(true), r = fill(false);
    const Comparison c = compare(p, r, p.size());
    CHECK(c.compared_s == doctest::Approx(3.0));
    CHECK(c.window_s == 1.0);
    REQUIRE(c.rows.size() == 8u);
    CHECK(c.rows[0].quantity == "omega1");
    CHECK(c.rows[0].rel_rms == 0.0);
    CHECK(c.rows[2].quantity == "ratio omega1/omega2");
    CHECK(c.rows[2].plant_ss == doctest::Approx(2.0));
    CHECK(c.rows[2].reference_ss == doctest::Approx(2.5));
    CHECK(c.rows[2].rel_rms == doctest::Approx(0.2));  // |2 - 2.5| / 2.5 where both turn
    CHECK(c.rows[4].quantity == "torque on the driver");
    CHECK(c.rows[4].ss_rel == doctest::Approx(-0.01));
    CHECK(c.rows[6].quantity == "geometric ratio r2/r1");
    CHECK(c.rows[6].rel_rms == doctest::Approx(0.25));
    CHECK(c.rows[6].ss_rel == doctest::Approx(0.25));
    // A quantity one model lacks has no error, not a zero one.
    CHECK(c.rows[7].quantity == "F_ax2 (mean)");
    CHECK(std::isnan(c.rows[7].rel_rms));
    CHECK(std::isnan(c.rows[7].plant_ss));
    CHECK(c.ripple_reference_N == 0.0);
    CHECK(c.ripple_plant_N == doctest::Approx(20.0).epsilon(1e-3));
    CHECK(c.gross_slip_plant_s == doctest::Approx(2.5));
    CHECK(c.gross_slip_reference_s == -1.0);
  }

  TEST_CASE("compare refuses grids that differ or are too short") {
    const auto fill = [](double dt) {
      Series s;
      for (int i = 0; i < 10; ++i) {
        s.t_s.push_back(dt * i);
        for (auto c : {&Series::omega1_rad_s, &Series::omega2_rad_s, &Series::F_ax1_N, &Series::torque_driver_Nm,
                       &Series::slip1_m_s, &Series::wrap_slip_m_s})
          (s.*c).push_back(1.0);
      }
      return s;
    };
    CHECK_THROWS_AS(compare(fill(1e-3), fill(2e-3), 10), RunError);
    CHECK_THROWS_AS(compare(fill(1e-3), fill(1e-3), 11), RunError);
    CHECK_THROWS_AS(compare(fill(1e-3), fill(1e-3), 1), RunError);
    CHECK_NOTHROW(compare(fill(1e-3), fill(1e-3), 10));
  }
}
