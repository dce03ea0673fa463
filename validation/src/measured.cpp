// A test rig's measured log as a calibration case (docs/validation.md#measured-csv).
#include "cvtplant/validation/measured.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "cvtplant/analysis/csv.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/plant.hpp"

namespace cvt::validation {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The quantities a log holds; a clamping is a force or a pressure.
enum class Col { time, tau_in, tau_load, clamp1, p1, clamp2, p2, omega1, omega2, ratio, count };
constexpr const char* kColName[] = {"time", "input torque", "load torque", "driver clamping force",
                                    "driver clamping pressure", "driven clamping force", "driven clamping pressure",
                                    "primary speed", "secondary speed", "ratio"};

// The column names a log may use: the quantity and its unit in the name,
// and the factor to SI. One list: the reader's and the docs' table.
struct Header {
  const char* name;
  Col col;
  double to_si;
};
constexpr Header kHeaders[] = {
    {"time_s", Col::time, 1.0},
    {"time_ms", Col::time, 1e-3},
    {"tau_in_Nm", Col::tau_in, 1.0},
    {"tau_load_Nm", Col::tau_load, 1.0},
    {"clamp1_N", Col::clamp1, 1.0},
    {"clamp1_kN", Col::clamp1, 1e3},
    {"p1_Pa", Col::p1, 1.0},
    {"p1_bar", Col::p1, 1e5},
    {"p1_MPa", Col::p1, 1e6},
    {"clamp2_N", Col::clamp2, 1.0},
    {"clamp2_kN", Col::clamp2, 1e3},
    {"p2_Pa", Col::p2, 1.0},
    {"p2_bar", Col::p2, 1e5},
    {"p2_MPa", Col::p2, 1e6},
    {"omega1_rad_s", Col::omega1, 1.0},
    {"omega1_rpm", Col::omega1, 2.0 * kPi / 60.0},
    {"omega2_rad_s", Col::omega2, 1.0},
    {"omega2_rpm", Col::omega2, 2.0 * kPi / 60.0},
    {"ratio", Col::ratio, 1.0},
};

const Header* find_header(const std::string& name) {
  for (const Header& h : kHeaders)
    if (name == h.name) return &h;
  return nullptr;
}

std::string known_headers() {
  std::string s;
  for (const Header& h : kHeaders) s += (s.empty() ? "" : ", ") + std::string(h.name);
  return s;
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::strchr(" \t\r", s[a]) != nullptr) ++a;
  while (b > a && std::strchr(" \t\r", s[b - 1]) != nullptr) --b;
  return s.substr(a, b - a);
}

// The `# piston_area1_m2 = V` lines before the header (other comments are
// comments). The file is read twice (these lines, then the table), so it
// must be a regular file.
PistonAreas read_metadata(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError("'" + path + "' is not a regular file (a measured log is read twice)");
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "'");
  PistonAreas a;
  std::string line;
  long no = 0;
  while (std::getline(in, line)) {
    ++no;
    const std::string t = trim(line);
    if (t.empty()) continue;
    if (t[0] != '#') break;
    const std::size_t eq = t.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(t.substr(1, eq - 1));
    double* into = key == "piston_area1_m2" ? &a.area1_m2 : key == "piston_area2_m2" ? &a.area2_m2 : nullptr;
    if (into == nullptr) continue;
    const std::string v = trim(t.substr(eq + 1));
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(x) || x <= 0.0)
      throw InputError(path + ":" + std::to_string(no) + ": " + key + " must be a positive area in m^2, not '" +
                       v.substr(0, 40) + "'");
    *into = x;
  }
  return a;
}

// Where time t falls in the rows: the row j at or before it and the weight
// w of row j + 1, linear between rows and held beyond the ends; `at` is a
// cursor for a caller asking in increasing t.
struct Where {
  std::size_t j = 0;
  double w = 0;
  double of(const std::vector<double>& v) const { return w == 0.0 ? v[j] : v[j] + w * (v[j + 1] - v[j]); }
};
Where locate(const std::vector<double>& t_s, double t, std::size_t& at) {
  while (at + 1 < t_s.size() && t_s[at + 1] <= t) ++at;
  Where p;
  p.j = at;
  if (at + 1 < t_s.size() && t > t_s[at]) p.w = (t - t_s[at]) / (t_s[at + 1] - t_s[at]);
  return p;
}

