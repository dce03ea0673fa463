// Reference runs cached on disk by their inputs (docs/validation.md#cache).
#include "cvtplant/validation/cache.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <type_traits>

#include "cvtplant/files/paths.hpp"
#include "cvtplant/files/replace.hpp"
#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

namespace {

// The CSV's format: raised when its columns change (the key carries it).
constexpr int kCacheFormat = 6;

// One line per field: "group.name value"; doubles to 17 digits (every bit).
struct KeyWriter {
  std::ostringstream& k;

  void name(const cvt::ParamField& f) {
    if (f.group[0] != '\0') k << f.group << '.';
    k << f.name << ' ';
  }
  template <class X>
  void operator()(const cvt::ParamField& f, const X& x) {
    if (f.cap) return;
    name(f);
    if constexpr (std::is_enum_v<X>) {
      k << cvt::value_name(value_names(x), x);
    } else if constexpr (std::is_same_v<X, cvt::mbd::TimeProfile>) {
      k << x.points.size();
      for (const auto& pt : x.points) k << ' ' << pt.first << ':' << pt.second;
    } else {
      static_assert(std::is_arithmetic_v<X>, "a field the key cannot write");
      k << x;
    }
    k << '\n';
  }
};

// The whole of a file; `found` false when it cannot be opened.
std::string read_all(const std::string& path, bool& found) {
  std::ifstream f(path, std::ios::binary);
  found = static_cast<bool>(f);
  if (!found) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The entry under `key` if it is there and passes its checks (with the
// run's sample grid when `r` is given); `problem` names the first failed
// check of an entry that is there, else stays empty.
std::optional<ReferenceRun> lookup(const std::string& key, const std::string& cache_dir,
                                   const cvt::mbd::RunOptions* r, std::string& problem) {
  const std::string base = cache_dir + "/" + key_hash(key);
  problem.clear();
  bool have_key = false, have_csv = false;
  const std::string key_file = read_all(base + ".key", have_key);
  // No key file: no entry (the key is written last, so a run cut short
  // leaves none).
  if (!have_key) return std::nullopt;
  const std::string csv_file = read_all(base + ".csv", have_csv);
  ReferenceRun out;
  if (!have_csv)
    problem = base + ".csv: missing";
  else
    problem = r != nullptr ? parse_cache_entry(key_file, csv_file, key, *r, base, out)
                           : parse_cache_entry(key_file, csv_file, key, base, out);
  if (!problem.empty()) return std::nullopt;
  out.from_cache = true;
  out.cpu_s = out.wall_s = std::nan("");
  return out;
}

}  // namespace

std::string reference_key(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r) {
  std::ostringstream k;
  k.precision(17);
  k << "cvtplant multibody reference v" << cvt::mbd::kReferenceVersion << ", cache format " << kCacheFormat << "\n";
  KeyWriter w{k};
  cvt::mbd::visit_mbd_params(p, w);
  cvt::mbd::visit_run_options(r, w);
  return k.str();
}

std::optional<ReferenceRun> cached_run(const std::string& key, const std::string& cache_dir,
                                       std::string* problem) {
  std::string why;
  auto hit = lookup(key, cache_dir, nullptr, why);
  if (problem != nullptr) *problem = why;
  return hit;
}

bool store_run(const std::string& key, const std::string& cache_dir, const ReferenceRun& run) {
  std::string key_text, csv_text;
  format_cache_entry(run, key, key_text, csv_text);
  // A run whose values the checks would refuse (a start that failed with
  // values beyond any quantity of the reference) is used, not kept: stored,
  // it would be refused and run again every time.
  ReferenceRun back;
  if (!parse_cache_entry(key_text, csv_text, key, "entry", back).empty()) return false;
  const std::string base = cache_dir + "/" + key_hash(key);
  try {
    cvt::files::replace_file(base + ".csv", csv_text);
    cvt::files::replace_file(base + ".key", key_text);
  } catch (const cvt::files::PathError& e) {
    throw InputError(std::string("the reference cache: ") + e.what());
  } catch (const cvt::files::WriteError& e) {
    throw RunError(std::string("the reference cache: ") + e.what());
  }
  return true;
}

void append_sample(ReferenceRun& out, const cvt::mbd::Sample& s) {
  out.series.t_s.push_back(s.t_s);
  out.series.omega1_rad_s.push_back(s.omega_rad_s[0]);
  out.series.omega2_rad_s.push_back(s.omega_rad_s[1]);
  out.series.F_ax1_N.push_back(s.F_ax_N[0]);
  // The chain's moment on the driver opposes the input: the torque the
  // chain takes off the driver is its negative (docs/mbd.md#equations-of-motion).
  out.series.torque_driver_Nm.push_back(-s.chain_torque_Nm[0]);
  out.series.slip1_m_s.push_back(s.slip_m_s[0]);
  out.series.wrap_slip_m_s.push_back(whole_wrap_slip(s.slip_min_m_s[0], s.slip_max_m_s[0]));
  out.series.ratio_geom.push_back(s.radius_m[1] / s.radius_m[0]);
  out.series.F_ax2_N.push_back(s.F_ax_N[1]);
  out.series.clamp1_N.push_back(s.clamp_N[0]);
  out.series.clamp2_N.push_back(s.clamp_N[1]);
  out.series.tau_in_Nm.push_back(s.tau_in_Nm);
  out.series.tau_load_Nm.push_back(s.tau_load_Nm);
  out.sheave1_m.push_back(s.sheave_opening_m[0]);
  out.sheave2_m.push_back(s.sheave_opening_m[1]);
}

ReferenceRun reference_run(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r, const std::string& cache_dir,
                           const cvt::mbd::ProgressSink& on_progress) {
  const std::string key = reference_key(p, r);
  std::string problem;
  // An entry that fails its checks (here also against the run's sample
  // grid) is run again, and the problem goes with the new run.
  if (auto hit = lookup(key, cache_dir, &r, problem)) return std::move(*hit);
  ReferenceRun out;
  out.cache_problem = problem;
  const std::size_t n = static_cast<std::size_t>(r.t_end_s / r.sample_s) + 2;
  out.series.reserve(n);
  out.sheave1_m.reserve(n);
  out.sheave2_m.reserve(n);
  auto on_sample = [&](const cvt::mbd::Sample& s, const cvt::mbd::ChainModel&, const double*) {
    append_sample(out, s);
  };
  cvt::mbd::RunStats st;
  bool capped = false;
  try {
    st = cvt::mbd::simulate(p, r, on_sample, on_progress);
  } catch (const cvt::mbd::RunFailure& e) {
    // The samples before the failure are still a valid reference: kept, and
    // the comparison ends there.
    char buf[96];
    std::snprintf(buf, sizeof buf, "the reference stopped at t = %.6g s after %lld steps: ", e.t_s, e.stats.steps);
    out.failure = buf + e.quantity;
    st = e.stats;
    capped = e.stats.steps >= r.max_steps;
  }
  if (out.series.size() < 2) throw RunError(out.failure.empty() ? "the reference made no samples" : out.failure);
  out.cpu_s = st.cpu_s;
  out.wall_s = st.wall_s;
  out.steps = st.steps;
  out.ledger_residual_rel = st.ledger_residual_max_rel;
  // A run the step cap ended is used, not kept: the cap is no part of the
  // key, and a larger one would go further.
  if (!capped) store_run(key, cache_dir, out);
  return out;
}

double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m) {
  const std::vector<double>& v = sheave == 0 ? r.sheave1_m : r.sheave2_m;
  for (std::size_t i = 0; i < v.size() && i < r.series.size(); ++i)
    if (std::fabs(v[i]) >= sheave_stop_m - 1e-4) return r.series.t_s[i];
  return -1.0;
}

}  // namespace cvt::validation
