// The link-passing ripple of the chordal-action feature (docs/rom.md#link-ripple):
// the lumps' normal load and the reported F_ax carry F_ax (1 + A cos(theta)),
// the sheave's own balance does not; with the tension feature the link phase
// follows the chain's link passing. Closed forms written here from the docs'
// equations, the Jacobian against dual numbers and central differences, the
// energy ledger with the ripple, the watchdog's rule on the phase rate.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "rom_jacobian_check.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
namespace f = cvt::rom_feature;

// docs/rom.md#link-ripple, written from the docs: n_w = r1 theta1 / L links in
// the driver wrap, d = n_w - floor(n_w), A = gain (2/pi) sin(pi d) / n_w,
// theta = pi psi / alpha + pi (1 - d), alpha = asin(L / (2 r1)).
double theta1(const cvt::RomParams& p) { return kPi - 2.0 * std::asin((p.r2_m - p.r1_m) / p.center_distance_m); }
double wrap_links(const cvt::RomParams& p) { return p.r1_m * theta1(p) / p.pitch_m; }
double duty(const cvt::RomParams& p) { return wrap_links(p) - std::floor(wrap_links(p)); }
double amplitude(const cvt::RomParams& p) { return p.ripple_gain * 2.0 / kPi * std::sin(kPi * duty(p)) / wrap_links(p); }
double half_angle(const cvt::RomParams& p) { return std::asin(p.pitch_m / (2.0 * p.r1_m)); }
double ripple(const cvt::RomParams& p, double psi) {
  return 1.0 + amplitude(p) * std::cos(kPi * psi / half_angle(p) + kPi * (1.0 - duty(p)));
}

// seed-case1 on fixed sheaves with chordal action (tools/scenes/seed-case1-ripple.toml).
cvt::Scene ripple_scene() {
  cvt::Scene s = *cvt::find_builtin_scene("seed-case1");
  s.features = f::tension | f::polygon;
  s.params.fixed_sheaves = true;
  s.params.ripple_gain = 1.0;
  s.substeps = 4;
  s.t_end_s = 3.0;
  return s;
}

}  // namespace

TEST_CASE("link ripple: the lumps and F_ax carry F_ax (1 + A cos(pi psi / alpha + pi (1 - d))), the sheave does not") {
  cvt::RomParams p;
  CHECK(p.ripple_gain == 0.0);  // off by default
  p.ripple_gain = 1.0;
  // Table 1: 7.592 links in the driver wrap, so 7 or 8 bolts loaded, 8 for
  // 59 % of a link: the fundamental of a 1/n_w step with that duty.
  CHECK(wrap_links(p) == doctest::Approx(7.592).epsilon(1e-4));
  CHECK(amplitude(p) == doctest::Approx(0.0804).epsilon(1e-3));
  CHECK(cvt::rom_ripple_amplitude(p) == doctest::Approx(amplitude(p)).epsilon(1e-12));
  for (const double gain : {1.0, 0.25, 0.0}) {
    CAPTURE(gain);
    p.ripple_gain = gain;
    cvt::CvtRom<double, f::polygon | f::axial> rom(p);
    rom.inputs.clamp_N = 3300.0;
    rom.inputs.tau_in_Nm = 80.0;
    cvt::RomInitial x0;
    x0.omega1_rad_s = 100.0;
    x0.omega2_rad_s = 60.0;
    auto x = rom.initial_state(x0);
    using L = decltype(rom)::Layout;
    const double fax = p.K_ax_N_m * x(L::kDelta);  // the bolt force, seed Eq. 5 lumped
    double mean = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i) {
      const double psi = -half_angle(p) + 2.0 * half_angle(p) * (i + 0.5) / n;
      CAPTURE(psi);
      x(L::kPsi) = psi;
      const auto o = rom.outputs(x);
      CHECK(o.clamp_force_N == doctest::Approx(fax * ripple(p, psi)).epsilon(1e-12));
      // The lumps' friction: -phi(v_rel) load_i F_ax (1 + A cos theta).
      const double load1 = 2.0 * p.entry_load_share * p.normal_load_factor / std::cos(p.beta0_rad);
      const double phi1 = cvt::friction_characteristic(p.friction, o.v_rel1_m_s);
      CHECK(o.friction1_N == doctest::Approx(-phi1 * load1 * fax * ripple(p, psi)).epsilon(1e-12));
      // The sheave's balance feels the bolt force alone: m_s delta'' = F_h - F_b - c_s delta'.
      decltype(rom)::State dx;
      rom.derivative(x, dx);
      CHECK(dx(L::kDeltaDot) == doctest::Approx((x(L::kFh) - fax) / p.sheave_mass_kg).scale(1.0).epsilon(1e-12));
      mean += o.clamp_force_N / n;
    }
    // The ripple moves no load on average over a link.
    CHECK(mean == doctest::Approx(fax).epsilon(1e-12));
    if (gain == 0.0) CHECK(rom.outputs(x).clamp_force_N == fax);
  }
}

