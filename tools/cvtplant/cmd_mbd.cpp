// `cvtplant mbd`: the multibody chain CVT, the offline reference (docs/cli.md#mbd,
// docs/mbd.md): seed case 1 or 2, BDF (CVODE) or the seed's RK4, a CSV
// per sample, a JSON or text summary, a progress bar on a terminal.
#include "cmd_mbd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "commands.hpp"
#include "field_json.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "registry.hpp"

namespace cvtcli::mbdcli {

namespace {

using cvt::mbd::Method;
using cvt::mbd::SheaveMode;

void require_range(double v, double lo, double hi, const std::string& what, const std::string& unit) {
  if (!(v >= lo && v <= hi))
    throw UsageError{what + ": " + num(v) + " is outside [" + num(lo) + ", " + num(hi) + "]" +
                     (unit.empty() ? "" : " " + unit)};
}

// "V" (constant) or "t:V,t:V,..." with increasing t >= 0 [s], each V in [lo, hi] (unit).
cvt::mbd::TimeProfile parse_profile(const std::string& text, const std::string& what, double lo, double hi,
                                    const std::string& unit) {
  cvt::mbd::TimeProfile p;
  if (text.find(':') == std::string::npos) {
    p.points.emplace_back(0.0, parse_finite(text, what));
  } else {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = text.find(',', start);
      const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      const std::size_t colon = item.find(':');
      if (colon == std::string::npos) throw UsageError{what + ": '" + item + "' is not t:value"};
      const double t = parse_finite(item.substr(0, colon), what + " (time)");
      const double f = parse_finite(item.substr(colon + 1), what + " (value)");
      if (t < 0) throw UsageError{what + ": times must be >= 0 s"};
      if (!p.points.empty() && t <= p.points.back().first) throw UsageError{what + ": times must increase"};
      p.points.emplace_back(t, f);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  if (p.points.size() > 10000) throw UsageError{what + ": more than 10000 points"};
  for (const auto& pt : p.points) require_range(pt.second, lo, hi, what, unit);
  return p;
}

cvt::mbd::TimeProfile parse_clamp(const std::string& text, const std::string& what) {
  return parse_profile(text, what, 100.0, 1e5, "N");
}

cvt::mbd::TimeProfile parse_torque(const std::string& text, const std::string& what) {
  return parse_profile(text, what, -1000.0, 1000.0, "N m");
}

// docs/rom.md#road-load, the plant's ranges (scene validation) with caps on work.
cvt::mbd::RoadLoad parse_road_load(const std::string& text) {
  const std::vector<double> v = parse_list(text, 0, "--road-load");
  if (v.size() < 3 || v.size() > 4) throw UsageError{"--road-load: expected T0,cv,ca or T0,cv,ca,w_eps"};
  cvt::mbd::RoadLoad r;
  r.T0_Nm = v[0];
  r.cv_Nms_rad = v[1];
  r.ca_Nms2_rad2 = v[2];
  if (v.size() == 4) r.w_eps_rad_s = v[3];
  require_range(r.T0_Nm, 0.0, 1000.0, "--road-load T0", "N m");
  require_range(r.cv_Nms_rad, 0.0, 100.0, "--road-load cv", "N m s/rad");
  require_range(r.ca_Nms2_rad2, 0.0, 10.0, "--road-load ca", "N m s^2/rad^2");
  if (!(r.w_eps_rad_s > 0 && r.w_eps_rad_s <= 1000.0))
    throw UsageError{"--road-load w_eps: " + num(r.w_eps_rad_s) + " is outside (0, 1000] rad/s"};
  return r;
}

// docs/mbd.md#start-at-speed: both speeds positive (the chain runs forward).
cvt::mbd::StartAtSpeed parse_omega0(const std::string& text) {
  const std::vector<double> v = parse_list(text, 2, "--omega0");
  for (int j = 0; j < 2; ++j)
    if (!(v[j] > 0 && v[j] <= 1000.0))
      throw UsageError{"--omega0: " + num(v[j]) + " is outside (0, 1000] rad/s"};
  cvt::mbd::StartAtSpeed s;
  s.active = true;
  s.omega1_rad_s = v[0];
  s.omega2_rad_s = v[1];
  return s;
}

nlohmann::json jnum(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

void add_model_options(CLI::App* sub, ModelOptions& o) {
  sub->add_option("--set", o.set,
                  "Parameter set: seed (Table 1, with --case) | production (the production-like chain CVT, "
                  "docs/mbd-production.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"seed", "production"}));
  sub->add_option("--t-end", o.t_end_s, "Simulated time after the release [s], (0, 3600]")->capture_default_str();
  sub->add_option("--sheaves", o.sheaves,
                  "fixed (the seed's pulleys) | clamped (movable sheave per pulley, axial force given); default: "
                  "fixed for the seed set, clamped for production")
      ->check(CLI::IsMember({"fixed", "clamped"}));
  o.clamp1_opt = sub->add_option("--clamp-N", o.clamp1,
                                 "Driver clamping force for --sheaves clamped: F, or a profile t:F,t:F,... [s:N], F in [100, 1e5]");
  o.clamp2_opt = sub->add_option("--clamp2-N", o.clamp2,
                                 "Driven clamping force (default: driver's times the static thrust ratio theta2/theta1)");
  sub->add_option("--method", o.method, "bdf (CVODE BDF, --linear-solver) | rk4 (fixed step, the seed's method)")
      ->capture_default_str()
      ->check(CLI::IsMember({"bdf", "rk4"}));
  o.dt_opt = sub->add_option("--dt", o.dt_s, "RK4 step [s], [1e-8, 1e-4] (default 1e-6)");
  o.rtol_opt = sub->add_option("--rtol", o.rtol, "BDF relative tolerance, [1e-11, 1e-3] (default 5e-7)");
  o.solver_opt = sub->add_option("--linear-solver", o.linear_solver,
                                 "BDF Newton systems: chain (block elimination along the chain) | klu (sparse LU); "
                                 "docs/mbd.md#linear-algebra")
                     ->capture_default_str()
                     ->check(CLI::IsMember({"chain", "klu"}));
  o.links_opt = sub->add_option("--links", o.links, "Number of links N of the seed set, [36, 53]; sets the pretension")
                    ->capture_default_str();
  sub->add_option("--sample", o.sample_s, "Output interval [s], [1e-6, t-end]")->capture_default_str();
  sub->add_option("--tau-in", o.tau_in,
                  "Driver torque from the release: T, or a profile t:T,t:T,... [s:N m], T in [-1000, 1000]")
      ->capture_default_str();
  sub->add_option("--tau-load", o.tau_load, "Load torque on the driven pulley, same syntax")->capture_default_str();
  o.road_opt = sub->add_option("--road-load", o.road_load,
                               "Road load on the driven pulley, T0,cv,ca[,w_eps]: T0 tanh(w2/w_eps) + cv w2 + ca w2|w2| "
                               "added to --tau-load [N m, N m s/rad, N m s^2/rad^2, rad/s]");
  o.omega0_opt = sub->add_option("--omega0", o.omega0,
                                 "Start at speed W1,W2 [rad/s], each in (0, 1000]: spin-up and hold before the "
                                 "release (docs/mbd.md#start-at-speed)");
  sub->add_option("--ledger-tol", o.ledger_tol, "Stop when the energy ledger is off by more (relative), [1e-12, 1]")->capture_default_str();
  sub->add_option("--max-steps", o.max_steps, "Cap on integrator steps (work), [1, 1e12]")->capture_default_str();
  sub->add_option("--max-rows", o.max_rows, "Cap on output rows (memory and disk), [1, 1e9]")->capture_default_str();
}

void validate(const ModelOptions& o) {
  require_range(o.t_end_s, 1e-6, 3600.0, "--t-end", "s");
  require_range(o.sample_s, 1e-6, o.t_end_s, "--sample", "s (and at most --t-end)");
  require_range(o.links, 36, 53, "--links", "");
  if (o.production() && o.links_opt != nullptr && o.links_opt->count() > 0)
    throw UsageError{"--links applies to --set seed (the production set has 53 links)"};
  parse_torque(o.tau_in, "--tau-in");
  parse_torque(o.tau_load, "--tau-load");
  if (o.road_opt != nullptr && o.road_opt->count() > 0) parse_road_load(o.road_load);
  if (o.omega0_opt != nullptr && o.omega0_opt->count() > 0) parse_omega0(o.omega0);
  require_range(o.ledger_tol, 1e-12, 1.0, "--ledger-tol", "");
  require_range(static_cast<double>(o.max_steps), 1, 1e12, "--max-steps", "");
  require_range(static_cast<double>(o.max_rows), 1, 1e9, "--max-rows", "");
  if (o.method == "bdf") {
    if (o.dt_opt != nullptr && o.dt_opt->count() > 0) throw UsageError{"--dt applies to --method rk4 only"};
    require_range(o.rtol, 1e-11, 1e-3, "--rtol", "");
  } else {
    if (o.rtol_opt != nullptr && o.rtol_opt->count() > 0) throw UsageError{"--rtol applies to --method bdf only"};
    if (o.solver_opt != nullptr && o.solver_opt->count() > 0)
      throw UsageError{"--linear-solver applies to --method bdf only"};
    require_range(o.dt_s, 1e-8, 1e-4, "--dt", "s");
    if (o.sample_s < o.dt_s) throw UsageError{"--sample: must be at least --dt"};
    const double steps = std::round(o.t_end_s / o.dt_s);
    if (steps > static_cast<double>(o.max_steps))
      throw UsageError{"--t-end/--dt: " + num(steps) + " RK4 steps exceed --max-steps " +
                       std::to_string(o.max_steps) + " (raise --max-steps)"};
  }
  const double rows = std::ceil(o.t_end_s / o.sample_s - 1e-9) + 1.0;
  if (rows > static_cast<double>(o.max_rows))
    throw UsageError{"--t-end/--sample: " + num(rows) + " output rows exceed --max-rows " +
                     std::to_string(o.max_rows) + " (raise --max-rows or --sample)"};
  const bool given1 = o.clamp1_opt != nullptr && o.clamp1_opt->count() > 0;
  const bool given2 = o.clamp2_opt != nullptr && o.clamp2_opt->count() > 0;
  if (o.sheave_mode() == "clamped") {
    if (!given1) throw UsageError{"--sheaves clamped needs --clamp-N"};
    parse_clamp(o.clamp1, "--clamp-N");
    if (given2) parse_clamp(o.clamp2, "--clamp2-N");
  } else if (given1 || given2) {
    throw UsageError{"--clamp-N/--clamp2-N apply to --sheaves clamped only"};
  }
}

cvt::mbd::MbdParams params_for(const ModelOptions& o, int friction_case) {
  cvt::mbd::MbdParams p = o.production() ? cvt::mbd::production_set() : cvt::mbd::seed_case(friction_case);
  if (!o.production()) p.links = o.links;
  p.tau_in_Nm = parse_torque(o.tau_in, "--tau-in");
  p.tau_load_Nm = parse_torque(o.tau_load, "--tau-load");
  if (!o.road_load.empty()) p.road = parse_road_load(o.road_load);
  if (!o.omega0.empty()) {
    // The set's own spin-up and hold (the production set: 0.2 s each).
    const cvt::mbd::StartAtSpeed w = parse_omega0(o.omega0);
    p.start.active = true;
    p.start.omega1_rad_s = w.omega1_rad_s;
    p.start.omega2_rad_s = w.omega2_rad_s;
  }
  p.sheaves = SheaveMode::fixed;
  if (o.sheave_mode() == "clamped") {
    p.sheaves = SheaveMode::clamped;
    p.clamp1_N = parse_clamp(o.clamp1, "--clamp-N");
    if (!o.clamp2.empty()) p.clamp2_N = parse_clamp(o.clamp2, "--clamp2-N");
  }
  return p;
}

cvt::mbd::RunOptions run_options_for(const ModelOptions& o) {
  cvt::mbd::RunOptions r;
  r.method = o.method == "rk4" ? Method::rk4 : Method::bdf;
  r.t_end_s = o.t_end_s;
  r.rtol = o.rtol;
  r.linear_solver = o.linear_solver == "klu" ? cvt::mbd::LinearSolver::klu : cvt::mbd::LinearSolver::chain;
  r.dt_s = o.dt_s;
  r.sample_s = o.sample_s;
  r.max_steps = o.max_steps;
  r.ledger_tol = o.ledger_tol;
  // docs/mbd.md#start-up: the production set's stiff chain settles and
  // spins up at 1e-6 (1e-8 costs it about 6x the steps); the seed's at 1e-8.
  if (o.production()) r.settle_rtol = 1e-6;
  return r;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string method_label(const ModelOptions& o) {
  return o.method == "rk4" ? "RK4 dt " + num(o.dt_s) + " s" : "BDF (" + o.linear_solver + ") rtol " + num(o.rtol);
}

std::string case_label(int c) { return c == 1 ? "case 1 (Coulomb)" : "case 2 (Stribeck)"; }

void write_csv_header(std::FILE* f, bool clamped) {
  std::fprintf(f,
               "t_s,omega1_rad_s,omega2_rad_s,ratio,F_ax1_N,F_ax2_N,T_chain_driver_Nm,T_transmitted_Nm,tau_in_Nm,"
               "tau_load_Nm,slip1_m_s,slip2_m_s,T_tight_N,T_slack_N,wrap_links1,wrap_links2,");
  if (clamped) std::fprintf(f, "sheave1_m,sheave2_m,clamp1_N,clamp2_N,");
  std::fprintf(f, "W_in_J,W_load_J,D_friction_J,D_damping_J,W_clamp_J,E_kin_J,E_el_J,ledger_residual_rel\n");
}

void write_csv_row(std::FILE* f, const cvt::mbd::Sample& s, double res, bool clamped) {
  std::fprintf(f, "%.9g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.9g,%.9g,%.9g,%.9g,%d,%d,", s.t_s,
               s.omega_rad_s[0], s.omega_rad_s[1], s.ratio, s.F_ax_N[0], s.F_ax_N[1], s.chain_torque_Nm[0],
               s.chain_torque_Nm[1], s.tau_in_Nm, s.tau_load_Nm, s.slip_m_s[0], s.slip_m_s[1], s.tension_tight_N,
               s.tension_slack_N, s.wrap_links[0], s.wrap_links[1]);
  if (clamped)
    std::fprintf(f, "%.9g,%.9g,%.9g,%.9g,", s.sheave_opening_m[0], s.sheave_opening_m[1], s.clamp_N[0], s.clamp_N[1]);
  std::fprintf(f, "%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.3g\n", s.W_in_J, s.W_load_J, s.D_friction_J,
               s.D_damping_J, s.W_clamp_J, s.E_kin_J, s.E_el_J, res);
}

void write_links_header(std::FILE* f) {
  std::fprintf(f, "t_s,link,x_m,y_m,theta_rad,rear_x_m,rear_y_m,front_x_m,front_y_m,pulley,bolt_force_N,slip_m_s,"
                  "tension_N\n");
}

void write_links_rows(std::FILE* f, double t, const std::vector<cvt::mbd::LinkState>& links) {
  for (std::size_t i = 0; i < links.size(); ++i) {
    const auto& l = links[i];
    std::fprintf(f, "%.9g,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%.9g,%.9g\n", t, i, l.x_m, l.y_m,
                 l.theta_rad, l.rear_x_m, l.rear_y_m, l.front_x_m, l.front_y_m, l.pulley, l.bolt_force_N, l.slip_m_s,
                 l.tension_N);
  }
}

RunOutcome run_case(const ModelOptions& o, int friction_case, std::FILE* csv, std::FILE* links_csv,
                    double links_every_s, double picture_t_s, const std::string& label) {
  const cvt::mbd::MbdParams params = params_for(o, friction_case);
  const cvt::mbd::RunOptions ropt = run_options_for(o);
  const bool clamped = params.sheaves == SheaveMode::clamped;
  RunOutcome out;
  cvt::mbd::SummaryBuilder summary(o.t_end_s);
  Progress progress(label, o.t_end_s);
  double energy0 = std::numeric_limits<double>::quiet_NaN();
  double next_links_t = 0.0;
  if (csv != nullptr) write_csv_header(csv, clamped);
  if (links_csv != nullptr) write_links_header(links_csv);
  auto on_sample = [&](const cvt::mbd::Sample& s, const cvt::mbd::ChainModel& m, const double* y) {
    if (std::isnan(energy0)) energy0 = s.E_kin_J + s.E_el_J;
    summary.add(s);
    if (csv != nullptr) {
      const double res = std::fabs(cvt::mbd::ledger_residual_J(s, energy0)) /
                         cvt::mbd::ledger_scale_J(s, energy0, m.tolerance_energy_J());
      write_csv_row(csv, s, res, clamped);
    }
    if (links_csv != nullptr && s.t_s >= next_links_t - 1e-12) {
      write_links_rows(links_csv, s.t_s, m.link_states(y));
      next_links_t += links_every_s;
    }
    if (picture_t_s >= 0 && out.picture_t_s < 0 && s.t_s >= picture_t_s - 1e-12) {
      out.picture = m.link_states(y);
      out.picture_t_s = s.t_s;
    }
  };
  try {
    out.stats = cvt::mbd::simulate(params, ropt, on_sample, [&](double t) { progress.update(t); });
  } catch (const cvt::mbd::RunFailure& e) {
    out.stats = e.stats;
    out.failed = true;
    out.fail_t_s = e.t_s;
    out.fail_quantity = e.quantity;
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  progress.finish();
  out.summary = summary.result();
  return out;
}

namespace {

// docs/mbd.md#start-at-speed: the hold before the release and how steady it was.
nlohmann::json start_json(const ModelOptions& o, const cvt::mbd::RunStats& st) {
  if (o.omega0.empty() || st.hold_samples.empty()) return nullptr;
  const cvt::mbd::StartAtSpeed start = params_for(o, 1).start;
  const cvt::mbd::Sample& rel = st.hold_samples.back();
  nlohmann::json j = {{"omega1_rad_s", start.omega1_rad_s},
                      {"omega2_rad_s", start.omega2_rad_s},
                      {"spinup_s", start.spinup_s},
                      {"hold_s", start.hold_s},
                      {"steps", st.start_steps},
                      {"omega2_release_rad_s", rel.omega_rad_s[1]},
                      {"holding_torque_Nm", rel.tau_in_Nm},
                      {"F_ax1_release_N", rel.F_ax_N[0]},
                      {"F_ax2_release_N", rel.F_ax_N[1]}};
  const double window = std::min(0.2, start.hold_s);  // two halves of about a lap at 150 rad/s
  if (window > 0) {
    const cvt::mbd::HoldSteadiness h = cvt::mbd::hold_steadiness(st.hold_samples, window);
    j["hold_window_s"] = h.window_s;
    j["omega2_range_rel"] = h.omega2_range_rel;
    j["holding_torque_mean_Nm"] = h.holding_torque_mean_Nm;
    j["holding_torque_change_rel"] = h.holding_torque_change_rel;
    j["F_ax1_change_rel"] = h.F_ax_change_rel[0];
    j["F_ax2_change_rel"] = h.F_ax_change_rel[1];
  }
  return j;
}

nlohmann::json summary_json(const ModelOptions& o, int friction_case, const RunOutcome& r) {
  const auto& st = r.stats;
  const auto& s = r.summary;
  nlohmann::json j;
  j["subcommand"] = "mbd";
  j["status"] = r.failed ? "failed" : "ok";
  if (r.failed) j["failure"] = {{"t_s", r.fail_t_s}, {"quantity", r.fail_quantity}};
  j["set"] = o.set;
  j["case"] = o.production() ? nlohmann::json(nullptr) : nlohmann::json(friction_case);
  j["friction"] = o.production() ? "production" : friction_case == 1 ? "case1" : "case2";
  j["method"] = o.method;
  if (o.method == "bdf") j["linear_solver"] = o.linear_solver;
  j["rtol"] = o.method == "bdf" ? nlohmann::json(o.rtol) : nlohmann::json(nullptr);
  j["dt_s"] = o.method == "rk4" ? nlohmann::json(o.dt_s) : nlohmann::json(nullptr);
  j["sheaves"] = o.sheave_mode();
  j["links"] = o.production() ? cvt::mbd::production_set().links : o.links;
  // Every input of the model, by the reference's field list.
  j["params"] = field_rows(params_for(o, friction_case),
                           [](const cvt::mbd::MbdParams& p, FieldRows& w) { cvt::mbd::visit_mbd_params(p, w); });
  j["t_end_s"] = o.t_end_s;
  j["t_reached_s"] = s.last.t_s;
  j["sample_s"] = o.sample_s;
  j["samples"] = st.samples;
  j["wall_s"] = st.wall_s;
  j["cpu_s"] = st.cpu_s;
  j["settle_wall_s"] = st.settle_wall_s;
  j["settle_cpu_s"] = st.settle_cpu_s;
  j["steps"] = st.steps;
  j["rhs_evals"] = st.rhs_evals;
  j["jac_evals"] = st.jac_evals;
  j["linear_setups"] = st.linear_setups;
  j["newton_iters"] = st.newton_iters;
  j["error_test_fails"] = st.error_test_fails;
  j["newton_fails"] = st.newton_fails;
  j["states"] = st.states;
  j["jacobian_nnz"] = st.jacobian_nnz;
  j["energy_residual_rel"] = st.ledger_residual_max_rel;
  const double e_end = s.last.E_kin_J + s.last.E_el_J;
  j["energy"] = {{"E0_J", st.energy0_J},
                 {"E_end_J", e_end},
                 {"W_in_J", s.last.W_in_J},
                 {"W_load_J", s.last.W_load_J},
                 {"D_friction_J", s.last.D_friction_J},
                 {"D_damping_J", s.last.D_damping_J},
                 {"W_clamp_J", s.last.W_clamp_J},
                 {"residual_J", cvt::mbd::ledger_residual_J(s.last, st.energy0_J)}};
  j["omega1_end_rad_s"] = s.omega_end_rad_s[0];
  j["omega2_end_rad_s"] = s.omega_end_rad_s[1];
  j["ratio_mean"] = jnum(s.ratio_mean);
  j["ratio_end"] = jnum(s.ratio_end);
  j["ratio_last_window"] = jnum(s.ratio_window);
  j["window_s"] = s.window_s;
  j["F_ax1_mean_N"] = jnum(s.F_ax_mean_N[0]);
  j["F_ax2_mean_N"] = jnum(s.F_ax_mean_N[1]);
  j["F_ax1_ripple_N"] = jnum(s.F_ax1_ripple_N);
  j["F_ax1_last_window_mean_N"] = jnum(s.F_ax_window_mean_N[0]);
  j["F_ax2_last_window_mean_N"] = jnum(s.F_ax_window_mean_N[1]);
  j["slip1_last_window_m_s"] = jnum(s.slip_window_mean_m_s[0]);
  j["slip2_last_window_m_s"] = jnum(s.slip_window_mean_m_s[1]);
  j["T_tight_end_N"] = jnum(s.tension_tight_end_N);
  j["T_slack_end_N"] = jnum(s.tension_slack_end_N);
  j["wrap_links_end"] = {s.wrap_links_end[0], s.wrap_links_end[1]};
  j["start_at_speed"] = start_json(o, st);
  return j;
}

void print_text(const ModelOptions& o, int c, const RunOutcome& r) {
  const auto& st = r.stats;
  const auto& s = r.summary;
  std::printf("Multibody chain CVT, %s, %d links, %s sheaves, %s\n",
              o.production() ? "production-like set" : ("seed " + case_label(c)).c_str(),
              o.production() ? cvt::mbd::production_set().links : o.links, o.sheave_mode().c_str(),
              method_label(o).c_str());
  std::printf("  t = %g s: omega1 %.3f rad/s, omega2 %.3f rad/s, ratio %.4f (mean over the run %.4f)\n", s.last.t_s,
              s.omega_end_rad_s[0], s.omega_end_rad_s[1], s.ratio_end, s.ratio_mean);
  std::printf("  driver axial force: mean %.1f N, last %.3g s: mean %.1f N, peak to peak %.1f N\n",
              s.F_ax_mean_N[0], s.window_s, s.F_ax_window_mean_N[0], s.F_ax1_ripple_N);
  std::printf("  strands at the end: tight %.1f N, slack %.1f N; links in the wraps %d, %d\n", s.tension_tight_end_N,
              s.tension_slack_end_N, s.wrap_links_end[0], s.wrap_links_end[1]);
  if (!st.hold_samples.empty()) {
    const cvt::mbd::Sample& rel = st.hold_samples.back();
    std::printf("  start at speed: released at omega1 %.3f rad/s, omega2 %.3f rad/s, driver holding torque %.2f N m\n",
                rel.omega_rad_s[0], rel.omega_rad_s[1], rel.tau_in_Nm);
  }
  std::printf("  energy ledger: max residual %.2e of the largest term\n", st.ledger_residual_max_rel);
  std::printf("  %lld steps, %lld rhs, %lld jacobians, %.2f s wall (settle %.2f s)\n", st.steps, st.rhs_evals,
              st.jac_evals, st.wall_s, st.settle_wall_s);
}

struct RunCliOptions {
  int friction_case = 0;
  std::string csv, links_csv;
  double links_every_s = 0;
  bool json = false;
  ModelOptions model;
  CLI::App* figures = nullptr;
  FigureOptions fig;
};

Action register_mbd(CLI::App& app) {
  auto opt = std::make_shared<RunCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "mbd", "Multibody chain CVT (seed section 2), the offline reference: run a seed case or draw its figures");
  sub->add_option("--case", opt->friction_case, "Seed case: 1 (Coulomb) or 2 (Stribeck friction, Table 2)")
      ->check(CLI::IsMember({1, 2}));
  add_model_options(sub, opt->model);
  sub->add_option("--csv", opt->csv, "Write one row per sample (docs/cli.md#mbd-csv); '-' for stdout");
  sub->add_option("--links-csv", opt->links_csv, "Write every link's state (long format) per --links-every");
  sub->add_option("--links-every", opt->links_every_s, "Interval of --links-csv [s] (default: --sample)");
  sub->add_flag("--json", opt->json, "Print the summary as JSON");
  opt->figures = sub->add_subcommand("figures", "Draw the seed's Figs. 13-14 and the chain on the pulleys as PNG");
  add_figure_options(opt->figures, opt->fig);
  return [opt]() -> int {
    if (opt->figures->parsed()) return run_figures(opt->fig);
    const ModelOptions& m = opt->model;
    if (m.production() && opt->friction_case != 0)
      throw UsageError{"--case applies to --set seed (the production set has its own friction)"};
    if (!m.production() && opt->friction_case == 0) throw UsageError{"--case 1|2 is required"};
    validate(m);
    double every = opt->links_every_s;
    if (!opt->links_csv.empty()) {
      if (every == 0) every = m.sample_s;
      require_range(every, m.sample_s, m.t_end_s, "--links-every", "s (from --sample to --t-end)");
      const double rows = (std::floor(m.t_end_s / every) + 1.0) * (m.production() ? 53 : m.links);
      if (rows > static_cast<double>(m.max_rows))
        throw UsageError{"--links-csv: " + num(rows) + " rows exceed --max-rows (raise it or --links-every)"};
    } else if (opt->links_every_s != 0) {
      throw UsageError{"--links-every applies with --links-csv only"};
    }
    if (opt->json && opt->csv == "-") throw UsageError{"--csv -: stdout carries the JSON summary; give a file"};
    if (opt->csv == "-" && opt->links_csv == "-") throw UsageError{"--csv and --links-csv cannot both be stdout"};
    std::FILE* csv = opt->csv.empty() ? nullptr : open_output(opt->csv);
    std::FILE* links = opt->links_csv.empty() ? nullptr : open_output(opt->links_csv);
    const RunOutcome r = run_case(m, opt->friction_case, csv, links, every, -1,
                                  m.production() ? std::string("mbd production") : "mbd " + case_label(opt->friction_case));
    close_output(csv);
    close_output(links);
    if (opt->json) print_json(summary_json(m, opt->friction_case, r));
    else if (opt->csv != "-" && opt->links_csv != "-") print_text(m, opt->friction_case, r);
    if (r.failed) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "at t = %.6g s: ", r.fail_t_s);
      throw RunError{buf + r.fail_quantity};
    }
    return 0;
  };
}

const bool registered = add_registrar(&register_mbd);

}  // namespace

}  // namespace cvtcli::mbdcli
