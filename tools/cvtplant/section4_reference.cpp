// The multibody reference's section-4 runs, cached (docs/seed-section4.md#runs).
#include "section4_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "progress.hpp"
#include "cvtplant/validation/cache.hpp"
#include <ctime>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cvtplant/mbd/model.hpp"
#include "cvtplant/mbd/stepper.hpp"

namespace cvtcli::section4ref {

namespace {

// The cache's format: its CSV columns and the start's record. Part of the key.
constexpr int kCacheFormat = 1;

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void write_all(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  if (!f) throw UsageError{"cannot write " + path};
}

std::vector<std::vector<double>*> columns(Run& r) {
  return {&r.t_s,        &r.omega1_rad_s, &r.omega2_rad_s, &r.F_ax1_N,   &r.F_ax2_N, &r.torque1_Nm,
          &r.torque2_Nm, &r.slip1_m_s,    &r.slip2_m_s,    &r.wrap1,     &r.wrap2};
}
const char* kHeader = "t_s,omega1_rad_s,omega2_rad_s,F_ax1_N,F_ax2_N,torque1_Nm,torque2_Nm,slip1_m_s,slip2_m_s,wrap1,wrap2";

void write_run(const std::string& base, Run& r) {
  std::FILE* f = std::fopen((base + ".csv").c_str(), "w");
  if (f == nullptr) throw UsageError{"cannot write " + base + ".csv"};
  std::fprintf(f, "%s\n", kHeader);
  const auto cols = columns(r);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t c = 0; c < cols.size(); ++c) std::fprintf(f, "%.17g%c", (*cols[c])[i], c + 1 < cols.size() ? ',' : '\n');
  std::fprintf(f, "# passages\n");
  for (double t : r.passages1_s) std::fprintf(f, "1,%.17g\n", t);
  for (double t : r.passages2_s) std::fprintf(f, "2,%.17g\n", t);
  if (std::fclose(f) != 0) throw UsageError{"cannot write " + base + ".csv"};
  std::ostringstream m;
  m.precision(17);
  m << r.tau_in_Nm << ' ' << r.holding_torque_Nm << ' ' << r.omega2_release_rad_s << ' ' << r.hold_omega2_range_rel
    << ' ' << r.hold_torque_change_rel << ' ' << r.cpu_s << ' ' << r.ledger_residual_rel << ' ' << r.steps << '\n'
    << r.failure;
  write_all(base + ".meta", m.str());
}

bool read_run(const std::string& base, Run& r) {
  std::FILE* f = std::fopen((base + ".csv").c_str(), "r");
  if (f == nullptr) return false;
  char line[1024];
  bool ok = std::fgets(line, sizeof line, f) != nullptr;
  const auto cols = columns(r);
  while (ok && std::fgets(line, sizeof line, f) != nullptr) {
    if (line[0] == '#') break;
    std::stringstream ss(line);
    std::string cell;
    std::size_t c = 0;
    while (c < cols.size() && std::getline(ss, cell, ',')) cols[c++]->push_back(std::strtod(cell.c_str(), nullptr));
    ok = c == cols.size();
  }
  while (ok && std::fgets(line, sizeof line, f) != nullptr) {
    int which = 0;
    double t = 0;
    if (std::sscanf(line, "%d,%lf", &which, &t) != 2) {
      ok = false;
      break;
    }
    (which == 1 ? r.passages1_s : r.passages2_s).push_back(t);
  }
  std::fclose(f);
  std::stringstream m(read_all(base + ".meta"));
  ok = ok && static_cast<bool>(m >> r.tau_in_Nm >> r.holding_torque_Nm >> r.omega2_release_rad_s >>
                               r.hold_omega2_range_rel >> r.hold_torque_change_rel >> r.cpu_s >> r.ledger_residual_rel >>
                               r.steps);
  if (ok) {
    std::string rest;
    std::getline(m, rest);
    std::getline(m, r.failure, '\0');
  }
  return ok && r.size() > 0;
}

cvt::mbd::RunOptions run_options(const Scenario& s, const Numerics& n) {
  cvt::mbd::RunOptions o;
  o.method = n.method;
  o.rtol = n.rtol;
  o.dt_s = n.dt_s;
  o.t_end_s = n.t_end_s > 0 ? std::min(n.t_end_s, s.t_end_s) : s.t_end_s;
  o.sample_s = 1e-3;
  o.max_steps = 1000000000;
  return o;
}

// The hold of a steady point alone (t_end one sample): its holding torque and
// steadiness. Cached by the start's inputs (the hold runs at the settle's
// tolerance whatever the numerics after the release).
void hold_of(const Scenario& s, const std::string& cache_dir, const std::string& label, Run& r) {
  const cvt::mbd::MbdParams p = scenario_params(s, 0.0);
  cvt::mbd::RunOptions o;
  o.t_end_s = 1e-3;
  const std::string key = "section4 hold, cache format " + std::to_string(kCacheFormat) + "\n" +
                          cvt::validation::reference_key(p, o);
  const std::string base = cache_dir.empty() ? "" : cache_dir + "/" + cvt::validation::key_hash(key);
  if (!base.empty() && read_all(base + ".key") == key) {
    std::stringstream m(read_all(base + ".hold"));
    if (m >> r.holding_torque_Nm >> r.omega2_release_rad_s >> r.hold_omega2_range_rel >> r.hold_torque_change_rel)
      return;
  }
  Progress progress(label + ": start at speed", 1e-3);
  cvt::mbd::RunStats st;
  try {
    st = cvt::mbd::simulate(p, o, {}, [&](double t) { progress.update(t); });
  } catch (const cvt::mbd::RunFailure& e) {
    throw RunError{label + ": the start at speed failed: " + std::string(e.what())};
  }
  progress.finish();
  const cvt::mbd::HoldSteadiness h = cvt::mbd::hold_steadiness(st.hold_samples, 0.2);
  r.holding_torque_Nm = h.holding_torque_mean_Nm;
  r.omega2_release_rad_s = st.hold_samples.back().omega_rad_s[1];
  r.hold_omega2_range_rel = h.omega2_range_rel;
  r.hold_torque_change_rel = h.holding_torque_change_rel;
  if (base.empty()) return;
  std::ostringstream m;
  m.precision(17);
  m << r.holding_torque_Nm << ' ' << r.omega2_release_rad_s << ' ' << r.hold_omega2_range_rel << ' '
    << r.hold_torque_change_rel << '\n';
  write_all(base + ".hold", m.str());
  write_all(base + ".key", key);
}

}  // namespace

