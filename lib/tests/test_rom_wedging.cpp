// The wedging feature of the reduced-order plant (docs/rom.md#wedging): the
// chain's radial degree of freedom on the driver, seed Eq. 7, the ratio from
// chain length conservation, end stops.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
namespace f = cvt::rom_feature;
constexpr std::uint32_t kWedge = f::axial | f::wedging;
constexpr std::uint32_t kWedgeRoad = f::axial | f::road_load | f::wedging;
using Rom = cvt::CvtRom<double, kWedge>;
using L = cvt::RomLayout<kWedge>;

// Exact driven radius for driver radius r1 + rho at the chain length of the
// set-up radii (the test's own Newton, in <cmath>).
double driven_radius_by_length(const cvt::RomParams& p, double rho) {
  const double C = p.center_distance_m;
  auto length = [&](double a, double b) {
    const double s = std::asin((b - a) / C);
    return a * (kPi - 2 * s) + b * (kPi + 2 * s) + 2 * std::sqrt(C * C - (b - a) * (b - a));
  };
  const double L0 = length(p.r1_m, p.r2_m);
  double b = p.r2_m;
  for (int i = 0; i < 60; ++i) {
    const double h = 1e-7;
    b -= (length(p.r1_m + rho, b) - L0) / ((length(p.r1_m + rho, b + h) - length(p.r1_m + rho, b - h)) / (2 * h));
  }
  return b;
}

// Driving: driver 150 rad/s, lumps slipping a little, strands stretched,
// the chain 4 mm off its seat.
cvt::RomInitial driving_initial() {
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.omega2_rad_s = 99.95;
  x0.x1_m = 0.01;
  x0.x2_m = 0.012;
  x0.radius_offset_m = 0.004;
  return x0;
}

// A driving state with radial motion: the chain moving inward at 2 cm/s.
Rom::State moving_state(const Rom& rom) {
  Rom::State x = rom.initial_state(driving_initial());
  x(L::kRhoDot) = -0.02;
  x(L::kDeltaDot) = 0.001;
  return x;
}

cvt::Scene ratio_scene(double clamp_before_N, double clamp_after_N) {
  cvt::Scene s = *cvt::find_builtin_scene("tip-in");
  s.features = kWedgeRoad;
  s.tau_in = cvt::constant_profile(60.0);
  s.clamp = cvt::step_profile(clamp_before_N, clamp_after_N, 1.0);
  s.t_end_s = 5.0;
  return s;
}

struct RunEnd {
  cvt::RomFault fault;
  double rho_m, r1_m, r2_m, residual_rel, max_pen_m;
};

template <class T>
RunEnd run(const cvt::Scene& s, const cvt::RomSimConfig& cfg) {
  RunEnd e{};
  double max_rho = 0;
  e.fault = cvt::run_scene<T, kWedgeRoad>(s, cfg, [&](long, double, const auto& sim) {
    const auto xs = sim.state_si();
    max_rho = std::max(max_rho, std::fabs(xs(cvt::RomLayout<kWedgeRoad>::kRho)));
    const auto o = sim.outputs();
    e.rho_m = xs(cvt::RomLayout<kWedgeRoad>::kRho);
    e.r1_m = cvt::to_double(o.radius1_m);
    e.r2_m = cvt::to_double(o.radius2_m);
    e.residual_rel = std::fabs(double(sim.energy().residual_J())) / double(sim.energy().scale_J());
    return true;
  });
  e.max_pen_m = std::max(0.0, max_rho - s.params.radial_travel_m);
  return e;
}
template <class T>
RunEnd run(const cvt::Scene& s) {
  return run<T>(s, cvt::sim_config_of(s));
}

}  // namespace

