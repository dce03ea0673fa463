// The multibody reference behind the SIL bridge (docs/sil.md#reference-plant).
#include "cvtplant/cosim/reference_plant.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cvtplant/math/detmath.hpp"
#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/mbd/params.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/reference.hpp"

namespace cvt::cosim {

using cvt::mbd::StepFault;
using cvt::mbd::Stepper;

namespace {

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The release state depends on the parameters and the start-up's tolerance
// only (docs/mbd.md#start-up): the key is the validation cache's text of
// them (every field, the reference's version) under a head line of its own.
std::string release_key(const cvt::mbd::MbdParams& p, const cvt::mbd::StepperOptions& o) {
  cvt::mbd::RunOptions r;
  r.settle_rtol = o.settle_rtol;
  return "cvtplant reference release state 1\n" + cvt::validation::reference_key(p, r);
}

// Release states of this process, by key: every bridge, comparison and test
// in it pays a scene's start-up once.
std::map<std::string, std::shared_ptr<const Stepper::Snapshot>>& memory_cache() {
  static std::map<std::string, std::shared_ptr<const Stepper::Snapshot>> cache;
  return cache;
}

std::string cache_file(const std::string& dir, const std::string& key) {
  return dir + "/" + cvt::validation::key_hash(key) + ".release";
}

// The file: the key, a line "--", the inputs held at the release and the
// state, one value per line to 17 digits (every bit).
std::shared_ptr<const Stepper::Snapshot> read_release(const std::string& path, const std::string& key) {
  std::ifstream f(path);
  if (!f) return nullptr;
  std::string line, text;
  while (std::getline(f, line) && line != "--") text += line + "\n";
  if (text != key) return nullptr;  // another key with the same hash
  auto s = std::make_shared<Stepper::Snapshot>();
  double in[4];
  for (double& v : in)
    if (!(f >> v)) return nullptr;
  s->inputs = {in[0], in[1], in[2], in[3]};
  for (double v; f >> v;) s->y.push_back(v);
  if (!f.eof() || s->y.empty()) return nullptr;
  return s;
}

void write_release(const std::string& path, const std::string& key, const Stepper::Snapshot& s) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (f == nullptr) return;  // a cache that cannot be written costs the start-up next time, nothing else
  bool ok = std::fputs(key.c_str(), f) >= 0 && std::fputs("--\n", f) >= 0;
  for (double v : {s.inputs.clamp1_N, s.inputs.clamp2_N, s.inputs.tau_in_Nm, s.inputs.tau_load_Nm})
    ok = ok && std::fprintf(f, "%.17g\n", v) > 0;
  for (double v : s.y) ok = ok && std::fprintf(f, "%.17g\n", v) > 0;
  ok = std::fclose(f) == 0 && ok;
  if (ok) std::rename(tmp.c_str(), path.c_str());
  else std::remove(tmp.c_str());
}

double saturate(double f_N, double max_N) { return f_N < 0.0 ? 0.0 : (f_N > max_N ? max_N : f_N); }

std::string at_time(double t, const std::string& what) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "at t = %.6g s: ", t);
  return buf + what;
}

}  // namespace

cvt::can::PlantFault plant_fault_code(StepFault f) {
  using cvt::can::PlantFault;
  switch (f) {
    case StepFault::none: return PlantFault::None;
    case StepFault::input: return PlantFault::Input;
    case StepFault::ledger: return PlantFault::EnergyCheck;
    case StepFault::torn_chain: return PlantFault::TornChain;
    case StepFault::runaway: return PlantFault::SpeedOutOfRange;
    case StepFault::step_cap: return PlantFault::StepCap;
    case StepFault::solver: return PlantFault::SolverFailed;
    case StepFault::state: return PlantFault::StateInvalid;
  }
  return PlantFault::StateInvalid;
}

StepFault step_fault_by_name(const std::string& name) {
  for (StepFault f : {StepFault::none, StepFault::input, StepFault::ledger, StepFault::torn_chain, StepFault::runaway,
                      StepFault::step_cap, StepFault::solver, StepFault::state})
    if (name == cvt::mbd::step_fault_name(f)) return f;
  throw std::invalid_argument("unknown fault '" + name +
                              "' (input, ledger, torn_chain, runaway, step_cap, solver, state)");
}

// What a loaded scene fixes: the reference's parameters, its release state,
// the actuators' constants and what the plant publishes.
struct ReferencePlant::Loaded {
  cvt::mbd::MbdParams params;
  std::string key;
  std::shared_ptr<const Stepper::Snapshot> release;
  double lag = 1.0;            // the actuators' frame update, 1 - exp(-frame / tau)
  double clamp_max_N = 0.0;
  double thrust_ratio = 1.0;   // driven over driver clamping without a driven command (theta2 / theta1)
  cvt::sil::PublishedParams published;
  double settle_rtol = 1e-8;   // the start-up's tolerance: the set's (docs/mbd.md#start-up)
  int keeps_time = -1;         // the probe's verdict: -1 not yet measured
  std::string realtime_refusal;  // why not, when not
};

