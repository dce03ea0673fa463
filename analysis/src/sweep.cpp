#include "cvtplant/analysis/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "cvtplant/analysis/errors.hpp"

namespace cvt::analysis {

SweepAxis parse_axis(const std::string& spec) {
  SweepAxis a;
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("axis '" + spec + "': expected name=lo:hi:n");
  a.param = spec.substr(0, eq);
  std::vector<std::string> parts;
  std::stringstream ss(spec.substr(eq + 1));
  std::string item;
  while (std::getline(ss, item, ':')) parts.push_back(item);
  if (parts.size() != 3) throw InputError("axis '" + spec + "': expected name=lo:hi:n");
  auto num = [&](const std::string& t) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !std::isfinite(v)) throw InputError("axis '" + spec + "': '" + t + "' is not a number");
    return v;
  };
  a.lo = num(parts[0]);
  a.hi = num(parts[1]);
  const double n = num(parts[2]);
  if (n < 1 || n != std::floor(n) || n > 100000) throw InputError("axis '" + spec + "': n must be an integer in 1..100000");
  a.n = static_cast<int>(n);
  return a;
}

std::string SweepSpec::signature() const {
  std::ostringstream s;
  s.precision(17);
  s << "scene=" << scene << " a1=" << a1.param << ":" << a1.lo << ":" << a1.hi << ":" << a1.n;
  if (has_a2) s << " a2=" << a2.param << ":" << a2.lo << ":" << a2.hi << ":" << a2.n;
  for (const auto& [k, v] : overrides) s << " " << k << "=" << v;
  s << " x0=";
  for (double v : x0) s << v << ",";
  s << " dt=" << benettin.dt << " t_transient=" << benettin.t_transient << " t_end=" << benettin.t_end
    << " state=" << bif_state << " total=" << total();
  return s.str();
}

namespace {

// Local maxima of one state (docs/analysis.md#sweep-peaks). A map's iterates
// are the orbit itself, not samples of a curve: the iterate is the peak (a
// parabola through three unrelated iterates put the logistic map's peaks
// above its maximum, 1.02 > 1). A flow's samples bracket its peak, refined by
// the parabola through the three samples around it; with b above both
// neighbours the vertex is within half a step of b and above it by at most
// 1/8 of the larger drop, (b - min(a, c)) / 8.
std::vector<double> local_maxima(const std::vector<double>& rows, int dim, int state, int max_peaks, bool is_map) {
  std::vector<double> out;
  const std::size_t n = rows.size() / dim;
  for (std::size_t i = 1; i + 1 < n && static_cast<int>(out.size()) < max_peaks; ++i) {
    const double a = rows[(i - 1) * dim + state], b = rows[i * dim + state], c = rows[(i + 1) * dim + state];
    if (!(b > a && b >= c)) continue;
    if (is_map) {
      out.push_back(b);
      continue;
    }
    const double den = a - 2 * b + c;  // < 0: b is above both neighbours
    out.push_back(den < 0 ? b - 0.125 * (a - c) * (a - c) / den : b);
  }
  return out;
}

}  // namespace