TEST_CASE("link ripple: with tension psi' = (2 alpha / L) v_c kL / (kL + T_s), without it psi' = w1") {
  cvt::RomParams p;
  p.fixed_sheaves = true;
  cvt::RomInitial x0;
  x0.omega1_rad_s = 120.0;
  x0.omega2_rad_s = 55.0;
  x0.x1_m = 0.2;  // the strands loaded: dT = k1 x1 = 542 N
  x0.phase_rad = 0.07;
  cvt::CvtRom<double, f::tension | f::polygon> rom(p);
  auto x = rom.initial_state(x0);
  using L = decltype(rom)::Layout;
  decltype(rom)::State dx;
  rom.derivative(x, dx);
  const auto o = rom.outputs(x);
  const double Ts = o.tension_slack_N;
  CHECK(Ts > 50.0);
  const double links_per_s = p.r2_m * x0.omega2_rad_s / (p.pitch_m * (1.0 + Ts / p.chain_stiffness_N));
  CHECK(dx(L::kPsi) == doctest::Approx(2.0 * half_angle(p) * links_per_s).epsilon(1e-12));
  CHECK(rom.phase_rate(x, rom.contact(x)) == doctest::Approx(dx(L::kPsi)).epsilon(1e-15));
  // A rigid chain that grips (T_s = 0, v_c the driver's mean surface speed
  // r1 w1 sin(alpha) / alpha) passes a link per 2 alpha of the driver: psi' = w1.
  cvt::RomParams q = p;
  q.stop_tension_N = 0.0;
  q.chain_mass_kg_m = 0.0;
  cvt::CvtRom<double, f::tension | f::polygon> rigid(q);
  cvt::RomInitial y;
  y.omega1_rad_s = 120.0;
  y.omega2_rad_s = 120.0 * q.r1_m * std::sin(half_angle(q)) / half_angle(q) / q.r2_m;
  const auto xr = rigid.initial_state(y);
  REQUIRE(rigid.outputs(xr).tension_slack_N == 0.0);
  rigid.derivative(xr, dx);
  CHECK(dx(L::kPsi) == doctest::Approx(120.0).epsilon(1e-12));
  // Without tension the phase turns with the driver, bit for bit.
  cvt::CvtRom<double, f::polygon | f::axial> plain(p);
  auto xp = plain.initial_state(x0);
  decltype(plain)::State dp;
  plain.derivative(xp, dp);
  CHECK(dp(decltype(plain)::Layout::kPsi) == x0.omega1_rad_s);
  CHECK(plain.phase_rate(xp, plain.contact(xp)) == x0.omega1_rad_s);
}

namespace {

template <std::uint32_t F>
void check_ripple_jacobian(const cvt::RomParams& p, const cvt::RomInitial& x0, double clamp_N, double x_offset,
                           bool central = true) {
  using L = cvt::RomLayout<F>;
  const auto rom = rom_test::loaded_plant<F>(p, clamp_N);
  auto x = rom_test::offset_state(rom, x0);
  x(L::kX1) += x_offset;
  // The bolt compressed at the clamping force (with wedging, delta - 2 tan(beta0) rho).
  if constexpr (L::kAxial) x(L::kDelta) = clamp_N / p.K_ax_N_m;
  if constexpr (L::kWedge) x(L::kDelta) += 2.0 * std::tan(p.beta0_rad) * x(L::kRho);
  rom_test::check_jacobian_at(rom, x, central);
}

}  // namespace