ReferencePlant::ReferencePlant(ReferenceOptions o) : opt_(std::move(o)) {}
ReferencePlant::~ReferencePlant() = default;

bool ReferencePlant::load(const cvt::Scene& s) {
  const double us = s.frame_s * 1e6;
  const auto frame_us = static_cast<std::int64_t>(us + 0.5);
  if (frame_us < 1 || static_cast<double>(frame_us) != us) {
    load_refusal_ = "its frame is not a whole number of microseconds";
    return false;
  }
  // The scene's parameter set (docs/validation.md#parameter-sets): the
  // controller scenes run against the production-like chain CVT.
  const auto set = cvt::mbd::parameter_set_by_name(s.reference_set ? s.reference_set : "");
  if (!set) {
    load_refusal_ = std::string("unknown reference parameter set '") + (s.reference_set ? s.reference_set : "") +
                    "' (seed, production)";
    return false;
  }
  std::string why;
  const auto p = cvt::validation::reference_params(s, cvt::validation::SheaveChoice::scene, *set, why);
  if (!p) {
    load_refusal_ = "the multibody reference cannot run it: " + why;
    return false;
  }
  auto l = std::make_unique<Loaded>();
  l->params = *p;
  l->settle_rtol = cvt::validation::settle_rtol(*set);
  cvt::mbd::StepperOptions keyed = opt_.stepper;
  keyed.settle_rtol = l->settle_rtol;
  l->key = release_key(*p, keyed);
  const cvt::RomParams& rp = s.params;
  // docs/rom.md#axial: the real-time plant's actuators, updated once per
  // frame as its driven actuator is (docs/rom.md#driven-clamping).
  l->lag = 1.0 - cvt::dm::exp(-s.frame_s / rp.actuator_tau_s);
  l->clamp_max_N = rp.clamp_max_N;
  // docs/sil.md#reference-published
  const cvt::mbd::DriveGeometry geo(p->r1_m, p->r2_m, p->center_distance_m);
  l->thrust_ratio = geo.wrap_rad[1] / geo.wrap_rad[0];
  cvt::sil::PublishedParams& q = l->published;
  q.variable_ratio = (s.features & cvt::rom_feature::wedging) != 0;
  q.capacity_coeff = p->friction.mu0 * cvt::lump_load_per_axial(1.0, 1.0, cvt::dm::cos(p->beta0_rad));
  q.radius_driver_m = p->start_r1_m > 0 ? p->start_r1_m : p->r1_m;
  q.clamp_max_N = rp.clamp_max_N;
  if (q.variable_ratio) {
    // The stops' opening is the radial travel seen axially, 2 tan(beta0) per
    // metre of travel (docs/mbd.md#clamped-sheaves).
    const double travel_m = p->sheave_stop_m * cvt::dm::cos(p->beta0_rad) / (2.0 * cvt::dm::sin(p->beta0_rad));
    const double rho[3] = {travel_m, 0.0, -travel_m};
    for (int i = 0; i < 3; ++i) {
      const double r1 = p->r1_m + rho[i];
      const double r2 = cvt::mbd::driven_radius_for(r1, geo.pitch_line_m, p->center_distance_m);
      q.ratio[i] = r2 / r1;
      q.thrust_ratio[i] = cvt::seed::wrap_angle_driver_rad(r1, r2, p->center_distance_m) /
                          cvt::seed::wrap_angle_driven_rad(r1, r2, p->center_distance_m);
    }
  }
  scene_ = &s;
  frame_ns_ = frame_us * 1000;
  cur_ = std::move(l);
  stepper_.reset();
  load_refusal_.clear();
  return true;
}

bool ReferencePlant::variable_ratio() const { return loaded() && cur_->published.variable_ratio; }

cvt::sil::PublishedParams ReferencePlant::published() const {
  return loaded() ? cur_->published : cvt::sil::PublishedParams{};
}

void ReferencePlant::fail(StepFault f, const std::string& what) {
  fault_ = f;
  fault_message_ = what;
}

cvt::mbd::StepperOptions ReferencePlant::stepper_options() const {
  cvt::mbd::StepperOptions so = opt_.stepper;
  so.frame_s = static_cast<double>(frame_ns_) * 1e-9;
  if (cur_) so.settle_rtol = cur_->settle_rtol;
  return so;
}

