// Manoeuvres and suites (docs/validation.md#suite): the operating point's
// closed forms, the inputs a manoeuvre applies, the cache key, the suites'
// make-up, the uncertainty's arithmetic, and the plant on a hold and a
// clamping step (no reference run: the CLI test runs one). Cost (host
// release): about 0.3 s, the plant's two manoeuvres.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/maps.hpp"
#include "cvtplant/validation/manoeuvre.hpp"
#include "cvtplant/validation/suite.hpp"
#include "cvtplant/validation/suite_check.hpp"

using namespace cvt::validation;

namespace {

const cvt::mbd::MbdParams& production() {
  static const cvt::mbd::MbdParams p = cvt::mbd::production_set();
  return p;
}

bool same_point(const OperatingPoint& a, const OperatingPoint& b) {
  return a.omega1_rad_s == b.omega1_rad_s && a.ratio == b.ratio && a.tau_in_Nm == b.tau_in_Nm;
}

}  // namespace

TEST_SUITE("suite") {
  TEST_CASE("the driver radius for a ratio keeps the chain's pitch line") {
    const auto& p = production();
    // At the set's own pitch radii the ratio is r2/r1.
    CHECK(driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, p.r2_m / p.r1_m) ==
          doctest::Approx(p.r1_m).epsilon(1e-9));
    const double line = cvt::mbd::DriveGeometry(p.r1_m, p.r2_m, p.center_distance_m).pitch_line_m;
    double last_r1 = 1.0;
    for (const double ratio : {0.95, 1.2, 1.5, 2.0, 2.5}) {
      const double r1 = driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, ratio);
      const double r2 = cvt::mbd::driven_radius_for(r1, line, p.center_distance_m);
      CHECK(r2 / r1 == doctest::Approx(ratio).epsilon(1e-9));
      // The same chain: its pitch line at the new radii is the old one.
      CHECK(cvt::mbd::DriveGeometry(r1, r2, p.center_distance_m).pitch_line_m == doctest::Approx(line).epsilon(1e-12));
      CHECK(r1 < last_r1);  // underdrive: the chain lower on the driver
      last_r1 = r1;
    }
    CHECK_THROWS_AS(driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, 0.1), InputError);
    CHECK_THROWS_AS(driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, std::nan("")), InputError);
  }

  TEST_CASE("the operating point's road load and clamping are their closed forms") {
    OperatingPoint op;
    op.omega1_rad_s = 180.0;
    op.ratio = 2.0;
    op.tau_in_Nm = 90.0;
    // The load carries the input torque times the ratio at omega2 = omega1 / ratio.
    CHECK(balancing_road_cv(op) * (op.omega1_rad_s / op.ratio) == doctest::Approx(op.tau_in_Nm * op.ratio));
    // The capacity 2 mu0 F r1 / cos(beta0) of the clamping is the torque times the safety factor.
    const double f = capacity_clamp_N(120.0, 0.05, 0.09, 0.26, 1.3);
    CHECK(2.0 * 0.09 * f * 0.05 / std::cos(0.26) == doctest::Approx(1.3 * 120.0));
    // The controller's driven clamping: the floor, or the capacity at the safety factor above it.
    const auto e = cvt::mbd::production_envelope();
    const auto& p = production();
    for (const double ratio : {0.95, 1.5, 2.5})
      for (const double torque : {0.0, 40.0, e.rated_torque_Nm}) {
        const double f2 = controller_clamp2_N(torque, ratio);
        const double r1 = driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, ratio);
        CHECK(f2 >= e.clamp_min_N);
        CHECK(f2 <= e.clamp_max_N);
        CHECK(2.0 * p.friction.mu0 * f2 * r1 / std::cos(p.beta0_rad) >= e.clamp_safety * torque * (1 - 1e-12));
      }
  }

  TEST_CASE("a manoeuvre's inputs: factors on the holding and start clampings, its torque profile") {
    OperatingPoint op;
    op.clamp2_N = 14000;
    const Manoeuvre m = clamp_step_manoeuvre(op, 0.1, 0.05, 0.3);
    CHECK(m.kind == "clamp-step");
    const RigInputs before = manoeuvre_inputs(m, 11000, 0.04), after = manoeuvre_inputs(m, 11000, 0.2);
    CHECK(before.clamp1_N == doctest::Approx(11000));
    CHECK(after.clamp1_N == doctest::Approx(11000 * std::exp(0.1)));
    CHECK(before.clamp2_N == 14000);
    CHECK(after.clamp2_N == 14000);
    CHECK(after.tau_in_Nm == op.tau_in_Nm);
    CHECK(after.tau_load_Nm == 0);
    const Manoeuvre down = clamp_step_manoeuvre(op, -0.1, 0.05, 0.3);
    CHECK(manoeuvre_inputs(down, 11000, 0.2).clamp1_N == doctest::Approx(11000 * std::exp(-0.1)));
    CHECK(down.name != m.name);
  }

  TEST_CASE("a manoeuvre out of range is refused with its name") {
    Manoeuvre m = hold_manoeuvre(150, 1.5, 60, 0.3);
    CHECK_NOTHROW(check_manoeuvre(m));
    Manoeuvre bad = m;
    bad.start.omega1_rad_s = std::nan("");
    CHECK_THROWS_AS(check_manoeuvre(bad), InputError);
    bad = m;
    bad.t_end_s = 0;
    CHECK_THROWS_AS(check_manoeuvre(bad), InputError);
    bad = m;
    bad.clamp1_factor = cvt::mbd::TimeProfile{{{0.0, 1.0}, {0.1, -0.5}}};
    CHECK_THROWS_AS(check_manoeuvre(bad), InputError);
    bad = m;
    bad.start.clamp2_N = 50;
    CHECK_THROWS_AS(check_manoeuvre(bad), InputError);
    bad = m;
    bad.tau_in_Nm = cvt::mbd::TimeProfile{{{0.0, 60.0}, {0.1, 5000.0}}};
    try {
      check_manoeuvre(bad);
      FAIL("accepted a torque of 5 kN m");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(m.name) != std::string::npos);
    }
  }

  TEST_CASE("the cache key changes with every input and every reference option") {
    const Manoeuvre m = hold_manoeuvre(150, 1.5, 60, 0.3);
    ReferenceConfig c;
    const std::string k = manoeuvre_key(m, c);
    CHECK(manoeuvre_key(hold_manoeuvre(150, 1.5, 60, 0.3), c) == k);
    Manoeuvre m2 = m;
    m2.clamp2_factor = cvt::mbd::TimeProfile{{{0.1, 1.0}, {0.2, 1.01}}};
    CHECK(manoeuvre_key(m2, c) != k);
    m2 = m;
    m2.t_end_s = 0.31;
    CHECK(manoeuvre_key(m2, c) != k);
    m2 = m;
    m2.start.ratio = 1.51;
    CHECK(manoeuvre_key(m2, c) != k);
    ReferenceConfig c2 = c;
    c2.rtol = c.rtol / 10;
    CHECK(manoeuvre_key(m, c2) != k);
    c2 = c;
    c2.overrides.emplace_back("friction.mu0", 0.08);
    CHECK(manoeuvre_key(m, c2) != k);
    c2 = c;
    c2.set = cvt::mbd::ParameterSet::seed;
    CHECK(manoeuvre_key(m, c2) != k);
    // An override names a field of the set's list, and a number.
    c2 = c;
    c2.overrides.emplace_back("friction.no_such_field", 1.0);
    CHECK_THROWS_AS(config_params(c2), InputError);
    c2 = c;
    c2.overrides.emplace_back("friction.mu0", 0.08);
    CHECK(config_params(c2).friction.mu0 == 0.08);
  }

  TEST_CASE("the controller suite covers the envelope; its held-out runs start where no fit run does") {
    const Suite s = suite_by_name("controller");
    std::set<double> ratios, torques;
    std::set<std::string> kinds, names;
    int steps_up = 0, steps_down = 0;
    std::set<double> step_speeds;
    for (const auto* part : {&s.fit, &s.held_out})
      for (const auto& m : *part) {
        CHECK_NOTHROW(check_manoeuvre(m));
        CHECK(names.insert(m.name).second);  // unique names: the table's rows, the overlay files
        kinds.insert(m.kind);
      }
    for (const auto& m : s.fit) {
      if (m.kind == "hold") {
        ratios.insert(m.start.ratio);
        torques.insert(m.start.tau_in_Nm);
      }
      if (m.kind == "clamp-step") {
        const double d = std::log(m.clamp1_factor.at(m.t_end_s));
        (d > 0 ? steps_up : steps_down) += 1;
        step_speeds.insert(m.start.omega1_rad_s);
      }
    }
    CHECK(ratios.size() >= 5);
    CHECK(torques.size() >= 3);
    CHECK(steps_up >= 2);
    CHECK(steps_down >= 2);
    CHECK(step_speeds.size() >= 2);
    for (const char* k : {"hold", "clamp-step", "sweep", "kick-down", "slip"}) CHECK(kinds.count(k) == 1);
    const auto e = cvt::mbd::production_envelope();
    for (const auto& h : s.held_out) {
      for (const auto& f : s.fit) CHECK_FALSE(same_point(h.start, f.start));
      CHECK(h.start.omega1_rad_s >= e.omega1_min_rad_s);
      CHECK(h.start.omega1_rad_s <= e.omega1_max_rad_s);
    }
    CHECK_FALSE(s.held_out.empty());
    for (const auto& u : s.uncertainty_runs) CHECK(names.count(u) == 1);
    // Every run inside the envelope's ratios and torques.
    for (const auto* part : {&s.fit, &s.held_out})
      for (const auto& m : *part) {
        CHECK(m.start.ratio > e.ratio_overdrive);
        CHECK(m.start.ratio < e.ratio_underdrive);
        CHECK(m.start.tau_in_Nm <= e.rated_torque_Nm);
      }
    CHECK_THROWS_AS(suite_by_name("nope"), InputError);
    for (const auto& n : suite_names()) CHECK_NOTHROW(suite_by_name(n));
  }

  TEST_CASE("the suite's size in simulated seconds adds each plan's runs") {
    const Suite s = suite_by_name("ci");
    ReferenceConfig c;
    SuiteOptions o;
    o.maps = false;
    o.uncertainty = "none";
    const double runs = s.fit[0].t_end_s + s.fit[1].t_end_s;
    CHECK(suite_reference_s(s, c, o) == doctest::Approx(runs));
    // The tolerance twice and each open choice at its two ends, on both runs.
    o.uncertainty = "subset";
    const double variants = 2.0 + 2.0 * static_cast<double>(open_choices(c.set).size());
    CHECK(suite_reference_s(s, c, o) == doctest::Approx(runs * (1.0 + variants)));
    CHECK(open_choices(cvt::mbd::ParameterSet::seed).empty());
  }

  TEST_CASE("uncertainty: a uniform distribution's standard deviation, combined in quadrature") {
    // Over [0, w] the variance is w^2 / 12: check against a fine sum.
    const double w = 0.04;
    double s2 = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) / n * w - 0.5 * w;
      s2 += x * x;
    }
    CHECK(input_share(w) == doctest::Approx(std::sqrt(s2 / n)).epsilon(1e-6));
    Uncertainty u;
    u.u_num10 = 0.5;  // not the one used: the 100x change is
    u.u_num100 = 0.03;
    u.u_input = 0.04;
    CHECK(u.u_val() == doctest::Approx(0.05));
  }

  TEST_CASE("a slope over a window, and the clamping at the first sample in gross slip") {
    std::vector<double> t, y;
    for (int i = 0; i <= 100; ++i) {
      t.push_back(i * 1e-3);
      y.push_back(i == 50 ? std::nan("") : (i < 20 ? 100.0 : 1.5 - 0.3 * t.back()));
    }
    CHECK(slope_over(t, y, 0.02, 0.1) == doctest::Approx(-0.3));
    CHECK(std::isnan(slope_over(t, y, 0.2, 0.3)));
    Series s;
    for (int i = 0; i <= 100; ++i) {
      s.t_s.push_back(i * 1e-3);
      s.clamp2_N.push_back(20000.0 - 100.0 * i);
      s.wrap_slip_m_s.push_back(i >= 37 ? -1.5 : 0.01);
    }
    CHECK(onset_clamp2_N(s) == doctest::Approx(20000.0 - 3700.0));
    for (auto& v : s.wrap_slip_m_s) v = 0.5;
    CHECK(std::isnan(onset_clamp2_N(s)));
  }

  TEST_CASE("the plant holds its ratio at its holding clamping and upshifts when the driver's rises") {
    const cvt::Scene* plant = cvt::find_builtin_scene("ratio-control");
    REQUIRE(plant != nullptr);
    OperatingPoint op;
    op.omega1_rad_s = 150;
    op.ratio = 1.5;
    op.tau_in_Nm = 60;
    op.clamp2_N = controller_clamp2_N(60, 1.5);
    Manoeuvre hold = hold_manoeuvre(150, 1.5, 60, 0.1);
    PlantHold h;
    const Series a = plant_manoeuvre(hold, *plant, nullptr, &h);
    REQUIRE(a.size() == 101u);
    CHECK(h.clamp1_N > 0);
    const double drift = std::fabs(a.ratio_geom.back() - a.ratio_geom.front());
    const Series b = plant_manoeuvre(clamp_step_manoeuvre(op, 0.1, 0.01, 0.1), *plant, nullptr);
    REQUIRE(b.size() == 101u);
    // More driver clamping closes the driver's groove: r2/r1 falls, by more
    // than the hold drifts.
    CHECK(b.ratio_geom.back() < a.ratio_geom.back());
    CHECK(a.ratio_geom.back() - b.ratio_geom.back() > 5 * drift);
    // Both start from the same locked state and clamping.
    CHECK(a.ratio_geom.front() == b.ratio_geom.front());
    CHECK(b.clamp1_N.back() == doctest::Approx(h.clamp1_N * std::exp(0.1)));
    // A plant without a variable ratio is refused.
    CHECK_THROWS_AS(plant_manoeuvre(hold, *cvt::find_builtin_scene("seed-case1"), nullptr), InputError);
  }
}
