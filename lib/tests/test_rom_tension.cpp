// The chain's tension state (feature tension, docs/rom.md#tension): creep of
// the soft chain under load, its centrifugal tension, and the driver sheave
// held by its clamping force or on its stop. Closed forms written here from
// the docs' equations, the Jacobian against dual numbers and central
// differences, the energy ledger with the creep loss, the watchdog.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/plant_set.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "rom_jacobian_check.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
namespace f = cvt::rom_feature;

// The closed forms of docs/rom.md#tension, written from the docs.
double theta1(const cvt::RomParams& p) { return kPi - 2.0 * std::asin((p.r2_m - p.r1_m) / p.center_distance_m); }
double axial_per_tension(const cvt::RomParams& p) { return theta1(p) / (2.0 * std::tan(p.beta0_rad)); }
double centrifugal(const cvt::RomParams& p, double v) { return p.centrifugal_gain * p.chain_mass_kg_m * v * v; }
// On the stop: F_ax = c_F (T_max + eta_s dT - kappa m' v^2), at least 0.
double stop_axial_force(const cvt::RomParams& p, double dT, double v) {
  return std::max(0.0, axial_per_tension(p) * (p.stop_tension_N + p.stop_tension_share * dT - centrifugal(p, v)));
}

// Constant mu0 = 0.25 with the atan sign: a gripping lump's slip is a few
// um/s, so the kinematics show without the case-1 law's creep of its own.
cvt::RomParams constant_mu_params() {
  cvt::RomParams p;
  p.friction = cvt::FrictionParams<double>{};
  return p;
}

// Both pulleys held at chain speed v, lumps at rest: no strand force, dT = 0.
template <class T, std::uint32_t F>
cvt::RomOutputs<T> held_outputs(const cvt::RomParams& p0, double v, double clamp_N, int frames) {
  cvt::RomParams p = p0;
  p.hold_driver_speed = p.hold_driven_speed = true;
  cvt::RomSimulator<T, F> sim(p, cvt::RomSimConfig{});
  cvt::RomInitial x0;
  x0.omega1_rad_s = v / p.r1_m;
  x0.omega2_rad_s = v / p.r2_m;
  cvt::RomInputs<T> u;
  u.clamp_N = T(clamp_N);
  sim.reset(x0, u);
  for (int i = 0; i < frames; ++i) REQUIRE(sim.step_frame(u) == cvt::RomFault::none);
  return sim.outputs();
}

// Mean of the speed ratio over the last second of a run of `t_end_s`.
struct Steady {
  cvt::RomFault fault;
  double ratio, dT_N, T_s_N, eps, slip1_m_s;
  bool on_stop;
};
template <std::uint32_t F>
Steady steady_state(const cvt::Scene& s) {
  Steady r{};
  double sum = 0;
  long n = 0;
  r.fault = cvt::run_scene<double, F>(s, cvt::sim_config_of(s), [&](long, double t, const auto& sim) {
    const auto o = sim.outputs();
    if (t > s.t_end_s - 1.0) {
      sum += o.omega1_rad_s / o.omega2_rad_s;
      ++n;
    }
    r.dT_N = o.tension_tight_N - o.tension_slack_N;
    r.T_s_N = o.tension_slack_N;
    r.eps = o.creep_strain;
    r.slip1_m_s = o.v_rel1_m_s;
    r.on_stop = o.sheave_on_stop;
    return true;
  });
  r.ratio = sum / static_cast<double>(n);
  return r;
}

}  // namespace

