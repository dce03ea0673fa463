// The plant against the multibody reference: inputs, cached reference runs,
// error measures (docs/validation.md).
#include "validation.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "progress.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/mbd/model.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvtcli::validation {

void Series::reserve(std::size_t n) {
  for (auto* v : {&t_s, &omega1_rad_s, &omega2_rad_s, &F_ax1_N, &torque_driver_Nm, &slip1_m_s, &wrap_slip_m_s})
    v->reserve(n);
}

Series Series::select(std::size_t n, std::size_t step) const {
  Series o;
  std::vector<double> Series::*const cols[] = {&Series::t_s,          &Series::omega1_rad_s,     &Series::omega2_rad_s,
                                               &Series::F_ax1_N,      &Series::torque_driver_Nm, &Series::slip1_m_s,
                                               &Series::wrap_slip_m_s};
  for (const auto c : cols) {
    const std::vector<double>& from = this->*c;
    std::vector<double>& to = o.*c;
    for (std::size_t i = 0; i < std::min(n, from.size()); i += std::max<std::size_t>(1, step)) to.push_back(from[i]);
  }
  return o;
}

namespace {

// A scene's input profile as the reference's piecewise-linear one (a step
// becomes a 1 ms ramp: the reference integrates it, the plant samples it per
// frame). what: "clamping" or "torque", for the reason a sine is refused.
std::optional<cvt::mbd::TimeProfile> time_profile(const cvt::Profile& p, const char* what, std::string& why_not) {
  cvt::mbd::TimeProfile f;
  switch (p.kind) {
    case cvt::ProfileKind::constant: f.points = {{0.0, p.value}}; break;
    case cvt::ProfileKind::step: f.points = {{p.t0_s, p.value}, {p.t0_s + 1e-3, p.value2}}; break;
    case cvt::ProfileKind::ramp: f.points = {{p.t0_s, p.value}, {p.t1_s, p.value2}}; break;
    case cvt::ProfileKind::table:
      for (int i = 0; i < p.n; ++i) f.points.emplace_back(p.t_s[i], p.v[i]);
      break;
    case cvt::ProfileKind::sine:
      why_not = std::string("a sine ") + what + " profile (the reference takes piecewise-linear profiles)";
      return std::nullopt;
  }
  return f;
}

}  // namespace

const char* sheave_mode_name(cvt::mbd::SheaveMode m) { return m == cvt::mbd::SheaveMode::fixed ? "fixed" : "clamped"; }

CLI::Option* add_sheaves_option(CLI::App* sub, std::string& choice) {
  return sub
      ->add_option("--sheaves", choice,
                   "The reference's sheaves: scene (fixed for a scene whose plant has fixed sheaves, else clamped), "
                   "clamped (pushed by the scene's clamping) or fixed (the seed's pulleys; the axial force is then "
                   "the reference's output)")
      ->capture_default_str()
      ->check(CLI::IsMember({"scene", "clamped", "fixed"}));
}

SheaveChoice sheave_choice(const std::string& name) {
  if (name == "fixed") return SheaveChoice::fixed;
  if (name == "clamped") return SheaveChoice::clamped;
  return SheaveChoice::scene;
}

cvt::mbd::SheaveMode reference_sheaves(const cvt::Scene& s, SheaveChoice c) {
  switch (c) {
    case SheaveChoice::fixed: return cvt::mbd::SheaveMode::fixed;
    case SheaveChoice::clamped: return cvt::mbd::SheaveMode::clamped;
    case SheaveChoice::scene: break;
  }
  // fixed_sheaves acts only with the tension feature (docs/rom.md#tension);
  // without it the plant's axial force is its clamping input.
  const bool fixed = (s.features & cvt::rom_feature::tension) != 0 && s.params.fixed_sheaves;
  return fixed ? cvt::mbd::SheaveMode::fixed : cvt::mbd::SheaveMode::clamped;
}

double whole_wrap_slip(double lo, double hi) {
  if (!(lo <= hi)) return std::nan("");  // no part in the wrap (NaN)
  if (lo > 0.0) return lo;
  if (hi < 0.0) return hi;
  return 0.0;
}

