// Reference runs cached on disk by their inputs (docs/validation.md#cache).
#include "cvtplant/validation/cache.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

namespace {

// The CSV's format: raised when its columns change (the key carries it).
constexpr int kCacheFormat = 5;

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

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

constexpr const char* kCsvHeader =
    "t_s,omega1_rad_s,omega2_rad_s,F_ax1_N,torque_driver_Nm,slip1_m_s,wrap_slip1_m_s,ratio_geom,F_ax2_N,clamp1_N,"
    "clamp2_N,tau_in_Nm,tau_load_Nm,sheave1_m,sheave2_m\n";
constexpr int kCsvColumns = 15;  // the series' columns, then the two sheave openings

// The cache's CSV: the series' columns (kSeriesColumns) and the sheave
// openings, every value to 17 digits, so a run read back is bit for bit the
// run that was stored.
bool read_series(const std::string& path, ReferenceRun& out) {
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) return false;
  char line[1024];
  bool ok = std::fgets(line, sizeof line, f) != nullptr && std::string(line) == kCsvHeader;
  std::vector<double>* cols[kCsvColumns];
  int c = 0;
  for (const auto col : kSeriesColumns) cols[c++] = &(out.series.*col);
  cols[c++] = &out.sheave1_m;
  cols[c++] = &out.sheave2_m;
  while (ok && std::fgets(line, sizeof line, f) != nullptr) {
    const char* p = line;
    double v[kCsvColumns];
    for (int i = 0; i < kCsvColumns && ok; ++i) {
      char* end = nullptr;
      v[i] = std::strtod(p, &end);
      ok = end != p && *end == (i + 1 < kCsvColumns ? ',' : '\n');
      p = end + 1;
    }
    if (ok)
      for (int i = 0; i < kCsvColumns; ++i) cols[i]->push_back(v[i]);
  }
  std::fclose(f);
  return ok && out.series.size() > 0;
}

void write_series(const std::string& path, const ReferenceRun& r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw InputError("cannot write " + path);
  std::fputs(kCsvHeader, f);
  const Series& s = r.series;
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (const auto col : kSeriesColumns) std::fprintf(f, "%.17g,", (s.*col)[i]);
    std::fprintf(f, "%.17g,%.17g\n", r.sheave1_m[i], r.sheave2_m[i]);
  }
  if (std::fclose(f) != 0) throw InputError("cannot write " + path);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  if (!f) throw InputError("cannot write " + path);
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

std::optional<ReferenceRun> cached_run(const std::string& key, const std::string& cache_dir) {
  const std::string base = cache_dir + "/" + key_hash(key);
  ReferenceRun out;
  // The key file is written last: a run cut short leaves no key, so no hit.
  if (read_all(base + ".key") != key || !read_series(base + ".csv", out)) return std::nullopt;
  out.from_cache = true;
  out.failure = read_all(base + ".failure");
  return out;
}

void store_run(const std::string& key, const std::string& cache_dir, const ReferenceRun& run) {
  const std::string base = cache_dir + "/" + key_hash(key);
  write_series(base + ".csv", run);
  if (!run.failure.empty())
    write_text(base + ".failure", run.failure);
  else
    std::remove((base + ".failure").c_str());
  write_text(base + ".key", key);
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
  if (auto hit = cached_run(key, cache_dir)) return std::move(*hit);
  ReferenceRun out;
  const std::size_t n = static_cast<std::size_t>(r.t_end_s / r.sample_s) + 2;
  out.series.reserve(n);
  out.sheave1_m.reserve(n);
  out.sheave2_m.reserve(n);
  auto on_sample = [&](const cvt::mbd::Sample& s, const cvt::mbd::ChainModel&, const double*) {
    append_sample(out, s);
  };
  cvt::mbd::RunStats st;
  try {
    st = cvt::mbd::simulate(p, r, on_sample, on_progress);
  } catch (const cvt::mbd::RunFailure& e) {
    // The samples before the failure are still a valid reference: kept, and
    // the comparison ends there.
    char buf[96];
    std::snprintf(buf, sizeof buf, "the reference stopped at t = %.6g s after %lld steps: ", e.t_s, e.stats.steps);
    out.failure = buf + e.quantity;
    st = e.stats;
  }
  if (out.series.size() < 2) throw RunError(out.failure.empty() ? "the reference made no samples" : out.failure);
  out.cpu_s = st.cpu_s;
  out.wall_s = st.wall_s;
  out.steps = st.steps;
  out.ledger_residual_rel = st.ledger_residual_max_rel;
  store_run(key, cache_dir, out);
  return out;
}

double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m) {
  const std::vector<double>& v = sheave == 0 ? r.sheave1_m : r.sheave2_m;
  for (std::size_t i = 0; i < v.size() && i < r.series.size(); ++i)
    if (std::fabs(v[i]) >= sheave_stop_m - 1e-4) return r.series.t_s[i];
  return -1.0;
}

}  // namespace cvt::validation