TEST_CASE("tension: a gripping entry lump turns the pulleys at (r2/r1)(1 + g dT/(kL + T_s)), dT = tau_load/r2") {
  // Driver held at 80 rad/s, constant load on the free driven pulley: at the
  // steady state the strands carry dT = tau_load / r2, the entry lump grips
  // (the exit lump slides at the creep speed) and w1/w2 = (r2/r1)(1 + g eps).
  cvt::Scene s;
  s.features = f::tension;
  s.params = constant_mu_params();
  s.params.hold_driver_speed = true;
  s.params.entry_load_share = 0.705;
  s.initial.omega1_rad_s = 80.0;
  s.initial.omega2_rad_s = 80.0 * s.params.r1_m / s.params.r2_m;
  s.tau_load = cvt::constant_profile(40.0);
  s.t_end_s = 30.0;  // the driveline mode (1 Hz, damping ratio 0.1) settles
  const double dT = 40.0 / s.params.r2_m;
  const double r21 = s.params.r2_m / s.params.r1_m;
  for (const bool fixed : {false, true}) {
    for (const double g : {1.0, 0.5, 0.0}) {
      CAPTURE(fixed);
      CAPTURE(g);
      s.params.fixed_sheaves = fixed;
      s.params.creep_gain = g;
      // 1.5 kN holds the sheave off its stop at these speeds (T_clamp < T_stop).
      s.clamp = cvt::constant_profile(1500.0);
      const Steady st = steady_state<f::tension>(s);
      REQUIRE(st.fault == cvt::RomFault::none);
      CHECK(st.on_stop == fixed);
      // The driven speed of the closed form: v_c from w1 r1 = v_c (1 + g eps),
      // with T_c = kappa m' v_c^2 in T_1, iterated to its fixed point.
      const cvt::RomParams& p = s.params;
      double vc = 80.0 * p.r1_m, T_s = 0, eps = 0;
      for (int it = 0; it < 50; ++it) {
        const double T1 = fixed ? p.stop_tension_N + p.stop_tension_share * dT
                                : 1500.0 / axial_per_tension(p) + centrifugal(p, vc);
        T_s = T1 - (p.wrap_excess_share + 0.5) * dT;
        eps = dT / (p.chain_stiffness_N + T_s);
        vc = 80.0 * p.r1_m / (1.0 + g * eps);
      }
      // (without creep both lumps grip, and the driveline's last 2e-5 of
      // its start-up swing is left after 30 s)
      CHECK(st.dT_N == doctest::Approx(dT).epsilon(1e-4));
      CHECK(st.T_s_N == doctest::Approx(T_s).epsilon(1e-4));
      CHECK(st.eps == doctest::Approx(eps).epsilon(1e-4));
      // The entry lump grips to a few um/s (constant mu0 with the atan sign).
      CHECK(std::fabs(st.slip1_m_s) < 1e-4);
      CHECK(st.ratio == doctest::Approx(r21 * (1.0 + g * eps)).epsilon(2e-5));
      if (g == 1.0) CHECK(st.ratio > 1.08 * r21);  // creep is 9 % here: the test sees it
    }
  }
}

TEST_CASE("tension: fixed sheaves unload as m' v^2 grows, F_ax = theta1 (T_max - m' v^2) / (2 tan beta0)") {
  cvt::RomParams p = constant_mu_params();
  p.fixed_sheaves = true;
  // kappa = 1: the V-belt form at v_c; the default 1.79 (docs/rom.md#tension).
  // Up to 13 m/s (m' v^2 = 522 N of T_max = 537 N), then beyond: the chain
  // lifts off (at 9.9 m/s with the default kappa).
  for (const double kappa : {1.0, cvt::RomParams{}.centrifugal_gain}) {
    for (const double v : {0.0, 3.0, 8.0, 9.5, 11.0, 12.5, 13.0, 13.5, 16.0}) {
      CAPTURE(v);
      CAPTURE(kappa);
      p.centrifugal_gain = kappa;
      if (kappa == 1.0)  // theta1 (T_max - m' v^2) / (2 tan beta0), written out
        CHECK(stop_axial_force(p, 0.0, v) ==
              doctest::Approx(std::max(0.0, theta1(p) * (p.stop_tension_N - p.chain_mass_kg_m * v * v) /
                                                (2.0 * std::tan(p.beta0_rad))))
                  .epsilon(1e-12));
      const double expect = stop_axial_force(p, 0.0, v);
      const auto o = held_outputs<double, f::tension>(p, v, 0.0, 20);
      CHECK(o.clamp_force_N == doctest::Approx(expect).epsilon(1e-12).scale(1e-9));
      CHECK(o.centrifugal_tension_N == doctest::Approx(centrifugal(p, v)).epsilon(1e-12));
      CHECK(o.sheave_on_stop);
      CHECK(std::fabs(o.creep_strain) < 1e-12);  // no strand force but rounding
      // Float and q16.16 compute the same law; q16.16 to its constants'
      // resolution (r2 is 3e-5 off, so m' v^2 is 6e-5 off: 0.13 N of F_ax at 11 m/s).
      const auto of = held_outputs<float, f::tension>(p, v, 0.0, 20);
      CHECK(std::fabs(double(of.clamp_force_N) - expect) < 0.01);
      const auto oq = held_outputs<cvt::q16_16, f::tension>(p, v, 0.0, 20);
      CHECK(std::fabs(cvt::to_double(oq.clamp_force_N) - expect) < 0.5);
    }
  }
  CHECK(stop_axial_force(p, 0.0, 0.0) == doctest::Approx(2994.42).epsilon(1e-5));  // the reference's at rest
  CHECK(stop_axial_force(p, 0.0, 13.5) == 0.0);
  // The clamp input does nothing on fixed sheaves.
  CHECK(held_outputs<double, f::tension>(p, 8.0, 500.0, 5).clamp_force_N ==
        held_outputs<double, f::tension>(p, 8.0, 9000.0, 5).clamp_force_N);
}