// A speed at the log's first time (measured_start).
double start_value(const std::vector<double>& t_s, const std::vector<double>& v) {
  std::size_t n = 0;
  while (n < t_s.size() && (n < 3 || t_s[n] - t_s[0] <= 0.02)) ++n;
  double st = 0, sv = 0;
  for (std::size_t i = 0; i < n; ++i) {
    st += t_s[i] - t_s[0];
    sv += v[i];
  }
  st /= double(n);
  sv /= double(n);
  double stt = 0, stv = 0;
  for (std::size_t i = 0; i < n; ++i) {
    stt += (t_s[i] - t_s[0] - st) * (t_s[i] - t_s[0] - st);
    stv += (t_s[i] - t_s[0] - st) * (v[i] - sv);
  }
  return stt > 0 ? sv - st * stv / stt : sv;
}

long frames_of(const MeasuredLog& log, double frame_s) {
  const double span = log.t_s.back() - log.t_s.front();
  return std::max(1L, static_cast<long>(std::ceil(span / frame_s - 1e-9)));
}

}  // namespace

MeasuredLog read_measured_csv(const std::string& path, const PistonAreas& areas) {
  PistonAreas a = read_metadata(path);
  if (areas.area1_m2 > 0) a.area1_m2 = areas.area1_m2;
  if (areas.area2_m2 > 0) a.area2_m2 = areas.area2_m2;
  // Which header names the file uses for which quantity.
  const Header* used[static_cast<int>(Col::count)] = {};
  std::vector<std::string> wanted;
  std::vector<const Header*> order;
  std::vector<cvt::analysis::CsvColumn> cols;
  try {
    cols = cvt::analysis::read_csv_columns(path, [&](const std::vector<std::string>& names) {
      for (const std::string& n : names) {
        const Header* h = find_header(n);
        if (h == nullptr)
          throw InputError(path + ": unknown column '" + n.substr(0, 40) +
                           "' (a quantity and its unit, one of: " + known_headers() + ")");
        const Header*& slot = used[static_cast<int>(h->col)];
        if (slot != nullptr)
          throw InputError(path + ": the " + std::string(kColName[static_cast<int>(h->col)]) + " is given twice ('" +
                           slot->name + "' and '" + h->name + "')");
        slot = h;
        wanted.push_back(n);
        order.push_back(h);
      }
      const auto need = [&](Col c, Col alt, const char* names) {
        if (used[static_cast<int>(c)] == nullptr && (alt == Col::count || used[static_cast<int>(alt)] == nullptr))
          throw InputError(path + ": no column of the " + std::string(kColName[static_cast<int>(c)]) + " (" + names +
                           ")");
      };
      need(Col::time, Col::count, "time_s or time_ms");
      need(Col::tau_in, Col::count, "tau_in_Nm");
      need(Col::clamp1, Col::p1, "clamp1_N, clamp1_kN or a pressure p1_Pa, p1_bar, p1_MPa");
      need(Col::omega1, Col::count, "omega1_rad_s or omega1_rpm");
      need(Col::omega2, Col::count, "omega2_rad_s or omega2_rpm");
      const auto clash = [&](Col f, Col p) {
        if (used[static_cast<int>(f)] != nullptr && used[static_cast<int>(p)] != nullptr)
          throw InputError(path + ": both a force ('" + std::string(used[static_cast<int>(f)]->name) +
                           "') and a pressure ('" + used[static_cast<int>(p)]->name + "') of one clamping");
      };
      clash(Col::clamp1, Col::p1);
      clash(Col::clamp2, Col::p2);
      if (used[static_cast<int>(Col::p1)] != nullptr && !(a.area1_m2 > 0))
        throw InputError(path + ": a driver clamping pressure needs the piston area (a line '# piston_area1_m2 = "
                                "A' before the header, or --piston-area1)");
      if (used[static_cast<int>(Col::p2)] != nullptr && !(a.area2_m2 > 0))
        throw InputError(path + ": a driven clamping pressure needs the piston area (a line '# piston_area2_m2 = "
                                "A' before the header, or --piston-area2)");
      return wanted;
    });
  } catch (const cvt::analysis::InputError& e) {
    throw InputError(e.what());
  }
  MeasuredLog log;
  log.source = path;
  const std::size_t rows = cols.front().values.size();
  if (rows < kMeasuredMinRows)
    throw InputError(path + ": " + std::to_string(rows) + " data row(s), a log needs at least " +
                     std::to_string(kMeasuredMinRows));
  for (std::size_t k = 0; k < cols.size(); ++k) {
    const Header& h = *order[k];
    std::vector<double> v = cols[k].values;
    for (double& x : v) x *= h.to_si;
    std::vector<double>* into = nullptr;
    switch (h.col) {
      case Col::time: into = &log.t_s; break;
      case Col::tau_in: into = &log.tau_in_Nm; break;
      case Col::tau_load: into = &log.tau_load_Nm; break;
      case Col::clamp1: into = &log.clamp1_N; break;
      case Col::clamp2: into = &log.clamp2_N; break;
      case Col::p1:
        log.piston_area1_m2 = a.area1_m2;
        for (double& x : v) x *= a.area1_m2;
        into = &log.clamp1_N;
        break;
      case Col::p2:
        log.piston_area2_m2 = a.area2_m2;
        for (double& x : v) x *= a.area2_m2;
        into = &log.clamp2_N;
        break;
      case Col::omega1: into = &log.omega1_rad_s; break;
      case Col::omega2: into = &log.omega2_rad_s; break;
      case Col::ratio: into = &log.ratio; break;
      case Col::count: break;
    }
    if (h.col == Col::clamp1 || h.col == Col::clamp2 || h.col == Col::p1 || h.col == Col::p2 || h.col == Col::ratio)
      for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i] < 0.0 || (h.col == Col::ratio && v[i] == 0.0))
          throw InputError(path + ": column '" + h.name + "', data row " + std::to_string(i + 1) + ": " +
                           (h.col == Col::ratio ? "a ratio must be > 0" : "a clamping must be >= 0"));
    *into = std::move(v);
  }
  if (log.tau_load_Nm.empty()) log.tau_load_Nm.assign(rows, 0.0);
  for (std::size_t i = 1; i < rows; ++i)
    if (!(log.t_s[i] > log.t_s[i - 1]))
      throw InputError(path + ": time must increase from row to row; data row " + std::to_string(i + 1) + " (t = " +
                       std::to_string(log.t_s[i]) + " s) does not follow row " + std::to_string(i) + " (t = " +
                       std::to_string(log.t_s[i - 1]) + " s)");
  return log;
}