std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice choice, std::string& why_not) {
  const cvt::mbd::SheaveMode sheaves = reference_sheaves(s, choice);
  const cvt::RomParams& rp = s.params;
  const cvt::RomInitial& in = s.initial;
  if (rp.hold_driver_speed || rp.hold_driven_speed) {
    why_not = "held pulleys (the oscillator scenes; the reference is a drive train)";
    return std::nullopt;
  }
  if (in.x1_m != 0.0 || in.xd1_m_s != 0.0 || in.x2_m != 0.0 || in.xd2_m_s != 0.0 || in.radius_offset_m != 0.0) {
    why_not = "initial lump or radial states (the reference's chain starts settled on its pitch line)";
    return std::nullopt;
  }
  const bool at_rest = in.omega1_rad_s == 0.0 && in.omega2_rad_s == 0.0;
  if (!at_rest && !(in.omega1_rad_s > 0.0 && in.omega2_rad_s > 0.0)) {
    why_not = "a start with a pulley at rest or turning backwards (the reference starts from rest or with both "
              "pulleys running forward)";
    return std::nullopt;
  }
  // The chain and its pulley radii stay the seed's (Table 1): the plant's
  // r1, r2 and lump parameters are effective values fitted to this chain
  // (`cvtplant calibrate`), not inputs of the reference.
  cvt::mbd::MbdParams p = cvt::mbd::seed_case(1);
  p.friction = rp.friction;
  p.J1_kgm2 = rp.J1_kgm2;
  p.J2_kgm2 = rp.J2_kgm2;
  p.beta0_rad = rp.beta0_rad;
  auto tau_in = time_profile(s.tau_in, "torque", why_not);
  if (!tau_in) return std::nullopt;
  auto tau_load = time_profile(s.tau_load, "torque", why_not);
  if (!tau_load) return std::nullopt;
  p.tau_in_Nm = *tau_in;
  p.tau_load_Nm = *tau_load;
  if (s.features & cvt::rom_feature::road_load) {
    // docs/rom.md#road-load, the same law (cvt::road_load_torque).
    p.road.T0_Nm = rp.road_T0_Nm;
    p.road.cv_Nms_rad = rp.road_cv_Nms_rad;
    p.road.ca_Nms2_rad2 = rp.road_ca_Nms2_rad2;
    p.road.w_eps_rad_s = rp.road_w_eps_rad_s;
  }
  if (!at_rest) {
    // docs/mbd.md#start-at-speed
    p.start.active = true;
    p.start.omega1_rad_s = in.omega1_rad_s;
    p.start.omega2_rad_s = in.omega2_rad_s;
  }
  p.sheaves = sheaves;
  // Fixed sheaves: the seed's pulleys, the axial force is the reference's
  // output and the scene's clamping is not an input.
  if (sheaves == cvt::mbd::SheaveMode::fixed) return p;
  auto clamp = time_profile(s.clamp, "clamping", why_not);
  if (!clamp) return std::nullopt;
  for (const auto& pt : clamp->points)
    if (!(pt.second >= 100.0)) {
      why_not = "a clamping force below 100 N (the reference's clamped sheaves need a seated chain)";
      return std::nullopt;
    }
  p.clamp1_N = *clamp;
  // The wedging plant holds the driven clamping constant; without wedging the
  // plant has no driven clamping and the reference's default (the static
  // thrust ratio) keeps its ratio.
  if (s.features & cvt::rom_feature::wedging) p.clamp2_N.points = {{0.0, rp.driven_clamp_N}};
  return p;
}

std::string reference_key(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r) {
  std::ostringstream k;
  k.precision(17);
  // The cache's format (its CSV columns) is part of the key too.
  k << "cvtplant multibody reference v" << cvt::mbd::kReferenceVersion << ", cache format 3\n";
  k << "beta0 " << p.beta0_rad << " C " << p.center_distance_m << " m " << p.link_mass_kg << " J " << p.J1_kgm2 << ' '
    << p.J2_kgm2 << " L " << p.link_length_m << " Kb " << p.bolt_stiffness_N_m << " lb " << p.bolt_length_m << " k "
    << p.joint_stiffness_N_m << " p " << p.joint_damping_Ns_m << " r " << p.r1_m << ' ' << p.r2_m << "\n";
  k << "links " << p.links << " I " << p.link_inertia() << " deformation " << p.sheave_deformation << "\n";
  const auto& f = p.friction;
  k << "friction law " << static_cast<int>(f.law) << " sign " << static_cast<int>(f.sign) << " mu0 " << f.mu0 << " a "
    << f.a << " b " << f.b_m_s << " sigma " << f.sigma << " kappa " << f.kappa_s_m << " chi " << f.chi_s_m
    << " lambda " << f.lambda_s_m << "\n";
  const auto profile = [&k](const char* name, const cvt::mbd::TimeProfile& f) {
    k << ' ' << name;
    for (const auto& pt : f.points) k << ' ' << pt.first << ':' << pt.second;
  };
  k << "tau";
  profile("in", p.tau_in_Nm);
  profile("load", p.tau_load_Nm);
  k << " road " << p.road.T0_Nm << ' ' << p.road.cv_Nms_rad << ' ' << p.road.ca_Nms2_rad2 << ' '
    << p.road.w_eps_rad_s << " hold " << p.hold1.active << ' ' << p.hold1.omega_rad_s << ' ' << p.hold2.active << ' '
    << p.hold2.omega_rad_s << "\n";
  k << "sheaves " << sheave_mode_name(p.sheaves);
  profile("clamp1", p.clamp1_N);
  profile("clamp2", p.clamp2_N);
  k << " ms " << p.sheave_mass_kg << " cs " << p.sheave_damping_Ns_m << " stop " << p.sheave_stop_m << ' '
    << p.sheave_stop_N_m << "\n";
  k << "settle " << p.settle_s << ' ' << p.settle_drag_Ns_m << " start " << p.start.active << ' '
    << p.start.omega1_rad_s << ' ' << p.start.omega2_rad_s << ' ' << p.start.spinup_s << ' ' << p.start.hold_s << "\n";
  k << "method " << static_cast<int>(r.method) << " t_end " << r.t_end_s << " rtol " << r.rtol << " dt " << r.dt_s
    << " sample " << r.sample_s << " ledger " << r.ledger_tol << " settle_rtol " << r.settle_rtol << "\n";
  return k.str();
}