void ReferencePlant::reset() {
  if (!loaded()) return;
  const double c0 = thread_cpu_s();
  const cvt::mbd::StepperOptions so = stepper_options();
  fault_ = StepFault::none;
  fault_message_.clear();
  frames_ = 0;
  step_cpu_s_ = 0;
  stepper_.reset();
  Loaded& l = *cur_;
  release_from_cache_ = true;
  if (!l.release) {
    auto& mem = memory_cache();
    const auto hit = mem.find(l.key);
    if (hit != mem.end()) l.release = hit->second;
    else if (!opt_.release_cache_dir.empty()) l.release = read_release(cache_file(opt_.release_cache_dir, l.key), l.key);
  }
  try {
    if (l.release) {
      stepper_ = std::make_unique<Stepper>(l.params, so, *l.release);
    } else {
      release_from_cache_ = false;
      stepper_ = std::make_unique<Stepper>(l.params, so);
      if (!stepper_->faulted()) {
        l.release = std::make_shared<const Stepper::Snapshot>(stepper_->save());
        memory_cache()[l.key] = l.release;
        if (!opt_.release_cache_dir.empty()) write_release(cache_file(opt_.release_cache_dir, l.key), l.key, *l.release);
      }
    }
  } catch (const std::exception& e) {
    // Parameters the model refuses, or a release state of another model.
    stepper_.reset();
    fail(StepFault::input, at_time(0.0, e.what()));
  }
  if (stepper_ && stepper_->faulted()) fail(stepper_->outputs().fault, stepper_->fault_message());
  // The actuators start where the reference was released: the scene's
  // clamping at t = 0 (the driven one the set-up's, or the thrust ratio's).
  actuator_N_[0] = stepper_ ? stepper_->inputs().clamp1_N : 0.0;
  actuator_N_[1] = stepper_ ? stepper_->inputs().clamp2_N : 0.0;
  driven_cmd_N_ = actuator_N_[1];
  lifted_frames_ = 0;
  held_radius_m_[0] = held_radius_m_[1] = 0.0;
  if (stepper_) hold_radii();
  reset_cpu_s_ = thread_cpu_s() - c0;
}

void ReferencePlant::step(const cvt::RomInputs<double>& u) {
  if (!loaded() || faulted() || !stepper_) return;
  const double c0 = thread_cpu_s();
  const Loaded& l = *cur_;
  // docs/sil.md#reference-plant: command -> saturation -> first-order lag,
  // one update per frame before the frame, as the real-time plant's driven
  // actuator. Without a driven command (no wedging) the driven clamping is
  // the driver's times the static thrust ratio, the mapping's default.
  actuator_N_[0] += (saturate(u.clamp_N, l.clamp_max_N) - actuator_N_[0]) * l.lag;
  if (l.published.variable_ratio) {
    actuator_N_[1] += (saturate(driven_cmd_N_, l.clamp_max_N) - actuator_N_[1]) * l.lag;
  } else {
    actuator_N_[1] = actuator_N_[0] * l.thrust_ratio;
  }
  cvt::mbd::StepInputs in;
  in.clamp1_N = actuator_N_[0];
  in.clamp2_N = actuator_N_[1];
  in.tau_in_Nm = u.tau_in_Nm;
  in.tau_load_Nm = u.tau_load_Nm;
  stepper_->step(in);
  ++frames_;
  if (!hold_radii()) ++lifted_frames_;
  if (stepper_->faulted()) {
    fail(stepper_->outputs().fault, stepper_->fault_message());
  } else if (opt_.inject.kind != StepFault::none && stepper_->t_s() >= opt_.inject.at_s - 1e-12) {
    fail(opt_.inject.kind, at_time(stepper_->t_s(), std::string(cvt::mbd::step_fault_name(opt_.inject.kind)) +
                                                        " injected (test hook)"));
  }
  step_cpu_s_ += thread_cpu_s() - c0;
}

bool ReferencePlant::hold_radii() {
  const cvt::mbd::StepOutputs& r = stepper_->outputs();
  const double now[2] = {r.r1_m, r.r2_m};
  bool both = true;
  for (int j = 0; j < 2; ++j) {
    if (std::isfinite(now[j]) && now[j] > 0) {
      held_radius_m_[j] = now[j];
    } else {
      both = false;
    }
  }
  return both;
}

const cvt::mbd::StepOutputs& ReferencePlant::reference_outputs() const {
  static const cvt::mbd::StepOutputs none{};
  return stepper_ ? stepper_->outputs() : none;
}