TEST_CASE("link ripple: analytic Jacobian equals the dual-number Jacobian and central differences") {
  cvt::RomParams p = rom_test::road_load_params();
  p.ripple_gain = 3.0;  // a large ripple, so its entries stand out
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.x1_m = 0.02;
  x0.x2_m = 0.03;
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    p.friction = fr;
    CAPTURE(static_cast<int>(fr.law));
    // Phases away from stick: at psi = 0.02 (0.03 after the offsets) the
    // clamped polygon plant's friction is curved within a central step (the
    // dual-number check holds there; the differences do not).
    for (const double psi : {-0.15, 0.07, 0.19}) {
      CAPTURE(psi);
      x0.phase_rad = psi;
      x0.omega2_rad_s = 99.9;
      check_ripple_jacobian<f::polygon>(p, x0, 3000.0, 0.0);
      check_ripple_jacobian<f::polygon | f::axial>(p, x0, 3000.0, 0.0);
      // Wedging: the lumps' normal load through Eq. 7's contact (central
      // differences cross its end-stop and contact kinks; duals only).
      check_ripple_jacobian<f::all>(p, x0, 3000.0, 0.0, false);
      // The phase row of the tension feature in each regime of the slack strand.
      check_ripple_jacobian<f::tension | f::polygon>(p, x0, 3000.0, 0.0);           // on the stop
      check_ripple_jacobian<f::tension | f::basic>(p, x0, 3000.0, 0.0);             // on the stop, with the bolt
      check_ripple_jacobian<f::tension | f::basic>(p, x0, 3000.0, -0.6);            // tight strand on its floor
      x0.omega2_rad_s = 30.0;
      check_ripple_jacobian<f::tension | f::basic>(p, x0, 1500.0, 0.0);             // clamped: T_s through delta
      check_ripple_jacobian<f::tension | f::basic>(p, x0, 2500.0, 0.5);             // slack strand on its floor
      check_ripple_jacobian<f::tension | f::polygon | f::axial>(p, x0, 1500.0, -0.3);  // overrun
      x0.omega2_rad_s = 300.0;
      check_ripple_jacobian<f::tension | f::polygon | f::axial>(p, x0, 1500.0, 0.0);   // lifted off
    }
  }
  // Fixed sheaves, and a held driven pulley: the phase row's w2 column goes.
  p.fixed_sheaves = true;
  x0.omega2_rad_s = 60.0;
  check_ripple_jacobian<f::tension | f::polygon | f::road_load | f::deformation>(p, x0, 0.0, 0.0);
  p.hold_driven_speed = true;
  check_ripple_jacobian<f::tension | f::polygon>(p, x0, 0.0, 0.0);
}

TEST_CASE("link ripple: the energy ledger closes, the ripple acting on the friction's normal load only") {
  // The bolt spring keeps its potential 1/2 K_ax delta^2 (docs/rom.md#axial):
  // the ripple changes the lumps' friction forces, whose work the ledger
  // books as it happens. Clamped sheave (axial, 10 s of seed-case1 with
  // chordal action) and fixed sheaves with the tension feature (3 s).
  auto run = [](cvt::Scene s, auto mask_tag, double& worst, double& ripple_std_N, double& friction_J) {
    constexpr std::uint32_t F = decltype(mask_tag)::value;
    worst = 0;
    double sum = 0, sum2 = 0, prev = 0;
    long n = 0;
    const cvt::RomFault fault =
        cvt::run_scene<double, F>(s, cvt::sim_config_of(s), [&](long i, double t, const auto& sim) {
          const auto& e = sim.energy();
          if (e.scale_J() > 10.0) worst = std::max(worst, std::fabs(e.residual_J() / e.scale_J()));
          // The spread of F_ax's frame-to-frame change over 1-3 s: the ripple's.
          const double fax = sim.outputs().clamp_force_N;
          if (t > 1.0 && t <= 3.0) {
            sum += fax - prev;
            sum2 += (fax - prev) * (fax - prev);
            ++n;
          }
          prev = fax;
          friction_J = e.friction_loss_J;
          (void)i;
          return true;
        });
    REQUIRE(fault == cvt::RomFault::none);
    ripple_std_N = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  };
  double worst = 0, std_on = 0, std_off = 0, fric_on = 0, fric_off = 0;
  cvt::Scene clamped = *cvt::find_builtin_scene("seed-case1");
  clamped.features = f::axial | f::polygon;
  clamped.params.ripple_gain = 1.0;
  clamped.substeps = 8;
  clamped.t_end_s = 3.0;
  using Clamped = std::integral_constant<std::uint32_t, f::axial | f::polygon>;
  using Fixed = std::integral_constant<std::uint32_t, f::tension | f::polygon>;
  for (const auto& [s, label] : {std::pair{clamped, "clamped"}, std::pair{ripple_scene(), "fixed sheaves"}}) {
    CAPTURE(label);
    cvt::Scene off = s;
    off.params.ripple_gain = 0.0;
    if (s.features & f::axial) {
      run(s, Clamped{}, worst, std_on, fric_on);
      CHECK(worst < 1e-4);
      run(off, Clamped{}, worst, std_off, fric_off);
    } else {
      run(s, Fixed{}, worst, std_on, fric_on);
      CHECK(worst < 1e-4);
      run(off, Fixed{}, worst, std_off, fric_off);
    }
    MESSAGE(label << ": worst residual " << worst << " of the flows; F_ax frame-to-frame spread " << std_on
                  << " N with the ripple, " << std_off << " N without; friction loss " << fric_on << " / " << fric_off
                  << " J");
    // The ripple is there (tens of N from frame to frame) and the ledger still closes.
    CHECK(std_on > 10.0 * std_off);
    CHECK(fric_on != fric_off);
  }
}