TEST_CASE("wedging: the driven radius keeps the chain length (cubic fit within 1e-5 m over the travel)") {
  const cvt::RomParams p;
  Rom rom(p);
  for (double rho = -p.radial_travel_m; rho <= p.radial_travel_m + 1e-12; rho += p.radial_travel_m / 10) {
    CAPTURE(rho);
    Rom::State x = rom.initial_state(cvt::RomInitial{});
    x(L::kRho) = rho;
    CHECK(std::fabs(rom.pitch_radius2(x) - driven_radius_by_length(p, rho)) < 1e-5);
  }
  // kappa = -dr2/dr1 is the wrap angle ratio theta1/theta2 at the set-up radii.
  const double a = std::asin((p.r2_m - p.r1_m) / p.center_distance_m);
  CHECK(rom.ratio_slope(0.0) == doctest::Approx((kPi - 2 * a) / (kPi + 2 * a)).epsilon(1e-5));
  // The radial mass and driven clamping defaults follow from Table 1 (docs/rom.md#wedging).
  const double n_w1 = p.r1_m * (kPi - 2 * a) / 0.03, n_w2 = p.r2_m * (kPi + 2 * a) / 0.03;
  const double kappa = (kPi - 2 * a) / (kPi + 2 * a);
  CHECK(p.radial_mass_kg == doctest::Approx((n_w1 + kappa * kappa * n_w2) * 0.1125).epsilon(1e-12));
  CHECK(p.driven_clamp_N == doctest::Approx(3300.0 / kappa).epsilon(1e-12));
}

TEST_CASE("wedging: contact forces satisfy seed Eq. 7 and oppose the slip velocity") {
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    cvt::RomParams p;
    p.friction = fr;
    Rom rom(p);
    const double fax = 3300.0, cb = std::cos(p.beta0_rad), tb = std::tan(p.beta0_rad);
    for (const double vt : {0.3, -0.05, 1e-4, 0.0}) {
      for (const double rhod : {-0.02, 0.0, 0.01}) {
        CAPTURE(vt);
        CAPTURE(rhod);
        const auto c = rom.lump_forces(vt, vt, rhod, fax);
        const double gr = rhod / cb;
        const double F = std::hypot(c.F1, c.Fr1);
        // N from Eq. 7, and |F_f| = mu(|v|) s(|v|) N.
        const double N = c.Fr1 * tb + fax / cb;
        const double speed = std::hypot(vt, gr);
        if (speed > 0) {
          CHECK(F == doctest::Approx(cvt::friction_characteristic(p.friction, speed) * N).epsilon(1e-12));
          // The friction vector is antiparallel to (v_t, g_r).
          CHECK(c.F1 * gr - c.Fr1 * vt == doctest::Approx(0.0).scale(1e-9 * F));
          CHECK(c.F1 * vt + c.Fr1 * gr <= 0.0);
        } else {
          CHECK(F == 0.0);
        }
        // Moving inward (g_r < 0) wedges the chain: more normal force.
        if (rhod < 0 && vt == 1e-4) CHECK(N > fax / cb);
        if (rhod > 0 && vt == 1e-4) CHECK(N < fax / cb);
      }
    }
  }
}

TEST_CASE("wedging: without radial motion the plant is the axial plant (tangential rows agree to rounding)") {
  cvt::RomParams p;
  Rom rom(p);
  cvt::CvtRom<double, f::axial> ref(p);
  for (auto* r : {&rom.inputs, &ref.inputs}) {
    r->tau_in_Nm = 80.0;
    r->tau_load_Nm = 40.0;
    r->clamp_N = 3300.0;
  }
  cvt::RomInitial x0;
  x0.omega1_rad_s = 150.0;
  x0.omega2_rad_s = 99.9;
  x0.x1_m = 0.01;
  const Rom::State x = rom.initial_state(x0);
  const auto xr = ref.initial_state(x0);
  Rom::State d;
  cvt::CvtRom<double, f::axial>::State dr;
  rom.derivative(x, d);
  ref.derivative(xr, dr);
  for (int i = 0; i < 9; ++i) {
    CAPTURE(i);
    CHECK(d(i) == doctest::Approx(dr(i)).epsilon(1e-11).scale(1e-9));
  }
  // Driven clamping at 3.3 kN / kappa: radial forces balance at rho = 0, to
  // the 1e-5 of the cubic's slope against theta1/theta2.
  const double radial_push_N = 2 * std::tan(p.beta0_rad) * 3300.0;
  CHECK(std::fabs(d(L::kRhoDot)) * p.radial_mass_kg < 1e-5 * radial_push_N);
}