std::vector<SweepPoint> run_sweep(const SweepSpec& spec, int shard_i, int shard_n, int jobs,
                                  const std::function<void(long done, long total)>& on_point) {
  const Model& scene = spec.model != nullptr ? *spec.model : find_model(spec.scene);
  if (shard_n < 1 || shard_i < 0 || shard_i >= shard_n) throw InputError("shard must be i/N with 0 <= i < N");
  if (spec.bif_state < 0 || spec.bif_state >= scene.dim)
    throw InputError("state index must be in 0.." + std::to_string(scene.dim - 1));
  // Each axis labels its own column of the output: two axes on one
  // parameter, or an override of a swept parameter, would label values that
  // were never used.
  if (spec.has_a2 && spec.a2.param == spec.a1.param)
    throw InputError("the second axis sweeps '" + spec.a1.param + "' too: give two different parameters");
  for (const SweepAxis* ax : {&spec.a1, spec.has_a2 ? &spec.a2 : nullptr})
    if (ax != nullptr && spec.overrides.count(ax->param) != 0)
      throw InputError("'" + ax->param + "' is swept: it cannot also be a fixed override");
  Params base = merge_params(scene, spec.overrides);
  // Axis parameters must exist too (merge_params throws otherwise).
  merge_params(scene, {{spec.a1.param, spec.a1.lo}});
  if (spec.has_a2) merge_params(scene, {{spec.a2.param, spec.a2.lo}});
  const std::vector<double> x0 = spec.x0.empty() ? scene.default_x0 : spec.x0;
  if (static_cast<int>(x0.size()) != scene.dim)
    throw InputError("x0 needs " + std::to_string(scene.dim) + " values for scene " + scene.name);
  std::vector<long> mine;
  for (long k = shard_i; k < spec.total(); k += shard_n) mine.push_back(k);
  std::vector<SweepPoint> out(mine.size());
  std::atomic<std::size_t> next{0};
  std::atomic<long> finished{0};
  auto worker = [&] {
    while (true) {
      const std::size_t t = next.fetch_add(1);
      if (t >= mine.size()) return;
      SweepPoint& pt = out[t];
      pt.index = mine[t];
      const int i1 = static_cast<int>(pt.index % spec.a1.n);
      const int i2 = static_cast<int>(pt.index / spec.a1.n);
      Params p = base;
      pt.p1 = spec.a1.value(i1);
      p[spec.a1.param] = pt.p1;
      if (spec.has_a2) {
        pt.p2 = spec.a2.value(i2);
        p[spec.a2.param] = pt.p2;
      }
      try {
        const SpectrumResult r = scene.spectrum(p, x0, spec.benettin);
        pt.exponents = r.exponents;
        pt.ci95 = r.ci95;
        const std::vector<double> rows =
            scene.trajectory(p, r.x_final, spec.benettin.dt, 0.0, spec.t_peaks, spec.benettin.dt);
        pt.peaks = local_maxima(rows, scene.dim, spec.bif_state, spec.max_peaks, scene.is_map);
        if (pt.peaks.empty() && !rows.empty()) pt.peaks.push_back(rows[rows.size() - scene.dim + spec.bif_state]);
      } catch (const std::exception& e) {
        pt.error = e.what();
      }
      const long done = finished.fetch_add(1) + 1;
      if (on_point) on_point(done, static_cast<long>(mine.size()));
    }
  };
  if (jobs <= 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  jobs = std::max(1, std::min<int>(jobs, static_cast<int>(mine.size())));
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& th : pool) th.join();
  return out;
}

void write_sweep_csv(std::FILE* f, const SweepSpec& spec, int dim, const std::vector<SweepPoint>& pts) {
  std::fprintf(f, "# cvtplant sweep %s\n", spec.signature().c_str());
  std::fprintf(f, "index,%s,%s", spec.a1.param.c_str(), spec.has_a2 ? spec.a2.param.c_str() : "p2");
  for (int i = 0; i < dim; ++i) std::fprintf(f, ",lambda%d", i + 1);
  for (int i = 0; i < dim; ++i) std::fprintf(f, ",ci%d", i + 1);
  std::fprintf(f, ",n_peaks,peaks,error\n");
  for (const auto& p : pts) {
    std::fprintf(f, "%ld,%.17g,%.17g", p.index, p.p1, p.p2);
    for (int i = 0; i < dim; ++i)
      std::fprintf(f, ",%.10g", i < static_cast<int>(p.exponents.size()) ? p.exponents[i] : std::nan(""));
    for (int i = 0; i < dim; ++i) std::fprintf(f, ",%.3g", i < static_cast<int>(p.ci95.size()) ? p.ci95[i] : std::nan(""));
    std::fprintf(f, ",%zu,", p.peaks.size());
    for (std::size_t k = 0; k < p.peaks.size(); ++k) std::fprintf(f, "%s%.8g", k ? ";" : "", p.peaks[k]);
    std::string err = p.error;
    std::replace(err.begin(), err.end(), ',', ' ');
    std::fprintf(f, ",%s\n", err.c_str());
  }
}