std::string key_hash(const std::string& key) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : key) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The cache's CSV: t, omega1, omega2, F_ax1, driver torque, driver slip,
// the whole driver wrap's slip, sheave openings.
bool read_series(const std::string& path, ReferenceRun& out) {
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) return false;
  char line[512];
  bool ok = std::fgets(line, sizeof line, f) != nullptr;  // header
  double v[9];
  Series& s = out.series;
  while (ok && std::fscanf(f, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                           &v[7], &v[8]) == 9) {
    s.t_s.push_back(v[0]);
    s.omega1_rad_s.push_back(v[1]);
    s.omega2_rad_s.push_back(v[2]);
    s.F_ax1_N.push_back(v[3]);
    s.torque_driver_Nm.push_back(v[4]);
    s.slip1_m_s.push_back(v[5]);
    s.wrap_slip_m_s.push_back(v[6]);
    out.sheave1_m.push_back(v[7]);
    out.sheave2_m.push_back(v[8]);
  }
  std::fclose(f);
  return ok && s.size() > 0;
}

void write_series(const std::string& path, const ReferenceRun& r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw UsageError{"cannot write " + path};
  const Series& s = r.series;
  std::fprintf(f, "t_s,omega1_rad_s,omega2_rad_s,F_ax1_N,torque_driver_Nm,slip1_m_s,wrap_slip1_m_s,sheave1_m,sheave2_m\n");
  for (std::size_t i = 0; i < s.size(); ++i)
    std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t_s[i], s.omega1_rad_s[i],
                 s.omega2_rad_s[i], s.F_ax1_N[i], s.torque_driver_Nm[i], s.slip1_m_s[i], s.wrap_slip_m_s[i],
                 r.sheave1_m[i], r.sheave2_m[i]);
  if (std::fclose(f) != 0) throw UsageError{"cannot write " + path};
}

}  // namespace

