// A reference cache entry's files: their format and their checks
// (docs/validation.md#cache). Apart from cache.cpp, which runs the
// reference, so the checks can be fuzzed alone (tests/fuzz).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>

#include "cvtplant/validation/cache.hpp"

namespace cvt::validation {

namespace {

constexpr const char* kCsvHeader =
    "t_s,omega1_rad_s,omega2_rad_s,F_ax1_N,torque_driver_Nm,slip1_m_s,wrap_slip1_m_s,ratio_geom,F_ax2_N,clamp1_N,"
    "clamp2_N,tau_in_Nm,tau_load_Nm,sheave1_m,sheave2_m\n";
// The series' columns (kSeriesColumns), then the two sheave openings.
constexpr int kCsvColumns = static_cast<int>(std::size(kSeriesColumns)) + 2;
static_assert(kCsvColumns == 15, "a new series column goes into kCsvHeader and may_be_nan, and raises the format");
// Columns 5, 6 and 7 (the driver's slip, the whole wrap's and the geometric
// ratio r2/r1) are nan when no bolt is in a wrap; every other value is
// finite.
constexpr bool may_be_nan(int col) { return col == 5 || col == 6 || col == 7; }
// No quantity of the reference comes near it (speeds below 1e4 rad/s,
// forces below 1e9 N): a larger cell is damage, not data.
constexpr double kCellLimit = 1e12;

// The run's sample times, as cvt::mbd::simulate makes them: 0, then
// min(t_end, k sample) for k = 1 .. ceil(t_end / sample) (RK4: the sample
// a whole number of steps).
struct SampleGrid {
  double sample_s = 0, t_end_s = 0;
  long long count = 0;  // samples including t = 0
  double at(long long k) const { return k == 0 ? 0.0 : std::min(t_end_s, static_cast<double>(k) * sample_s); }
};

SampleGrid grid_of(const cvt::mbd::RunOptions& r) {
  SampleGrid g;
  g.t_end_s = r.t_end_s;
  g.sample_s = r.sample_s;
  if (r.method == cvt::mbd::Method::rk4)
    g.sample_s = static_cast<double>(std::max<long long>(1, std::llround(r.sample_s / r.dt_s))) * r.dt_s;
  g.count = static_cast<long long>(std::ceil(r.t_end_s / g.sample_s - 1e-9)) + 1;
  return g;
}

// One line of the key file after the key: "entry NAME VALUE".
bool entry_value(const std::string& trailer, const std::string& name, std::string& value) {
  const std::string tag = "entry " + name + " ";
  std::size_t at = 0;
  while (at < trailer.size()) {
    const std::size_t end = trailer.find('\n', at);
    const std::string line = trailer.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (line.compare(0, tag.size(), tag) == 0) {
      value = line.substr(tag.size());
      return true;
    }
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return false;
}

bool whole_number(const std::string& text, long long& v) {
  if (text.empty() || text.size() > 18) return false;
  for (const char c : text)
    if (c < '0' || c > '9') return false;
  v = std::stoll(text);
  return true;
}

bool real_number(const std::string& text, double& v) {
  if (text.empty() || text.size() > 40 || text[0] == ' ' || text[0] == '\t') return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// A text for a message: at most 40 characters, control characters as '?'.
std::string shown(const std::string& text) {
  std::string s = text.substr(0, 40);
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + s + (text.size() > 40 ? "...'" : "'");
}

std::string one_line(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return s;
}

// The shortest text that reads back to v, for messages.
std::string shortest(double v) {
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string g17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

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

void format_cache_entry(const ReferenceRun& run, const std::string& key, std::string& key_file,
                        std::string& csv_file) {
  // The CSV: the series' columns (kSeriesColumns) and the sheave openings,
  // every value to 17 digits, so a run read back is bit for bit the run
  // that was stored.
  csv_file = kCsvHeader;
  const Series& s = run.series;
  char buf[64];
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (const auto col : kSeriesColumns) {
      std::snprintf(buf, sizeof buf, "%.17g,", (s.*col)[i]);
      csv_file += buf;
    }
    std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", run.sheave1_m[i], run.sheave2_m[i]);
    csv_file += buf;
  }
  key_file = key;
  key_file += "entry rows " + std::to_string(s.size()) + "\n";
  key_file += "entry csv_fnv1a64 " + key_hash(csv_file) + "\n";
  key_file += "entry steps " + std::to_string(run.steps) + "\n";
  key_file += "entry ledger_residual_rel " + g17(run.ledger_residual_rel) + "\n";
  if (!run.failure.empty()) key_file += "entry failure " + one_line(run.failure) + "\n";
}

std::string parse_cache_entry(const std::string& key_file, const std::string& csv_file, const std::string& key,
                              const std::string& name, ReferenceRun& out) {
  const std::string key_name = name + ".key", csv_name = name + ".csv";
  out = ReferenceRun{};
  if (key_file.size() < key.size() || key_file.compare(0, key.size(), key) != 0)
    return key_name + ": the stored key is not this run's";
  const std::string trailer = key_file.substr(key.size());
  std::string rows_text, sum, steps_text, residual_text, failure;
  long long rows_stored = 0;
  if (!entry_value(trailer, "rows", rows_text) || !whole_number(rows_text, rows_stored))
    return key_name + ": no row count";
  if (!entry_value(trailer, "csv_fnv1a64", sum) || sum.size() != 16) return key_name + ": no checksum";
  if (!entry_value(trailer, "steps", steps_text) || !whole_number(steps_text, out.steps))
    return key_name + ": no step count";
  if (!entry_value(trailer, "ledger_residual_rel", residual_text) ||
      !real_number(residual_text, out.ledger_residual_rel) || !std::isfinite(out.ledger_residual_rel))
    return key_name + ": no ledger residual";
  const bool failed = entry_value(trailer, "failure", failure);
  if (key_hash(csv_file) != sum)
    return csv_name + ": its bytes do not match the checksum in " + key_name + " (changed or cut short)";
  if (csv_file.compare(0, std::strlen(kCsvHeader), kCsvHeader) != 0) return csv_name + ": not the cache's header";
  std::vector<double>* cols[kCsvColumns];
  int c = 0;
  for (const auto col : kSeriesColumns) cols[c++] = &(out.series.*col);
  cols[c++] = &out.sheave1_m;
  cols[c++] = &out.sheave2_m;
  std::size_t at = std::strlen(kCsvHeader);
  long long row = 0;
  while (at < csv_file.size()) {
    const std::size_t end = csv_file.find('\n', at);
    const std::string where = csv_name + ": row " + std::to_string(row + 1);
    if (end == std::string::npos) return where + ": cut short (no end of line)";
    if (row >= rows_stored) return where + ": more rows than the " + std::to_string(rows_stored) + " in " + key_name;
    const std::string line = csv_file.substr(at, end - at);
    at = end + 1;
    std::size_t from = 0;
    for (int k = 0; k < kCsvColumns; ++k) {
      const std::size_t comma = line.find(',', from);
      if ((comma == std::string::npos) != (k == kCsvColumns - 1))
        return where + ": not " + std::to_string(kCsvColumns) + " cells";
      const std::string cell = line.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      from = comma + 1;
      double v = 0;
      if (!real_number(cell, v)) return where + ": " + shown(cell) + " is not a number";
      if (std::isnan(v) ? !may_be_nan(k) : !(std::fabs(v) <= kCellLimit))
        return where + ": " + shown(cell) + " is out of range";
      cols[k]->push_back(v);
    }
    const std::vector<double>& t = out.series.t_s;
    if (row > 0 && !(t[t.size() - 1] > t[t.size() - 2]))
      return where + ": t = " + shortest(t.back()) + " s, not after the row before's " + shortest(t[t.size() - 2]) +
             " s";
    ++row;
  }
  if (row != rows_stored)
    return csv_name + ": " + std::to_string(row) + " rows, " + key_name + " says " + std::to_string(rows_stored);
  if (row < 1) return csv_name + ": no rows";
  out.failure = failed ? failure : std::string();
  return {};
}

std::string parse_cache_entry(const std::string& key_file, const std::string& csv_file, const std::string& key,
                              const cvt::mbd::RunOptions& r, const std::string& name, ReferenceRun& out) {
  const std::string problem = parse_cache_entry(key_file, csv_file, key, name, out);
  if (!problem.empty()) return problem;
  const std::string csv_name = name + ".csv";
  const SampleGrid grid = grid_of(r);
  const long long rows = static_cast<long long>(out.series.size());
  const auto bad = [&](const std::string& why) {
    out = ReferenceRun{};
    return csv_name + ": " + why;
  };
  if (rows > grid.count)
    return bad(std::to_string(rows) + " rows, more than the run's " + std::to_string(grid.count) + " samples");
  for (long long k = 0; k < rows; ++k) {
    const double t = out.series.t_s[static_cast<std::size_t>(k)], t_expected = grid.at(k);
    if (!(std::fabs(t - t_expected) <= 1e-9 * grid.sample_s))
      return bad("row " + std::to_string(k + 1) + ": t = " + shortest(t) + " s, where the run samples at " +
                 shortest(t_expected) + " s");
  }
  if (rows < 2) return bad("fewer than two rows");
  if (out.failure.empty() && rows != grid.count)
    return bad(std::to_string(rows) + " rows where the run's span has " + std::to_string(grid.count) +
               " samples and no failure is recorded");
  return {};
}

}  // namespace cvt::validation