namespace {

// The analytic Jacobian of a wedging plant (docs/rom.md#wedging-jacobian)
// against the dual-number derivative of its right-hand side at x: a force
// law changed in derivative() without its partials fails here.
template <std::uint32_t F>
void check_wedge_jacobian_against_duals(const cvt::RomParams& p, const cvt::RomInitial& x0, double rhod_m_s,
                                        double delta_extra, bool stick = false) {
  using R = cvt::CvtRom<double, F>;
  using LL = cvt::RomLayout<F>;
  R rom(p);
  rom.inputs.tau_in_Nm = 80.0;
  rom.inputs.tau_load_Nm = 40.0;
  rom.inputs.clamp_N = 3300.0;
  typename R::State x = rom.initial_state(x0);
  x(LL::kRhoDot) = rhod_m_s;
  x(LL::kDeltaDot) = 0.001;
  x(LL::kDelta) += delta_extra;
  // Stick: the chain frame at the driver's surface speed, lumps at rest in it.
  if (stick) x(LL::kW2) = rom.driver_radius(x) * x(LL::kW1) / rom.pitch_radius2(x);
  typename R::Jacobian Ja, Jd;
  rom.jacobian(x, Ja);
  cvt::jacobian_by_duals(rom, x, Jd);
  const double scale = Jd.cwiseAbs().maxCoeff();
  for (int i = 0; i < R::kStates; ++i)
    for (int j = 0; j < R::kStates; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      // Exact derivatives of the same expressions: only rounding differs.
      CHECK(Ja(i, j) == doctest::Approx(Jd(i, j)).epsilon(1e-9).scale(1e-12 * scale));
    }
}

}  // namespace

TEST_CASE("wedging: analytic Jacobian equals the dual-number Jacobian for every wedging feature set") {
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    CAPTURE(static_cast<int>(fr.law));
    cvt::RomParams p;
    p.friction = fr;
    cvt::RomInitial x0 = driving_initial();
    x0.xd1_m_s = 0.003;
    x0.xd2_m_s = -0.002;
    x0.phase_rad = 0.05;
    check_wedge_jacobian_against_duals<kWedge>(p, x0, -0.02, 0.0);
    check_wedge_jacobian_against_duals<kWedgeRoad>(p, x0, -0.02, 0.0);
    check_wedge_jacobian_against_duals<kWedge | f::deformation>(p, x0, 0.03, 0.0);
    check_wedge_jacobian_against_duals<kWedge | f::polygon>(p, x0, -0.02, 0.0);
    check_wedge_jacobian_against_duals<f::all>(p, x0, 0.01, 0.0);
    // On the hub stop, and with the bolt unloaded (F_ax = 0).
    cvt::RomInitial on_stop = x0;
    on_stop.radius_offset_m = p.radial_travel_m + 0.002;
    check_wedge_jacobian_against_duals<kWedgeRoad>(p, on_stop, 0.0, 0.0);
    check_wedge_jacobian_against_duals<kWedgeRoad>(p, x0, -0.02, -1.0);
    // Near stick: lump slip of 1e-5 m/s and no radial motion.
    cvt::RomInitial stick = x0;
    stick.xd1_m_s = 1e-5;
    stick.xd2_m_s = -1e-5;
    check_wedge_jacobian_against_duals<kWedgeRoad>(p, stick, 0.0, 0.0, true);
    // The wrap-tension coupling (docs/rom.md#wrap-tension) at a share well
    // above the calibrated one: its strand-stretch and radial-pull terms are
    // zero at the default share of 0, so only here do they reach the check.
    cvt::RomParams coupled = p;
    coupled.wrap_tension_share = 0.4;
    check_wedge_jacobian_against_duals<kWedgeRoad>(coupled, x0, -0.02, 0.0);
    check_wedge_jacobian_against_duals<f::all>(coupled, x0, 0.01, 0.0);
    // Held pulleys: zero rows, like the right-hand side's.
    p.hold_driver_speed = true;
    p.hold_driven_speed = true;
    check_wedge_jacobian_against_duals<kWedgeRoad>(p, x0, -0.02, 0.0);
  }
}