std::string Numerics::label() const {
  char buf[64];
  if (method == cvt::mbd::Method::rk4)
    std::snprintf(buf, sizeof buf, "RK4 dt %g s", dt_s);
  else
    std::snprintf(buf, sizeof buf, "BDF rtol %g", rtol);
  return buf;
}

cvt::mbd::RoadLoad steady_road_load(const Scenario& s) {
  cvt::mbd::RoadLoad r;
  const double w2 = s.omega2_rad_s;
  r.ca_Nms2_rad2 = 3.0 * s.load_Nm / (w2 * w2);
  return r;
}

double steady_constant_load_Nm(const Scenario& s) { return -2.0 * s.load_Nm; }

cvt::mbd::MbdParams scenario_params(const Scenario& s, double tau_in_Nm) {
  cvt::mbd::MbdParams p = cvt::mbd::seed_case(s.friction_case);
  if (!s.steady) return p;  // the seed's 100 / 50 N m from rest
  p.start.active = true;
  p.start.omega1_rad_s = s.omega1_rad_s;
  p.start.omega2_rad_s = s.omega2_rad_s;
  p.start.hold_s = s.hold_s;
  p.tau_load_Nm = cvt::mbd::TimeProfile::constant(steady_constant_load_Nm(s));
  p.road = steady_road_load(s);
  p.tau_in_Nm = cvt::mbd::TimeProfile::constant(tau_in_Nm);
  return p;
}

std::string format_speed(double w) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", w);
  return buf;
}

const std::vector<std::string>& signal_names() {
  static const std::vector<std::string> names = {"F_ax1_N", "F_ax2_N", "omega1_rad_s", "omega2_rad_s"};
  return names;
}

std::string signal_unit(const std::string& name) { return name.rfind("F_", 0) == 0 ? "N" : "rad/s"; }

const std::vector<double>& Run::signal(const std::string& name) const {
  if (name == "F_ax1_N") return F_ax1_N;
  if (name == "F_ax2_N") return F_ax2_N;
  if (name == "omega1_rad_s") return omega1_rad_s;
  if (name == "omega2_rad_s") return omega2_rad_s;
  throw UsageError{"unknown signal '" + name + "' (F_ax1_N, F_ax2_N, omega1_rad_s, omega2_rad_s)"};
}