TEST_CASE("tension: a clamped sheave holds F_ax at the clamp until T_clamp passes T_stop, then follows the stop") {
  cvt::RomParams p = constant_mu_params();
  p.centrifugal_gain = 1.0;
  const double F = 2000.0;
  // T_clamp = F / c_F + m' v^2 reaches T_stop = T_max at v*.
  const double v_star = std::sqrt((p.stop_tension_N - F / axial_per_tension(p)) / p.chain_mass_kg_m);
  CHECK(v_star == doctest::Approx(7.595).epsilon(1e-3));
  for (const double k : {0.0, 0.5, 0.9, 0.99, 1.01, 1.1, 1.4, 2.0}) {
    const double v = k * v_star;
    CAPTURE(v);
    const double expect = k < 1.0 ? F : stop_axial_force(p, 0.0, v);
    const auto o = held_outputs<double, f::tension>(p, v, F, 5);
    CHECK(o.clamp_force_N == doctest::Approx(expect).epsilon(1e-12).scale(1e-9));
    CHECK(o.sheave_on_stop == (k > 1.0));
    // With the axial feature the clamping force is the bolt force the
    // actuator settles to: the same law.
    const auto oa = held_outputs<double, f::tension | f::axial>(p, v, F, 400);
    CHECK(oa.clamp_force_N == doctest::Approx(expect).epsilon(1e-9));
    CHECK(oa.sheave_on_stop == (k > 1.0));
  }
  // The regimes meet continuously at v*.
  CHECK(stop_axial_force(p, 0.0, v_star) == doctest::Approx(F).epsilon(1e-12));
}

TEST_CASE("tension: gross slip starts where 2 mu0 F_ax r1 / cos(beta0) falls below the transmitted torque") {
  // Fixed sheaves, driven pulley held at chain speed v, driver free with
  // tau_in: while it grips, dT = tau_in / r1, and the wrap's capacity
  // 2 mu0 F_ax / cos(beta0) (docs/rom.md#contact, f = 1) with F_ax = c_F
  // (T_max + eta_s dT - m' v^2) falls with v. The closed form's v_crit:
  cvt::RomParams p = constant_mu_params();
  p.fixed_sheaves = true;
  p.hold_driven_speed = true;
  const double tau_in = 60.0, dT = tau_in / p.r1_m;
  const double F_crit = dT * std::cos(p.beta0_rad) / (2.0 * p.friction.mu0);
  const double v_crit = std::sqrt((p.stop_tension_N + p.stop_tension_share * dT - F_crit / axial_per_tension(p)) /
                                  (p.centrifugal_gain * p.chain_mass_kg_m));
  CHECK(v_crit == doctest::Approx(8.47).epsilon(0.01));
  for (const double k : {0.98, 1.02}) {
    CAPTURE(k);
    cvt::Scene s;
    s.features = f::tension;
    s.params = p;
    const double v = k * v_crit;
    s.initial.omega2_rad_s = v / p.r2_m;
    // Start at the gripping steady state: strands at dT, the driver at the
    // creep speed v (1 + eps), so no start-up overshoot tests the capacity.
    const double T_s = p.stop_tension_N + (p.stop_tension_share - p.wrap_excess_share - 0.5) * dT;
    s.initial.omega1_rad_s = v * (1.0 + dT / (p.chain_stiffness_N + T_s)) / p.r1_m;
    s.initial.x1_m = s.initial.x2_m = 0.5 * dT / p.k1_N_m;
    s.tau_in = cvt::constant_profile(tau_in);
    s.t_end_s = 4.0;
    double slip = 0;  // the driver's surface over the chain entering its wrap
    const cvt::RomFault fault = cvt::run_scene<double, f::tension>(s, cvt::sim_config_of(s), [&](long, double, const auto& sim) {
      slip = -sim.outputs().v_rel1_m_s;
      return true;
    });
    REQUIRE(fault == cvt::RomFault::none);
    if (k < 1.0) CHECK(std::fabs(slip) < 0.01);  // gripping
    else CHECK(slip > 0.1);                       // the driver runs away
  }
}