TEST_CASE("wedging: analytic Jacobian matches central differences") {
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    cvt::RomParams p;
    p.friction = fr;
    p.wrap_tension_share = 0.4;  // the coupling's terms reach the check
    Rom rom(p);
    rom.inputs.tau_in_Nm = 80.0;
    rom.inputs.tau_load_Nm = 40.0;
    rom.inputs.clamp_N = 3300.0;
    const Rom::State x = moving_state(rom);
    Rom::Jacobian J;
    rom.jacobian(x, J);
    for (int j = 0; j < Rom::kStates; ++j) {
      const double h = 1e-6 * std::max(1.0, std::fabs(x(j)));
      Rom::State xp = x, xm = x, fp, fm;
      xp(j) += h;
      xm(j) -= h;
      rom.derivative(xp, fp);
      rom.derivative(xm, fm);
      for (int i = 0; i < Rom::kStates; ++i) {
        CAPTURE(i);
        CAPTURE(j);
        const double fd = (fp(i) - fm(i)) / (2 * h);
        CHECK(J(i, j) == doctest::Approx(fd).epsilon(1e-5).scale(1e-6 * (std::fabs(fd) + 1.0)));
      }
    }
  }
}

TEST_CASE("wedging: equal thrust ratio holds the ratio, a higher primary clamp upshifts to a new equilibrium") {
  // Driven clamping 3636.8 N holds rho = 0 at 3.3 kN primary.
  const RunEnd hold = run<double>(ratio_scene(3300.0, 3300.0));
  CHECK(hold.fault == cvt::RomFault::none);
  CHECK(std::fabs(hold.rho_m) < 2e-4);
  // 3.5 kN: the chain climbs the driver (r1 up, r2 down) towards
  // kappa(rho) = 3500 / 3636.8.
  const cvt::Scene s = ratio_scene(3300.0, 3500.0);
  const RunEnd up = run<double>(s);
  CHECK(up.fault == cvt::RomFault::none);
  CHECK(up.rho_m > 0.005);
  CHECK(up.r2_m < s.params.r2_m - 0.004);
  Rom rom(s.params);
  const double target = 3500.0 / s.params.driven_clamp_N;
  CHECK(std::fabs(rom.ratio_slope(up.rho_m) - target) < 0.5 * std::fabs(rom.ratio_slope(0.0) - target));
  // A lower primary clamp downshifts.
  const RunEnd down = run<double>(ratio_scene(3300.0, 3100.0));
  CHECK(down.fault == cvt::RomFault::none);
  CHECK(down.rho_m < -0.005);
}

TEST_CASE("wedging: energy balance closes (double and float), also against an end stop") {
  for (const double after : {3500.0, 1200.0}) {
    CAPTURE(after);
    const cvt::Scene s = ratio_scene(3300.0, after);
    const RunEnd d = run<double>(s);
    const RunEnd fl = run<float>(s);
    CHECK(d.fault == cvt::RomFault::none);
    CHECK(fl.fault == cvt::RomFault::none);
    CHECK(d.residual_rel < 1e-4);
    CHECK(fl.residual_rel < 1e-3);
    CHECK(fl.rho_m == doctest::Approx(d.rho_m).epsilon(0.02).scale(1e-4));
    if (after == 1200.0) {
      // 1.2 kN against 3.6 kN driven clamping drives the chain to the hub
      // stop; the 1e7 N/m stop holds it within a millimetre.
      CHECK(d.rho_m < -s.params.radial_travel_m);
      CHECK(d.max_pen_m < 1e-3);
    }
  }
}