void write_measured_csv(const std::string& path, const MeasuredLog& log) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
  std::fprintf(f, "# A test rig's log (docs/validation.md#measured-csv)\n");
  std::fprintf(f, "time_s,tau_in_Nm,tau_load_Nm,clamp1_N,%somega1_rad_s,omega2_rad_s%s\n",
               log.has_clamp2() ? "clamp2_N," : "", log.has_ratio() ? ",ratio" : "");
  for (std::size_t i = 0; i < log.size(); ++i) {
    std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,", log.t_s[i], log.tau_in_Nm[i], log.tau_load_Nm[i], log.clamp1_N[i]);
    if (log.has_clamp2()) std::fprintf(f, "%.17g,", log.clamp2_N[i]);
    std::fprintf(f, "%.17g,%.17g", log.omega1_rad_s[i], log.omega2_rad_s[i]);
    if (log.has_ratio()) std::fprintf(f, ",%.17g", log.ratio[i]);
    std::fprintf(f, "\n");
  }
  const bool bad = std::ferror(f) != 0;
  if (std::fclose(f) != 0 || bad) throw InputError("writing '" + path + "' failed");
}

bool measured_fits_scene(const MeasuredLog& log, const cvt::Scene& s, std::string& why) {
  if (log.has_clamp2() && (s.features & cvt::rom_feature::wedging) == 0) {
    why = "the log has a driven clamping, the scene's plant has none (no wedging feature)";
    return false;
  }
  cvt::Scene run = s;
  run.t_end_s = static_cast<double>(frames_of(log, s.frame_s)) * s.frame_s;
  const cvt::SceneIssue issue = cvt::validate_scene(run);
  if (!issue.ok) {
    why = std::string(issue.field) + ": " + issue.message + " (the scene run for the log's " +
          std::to_string(run.t_end_s) + " s)";
    return false;
  }
  return true;
}