Run reference_run(const Scenario& s, const Numerics& n, const std::string& cache_dir, const std::string& label) {
  Run r;
  if (s.steady) {
    hold_of(s, cache_dir, label, r);
    r.tau_in_Nm = r.holding_torque_Nm;
  } else {
    r.tau_in_Nm = cvt::mbd::seed_case(s.friction_case).tau_in_Nm.at(0.0);
  }
  const cvt::mbd::MbdParams p = scenario_params(s, r.tau_in_Nm);
  const cvt::mbd::RunOptions o = run_options(s, n);
  const std::string key = "section4 run, cache format " + std::to_string(kCacheFormat) + "\n" +
                          cvt::validation::reference_key(p, o);
  const std::string base = cache_dir.empty() ? "" : cache_dir + "/" + cvt::validation::key_hash(key);
  if (!base.empty() && read_all(base + ".key") == key) {
    Run c;
    if (read_run(base, c)) {
      c.from_cache = true;
      c.cache_file = base + ".csv";
      return c;
    }
  }
  const std::size_t reserve = static_cast<std::size_t>(o.t_end_s / o.sample_s) + 2;
  for (auto* c : columns(r)) c->reserve(reserve);
  // Previous front-pin positions, for the passages through the wraps' middles.
  std::vector<double> px, py;
  double pt = 0;
  const double C = cvt::mbd::seed_case(s.friction_case).center_distance_m;
  auto on_sample = [&](const cvt::mbd::Sample& sm, const cvt::mbd::ChainModel& m, const double* y) {
    r.t_s.push_back(sm.t_s);
    r.omega1_rad_s.push_back(sm.omega_rad_s[0]);
    r.omega2_rad_s.push_back(sm.omega_rad_s[1]);
    r.F_ax1_N.push_back(sm.F_ax_N[0]);
    r.F_ax2_N.push_back(sm.F_ax_N[1]);
    // The torque the chain takes off the driver is its moment's negative.
    r.torque1_Nm.push_back(-sm.chain_torque_Nm[0]);
    r.torque2_Nm.push_back(sm.chain_torque_Nm[1]);
    r.slip1_m_s.push_back(sm.slip_m_s[0]);
    r.slip2_m_s.push_back(sm.slip_m_s[1]);
    r.wrap1.push_back(sm.wrap_links[0]);
    r.wrap2.push_back(sm.wrap_links[1]);
    const std::vector<cvt::mbd::LinkState> links = m.link_states(y);
    if (!px.empty()) {
      for (std::size_t i = 0; i < links.size(); ++i) {
        const double x0 = px[i], y0 = py[i], x1 = links[i].front_x_m, y1 = links[i].front_y_m;
        // Driver (centre at the origin, running counter-clockwise): down
        // through y = 0 on its left; driven (centre at (C, 0)): up through
        // y = 0 on its right.
        const double f = y0 != y1 ? y0 / (y0 - y1) : 0.0;
        const double tc = pt + f * (sm.t_s - pt), xc = x0 + f * (x1 - x0);
        if (y0 > 0 && y1 <= 0 && xc < 0) r.passages1_s.push_back(tc);
        if (y0 < 0 && y1 >= 0 && xc > C) r.passages2_s.push_back(tc);
      }
    }
    px.resize(links.size());
    py.resize(links.size());
    for (std::size_t i = 0; i < links.size(); ++i) {
      px[i] = links[i].front_x_m;
      py[i] = links[i].front_y_m;
    }
    pt = sm.t_s;
  };
  Progress progress(label + " (" + n.label() + ")", o.t_end_s);
  cvt::mbd::RunStats st;
  try {
    st = cvt::mbd::simulate(p, o, on_sample, [&](double t) { progress.update(t); });
  } catch (const cvt::mbd::RunFailure& e) {
    // The samples before the failure stay; the analysis says where the run ended.
    char buf[96];
    std::snprintf(buf, sizeof buf, "the reference stopped at t = %.6g s: ", e.t_s);
    r.failure = buf + e.quantity;
    st = e.stats;
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  progress.finish();
  std::sort(r.passages1_s.begin(), r.passages1_s.end());
  std::sort(r.passages2_s.begin(), r.passages2_s.end());
  r.cpu_s = st.cpu_s;
  r.steps = st.steps;
  r.ledger_residual_rel = st.ledger_residual_max_rel;
  if (base.empty() || r.size() < 2) return r;
  write_run(base, r);
  write_all(base + ".key", key);  // last: a run cut short leaves no key, so no hit
  r.cache_file = base + ".csv";
  return r;
}

namespace {

// The reference as a restartable flow: a Stepper held at its release inputs.
class StepperFlow : public cvt::analysis::RestartableFlow {
 public:
  explicit StepperFlow(cvt::mbd::Stepper& s) : s_(s), in_(s.inputs()) {}
  double t_s() const override { return s_.t_s(); }
  std::vector<double> state() const override { return {s_.state(), s_.state() + s_.model().size()}; }
  void restart(double t, const std::vector<double>& y) override {
    cvt::mbd::Stepper::Snapshot snap = s_.save();
    snap.t_s = t;
    snap.y = y;
    s_.restore(snap);
  }
  void advance(double dt) override {
    const int frames = static_cast<int>(std::lround(dt / 1e-3));
    s_.step(in_, frames);
    if (s_.faulted()) throw std::runtime_error(s_.fault_message());
  }

 private:
  cvt::mbd::Stepper& s_;
  cvt::mbd::StepInputs in_;
};

}  // namespace

ExponentRun equation_exponent(const Scenario& s, double tau_in_Nm, double t_start_s, double rtol,
                              const cvt::analysis::TwoTrajectoryOptions& o, const std::string& cache_dir,
                              const std::string& label) {
  ExponentRun r;
  r.t_start_s = t_start_s;
  r.rtol = rtol;
  r.options = o;
  const cvt::mbd::MbdParams p = scenario_params(s, tau_in_Nm);
  cvt::mbd::RunOptions ro;
  ro.rtol = rtol;
  ro.t_end_s = t_start_s + (o.warmup + o.intervals) * o.t_renorm_s;
  std::ostringstream k;
  k.precision(17);
  k << "section4 two trajectories, cache format " << kCacheFormat << ": start " << t_start_s << " renorm "
    << o.t_renorm_s << " warmup " << o.warmup << " intervals " << o.intervals << " batches " << o.batches << " delta0 "
    << o.delta0 << " seed " << o.seed << "\n"
    << cvt::validation::reference_key(p, ro);
  const std::string key = k.str();
  const std::string base = cache_dir.empty() ? "" : cache_dir + "/" + cvt::validation::key_hash(key);
  if (!base.empty() && read_all(base + ".key") == key) {
    try {
      const nlohmann::json j = nlohmann::json::parse(read_all(base + ".exponent"));
      r.result.lambda = j.at("lambda");
      r.result.ci95 = j.at("ci95");
      r.result.max_stretch = j.at("max_stretch");
      r.result.intervals = j.at("intervals");
      r.result.batch_lambda = j.at("batch_lambda").get<std::vector<double>>();
      r.result.t_s = j.at("t_s").get<std::vector<double>>();
      r.result.cumulative = j.at("cumulative").get<std::vector<double>>();
      r.cpu_s = j.at("cpu_s");
      r.failure = j.at("failure");
      r.from_cache = true;
      return r;
    } catch (const nlohmann::json::exception&) {
      // an unreadable record: computed again
    }
  }
  const std::clock_t cpu0 = std::clock();
  cvt::mbd::StepperOptions so;
  so.rtol = rtol;
  // The bar counts the way to the start and each interval's two runs, in simulated seconds.
  const double pair_s = 2.0 * o.t_renorm_s;
  Progress progress(label + ": two trajectories", t_start_s + (o.warmup + o.intervals) * pair_s);
  try {
    cvt::mbd::Stepper st(p, so);
    if (st.faulted()) throw std::runtime_error(st.fault_message());
    // To the start, a second at a time for the progress display.
    while (st.t_s() < t_start_s - 1e-9) {
      const int frames = static_cast<int>(std::lround(std::min(1.0, t_start_s - st.t_s()) / 1e-3));
      st.step(st.inputs(), frames);
      if (st.faulted()) throw std::runtime_error(st.fault_message());
      progress.update(st.t_s());
    }
    // The state: links (x, y, theta and their rates) and pulley speeds, each
    // over its tolerance scale (docs/mbd.md#tolerances).
    const cvt::mbd::ChainModel& m = st.model();
    std::vector<double> w(static_cast<std::size_t>(m.size()), 0.0);
    for (int i = 0; i < 6 * m.links(); ++i) w[static_cast<std::size_t>(i)] = 1.0 / m.tolerance_scale(i);
    for (int j = 0; j < 2; ++j) w[static_cast<std::size_t>(m.pulley_speed(j))] = 1.0 / m.tolerance_scale(m.pulley_speed(j));
    StepperFlow flow(st);
    cvt::analysis::TwoTrajectoryOptions with_progress = o;
    with_progress.progress = [&](int done, int) { progress.update(t_start_s + done * pair_s); };
    r.result = cvt::analysis::largest_exponent_two_trajectories(flow, w, with_progress);
  } catch (const std::runtime_error& e) {
    r.failure = e.what();
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  progress.finish();
  r.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  if (base.empty()) return r;
  const nlohmann::json j{{"lambda", r.result.lambda},       {"ci95", r.result.ci95},
                         {"max_stretch", r.result.max_stretch}, {"intervals", r.result.intervals},
                         {"batch_lambda", r.result.batch_lambda}, {"t_s", r.result.t_s},
                         {"cumulative", r.result.cumulative},   {"cpu_s", r.cpu_s},
                         {"failure", r.failure}};
  write_all(base + ".exponent", j.dump());
  write_all(base + ".key", key);
  return r;
}

}  // namespace cvtcli::section4ref