TEST_CASE("tension: the energy ledger closes with the creep loss over the seed case on fixed sheaves") {
  // The built-in seed-case1 (the feature on fixed sheaves, the calibrated
  // set), 10 s: creep, centrifugal unloading and gross slip from about 5.3 s.
  const cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  REQUIRE(s.features == f::tension);
  REQUIRE(s.params.fixed_sheaves);
  double residual_rel = 0, creep_J = 0, scale = 0, worst = 0;
  bool slid = false;
  const cvt::RomFault fault = cvt::run_scene<double, f::tension>(s, cvt::sim_config_of(s), [&](long i, double, const auto& sim) {
    const auto& e = sim.energy();
    const auto o = sim.outputs();
    residual_rel = e.residual_J() / e.scale_J();
    scale = e.scale_J();
    if (scale > 10.0) worst = std::max(worst, std::fabs(residual_rel));
    // The creep loss F_1 g eps v_c, frame by frame (rectangle rule).
    if (i > 0) creep_J += o.friction1_N * o.creep_strain * s.params.r2_m * o.omega2_rad_s * s.frame_s;
    slid = slid || -o.v_rel1_m_s > 1.0;
    return true;
  });
  REQUIRE(fault == cvt::RomFault::none);
  MESSAGE("seed-case1 tension, fixed sheaves, 10 s: residual " << residual_rel << " of the flows (worst " << worst
                                                               << "), creep loss " << creep_J << " J");
  CHECK(slid);  // the fixed sheaves unloaded until the driver wrap slid
  CHECK(worst < 1e-4);
  // The creep loss is a real part of the balance: without it the ledger
  // would be off by far more than its residual.
  CHECK(creep_J > 100.0);
  CHECK(creep_J > 1e3 * std::fabs(residual_rel) * scale);
  // Float closes too.
  double residual_f = 0;
  REQUIRE(cvt::run_scene<float, f::tension>(s, cvt::sim_config_of(s), [&](long, double, const auto& sim) {
            residual_f = double(sim.energy().residual_J()) / double(sim.energy().scale_J());
            return true;
          }) == cvt::RomFault::none);
  CHECK(std::fabs(residual_f) < 1e-3);
}

namespace {

template <std::uint32_t F>
void check_tension_jacobian(const cvt::RomParams& p, const cvt::RomInitial& x0, double clamp_N, double x_offset) {
  using L = cvt::RomLayout<F>;
  const auto rom = rom_test::loaded_plant<F>(p, clamp_N);
  auto x = rom_test::offset_state(rom, x0);
  x(L::kX1) += x_offset;
  if constexpr (L::kAxial) x(L::kDelta) = clamp_N / p.K_ax_N_m;  // the bolt at the clamping force
  rom_test::check_jacobian_at(rom, x, true);
}

}  // namespace