TEST_CASE("wedging: the end stop is resolved by finer steps only while the chain is on it") {
  // docs/rom.md#end-stop: the 1e7 N/m stop against the 2 kg radial mass
  // rings at 2.8 ms, which one 1 ms step does not resolve.
  const cvt::Scene s = ratio_scene(3300.0, 1200.0);
  cvt::RomSimConfig plain = cvt::sim_config_of(s);
  plain.stop_substeps = 1;
  const RunEnd one = run<double>(s, plain);
  CHECK(one.fault == cvt::RomFault::none);
  // Unresolved: the ledger closes only to about 1e-3 of the flows.
  CHECK(one.residual_rel > 1e-4);
  CHECK(one.residual_rel < 5e-3);
  // The default takes the frames near the stop in 2 substeps of one W: the
  // ledger closes as with 2 substeps everywhere, at one step per frame off
  // it; so it does with a W of its own for every substep.
  const cvt::RomSimConfig def = cvt::sim_config_of(s);
  CHECK(def.stop_substeps == 2);
  CHECK(def.stop_keep_w);
  const RunEnd refined = run<double>(s, def);
  CHECK(refined.fault == cvt::RomFault::none);
  CHECK(refined.residual_rel < 1e-5);
  cvt::RomSimConfig fresh_w = def;
  fresh_w.stop_keep_w = false;
  const RunEnd refined_fresh = run<double>(s, fresh_w);
  CHECK(refined_fresh.fault == cvt::RomFault::none);
  CHECK(refined_fresh.residual_rel < 1e-5);
  CHECK(refined_fresh.max_pen_m < 0.5e-3);
  cvt::RomSimConfig two = plain;
  two.substeps = 2;
  const RunEnd everywhere = run<double>(s, two);
  CHECK(everywhere.residual_rel < 1e-5);
  // The other way, a stop law one step resolves: 1e6 N/m rings at 8.9 ms.
  // It closes the ledger but lets the chain well past the travel, a change
  // of the geometry at the ratio limits (docs/rom.md#end-stop).
  cvt::Scene soft = s;
  soft.params.radial_stop_N_m = 1e6;
  const RunEnd softer = run<double>(soft, plain);
  CHECK(softer.fault == cvt::RomFault::none);
  CHECK(softer.residual_rel < 1e-5);
  CHECK(softer.max_pen_m > 1e-3);
  CHECK(refined.max_pen_m < 0.5e-3);
  MESSAGE("ledger residual / flows on clamp-step with wedging (chain on the hub stop): one step per frame ",
          one.residual_rel, ", 2 substeps of one W near the stop ", refined.residual_rel, " (a W each ",
          refined_fresh.residual_rel, "), 2 substeps everywhere ", everywhere.residual_rel, "; 1e6 N/m stop at one step ",
          softer.residual_rel, ", deepest ", softer.max_pen_m * 1e3, " mm past the travel (1e7 N/m refined: ",
          refined.max_pen_m * 1e3, " mm, a W each ", refined_fresh.max_pen_m * 1e3, " mm)");
  // Only frames on the stop pay: before the clamp drop at 1 s none are.
  cvt::RomSimulator<double, kWedgeRoad> sim(s.params, def);
  sim.reset(s.initial, cvt::scene_inputs_at<double>(s, 0.0));
  for (int k = 0; k < 900; ++k) sim.step_frame(cvt::scene_inputs_at<double>(s, k * 1e-3));
  CHECK(sim.stop_refined_frames() == 0);
  for (int k = 900; k < 5000; ++k) sim.step_frame(cvt::scene_inputs_at<double>(s, k * 1e-3));
  CHECK(sim.fault() == cvt::RomFault::none);
  CHECK(sim.stop_refined_frames() > 0);
  CHECK(sim.stop_refined_frames() < 5000 - 900);
}