ReferenceRun reference_run(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r, const std::string& cache_dir,
                           const std::string& label) {
  const std::string key = reference_key(p, r);
  const std::string base = cache_dir + "/" + key_hash(key);
  ReferenceRun out;
  // The key file is written last: a run cut short leaves no key, so no hit.
  if (read_all(base + ".key") == key && read_series(base + ".csv", out)) {
    out.from_cache = true;
    out.failure = read_all(base + ".failure");
    return out;
  }
  out = ReferenceRun{};
  const std::size_t n = static_cast<std::size_t>(r.t_end_s / r.sample_s) + 2;
  out.series.reserve(n);
  out.sheave1_m.reserve(n);
  out.sheave2_m.reserve(n);
  auto on_sample = [&](const cvt::mbd::Sample& s, const cvt::mbd::ChainModel&, const double*) {
    out.series.t_s.push_back(s.t_s);
    out.series.omega1_rad_s.push_back(s.omega_rad_s[0]);
    out.series.omega2_rad_s.push_back(s.omega_rad_s[1]);
    out.series.F_ax1_N.push_back(s.F_ax_N[0]);
    // The chain's moment on the driver opposes the input: the torque the
    // chain takes off the driver is its negative (docs/mbd.md#equations-of-motion).
    out.series.torque_driver_Nm.push_back(-s.chain_torque_Nm[0]);
    out.series.slip1_m_s.push_back(s.slip_m_s[0]);
    out.series.wrap_slip_m_s.push_back(whole_wrap_slip(s.slip_min_m_s[0], s.slip_max_m_s[0]));
    out.sheave1_m.push_back(s.sheave_opening_m[0]);
    out.sheave2_m.push_back(s.sheave_opening_m[1]);
  };
  Progress progress(label, r.t_end_s);
  cvt::mbd::RunStats st;
  try {
    st = cvt::mbd::simulate(p, r, on_sample, [&](double t) { progress.update(t); });
  } catch (const cvt::mbd::RunFailure& e) {
    // The samples before the failure are still a valid reference: kept, and
    // the comparison ends there (comparable_samples).
    char buf[96];
    std::snprintf(buf, sizeof buf, "the reference stopped at t = %.6g s after %lld steps: ", e.t_s, e.stats.steps);
    out.failure = buf + e.quantity;
    st = e.stats;
  }
  progress.finish();
  if (out.series.size() < 2) throw RunError{out.failure.empty() ? "the reference made no samples" : out.failure};
  out.cpu_s = st.cpu_s;
  out.wall_s = st.wall_s;
  out.steps = st.steps;
  out.ledger_residual_rel = st.ledger_residual_max_rel;
  write_series(base + ".csv", out);
  if (!out.failure.empty()) {
    std::ofstream f(base + ".failure", std::ios::binary);
    f << out.failure;
    if (!f) throw UsageError{"cannot write " + base + ".failure"};
  } else {
    std::remove((base + ".failure").c_str());
  }
  std::ofstream k(base + ".key", std::ios::binary);
  k << key;
  if (!k) throw UsageError{"cannot write " + base + ".key"};
  return out;
}

double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m) {
  const std::vector<double>& v = sheave == 0 ? r.sheave1_m : r.sheave2_m;
  for (std::size_t i = 0; i < v.size() && i < r.series.size(); ++i)
    if (std::fabs(v[i]) >= sheave_stop_m - 1e-4) return r.series.t_s[i];
  return -1.0;
}

Series plant_run(const cvt::Scene& s, double sample_s) {
  const long every = std::max(1L, std::lround(sample_s / s.frame_s));
  Series out;
  out.reserve(static_cast<std::size_t>(s.t_end_s / sample_s) + 2);
  cvt::RomFault fault = cvt::RomFault::none;
  double fault_t = 0;
  // The plant in double through the scene dispatch (docs/architecture.md#scene-dispatch).
  auto holder = std::make_unique<cvt::SceneSimulator<cvt::AllRomPlants<double>>>();
  const cvt::SceneIssue issue = holder->load(s, cvt::sim_config_of(s));
  if (!issue.ok) throw UsageError{std::string(issue.field) + ": " + issue.message};
  auto on_frame = [&](long i, double t, const cvt::IRomSimulator<double>& v) {
    if (i % every != 0) return true;
    const cvt::RomOutputs<double> o = v.outputs();
    out.t_s.push_back(t);
    out.omega1_rad_s.push_back(o.omega1_rad_s);
    out.omega2_rad_s.push_back(o.omega2_rad_s);
    out.F_ax1_N.push_back(o.clamp_force_N);
    out.torque_driver_Nm.push_back(o.torque_transmitted_Nm);
    // v_rel is the lump's speed over the sheave's; the driver's slip is the
    // sheave's over the chain's: the mean over the two lumps, and the slip
    // both lumps share (the whole wrap's).
    out.slip1_m_s.push_back(-0.5 * (o.v_rel1_m_s + o.v_rel2_m_s));
    out.wrap_slip_m_s.push_back(
        whole_wrap_slip(std::min(-o.v_rel1_m_s, -o.v_rel2_m_s), std::max(-o.v_rel1_m_s, -o.v_rel2_m_s)));
    fault_t = t;
    return true;
  };
  fault = cvt::run_frames(holder->sim(), s, s.frame_s, on_frame);
  if (fault != cvt::RomFault::none) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "the plant faulted near t = %.6g s: ", fault_t);
    throw RunError{buf + std::string(cvt::rom_fault_name(fault))};
  }
  return out;
}

