// Manoeuvres on a clamped, shifting CVT (docs/validation.md#manoeuvres).
#include "cvtplant/validation/manoeuvre.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/mbd/stepper.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/reference.hpp"

namespace cvt::validation {

namespace {

constexpr double kFrame_s = 1e-3;      // both models' frame: the real-time plant's
constexpr double kAfterSlip_s = 0.02;  // what a run keeps after the onset of gross slip

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

double factor_at(const cvt::mbd::TimeProfile& f, double t) { return f.empty() ? 1.0 : f.at(t); }

long frames_of(double t_s) { return std::lround(t_s / kFrame_s); }

}  // namespace

double driver_radius_for_ratio(double r1_m, double r2_m, double c_m, double ratio) {
  if (!(ratio > 0.2 && ratio < 5.0)) throw InputError("a geometric ratio outside (0.2, 5): " + num(ratio));
  const double line = cvt::mbd::DriveGeometry(r1_m, r2_m, c_m).pitch_line_m;
  // r2/r1 falls as r1 grows along the pitch line: bisection on r1.
  double lo = 1e-3, hi = 0.5 * line / cvt::kPi;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    double r2 = std::nan("");  // no driven radius fits: the driver radius is too large
    try {
      r2 = cvt::mbd::driven_radius_for(mid, line, c_m);
    } catch (const std::invalid_argument&) {
    }
    if (!(std::isfinite(r2)) || r2 / mid < ratio)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

double balancing_road_cv(const OperatingPoint& op) {
  // docs/rom.md#road-load: c_v omega2 carries tau_in times the ratio.
  const double omega2 = op.omega1_rad_s / op.ratio;
  return op.tau_in_Nm * op.ratio / omega2;
}

double capacity_clamp_N(double torque_Nm, double r1_m, double mu0, double beta0_rad, double safety) {
  // docs/mbd-production.md#envelope: capacity 2 mu0 F r1 / cos(beta0).
  return safety * torque_Nm * std::cos(beta0_rad) / (2.0 * mu0 * r1_m);
}

RigInputs manoeuvre_inputs(const Manoeuvre& m, double hold_clamp1_N, double t_s) {
  RigInputs u;
  u.clamp1_N = hold_clamp1_N * factor_at(m.clamp1_factor, t_s);
  u.clamp2_N = m.start.clamp2_N * factor_at(m.clamp2_factor, t_s);
  u.tau_in_Nm = m.tau_in_Nm.empty() ? m.start.tau_in_Nm : m.tau_in_Nm.at(t_s);
  u.tau_load_Nm = m.tau_load_Nm.empty() ? 0.0 : m.tau_load_Nm.at(t_s);
  return u;
}

void check_manoeuvre(const Manoeuvre& m) {
  const auto bad = [&m](const std::string& why) { throw InputError("manoeuvre " + m.name + ": " + why); };
  const OperatingPoint& op = m.start;
  if (!(op.omega1_rad_s > 0 && op.omega1_rad_s <= 1000)) bad("primary speed outside (0, 1000] rad/s");
  if (!(op.ratio > 0.2 && op.ratio < 5)) bad("ratio outside (0.2, 5)");
  if (!(std::fabs(op.tau_in_Nm) <= 1000)) bad("input torque outside [-1000, 1000] N m");
  if (!(op.clamp2_N >= 100 && op.clamp2_N <= 1e5)) bad("driven clamping outside [100, 1e5] N");
  if (!(m.t_end_s > 0 && m.t_end_s <= 60)) bad("length outside (0, 60] s");
  for (const auto* f : {&m.clamp1_factor, &m.clamp2_factor})
    for (const auto& p : f->points)
      if (!(p.second > 0 && p.second < 100 && std::isfinite(p.first))) bad("a clamping factor outside (0, 100)");
  for (const auto* f : {&m.tau_in_Nm, &m.tau_load_Nm})
    for (const auto& p : f->points)
      if (!(std::fabs(p.second) <= 1000 && std::isfinite(p.first))) bad("a torque outside [-1000, 1000] N m");
}

// --- the reference

cvt::mbd::MbdParams config_params(const ReferenceConfig& c) {
  cvt::mbd::MbdParams p =
      c.set == cvt::mbd::ParameterSet::production ? cvt::mbd::production_set() : cvt::mbd::seed_case(1);
  for (const auto& override : c.overrides) {
    // Named, not a structured binding: C++17 does not let a lambda capture
    // one (clang refuses it).
    const std::string& name = override.first;
    const double value = override.second;
    bool found = false;
    cvt::mbd::visit_mbd_params(p, [&](const cvt::ParamField& f, auto& x) {
      const std::string full = f.group[0] != '\0' ? std::string(f.group) + "." + f.name : std::string(f.name);
      if (full != name) return;
      if constexpr (std::is_floating_point_v<std::remove_reference_t<decltype(x)>>) {
        x = value;
        found = true;
      } else {
        throw InputError("reference parameter '" + name + "' is not a number");
      }
    });
    if (!found) throw InputError("no reference parameter '" + name + "'");
  }
  return p;
}

cvt::mbd::MbdParams manoeuvre_params(const Manoeuvre& m, const ReferenceConfig& c) {
  check_manoeuvre(m);
  cvt::mbd::MbdParams p = config_params(c);
  const OperatingPoint& op = m.start;
  p.sheaves = cvt::mbd::SheaveMode::clamped;
  p.start_r1_m = driver_radius_for_ratio(p.r1_m, p.r2_m, p.center_distance_m, op.ratio);
  p.start_ratio_lock = true;
  p.start.active = true;
  p.start.omega1_rad_s = op.omega1_rad_s;
  p.start.omega2_rad_s = op.omega1_rad_s / op.ratio;
  p.road = cvt::mbd::RoadLoad{};
  p.road.cv_Nms_rad = balancing_road_cv(op);
  const RigInputs u0 = manoeuvre_inputs(m, 1.0, 0.0);
  p.tau_in_Nm = cvt::mbd::TimeProfile::constant(u0.tau_in_Nm);
  p.tau_load_Nm = cvt::mbd::TimeProfile::constant(u0.tau_load_Nm);
  // The locked driver sheave's force replaces the driver clamping at the
  // release (docs/mbd.md#stepping); the driven one is clamped from the start.
  p.clamp2_N = cvt::mbd::TimeProfile::constant(u0.clamp2_N);
  p.clamp1_N = p.clamp2_N;
  return p;
}

namespace {

cvt::mbd::StepperOptions stepper_options(const ReferenceConfig& c) {
  cvt::mbd::StepperOptions o;
  o.frame_s = kFrame_s;
  o.rtol = c.rtol;
  o.max_steps_per_frame = c.max_steps_per_frame;
  o.settle_rtol = settle_rtol(c.set);
  return o;
}

// The key of a manoeuvre's start: the reference's parameters and the options
// that decide the start (reference_key writes both through the field lists).
std::string start_key(const Manoeuvre& m, const ReferenceConfig& c) {
  const cvt::mbd::StepperOptions so = stepper_options(c);
  cvt::mbd::RunOptions r;
  r.t_end_s = m.t_end_s;  // the run's length is the manoeuvre's (its key below)
  r.rtol = so.rtol;
  r.sample_s = so.frame_s;
  r.ledger_tol = so.ledger_tol;
  r.settle_rtol = so.settle_rtol;
  r.max_steps = c.max_steps_per_frame;
  std::string k = reference_key(manoeuvre_params(m, c), r);
  // The t_end line is the manoeuvre's, not the start's: the start key leaves it out.
  const auto at = k.find("t_end_s ");
  if (at != std::string::npos) k.erase(at, k.find('\n', at) - at + 1);
  return k;
}

void write_profile(std::ostringstream& k, const char* name, const cvt::mbd::TimeProfile& f) {
  k << "manoeuvre." << name << ' ' << f.points.size();
  for (const auto& p : f.points) k << ' ' << num(p.first) << ':' << num(p.second);
  k << '\n';
}

}  // namespace

std::string manoeuvre_key(const Manoeuvre& m, const ReferenceConfig& c) {
  std::ostringstream k;
  k << start_key(m, c) << "stepper frames, the inputs of manoeuvre_inputs\n";
  k << "manoeuvre.t_end_s " << num(m.t_end_s) << '\n';
  write_profile(k, "clamp1_factor", m.clamp1_factor);
  write_profile(k, "clamp2_factor", m.clamp2_factor);
  write_profile(k, "tau_in_Nm", m.tau_in_Nm);
  write_profile(k, "tau_load_Nm", m.tau_load_Nm);
  k << "manoeuvre.stop_at_gross_slip " << (m.stop_at_gross_slip ? 1 : 0) << '\n';
  k << "manoeuvre.gross_slip_m_s " << num(kGrossSlip_m_s) << '\n';
  return k.str();
}

double reference_hold_clamp1_N(const Manoeuvre& m, const Series& reference) {
  if (reference.size() == 0) throw RunError("manoeuvre " + m.name + ": the reference has no sample");
  return reference.clamp1_N[0] / factor_at(m.clamp1_factor, 0.0);
}

namespace {

double process_cpu_s() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// One sample of the stepper, with the inputs of the frame that starts there.
void record(ReferenceRun& run, const cvt::mbd::Stepper& st, const RigInputs& u, double road_cv) {
  const cvt::mbd::Sample s = st.model().sample(st.t_s(), st.state());
  append_sample(run, s);
  Series& x = run.series;
  x.clamp1_N.back() = u.clamp1_N;
  x.clamp2_N.back() = u.clamp2_N;
  x.tau_in_Nm.back() = u.tau_in_Nm;
  x.tau_load_Nm.back() = u.tau_load_Nm + road_cv * s.omega_rad_s[1];
}

// Runs m on a stepper standing at the release; returns the run.
ReferenceRun run_on(cvt::mbd::Stepper& st, const Manoeuvre& m, double hold_N, double road_cv,
                    const cvt::mbd::ProgressSink& on_progress, double progress_base_s) {
  ReferenceRun run;
  const double cpu0 = process_cpu_s();
  const auto wall0 = std::chrono::steady_clock::now();
  const long long steps0 = st.counters().steps;
  const long frames = frames_of(m.t_end_s);
  run.series.reserve(static_cast<std::size_t>(frames) + 1);
  RigInputs u = manoeuvre_inputs(m, hold_N, 0.0);
  record(run, st, u, road_cv);
  long slip_frame = -1;
  for (long k = 0; k < frames; ++k) {
    const double t = static_cast<double>(k) * kFrame_s;
    u = manoeuvre_inputs(m, hold_N, t);
    st.step({u.clamp1_N, u.clamp2_N, u.tau_in_Nm, u.tau_load_Nm});
    if (st.faulted()) {
      run.failure = "the reference stopped " + st.fault_message() + " (" +
                    cvt::mbd::step_fault_name(st.outputs().fault) + ")";
      break;
    }
    record(run, st, manoeuvre_inputs(m, hold_N, t + kFrame_s), road_cv);
    if (on_progress && (k + 1) % 10 == 0) on_progress(progress_base_s + t + kFrame_s);
    if (m.stop_at_gross_slip) {
      if (slip_frame < 0 && std::fabs(run.series.wrap_slip_m_s.back()) > kGrossSlip_m_s) slip_frame = k;
      if (slip_frame >= 0 && k - slip_frame >= frames_of(kAfterSlip_s)) break;
    }
  }
  run.cpu_s = process_cpu_s() - cpu0;
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  run.steps = st.counters().steps - steps0;
  run.ledger_residual_rel = st.outputs().ledger_residual_rel;
  return run;
}

}  // namespace

std::vector<ReferenceRun> reference_manoeuvres(const std::vector<Manoeuvre>& ms, const ReferenceConfig& c,
                                               const std::string& cache_dir,
                                               const cvt::mbd::ProgressSink& on_progress) {
  std::vector<ReferenceRun> out(ms.size());
  std::vector<std::string> keys(ms.size());
  // Entries that failed their checks (docs/validation.md#cache): run again,
  // the problem kept with the new run.
  std::vector<std::string> problems(ms.size());
  // Misses, grouped by their start.
  std::map<std::string, std::vector<std::size_t>> groups;
  std::vector<std::string> order;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    keys[i] = manoeuvre_key(ms[i], c);
    if (auto hit = cached_run(keys[i], cache_dir, &problems[i])) {
      out[i] = std::move(*hit);
      continue;
    }
    const std::string sk = start_key(ms[i], c);
    if (groups.find(sk) == groups.end()) order.push_back(sk);
    groups[sk].push_back(i);
  }
  double done_s = 0;
  for (const std::string& sk : order) {
    const std::vector<std::size_t>& idx = groups[sk];
    const Manoeuvre& first = ms[idx.front()];
    const double cpu0 = process_cpu_s();
    std::unique_ptr<cvt::mbd::Stepper> st;
    try {
      st = std::make_unique<cvt::mbd::Stepper>(manoeuvre_params(first, c), stepper_options(c));
    } catch (const std::invalid_argument& e) {
      throw InputError("manoeuvre " + first.name + ": " + e.what());
    }
    const double start_cpu = process_cpu_s() - cpu0;
    const double hold_N = st->inputs().clamp1_N;
    const double road_cv = balancing_road_cv(first.start);
    // A run after save() and one after restore() are the same run, so
    // every manoeuvre of the group starts from the saved state.
    const cvt::mbd::Stepper::Snapshot snap = st->save();
    for (std::size_t j = 0; j < idx.size(); ++j) {
      const Manoeuvre& m = ms[idx[j]];
      if (j > 0) st->restore(snap);
      ReferenceRun run;
      if (st->faulted()) {
        run.failure = "the reference's start failed: " + st->fault_message();
        record(run, *st, manoeuvre_inputs(m, hold_N, 0.0), road_cv);
      } else {
        run = run_on(*st, m, hold_N, road_cv, on_progress, done_s);
      }
      if (j == 0) run.cpu_s += start_cpu;  // the start is the first run's
      done_s += m.t_end_s;
      run.cache_problem = problems[idx[j]];
      // A run its step cap ended is used, not kept: the cap is no part of
      // the key, and a larger one would go further.
      const bool capped = st->faulted() && st->outputs().fault == cvt::mbd::StepFault::step_cap;
      if (!capped) store_run(keys[idx[j]], cache_dir, run);
      out[idx[j]] = std::move(run);
    }
  }
  return out;
}

// --- the plant

namespace {

struct PlantRig {
  std::unique_ptr<cvt::SceneSimulator<cvt::AllRomPlants<double>>> holder;
  cvt::RomStateIndex ix;
  std::vector<double> x;  // scratch state