TEST_CASE("link ripple: the 8 steps per link hold the phase rate, the chain's with tension") {
  const cvt::Scene s = ripple_scene();
  const double limit = cvt::rom_polygon_resolved_speed_rad_s(s.params, s.frame_s / s.substeps);
  // The driver outruns the link passing: w1 = 2.1 v_c / r1 by 3 s, links
  // pass at the chain's speed. The rule holds the phase rate, not w1.
  double w1 = 0, rate = 0;
  using Sim = cvt::RomSimulator<double, f::tension | f::polygon>;
  Sim sim(s.params, cvt::sim_config_of(s));
  REQUIRE(cvt::run_frames(sim, s, s.frame_s, [&](long, double, const Sim& v) {
            w1 = v.state()(0);
            rate = v.plant().phase_rate(v.state(), v.plant().contact(v.state()));
            return true;
          }) == cvt::RomFault::none);
  MESSAGE("at 3 s: w1 " << w1 << " rad/s, phase rate " << rate << " rad/s, limit " << limit << " rad/s");
  CHECK(rate < 0.8 * w1);
  // One substep: 49.5 rad/s of phase rate resolved; the run faults on the
  // frame the rate passes it, with the state rolled back below it.
  cvt::Scene one = s;
  one.substeps = 1;
  const double limit1 = cvt::rom_polygon_resolved_speed_rad_s(one.params, one.frame_s);
  CHECK(limit1 == doctest::Approx(2.0 * half_angle(one.params) / 8.0 / 1e-3).epsilon(1e-12));
  Sim sim1(one.params, cvt::sim_config_of(one));
  double last_rate = 0;
  const cvt::RomFault fault = cvt::run_frames(sim1, one, one.frame_s, [&](long, double, const Sim& v) {
    last_rate = v.plant().phase_rate(v.state(), v.plant().contact(v.state()));
    return true;
  });
  CHECK(fault == cvt::RomFault::step_unresolved);
  CHECK(last_rate <= limit1);
  CHECK(last_rate > 0.98 * limit1);
  // Scene validation bounds the starting phase rate by the chain's speed,
  // (2 alpha / L) r2 |w2|, with tension; by w1 without.
  cvt::Scene fast = s;
  fast.initial.omega1_rad_s = 1.5 * limit;  // the driver alone: accepted
  CHECK(cvt::validate_scene(fast).ok);
  fast.initial.omega2_rad_s = 1.01 * limit * fast.params.pitch_m / (2.0 * half_angle(fast.params) * fast.params.r2_m);
  CHECK(std::string(cvt::validate_scene(fast).field) == "substeps");
  fast.features = f::polygon;
  fast.initial.omega2_rad_s = 0.0;
  CHECK(std::string(cvt::validate_scene(fast).field) == "substeps");
}

TEST_CASE("link ripple: scene validation names the field") {
  cvt::Scene s = ripple_scene();
  CHECK(cvt::validate_scene(s).ok);
  auto bad = [&](double gain, double pitch_m) {
    cvt::Scene t = s;
    t.params.ripple_gain = gain;
    t.params.pitch_m = pitch_m;
    const cvt::SceneIssue i = cvt::validate_scene(t);
    CAPTURE(gain);
    CHECK(!i.ok);
    CHECK(std::string(i.field) == "ripple_gain");
  };
  bad(-0.1, 0.03);
  bad(std::nan(""), 0.03);
  bad(11.0, 0.03);
  // Long links: n_w = 2.5, A = gain 0.25; gain 4 would press the lumps with a negative load.
  bad(4.0, 0.0911);
  s.params.ripple_gain = 10.0;
  CHECK(cvt::validate_scene(s).ok);  // A = 0.80 with Table 1's 7.6 links
}