TEST_CASE("tension: analytic Jacobian equals the dual-number Jacobian and central differences in every regime") {
  cvt::RomParams p = rom_test::road_load_params();  // Table 2 case 1
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.x1_m = 0.02;
  x0.x2_m = 0.03;
  x0.phase_rad = 0.05;
  auto each_mask = [&](double w2, double clamp_N, double x_offset) {
    x0.omega2_rad_s = w2;
    check_tension_jacobian<f::tension>(p, x0, clamp_N, x_offset);
    check_tension_jacobian<f::tension | f::axial>(p, x0, clamp_N, x_offset);
    check_tension_jacobian<f::tension | f::basic>(p, x0, clamp_N, x_offset);
  };
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    p.friction = fr;
    CAPTURE(static_cast<int>(fr.law));
    each_mask(30.0, 1500.0, 0.0);     // clamped: 1.5 kN below the stop's 3 kN at 3.4 m/s
    each_mask(99.9, 3000.0, 0.0);     // on the stop: T_c = 403 N at 11.4 m/s
    each_mask(30.0, 2500.0, 0.5);     // clamped, slack strand at its floor 0
    each_mask(30.0, 1500.0, -0.3);    // overrun: dT < 0
    each_mask(99.9, 1500.0, -0.6);    // on the stop, T_t at its floor: T_s = -dT
    each_mask(300.0, 1500.0, 0.0);    // the chain lifted off (T_c > T_stop)
  }
  p.fixed_sheaves = true;
  x0.omega2_rad_s = 60.0;
  check_tension_jacobian<f::tension>(p, x0, 1500.0, 0.0);
  check_tension_jacobian<f::tension | f::road_load | f::deformation | f::polygon>(p, x0, 1500.0, 0.0);
  p.hold_driven_speed = true;  // a held driven pulley: the w2 column goes
  check_tension_jacobian<f::tension>(p, x0, 1500.0, 0.0);
  // Each regime was reached: the plant's own flags at those states.
  using Rom = cvt::CvtRom<double, f::tension>;
  cvt::RomParams q;
  Rom rom(q);
  rom.inputs.clamp_N = 1500.0;
  cvt::RomInitial y;
  y.omega2_rad_s = 30.0;
  CHECK(!rom.contact(rom.initial_state(y)).tension.on_stop);
  y.omega2_rad_s = 99.9;
  rom.inputs.clamp_N = 3000.0;
  CHECK(rom.contact(rom.initial_state(y)).tension.on_stop);
  y.x1_m = 0.5;
  y.omega2_rad_s = 30.0;
  rom.inputs.clamp_N = 2500.0;
  CHECK(rom.contact(rom.initial_state(y)).tension.floored);
  y.x1_m = 0.0;
  y.omega2_rad_s = 300.0;
  CHECK(rom.contact(rom.initial_state(y)).tension.lifted);
}

TEST_CASE("tension: no strand carries compression, so kL + T_s >= kL and the creep strain stays finite") {
  using Rom = cvt::CvtRom<double, f::tension>;
  cvt::RomParams p;
  p.fixed_sheaves = true;
  Rom rom(p);
  cvt::RomInitial x0;
  x0.omega2_rad_s = 50.0;
  for (const double x1 : {2.0, -2.0}) {
    x0.x1_m = x1;  // dT = +-5.4 kN against T_stop of a few hundred N
    const auto o = rom.outputs(rom.initial_state(x0));
    const double dT = p.k1_N_m * x1;
    CHECK(o.tension_tight_N - o.tension_slack_N == doctest::Approx(dT));
    CHECK(std::min(o.tension_tight_N, o.tension_slack_N) == 0.0);
    CHECK(o.creep_strain == doctest::Approx(dT / (p.chain_stiffness_N + o.tension_slack_N)));
  }
}