cvt::RomOutputs<double> ReferencePlant::outputs() const {
  cvt::RomOutputs<double> o;
  if (!stepper_) return o;
  const cvt::mbd::StepOutputs& r = stepper_->outputs();
  o.omega1_rad_s = r.omega1_rad_s;
  o.omega2_rad_s = r.omega2_rad_s;
  o.speed_ratio = r.speed_ratio;
  // docs/sil.md#reference-outputs: in a frame that ends with no bolt
  // compressed in a wrap (the chain lifted off a slipping pulley) the
  // reference has no running radius there; the bus carries the last one, and
  // the ratio and the slip from it, not a radius of 0. The chain's force and
  // torque on that pulley are 0, as reported.
  o.radius1_m = held_radius_m_[0];
  o.radius2_m = held_radius_m_[1];
  o.geometric_ratio = held_radius_m_[0] > 0 ? held_radius_m_[1] / held_radius_m_[0] : 0.0;
  const double v1_m_s = r.omega1_rad_s * held_radius_m_[0];
  o.slip = std::fabs(v1_m_s) < 1e-3 ? 0.0 : r.slip1_m_s / v1_m_s;  // as the stepper's, on the held radius
  o.clamp_force_N = r.F_ax1_N;
  // The bus carries the torque the driver pulley passes to the chain (the
  // real-time plant's friction torque on its lumps, docs/rom.md#outputs);
  // the reference reports the chain's moment on the pulley, its reaction.
  o.torque_transmitted_Nm = -r.torque_transmitted_Nm;
  o.tau_in_Nm = r.tau_in_Nm;
  o.tau_load_Nm = r.tau_load_Nm;
  o.tension_tight_N = r.tension_tight_N;
  o.tension_slack_N = r.tension_slack_N;
  o.sheave_on_stop = r.sheave1_on_stop;
  return o;
}

double ReferencePlant::driven_axial_N() const { return stepper_ ? stepper_->outputs().F_ax2_N : 0.0; }

cvt::sil::EndStops ReferencePlant::end_stops() const {
  if (!stepper_ || !loaded()) return {};
  const cvt::mbd::StepOutputs& r = stepper_->outputs();
  // docs/mbd.md#clamped-sheaves: a positive opening puts the chain lower in
  // that groove. Driver low or driven high: underdrive; the reverse: overdrive.
  const bool driver_open = r.sheave1_on_stop && r.sheave1_m > 0, driver_closed = r.sheave1_on_stop && r.sheave1_m < 0;
  const bool driven_open = r.sheave2_on_stop && r.sheave2_m > 0, driven_closed = r.sheave2_on_stop && r.sheave2_m < 0;
  return {driver_open || driven_closed, driver_closed || driven_open};
}

const char* ReferencePlant::realtime_refusal() const { return loaded() ? cur_->realtime_refusal.c_str() : ""; }

bool ReferencePlant::keeps_time() {
  if (!loaded()) return false;
  Loaded& l = *cur_;
  if (l.keeps_time >= 0) return l.keeps_time == 1;
  char buf[320];
  if (!l.release) {
    // The start-up failed (reset() keeps its reason): nothing to pace.
    l.realtime_refusal = "the multibody reference did not start: " + fault_message_;
    return false;
  }
  const cvt::mbd::StepperOptions so = stepper_options();
  Stepper probe(l.params, so, *l.release);
  std::vector<double> cpu;
  cpu.reserve(static_cast<std::size_t>(opt_.probe_frames));
  const cvt::mbd::StepInputs in = probe.inputs();
  for (int k = 0; k < opt_.probe_frames && !probe.faulted(); ++k) {
    const double c0 = thread_cpu_s();
    probe.step(in);
    cpu.push_back(thread_cpu_s() - c0);
  }
  if (cpu.empty()) cpu.push_back(0.0);
  std::vector<double> sorted = cpu;
  std::sort(sorted.begin(), sorted.end());
  const double p99 = sorted[static_cast<std::size_t>(0.99 * static_cast<double>(sorted.size() - 1))];
  double sum = 0;
  for (double c : cpu) sum += c;
  const double frame_s = so.frame_s;
  l.keeps_time = !probe.faulted() && p99 <= 0.5 * frame_s ? 1 : 0;
  std::snprintf(buf, sizeof buf,
                "the multibody reference does not keep time on this host: its first %zu frames of %s took %.2f ms of "
                "CPU per %.2f ms frame (p99 %.2f ms, max %.2f ms; real time needs p99 <= half a frame); run it in "
                "lock-step",
                cpu.size(), scene_->name, 1e3 * sum / static_cast<double>(cpu.size()), frame_s * 1e3, p99 * 1e3,
                sorted.back() * 1e3);
  l.realtime_refusal = l.keeps_time == 1 ? "" : buf;
  if (probe.faulted()) l.realtime_refusal = "the multibody reference faulted in its real-time check: " + probe.fault_message();
  return l.keeps_time == 1;
}

}  // namespace cvt::cosim