namespace {

// The number of points a shard signature declares, checked against its axes
// (total = n1 * n2): a shard is input like any other file, and a forged or
// damaged total must be refused, not trusted (the merge walks 0..total-1).
long signature_total(const std::string& sig, const std::string& path) {
  auto bad = [&](const std::string& why) { return InputError("merge: '" + path + "': signature " + why); };
  // n of the axis token "aK=name:lo:hi:n" at `at`: its last ':' field. The
  // signature lists " a1=..." after the scene and " a2=..." right after it.
  auto axis_n = [&](std::size_t at, std::size_t& stop) -> long {
    stop = sig.find(' ', at + 1);
    const std::string tok = sig.substr(at + 1, stop == std::string::npos ? std::string::npos : stop - at - 1);
    const std::size_t colon = tok.rfind(':');
    const std::string n = colon == std::string::npos ? "" : tok.substr(colon + 1);
    if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos)
      throw bad("has a bad axis size in '" + tok + "'");
    const long v = std::stol(n);
    if (v < 1 || v > 100000) throw bad("has an axis size outside 1..100000 in '" + tok + "'");
    return v;
  };
  const std::size_t a1 = sig.find(" a1=");
  if (a1 == std::string::npos) throw bad("lacks a1=");
  std::size_t stop = 0;
  long expected = axis_n(a1, stop);
  if (stop != std::string::npos && sig.compare(stop, 4, " a2=") == 0) expected *= axis_n(stop, stop);
  const std::size_t t = sig.rfind(" total=");
  if (t == std::string::npos) throw bad("lacks total=");
  const std::string digits = sig.substr(t + 7);
  if (digits.empty() || digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos)
    throw bad("has a malformed total '" + digits + "'");
  const long total = std::stol(digits);
  if (total != expected)
    throw bad("declares total=" + digits + " but its axes give " + std::to_string(expected) + " points");
  return total;
}

}  // namespace

void merge_sweep_csv(const std::vector<std::string>& shards, std::FILE* out) {
  if (shards.empty()) throw InputError("merge: no shard files given");
  std::string signature, header;
  std::map<long, std::string> rows;
  long total = -1;
  std::size_t columns = 0;
  for (const auto& path : shards) {
    std::ifstream in(path);
    if (!in) throw InputError("merge: cannot read '" + path + "'");
    std::string sig, head, line;
    if (!std::getline(in, sig) || sig.rfind("# cvtplant sweep ", 0) != 0)
      throw InputError("merge: '" + path + "' is not a sweep shard (missing '# cvtplant sweep' line)");
    if (!std::getline(in, head)) throw InputError("merge: '" + path + "' has no header row");
    if (signature.empty()) {
      total = signature_total(sig, path);
      signature = sig;
      header = head;
      columns = static_cast<std::size_t>(std::count(head.begin(), head.end(), ',')) + 1;
    } else if (sig != signature) {
      throw InputError("merge: '" + path + "' comes from a different sweep ('" + sig.substr(17) + "' vs '" +
                       signature.substr(17) + "')");
    } else if (head != header) {
      throw InputError("merge: '" + path + "' has another header row than '" + shards.front() + "'");
    }
    long line_no = 2;
    while (std::getline(in, line)) {
      ++line_no;
      if (line.empty()) continue;
      const std::string where = path + ":" + std::to_string(line_no);
      char* end = nullptr;
      errno = 0;
      const long idx = std::strtol(line.c_str(), &end, 10);
      if (end == line.c_str() || *end != ',' || errno != 0) throw InputError("merge: " + where + ": bad row");
      if (idx < 0 || idx >= total)
        throw InputError("merge: " + where + ": point " + std::to_string(idx) + " is outside 0.." +
                         std::to_string(total - 1));
      if (static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1 != columns)
        throw InputError("merge: " + where + ": " + std::to_string(std::count(line.begin(), line.end(), ',') + 1) +
                         " columns, the header has " + std::to_string(columns));
      if (!rows.emplace(idx, line).second)
        throw InputError("merge: point " + std::to_string(idx) + " appears twice (" + path + ")");
    }
  }
  // Every index is in 0..total-1 and unique, so the count says how many are
  // missing; the first few are found within rows.size() + 10 probes.
  const long n_missing = total - static_cast<long>(rows.size());
  if (n_missing > 0) {
    std::string missing;
    int listed = 0;
    for (long k = 0; k < total && listed < 10; ++k)
      if (!rows.count(k)) missing += (listed++ ? "," : "") + std::to_string(k);
    throw InputError("merge: " + std::to_string(n_missing) + " of " + std::to_string(total) +
                     " points missing (first: " + missing + "); run the missing shards");
  }
  std::fprintf(out, "%s\n%s\n", signature.c_str(), header.c_str());
  for (const auto& [k, line] : rows) std::fprintf(out, "%s\n", line.c_str());
}

}  // namespace cvt::analysis