TEST_CASE("tension: fixed point faults tension-out-of-range where m' v_c^2 leaves q16.16, float runs on") {
  // The built-in seed-case1's calibrated kappa: sqrt(32767 N / (1.7355 x
  // 3.0911 kg/m)) = 78.2 m/s, 684 rad/s at r2.
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  s.t_end_s = 0.01;
  const double w_lim = std::sqrt(32767.0 / (s.params.centrifugal_gain * s.params.chain_mass_kg_m)) / s.params.r2_m;
  CHECK(w_lim == doctest::Approx(683.8).epsilon(0.01));
  for (const double w2 : {0.98 * w_lim, 1.02 * w_lim}) {
    CAPTURE(w2);
    s.initial.omega2_rad_s = w2;
    s.initial.omega1_rad_s = w2 * s.params.r2_m / s.params.r1_m;
    cvt::RomSimulator<cvt::q16_16, f::tension> q(s.params, cvt::sim_config_of(s));
    const cvt::RomFault fq = cvt::run_frames(q, s, s.frame_s, [](long, double, const auto&) { return true; });
    CHECK(fq == (w2 > w_lim ? cvt::RomFault::tension_out_of_range : cvt::RomFault::none));
    // Rolled back: the last good state is the start.
    if (w2 > w_lim) CHECK(cvt::to_double(q.state()(1)) == doctest::Approx(w2).epsilon(1e-4));
    CHECK(cvt::run_scene<float, f::tension>(s, cvt::sim_config_of(s), [](long, double, const auto&) {
            return true;
          }) == cvt::RomFault::none);
  }
  CHECK(std::string(cvt::rom_fault_name(cvt::RomFault::tension_out_of_range)) == "tension-out-of-range");
}

TEST_CASE("tension: float and q16.16 follow double over the seed case on fixed sheaves") {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");  // the feature on fixed sheaves
  s.t_end_s = 5.0;  // gripping, before gross slip makes the end state sensitive
  auto speeds = [&](auto tag) {
    using T = decltype(tag);
    double w1 = 0, w2 = 0, fax = 0;
    REQUIRE(cvt::run_scene<T, f::tension>(s, cvt::sim_config_of(s), [&](long, double, const auto& sim) {
              const auto o = sim.outputs();
              w1 = cvt::to_double(o.omega1_rad_s);
              w2 = cvt::to_double(o.omega2_rad_s);
              fax = cvt::to_double(o.clamp_force_N);
              return true;
            }) == cvt::RomFault::none);
    return std::array<double, 3>{w1, w2, fax};
  };
  const auto d = speeds(double{});
  const auto fl = speeds(float{});
  const auto q = speeds(cvt::q16_16{});
  MESSAGE("seed-case1 tension at 5 s: double " << d[0] << " " << d[1] << " " << d[2] << ", float " << fl[0] << " "
                                               << fl[1] << " " << fl[2] << ", q16.16 " << q[0] << " " << q[1] << " "
                                               << q[2]);
  for (int i = 0; i < 3; ++i) {
    CHECK(fl[i] == doctest::Approx(d[i]).epsilon(1e-4));
    CHECK(q[i] == doctest::Approx(d[i]).epsilon(2e-2));
  }
}