TEST_CASE("wedging: the driven clamping command shifts the ratio through the actuator lag, ledger closed") {
  // docs/rom.md#driven-clamping
  const cvt::Scene s = ratio_scene(3300.0, 3300.0);
  const cvt::RomSimConfig cfg = cvt::sim_config_of(s);
  cvt::RomSimulator<double, kWedgeRoad> sim(s.params, cfg);
  CHECK(sim.driven_clamp_N() == s.params.driven_clamp_N);
  sim.reset(s.initial, cvt::scene_inputs_at<double>(s, 0.0));
  for (int k = 0; k < 500; ++k) sim.step_frame(cvt::scene_inputs_at<double>(s, k * 1e-3));
  const double f0 = sim.driven_clamp_N();
  const double f_cmd = 3900.0;
  sim.set_driven_clamp_command(f_cmd);
  sim.step_frame(cvt::scene_inputs_at<double>(s, 0.5));
  // One frame of the first-order lag, exactly: F0 + (F_cmd - F0)(1 - e^(-frame/tau)).
  const double lag = 1.0 - std::exp(-cfg.frame_s / s.params.actuator_tau_s);
  CHECK(sim.driven_clamp_N() == doctest::Approx(f0 + (f_cmd - f0) * lag).epsilon(1e-12));
  for (int k = 501; k < 5000; ++k) sim.step_frame(cvt::scene_inputs_at<double>(s, k * 1e-3));
  CHECK(sim.fault() == cvt::RomFault::none);
  CHECK(sim.driven_clamp_N() == doctest::Approx(f_cmd).epsilon(1e-9));
  // More driven clamping: the chain moves in on the driver (downshift),
  // towards kappa(rho) = F1 / F2.
  const double rho = sim.state_si()(cvt::RomLayout<kWedgeRoad>::kRho);
  CHECK(rho < -0.003);
  cvt::CvtRom<double, kWedgeRoad> rom(s.params);
  const double target = 3300.0 / f_cmd;
  CHECK(std::fabs(rom.ratio_slope(rho) - target) < 0.5 * std::fabs(rom.ratio_slope(0.0) - target));
  // The command's potential change is booked as actuator work.
  CHECK(std::fabs(sim.energy().residual_J()) / sim.energy().scale_J() < 1e-4);
  // Saturated like the driver's command.
  sim.set_driven_clamp_command(-5.0);
  CHECK(sim.driven_clamp_command_N() == 0.0);
  sim.set_driven_clamp_command(1e9);
  CHECK(sim.driven_clamp_command_N() == s.params.clamp_max_N);
}

TEST_CASE("wedging: a chain driven through the stop is a reported fault, not a silent state") {
  cvt::Scene s = ratio_scene(3300.0, 1200.0);
  s.params.radial_stop_N_m = 10.0;  // far too soft to hold the driven clamping
  const RunEnd e = run<double>(s);
  CHECK(e.fault == cvt::RomFault::radius_out_of_range);
  CHECK(std::string(cvt::rom_fault_name(e.fault)) == "radius-out-of-range");
}

TEST_CASE("wedging: scene validation") {
  cvt::Scene s = ratio_scene(3300.0, 3500.0);
  CHECK(cvt::validate_scene(s).ok);
  auto field = [](const cvt::Scene& x) { return std::string(cvt::validate_scene(x).field); };
  cvt::Scene t = s;
  t.features = f::wedging;
  CHECK(field(t) == "features");
  t = s;
  t.scalar = cvt::ScalarKind::q16_16;
  CHECK(field(t) == "scalar");
  t = s;
  t.params.driven_clamp_N = -1;
  CHECK(field(t) == "driven_clamp_N");
  t = s;
  t.params.radial_travel_m = 0.05;  // 2 x travel > r1
  CHECK(field(t) == "radial_travel_m");
  t = s;
  t.params.friction.mu0 = 2.0;  // mu tan(15 deg) = 0.54: fine
  CHECK(cvt::validate_scene(t).ok);
  t.params.beta0_rad = 0.5;  // mu tan(28.6 deg) = 1.09: self-locking
  CHECK(field(t) == "beta0_deg");
  t = s;
  t.initial.radius_offset_m = 0.03;
  CHECK(field(t) == "initial");
  t = s;
  t.params.radial_mass_kg = std::nan("");
  CHECK(field(t) == "radial_mass_kg");
}