double rel_rms(const std::vector<double>& plant, const std::vector<double>& reference) {
  // Samples where either value is missing (NaN: the reference's wrap slip
  // with no bolt in the wrap) are left out.
  double d2 = 0, r2 = 0;
  std::size_t used = 0;
  const std::size_t n = std::min(plant.size(), reference.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(plant[i]) || !std::isfinite(reference[i])) continue;
    d2 += (plant[i] - reference[i]) * (plant[i] - reference[i]);
    r2 += reference[i] * reference[i];
    ++used;
  }
  return r2 > 0 ? std::sqrt(d2 / r2) : std::sqrt(d2 / static_cast<double>(std::max<std::size_t>(1, used)));
}

namespace {

double mean_from(const std::vector<double>& v, std::size_t from) {
  double s = 0;
  std::size_t n = 0;
  for (std::size_t i = from; i < v.size(); ++i)
    if (std::isfinite(v[i])) {
      s += v[i];
      ++n;
    }
  return n > 0 ? s / static_cast<double>(n) : std::nan("");
}

double peak_to_peak_from(const std::vector<double>& v, std::size_t from) {
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = from; i < v.size(); ++i)
    if (std::isfinite(v[i])) {
      lo = std::min(lo, v[i]);
      hi = std::max(hi, v[i]);
    }
  return hi >= lo ? hi - lo : std::nan("");
}

// The first sample at which the whole driver wrap slides faster than threshold.
double first_gross_slip(const Series& s, double threshold) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (std::fabs(s.wrap_slip_m_s[i]) > threshold) return s.t_s[i];
  return -1.0;
}

// omega1 / omega2 where both models' driven pulley turns (|omega2| >= 1 rad/s
// in each): the ratio is not defined through omega2 = 0, and the reference's
// driven pulley first turns backwards (docs/mbd.md#start-up).
void ratios(const Series& p, const Series& r, std::vector<double>& rp, std::vector<double>& rr) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::fabs(p.omega2_rad_s[i]) >= 1.0 && std::fabs(r.omega2_rad_s[i]) >= 1.0) {
      rp.push_back(p.omega1_rad_s[i] / p.omega2_rad_s[i]);
      rr.push_back(r.omega1_rad_s[i] / r.omega2_rad_s[i]);
    }
}

}  // namespace


Comparison compare(const Series& plant_all, const Series& ref_all, std::size_t n) {
  if (plant_all.size() < n || ref_all.size() < n || n < 2)
    throw RunError{"plant and reference have too few common samples to compare"};
  const Series plant = plant_all.select(n), ref = ref_all.select(n);
  for (std::size_t i = 0; i < plant.size(); ++i)
    if (std::fabs(plant.t_s[i] - ref.t_s[i]) > 1e-9) throw RunError{"plant and reference have different sample times"};
  Comparison c;
  const double t_end = ref.t_s.back();
  c.compared_s = t_end;
  c.window_s = std::min(1.0, 0.5 * t_end);
  std::size_t from = 0;
  while (from < ref.size() && ref.t_s[from] < t_end - c.window_s - 1e-9) ++from;
  auto row = [&](const char* q, const char* unit, const std::vector<double>& p, const std::vector<double>& r,
                 std::size_t ss_from) {
    ErrorRow e;
    e.quantity = q;
    e.unit = unit;
    e.rel_rms = rel_rms(p, r);
    e.plant_ss = mean_from(p, ss_from);
    e.reference_ss = mean_from(r, ss_from);
    e.ss_rel = e.reference_ss != 0 ? (e.plant_ss - e.reference_ss) / std::fabs(e.reference_ss) : 0.0;
    c.rows.push_back(e);
  };
  row("omega1", "rad/s", plant.omega1_rad_s, ref.omega1_rad_s, from);
  row("omega2", "rad/s", plant.omega2_rad_s, ref.omega2_rad_s, from);
  std::vector<double> rp, rr;
  ratios(plant, ref, rp, rr);
  // The ratio's window: the same number of samples at the end of the kept ones.
  const std::size_t keep = ref.size() - from;
  row("ratio omega1/omega2", "-", rp, rr, rp.size() > keep ? rp.size() - keep : 0);
  row("F_ax1 (mean)", "N", plant.F_ax1_N, ref.F_ax1_N, from);
  row("torque on the driver", "N m", plant.torque_driver_Nm, ref.torque_driver_Nm, from);
  row("driver slip", "m/s", plant.slip1_m_s, ref.slip1_m_s, from);
  c.ripple_plant_N = peak_to_peak_from(plant.F_ax1_N, from);
  c.ripple_reference_N = peak_to_peak_from(ref.F_ax1_N, from);
  c.gross_slip_plant_s = first_gross_slip(plant, kGrossSlip_m_s);
  c.gross_slip_reference_s = first_gross_slip(ref, kGrossSlip_m_s);
  return c;
}

}  // namespace cvtcli::validation