TEST_CASE("tension: seed case 2's exit lump sliding at the creep speed over the Stribeck peak has an unstable mode") {
  // docs/validation.md#seed-case2: why tools/scenes/seed-case2-tension.toml
  // (the built-in seed-case1 with Table 2 case 2) takes four steps per frame.
  // With creep the exit lump slides at eps v_c, which in case 2 reaches the
  // Stribeck peak within the first half second; beyond the peak the
  // coefficient falls with slip and the lump's mode against the chain's
  // springs grows. The exact Jacobian (no slope floor: both lumps slide far
  // outside the floor's 1/lambda layer, so W is J there) has eigenvalues
  // with a positive real part, and the lump runs a cycle through the peak.
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  s.params.friction = cvt::friction_presets::table2_case2<double>();
  s.substeps = 4;
  s.t_end_s = 0.5;
  using Sim = cvt::RomSimulator<double, f::tension>;
  const double floor_speed = 1.0 / s.params.friction.lambda_s_m;
  double max_growth = -1e300, growth_im = 0, slip2_lo = 1e300, slip2_hi = -1e300, slip1_max = 0, t_max = 0;
  const cvt::RomFault fault = cvt::run_scene<double, f::tension>(s, cvt::sim_config_of(s), [&](long, double t, const Sim& sim) {
    if (t < 0.4) return true;
    const auto o = sim.outputs();
    slip2_lo = std::min(slip2_lo, -o.v_rel2_m_s);
    slip2_hi = std::max(slip2_hi, -o.v_rel2_m_s);
    slip1_max = std::max(slip1_max, std::fabs(o.v_rel1_m_s));
    CHECK(std::fabs(o.v_rel1_m_s) > floor_speed);
    CHECK(std::fabs(o.v_rel2_m_s) > floor_speed);
    const auto& x = sim.state();
    typename Sim::Plant::Jacobian J;
    sim.plant().jacobian(x, sim.plant().contact(x), J, false);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(J);
    for (int k = 0; k < J.rows(); ++k)
      if (es.eigenvalues()[k].real() > max_growth) {
        max_growth = es.eigenvalues()[k].real();
        growth_im = es.eigenvalues()[k].imag();
        t_max = t;
      }
    return true;
  });
  REQUIRE(fault == cvt::RomFault::none);
  MESSAGE("seed case 2, tension, fixed sheaves, 0.4-0.5 s at 4 substeps: exit lump slip " << slip2_lo << " .. "
          << slip2_hi << " m/s, entry lump |v_rel| up to " << slip1_max << " m/s, largest growth rate " << max_growth
          << " +- " << std::fabs(growth_im) << "i 1/s at " << t_max << " s");
  CHECK(max_growth > 100.0);      // an unstable mode, growing by e in under 10 ms
  CHECK(std::fabs(growth_im) > 0.0);  // oscillatory
  CHECK(slip2_lo < 0.25);         // the exit lump's slip cycles through the peak
  CHECK(slip2_hi > 0.5);
  CHECK(slip1_max < 0.05);        // while the entry lump grips
  // One step per 1 ms frame does not follow the cycle: the ledger's watchdog
  // stops it within the first half second.
  s.substeps = 1;
  CHECK(cvt::run_scene<double, f::tension>(s, cvt::sim_config_of(s), [](long, double, const Sim&) { return true; }) ==
        cvt::RomFault::energy_growth);
}

TEST_CASE("tension: scene validation names the field") {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  s.features = f::tension;
  CHECK(cvt::validate_scene(s).ok);
  auto bad = [&](auto edit, const char* field) {
    cvt::Scene t = s;
    edit(t);
    const cvt::SceneIssue i = cvt::validate_scene(t);
    CAPTURE(field);
    CHECK(!i.ok);
    CHECK(std::string(i.field) == field);
  };
  // Tension composes with wedging (docs/rom.md#tension-radial); wedging still needs axial.
  bad([](cvt::Scene& t) { t.features |= f::wedging; }, "features");
  bad([](cvt::Scene& t) { t.features |= f::axial; t.params.fixed_sheaves = true; }, "fixed_sheaves");
  bad([](cvt::Scene& t) { t.params.beta0_rad = 0.0; }, "beta0_deg");
  bad([](cvt::Scene& t) { t.params.chain_mass_kg_m = -1.0; }, "chain_mass_kg_m");
  bad([](cvt::Scene& t) { t.params.chain_stiffness_N = 0.0; }, "chain_stiffness_N");
  bad([](cvt::Scene& t) { t.params.creep_gain = std::nan(""); }, "creep_gain");
  bad([](cvt::Scene& t) { t.params.centrifugal_gain = -0.1; }, "centrifugal_gain");
  bad([](cvt::Scene& t) { t.params.stop_tension_N = -5.0; }, "stop_tension_N");
  bad([](cvt::Scene& t) { t.params.stop_tension_share = 1.5; }, "stop_tension_share");
  bad([](cvt::Scene& t) { t.params.wrap_excess_share = 0.6; }, "wrap_excess_share");
  bad([](cvt::Scene& t) { t.features = f::axial; t.log |= cvt::rom_log::tension; }, "log");
  // q16.16 takes what fits its range.
  cvt::Scene big = s;
  big.scalar = cvt::ScalarKind::q16_16;
  big.params.chain_stiffness_N = 4e7;  // 39,063 x 1024 N
  CHECK(cvt::check_scene_plant<cvt::RomPlantSet<cvt::q16_16, f::tension>>(big).ok == false);
  CHECK(cvt::check_scene_plant<cvt::RomPlantSet<cvt::q16_16, f::tension>>(s).ok);
  // A set without the tension plants refuses the scene, never runs it without.
  CHECK(!cvt::check_scene_plant<cvt::RomPlantSet<double, f::axial>>(s).ok);
}