  cvt::IRomSimulator<double>& sim() { return holder->sim(); }

  std::vector<double> state() {
    std::vector<double> v(static_cast<std::size_t>(sim().state_count()));
    sim().state(v.data());
    return v;
  }

  // One frame with inputs u; false if the plant faulted.
  bool step(const RigInputs& u) {
    sim().set_driven_clamp_command(u.clamp2_N);
    cvt::RomInputs<double> in;
    in.tau_in_Nm = u.tau_in_Nm;
    in.tau_load_Nm = u.tau_load_Nm;
    in.clamp_N = u.clamp1_N;
    return sim().step_frame(in) == cvt::RomFault::none;
  }
};

void append_plant(Series& out, cvt::IRomSimulator<double>& v, double t, const RigInputs& u) {
  const cvt::RomOutputs<double> o = v.outputs();
  out.t_s.push_back(t);
  out.omega1_rad_s.push_back(o.omega1_rad_s);
  out.omega2_rad_s.push_back(o.omega2_rad_s);
  out.F_ax1_N.push_back(o.clamp_force_N);
  out.torque_driver_Nm.push_back(o.torque_transmitted_Nm);
  // As plant_run: the sheave's speed over the lumps', the mean and the slip
  // both lumps share.
  const double v1 = o.v_rel1_m_s, v2 = o.v_rel2_m_s;
  out.slip1_m_s.push_back(-0.5 * (v1 + v2));
  out.wrap_slip_m_s.push_back(whole_wrap_slip(std::min(-v1, -v2), std::max(-v1, -v2)));
  out.ratio_geom.push_back(o.geometric_ratio);
  out.F_ax2_N.push_back(o.driven_clamp_force_N);
  out.clamp1_N.push_back(u.clamp1_N);
  out.clamp2_N.push_back(u.clamp2_N);
  out.tau_in_Nm.push_back(u.tau_in_Nm);
  out.tau_load_Nm.push_back(o.tau_load_Nm);
}

// The plant's hold at the operating point: at least the reference's 0.2 s,
// then until the driven pulley's speed settles (its lumps start unloaded and
// take the torque up during the hold; the driven pulley's time constant
// under the road load, J2 / c_v, is about 0.5 s at 150 N m), at most 5 s.
constexpr long kLockFrames = 200, kLockMaxFrames = 5000;
constexpr double kSettled_rad_s = 1e-3;  // driven speed change over 10 frames that counts as settled
constexpr long kTrialFrames = 40;       // a trial release: the radius's rate over its last 30 frames
constexpr long kTrialSkipFrames = 10;

}  // namespace

Series plant_manoeuvre(const Manoeuvre& m, const cvt::Scene& plant, const Series* reference, PlantHold* hold) {
  check_manoeuvre(m);
  if ((plant.features & cvt::rom_feature::wedging) == 0)
    throw InputError("the plant of a manoeuvre needs the wedging feature (a variable ratio, docs/rom.md#wedging)");
  const OperatingPoint& op = m.start;
  cvt::Scene s = plant;
  s.features |= cvt::rom_feature::road_load;
  s.params.road_T0_Nm = 0;
  s.params.road_ca_Nms2_rad2 = 0;
  s.params.road_cv_Nms_rad = balancing_road_cv(op);
  // The plant's ledger does not survive the lock's state resets.
  s.energy_ledger = false;
  s.log = 0;
  const RigInputs u0 = manoeuvre_inputs(m, 1.0, 0.0);
  s.params.driven_clamp_N = u0.clamp2_N;
  const double r1 = driver_radius_for_ratio(s.params.r1_m, s.params.r2_m, s.params.center_distance_m, op.ratio);
  s.initial = cvt::RomInitial{};
  s.initial.omega1_rad_s = op.omega1_rad_s;
  s.initial.omega2_rad_s = op.omega1_rad_s / op.ratio;
  s.initial.radius_offset_m = r1 - s.params.r1_m;
  // The clamping that holds the ratio without load, kappa = theta1/theta2
  // (docs/rom.md#wedging), or the reference's: where the lock starts.
  const double r2 = op.ratio * r1;
  const double kappa0 = cvt::seed::wrap_angle_driver_rad(r1, r2, s.params.center_distance_m) /
                        cvt::seed::wrap_angle_driven_rad(r1, r2, s.params.center_distance_m);
  double hold_ref = reference != nullptr ? reference_hold_clamp1_N(m, *reference) : 0.0;
  RigInputs u = u0;
  u.clamp1_N = reference != nullptr ? hold_ref : kappa0 * u0.clamp2_N;
  s.clamp = cvt::constant_profile(u.clamp1_N);
  s.tau_in = cvt::constant_profile(u.tau_in_Nm);
  s.tau_load = cvt::constant_profile(u.tau_load_Nm);
  PlantRig rig;
  rig.holder = std::make_unique<cvt::SceneSimulator<cvt::AllRomPlants<double>>>();
  const cvt::SceneIssue issue = rig.holder->load(s, cvt::sim_config_of(s));
  if (!issue.ok) throw InputError(std::string("plant: ") + issue.field + ": " + issue.message);
  rig.ix = cvt::rom_state_index(s.features);
  const std::vector<double> x0 = rig.state();
  const auto fault = [&](const char* where) {
    throw RunError(std::string("manoeuvre ") + m.name + ": the plant faulted " + where + " (" +
                   cvt::rom_fault_name(rig.sim().fault()) + ")");
  };
  // Held at the operating point: the radial state and the primary speed
  // reset every frame, the rest settles under the load.
  const auto w1 = static_cast<std::size_t>(rig.ix.w1), rho = static_cast<std::size_t>(rig.ix.rho),
             rhod = static_cast<std::size_t>(rig.ix.rho_dot);
  const auto w2 = static_cast<std::size_t>(rig.ix.w2);
  double w2_before = x0[w2];
  for (long k = 0; k < kLockMaxFrames; ++k) {
    if (!rig.step(u)) fault("while held at the operating point");
    std::vector<double> x = rig.state();
    x[w1] = x0[w1];
    x[rho] = x0[rho];
    x[rhod] = x0[rhod];
    rig.sim().set_state(x.data());
    if ((k + 1) % 10 == 0) {
      if (k + 1 >= kLockFrames && std::fabs(x[w2] - w2_before) < kSettled_rad_s) break;
      w2_before = x[w2];
    }
  }
  const std::vector<double> locked = rig.state();
  // The plant's own holding clamping: trial releases, secant on ln F1 for a
  // zero rate of the driver radius.
  const auto rate_at = [&](double f1) {
    rig.sim().set_state(locked.data());
    RigInputs t = u;
    t.clamp1_N = f1;
    double r_a = 0;
    for (long k = 0; k < kTrialFrames; ++k) {
      if (!rig.step(t)) return std::nan("");
      if (k + 1 == kTrialSkipFrames) r_a = rig.sim().outputs().radius1_m;
    }
    return (rig.sim().outputs().radius1_m - r_a) / (static_cast<double>(kTrialFrames - kTrialSkipFrames) * kFrame_s);
  };
  PlantHold h;
  double fa = u.clamp1_N, ra = rate_at(fa);
  double fb = fa * 1.02, rb = rate_at(fb);
  h.trials = 2;
  while (std::isfinite(ra) && std::isfinite(rb) && std::fabs(rb) > 1e-6 && h.trials < 20 && rb != ra) {
    const double lb = std::log(fb) - rb * (std::log(fb) - std::log(fa)) / (rb - ra);
    fa = fb;
    ra = rb;
    fb = std::exp(std::clamp(lb, std::log(fa) - 0.5, std::log(fa) + 0.5));
    rb = rate_at(fb);
    ++h.trials;
  }
  h.clamp1_N = fb;
  h.r1_rate_m_s = rb;
  if (hold != nullptr) *hold = h;
  // The release from the locked state: the primary at the operating
  // point's speed (as the reference's, held through its start), the driven
  // pulley at the speed it found under the load.
  rig.sim().set_state(locked.data());
  const double hold_N = reference != nullptr ? hold_ref : h.clamp1_N;
  Series out;
  const long frames = frames_of(m.t_end_s);
  out.reserve(static_cast<std::size_t>(frames) + 1);
  u = manoeuvre_inputs(m, hold_N, 0.0);
  rig.sim().set_driven_clamp_command(u.clamp2_N);
  append_plant(out, rig.sim(), 0.0, u);
  long slip_frame = -1;
  for (long k = 0; k < frames; ++k) {
    const double t = static_cast<double>(k) * kFrame_s;
    u = manoeuvre_inputs(m, hold_N, t);
    if (!rig.step(u)) fault("after the release");
    append_plant(out, rig.sim(), t + kFrame_s, manoeuvre_inputs(m, hold_N, t + kFrame_s));
    if (m.stop_at_gross_slip) {
      if (slip_frame < 0 && std::fabs(out.wrap_slip_m_s.back()) > kGrossSlip_m_s) slip_frame = k;
      if (slip_frame >= 0 && k - slip_frame >= frames_of(kAfterSlip_s)) break;
    }
  }
  return out;
}

}  // namespace cvt::validation
