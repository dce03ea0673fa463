// The example controller's ratio law (docs/sil.md#ratio-control): the
// clamping level from the torque capacity at the running radius, the thrust
// ratio from the map plus the ratio error, slip protection that does not
// shift, and what it does without fresh data.
#include <doctest/doctest.h>

#include <cmath>

#include "cvtctl/ratio_law.hpp"

namespace {

cvtctl::RatioLawInputs at(float ratio, float target, float r1_m, float torque_Nm) {
  cvtctl::RatioLawInputs in;
  in.torque_demand_Nm = torque_Nm;
  in.torque_transmitted_Nm = torque_Nm;
  in.ratio_target = target;
  in.geometric_ratio = ratio;
  in.radius_driver_m = r1_m;
  in.plant_data_valid = true;
  return in;
}

}  // namespace

TEST_CASE("ratio law: clamping for the safety factor at the running radius, balance from the map at zero error") {
  const cvtctl::RatioLawParams p;
  cvtctl::RatioLaw law(p);
  // 200 N m: above the torque the clamping floor carries.
  const cvtctl::RatioLawOutputs o = law.step(at(1.5f, 1.5f, 0.0762f, 200.0f));
  // tau_cap = 2 mu0 F1 r1 / cos(beta) = safety * 200 N m.
  const double cap = 2.0 * p.clamp.mu0 * o.driver_clamp_cmd_N * 0.0762 / p.clamp.cos_beta;
  CHECK(cap == doctest::Approx(1.3 * 200.0).epsilon(1e-5));
  // At the set-point the thrust ratio is the map's equilibrium kappa(1.5).
  CHECK(o.driver_clamp_cmd_N / o.driven_clamp_cmd_N == doctest::Approx(0.90738).epsilon(1e-5));
  // At the underdrive end (r1 = 51.2 mm) the same torque needs 76.2/51.2 times the clamping.
  cvtctl::RatioLaw low(p);
  const cvtctl::RatioLawOutputs ol = low.step(at(2.6498f, 2.6498f, 0.0512f, 200.0f));
  CHECK(ol.driver_clamp_cmd_N / o.driver_clamp_cmd_N == doctest::Approx(0.0762 / 0.0512).epsilon(1e-5));
  CHECK(ol.driver_clamp_cmd_N / ol.driven_clamp_cmd_N == doctest::Approx(0.80494).epsilon(1e-5));
}

TEST_CASE("ratio law: below the floor's torque the smaller clamping sits at the floor, the other shifts") {
  // The production CVT's calibration: mu0 0.09, a 12.5 kN floor on each pulley.
  const cvtctl::RatioLawParams p;
  CHECK(p.clamp.mu0 == 0.09f);
  CHECK(p.clamp.clamp_min_N == 12500.0f);
  // 60 N m needs 5.5 kN at ratio 1.5: the driver (kappa < 1, the smaller) at the floor.
  cvtctl::RatioLaw mid(p);
  const cvtctl::RatioLawOutputs o = mid.step(at(1.5f, 1.5f, 0.0762f, 60.0f));
  CHECK(o.driver_clamp_cmd_N == 12500.0f);
  CHECK(o.driven_clamp_cmd_N == doctest::Approx(12500.0 / 0.90738).epsilon(1e-5));
  // In overdrive the map's kappa is above 1: the driven clamping is the
  // smaller one and sits at the floor, the driver's above it keeps the balance.
  cvtctl::RatioLaw od(p);
  const cvtctl::RatioLawOutputs q = od.step(at(0.8908f, 0.8908f, 0.0969f, 60.0f));
  CHECK(q.thrust_ratio == doctest::Approx(1.02855).epsilon(1e-5));
  CHECK(q.driven_clamp_cmd_N == doctest::Approx(12500.0).epsilon(1e-5));
  CHECK(q.driver_clamp_cmd_N / q.driven_clamp_cmd_N == doctest::Approx(1.02855).epsilon(1e-5));
}

TEST_CASE("ratio law: a ratio above the set-point raises the thrust ratio (upshift), below lowers it") {
  cvtctl::RatioLaw up, down;
  const float k_map = cvtctl::ThrustMap{}.at(1.5f);
  const cvtctl::RatioLawOutputs u = up.step(at(1.7f, 1.5f, 0.0762f, 60.0f));
  const cvtctl::RatioLawOutputs d = down.step(at(1.3f, 1.5f, 0.0762f, 60.0f));
  CHECK(u.thrust_ratio > k_map);
  CHECK(d.thrust_ratio < k_map);
  // Proportional part plus one period of the integral, exactly.
  const cvtctl::RatioLawParams p;
  CHECK(u.thrust_ratio == doctest::Approx(k_map + p.kp * 0.2f + p.ki * 0.2f * p.period_s).epsilon(1e-5));
  // The integral keeps growing while the error stays; the whole correction
  // stays within correction_max of the map (below the radial breakaway).
  float last = u.thrust_ratio;
  for (int i = 0; i < 1000; ++i) last = up.step(at(1.7f, 1.5f, 0.0762f, 60.0f)).thrust_ratio;
  CHECK(p.kp * 0.2f + p.integral_max > p.correction_max);
  CHECK(last == doctest::Approx(k_map + p.correction_max).epsilon(1e-5));
  cvtctl::RatioLaw far;
  CHECK(far.step(at(0.9f, 2.6f, 0.0762f, 60.0f)).thrust_ratio ==
        doctest::Approx(cvtctl::ThrustMap{}.at(2.6f) - p.correction_max).epsilon(1e-5));
}