void measured_start(const MeasuredLog& log, cvt::RomInitial& initial) {
  initial.omega1_rad_s = start_value(log.t_s, log.omega1_rad_s);
  initial.omega2_rad_s = start_value(log.t_s, log.omega2_rad_s);
}

Series measured_plant_run(const cvt::Scene& scene, const MeasuredLog& log, int every) {
  cvt::Scene s = scene;
  const long frames = frames_of(log, s.frame_s);
  s.t_end_s = static_cast<double>(frames) * s.frame_s;
  const double t0 = log.t_s.front();
  std::size_t at = 0;
  const auto drive = [&](double t) {
    const Where p = locate(log.t_s, t0 + t, at);
    FrameInputs f;
    f.tau_in_Nm = p.of(log.tau_in_Nm);
    f.tau_load_Nm = p.of(log.tau_load_Nm);
    f.clamp1_N = p.of(log.clamp1_N);
    f.clamp2_N = log.has_clamp2() ? p.of(log.clamp2_N) : std::nan("");
    return f;
  };
  // The frames around each compared row: the one at or before its time
  // and the next.
  const std::size_t step = static_cast<std::size_t>(std::max(1, every));
  const auto frame_of = [&](double t) {
    return std::min(static_cast<long>(std::max(0.0, std::floor(t / s.frame_s))), frames - 1);
  };
  std::vector<char> keep(static_cast<std::size_t>(frames) + 1, 0);
  for (std::size_t i = 0; i < log.size(); i += step) {
    const long j = frame_of(log.t_s[i] - t0);
    keep[static_cast<std::size_t>(j)] = keep[static_cast<std::size_t>(j) + 1] = 1;
  }
  const Series frame = plant_run_driven(s, frames, drive, &keep);
  // The plant's outputs on the rows' times, linear between its frames
  // (`place` is frame j's among the kept frames).
  Series out;
  long j_at = 0;
  std::size_t place = 0;
  for (std::size_t i = 0; i < log.size(); i += step) {
    const double t = log.t_s[i] - t0;
    const long j = frame_of(t);
    for (; j_at < j; ++j_at) place += keep[static_cast<std::size_t>(j_at)] != 0 ? 1 : 0;
    const double w = t / s.frame_s - static_cast<double>(j);
    for (const auto c : kSeriesColumns) {
      const std::vector<double>& v = frame.*c;
      (out.*c).push_back(c == &Series::t_s ? t : v[place] + w * (v[place + 1] - v[place]));
    }
  }
  return out;
}

Series measured_series(const MeasuredLog& log, int every) {
  Series out;
  const double nan = std::nan("");
  const double t0 = log.t_s.front();
  for (std::size_t i = 0; i < log.size(); i += static_cast<std::size_t>(std::max(1, every))) {
    out.t_s.push_back(log.t_s[i] - t0);
    out.omega1_rad_s.push_back(log.omega1_rad_s[i]);
    out.omega2_rad_s.push_back(log.omega2_rad_s[i]);
    out.ratio_geom.push_back(log.has_ratio() ? log.ratio[i] : nan);
    out.clamp1_N.push_back(log.clamp1_N[i]);
    out.clamp2_N.push_back(log.has_clamp2() ? log.clamp2_N[i] : nan);
    out.tau_in_Nm.push_back(log.tau_in_Nm[i]);
    out.tau_load_Nm.push_back(log.tau_load_Nm[i]);
    for (auto c : {&Series::F_ax1_N, &Series::torque_driver_Nm, &Series::slip1_m_s, &Series::wrap_slip_m_s,
                   &Series::F_ax2_N})
      (out.*c).push_back(nan);
  }
  return out;
}

}  // namespace cvt::validation