TEST_CASE_TEMPLATE("wedging: the right-hand side and the power terms from the shared contact are derivative() and "
                   "the outputs' terms bit for bit",
                   T, double, float) {
  using R = cvt::CvtRom<T, kWedgeRoad>;
  using LL = cvt::RomLayout<kWedgeRoad>;
  for (const auto& fr : {cvt::friction_presets::table2_case1<double>(), cvt::friction_presets::table2_case2<double>()}) {
    cvt::RomParams p;
    p.friction = fr;
    R rom(p);
    rom.inputs.tau_in_Nm = T(80.0);
    rom.inputs.tau_load_Nm = T(40.0);
    rom.inputs.clamp_N = T(3300.0);
    cvt::RomInitial x0;
    x0.omega1_rad_s = 150.0;
    x0.omega2_rad_s = 99.95;
    x0.xd1_m_s = 0.003;
    x0.radius_offset_m = 0.004;
    for (const double rhod : {-0.02, 0.0, 1e-7}) {
      typename R::State x = rom.initial_state(x0);
      x(LL::kRhoDot) = T(rhod);
      typename R::State f1, f2;
      // The contact the simulator evaluates once per state (docs/rom.md#cost)
      // and shares between the Jacobian (compared with the dual-number
      // Jacobian above), the right-hand side and the ledger's power terms.
      const typename R::Contact c = rom.contact(x);
      rom.derivative(x, f1);
      rom.derivative(x, c, f2);
      bool same = true;
      for (int i = 0; i < R::kStates; ++i) same = same && std::memcmp(&f1(i), &f2(i), sizeof(T)) == 0;
      CAPTURE(rhod);
      CHECK(same);
      // The power terms of docs/rom.md#energy-balance from the outputs'
      // forces, torques and slip speeds (rom_outputs evaluates the friction
      // separately): the ledger books the same power as before the sharing.
      const cvt::RomOutputs<T> o = rom.outputs(x);
      using A = cvt::RomAcc<T>;
      const cvt::RomPower<A> pc = rom.power(x, c);
      const A rd = A(x(LL::kRhoDot));
      const A w1 = A(x(LL::kW1)), w2 = A(x(LL::kW2)), v1 = A(x(LL::kV1)), v2 = A(x(LL::kV2));
      // The ledger's constants in the accounting type, from the set-up values
      // (the wrap-tension share is 0 here: the strands' stretch rate is xd_i).
      const A g = A(p.wrap_tension_share);
      const A sv1 = v1 + g * rd, sv2 = v2 + g * rd;
      const A inv_cos1 = A(rom.core().inv_cos1), inv_cos2 = A(rom.core().inv_cos2);
      const A friction_W = -(A(o.friction1_N) * A(o.v_rel1_m_s) + A(o.friction2_N) * A(o.v_rel2_m_s)) -
                           (A(o.radial_friction1_N) * rd * inv_cos1 + A(o.radial_friction2_N) * rd * inv_cos2);
      const A damping_W = A(p.c1_Ns_m) * (sv1 * sv1 + sv2 * sv2) + A(p.c2_Ns_m) * (v1 - v2) * (v1 - v2) +
                          A(p.sheave_damping_Ns_m) * A(x(LL::kDeltaDot)) * A(x(LL::kDeltaDot)) +
                          A(p.radial_damping_Ns_m) * rd * rd;
      CHECK(pc.input_W == A(o.tau_in_Nm) * w1);
      CHECK(pc.load_W == A(o.tau_load_Nm) * w2);
      CHECK(pc.actuator_W == A(x(LL::kFh)) * A(x(LL::kDeltaDot)));
      CHECK(pc.friction_loss_W == friction_W);
      CHECK(pc.damping_loss_W == damping_W);
    }
  }
}