TEST_CASE("ratio law: slip raises both clampings in proportion, so the balance does not move") {
  cvtctl::RatioLaw law;
  const cvtctl::RatioLawOutputs calm = law.step(at(1.5f, 1.5f, 0.0762f, 150.0f));
  cvtctl::RatioLawInputs in = at(1.5f, 1.5f, 0.0762f, 150.0f);
  in.slip = 0.2f;
  const cvtctl::RatioLawOutputs slipping = law.step(in);
  CHECK(slipping.driver_clamp_cmd_N > calm.driver_clamp_cmd_N + 1000.0f);
  CHECK(slipping.driver_clamp_cmd_N / slipping.driven_clamp_cmd_N ==
        doctest::Approx(calm.driver_clamp_cmd_N / calm.driven_clamp_cmd_N).epsilon(1e-5));
}

TEST_CASE("ratio law: without fresh data the integral and the slip extra are held, the last radius kept") {
  cvtctl::RatioLaw law;
  cvtctl::RatioLawInputs in = at(1.7f, 1.5f, 0.06f, 60.0f);
  in.slip = 0.2f;
  law.step(in);
  const float extra = law.extra_N();
  const cvtctl::RatioLawOutputs fresh = law.step(at(1.5f, 1.5f, 0.06f, 60.0f));
  cvtctl::RatioLawInputs stale = at(9.0f, 1.5f, 0.5f, 60.0f);  // garbage, marked invalid
  stale.plant_data_valid = false;
  stale.slip = 3.0f;
  const cvtctl::RatioLawOutputs held = law.step(stale);
  CHECK(law.extra_N() <= extra);
  CHECK(held.thrust_ratio == doctest::Approx(fresh.thrust_ratio).epsilon(1e-6));
  CHECK(std::isfinite(held.driver_clamp_cmd_N));
  CHECK(held.driver_clamp_cmd_N > 0.0f);
}

TEST_CASE("ratio law: a new set-point is followed at the bounded shift speed with the feed-forward of that speed") {
  const cvtctl::RatioLawParams p;
  const cvtctl::ThrustMap map;
  cvtctl::RatioLaw law(p);
  // The first set-point is taken as it is (no shift history after a reset).
  CHECK(law.step(at(1.5f, 1.5f, 0.0762f, 60.0f)).ratio_reference == 1.5f);
  // Set-point 2.5: the reference moves shift_rate_max * period per period.
  // The chain lags 0.02 behind the reference all the way.
  const float dref = p.shift_rate_max * p.period_s;
  const int n_full = static_cast<int>((2.5f - 1.5f) / dref);  // whole steps; the last one is shorter
  float ref = 1.5f;
  for (int i = 1; i < n_full; ++i) {
    const cvtctl::RatioLawOutputs o = law.step(at(ref + dref - 0.02f, 2.5f, 0.0762f, 60.0f));
    CHECK(o.ratio_reference == doctest::Approx(1.5f + dref * static_cast<float>(i)).epsilon(1e-5));
    ref = o.ratio_reference;
    // Map at the reference, the feed-forward asking for the reference's
    // speed (a lower thrust ratio shifts toward low), the proportional part;
    // the integral stays at zero while the reference moves.
    const float expect = map.at(ref) - p.shift_rate_max / p.shift_gain_per_s + p.kp * -0.02f;
    CHECK(o.thrust_ratio == doctest::Approx(expect).epsilon(1e-4));
  }
  // The last steps (the last one shorter) with the chain on the set-point:
  // the integral stays 0 (it runs only at rest, and there the error is 0).
  float last_ref = 0.0f;
  for (int i = 0; i < 3; ++i) last_ref = law.step(at(2.5f, 2.5f, 0.0762f, 60.0f)).ratio_reference;
  CHECK(last_ref == 2.5f);
  // At rest on the set-point: no feed-forward, the integral starts.
  const cvtctl::RatioLawOutputs rest = law.step(at(2.4f, 2.5f, 0.0762f, 60.0f));
  CHECK(rest.ratio_reference == 2.5f);
  CHECK(rest.thrust_ratio ==
        doctest::Approx(map.at(2.5f) + p.kp * -0.1f + p.ki * -0.1f * p.period_s).epsilon(1e-4));
  // The shift speed the reference asks for stays below the chain's radial
  // breakaway: feed-forward within the correction bound.
  CHECK(p.shift_rate_max / p.shift_gain_per_s < p.correction_max);
}

TEST_CASE("ratio law: on an end stop the integral rests, so a set-point beyond the travel does not wind it up") {
  const cvtctl::RatioLawParams p;
  const cvtctl::ThrustMap map;
  cvtctl::RatioLaw law(p);
  // Set-point 2.75 beyond the underdrive stop, the chain held on it at 2.65
  // (the proportional part, -0.2, inside the correction bound).
  cvtctl::RatioLawInputs in = at(2.65f, 2.75f, 0.0512f, 60.0f);
  in.on_end_stop = true;
  cvtctl::RatioLawOutputs o{};
  for (int i = 0; i < 500; ++i) o = law.step(in);
  // Proportional part only: the chain is pushed onto the stop, nothing stored.
  CHECK(o.thrust_ratio == doctest::Approx(map.at(2.75f) + p.kp * (2.65f - 2.75f)).epsilon(1e-5));
  // Off the stop the integral starts from zero.
  in.on_end_stop = false;
  o = law.step(in);
  CHECK(o.thrust_ratio ==
        doctest::Approx(map.at(2.75f) + p.kp * -0.1f + p.ki * -0.1f * p.period_s).epsilon(1e-5));
}
