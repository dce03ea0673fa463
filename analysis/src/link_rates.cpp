// Link-passing analysis (docs/analysis.md#link-rates).
#include "cvtplant/analysis/link_rates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "cvtplant/analysis/errors.hpp"

namespace cvt::analysis {

EventRate event_rate(const std::vector<double>& t, double t0, double t1, double quantum) {
  EventRate r;
  double first = NAN, last = NAN;
  for (double v : t) {
    if (!(v >= t0 && v < t1)) continue;
    if (r.events == 0) first = v;
    last = v;
    ++r.events;
  }
  if (r.events < 2 || !(last > first)) return r;
  r.Hz = static_cast<double>(r.events - 1) / (last - first);
  r.resolution_Hz = r.Hz * 2.0 * quantum / (last - first);
  return r;
}

RationalRatio rational_ratio(double ratio, double resolution_rel, long q_max) {
  if (!(ratio > 0) || !std::isfinite(ratio)) throw InputError("rational ratio: the ratio must be positive");
  RationalRatio r;
  r.ratio = ratio;
  r.resolution_rel = resolution_rel;
  // Convergents h/k of the continued fraction of the ratio.
  long h0 = 1, h1 = 0, k0 = 0, k1 = 1;  // h_{-1}, h_{-2}, k_{-1}, k_{-2}
  double x = ratio;
  r.p = std::lround(ratio);
  r.q = 1;
  for (int it = 0; it < 40; ++it) {
    const double a = std::floor(x);
    const long h = static_cast<long>(a) * h0 + h1, k = static_cast<long>(a) * k0 + k1;
    if (k > q_max || k <= 0) break;
    r.p = h;
    r.q = k;
    h1 = h0;
    h0 = h;
    k1 = k0;
    k0 = k;
    const double frac = x - a;
    if (frac < 1e-12) break;
    x = 1.0 / frac;
  }
  r.error_rel = std::fabs(ratio - static_cast<double>(r.p) / static_cast<double>(r.q)) / ratio;
  r.rational = r.error_rel <= resolution_rel;
  return r;
}

namespace {

// Every integer vector with sum |n_k| <= order (the zero vector excluded).
void combinations(std::size_t dims, int order, std::vector<int>& cur, std::vector<std::vector<int>>& out) {
  if (cur.size() == dims) {
    int s = 0;
    for (int v : cur) s += std::abs(v);
    if (s > 0) out.push_back(cur);
    return;
  }
  int used = 0;
  for (int v : cur) used += std::abs(v);
  for (int n = -(order - used); n <= order - used; ++n) {
    cur.push_back(n);
    combinations(dims, order, cur, out);
    cur.pop_back();
  }
}

}  // namespace

double alias_Hz(double f, double fs) {
  const double r = std::fmod(std::fabs(f), fs);
  return r <= 0.5 * fs ? r : fs - r;
}

std::vector<LineAttribution> attribute_lines(const Lines& lines, const std::vector<double>& base, int max_order,
                                             double tol_Hz, double sample_Hz) {
  if (base.empty() || base.size() > 4) throw InputError("line attribution: 1 to 4 base frequencies");
  if (max_order < 1 || max_order > 100) throw InputError("line attribution: max_order in 1..100");
  std::vector<std::vector<int>> combos;
  std::vector<int> cur;
  combinations(base.size(), max_order, cur, combos);
  std::vector<LineAttribution> out;
  for (std::size_t i = 0; i < lines.Hz.size(); ++i) {
    LineAttribution a;
    a.Hz = lines.Hz[i];
    a.power_rel = i < lines.power_rel.size() ? lines.power_rel[i] : 0.0;
    double best = INFINITY;
    int best_order = 1 << 30;
    for (const auto& c : combos) {
      double f = 0;
      int order = 0;
      for (std::size_t k = 0; k < base.size(); ++k) {
        f += c[k] * base[k];
        order += std::abs(c[k]);
      }
      if (!(f > 0)) continue;
      const double seen = sample_Hz > 0 ? alias_Hz(f, sample_Hz) : f;
      const double d = std::fabs(seen - a.Hz);
      // The nearest; of combinations equally near (within the tolerance), the lowest order.
      const bool better = (d <= tol_Hz && best <= tol_Hz) ? order < best_order || (order == best_order && d < best) : d < best;
      if (better) {
        best = d;
        best_order = order;
        a.coefficients = c;
        a.combination_Hz = seen;
      }
    }
    a.residual_Hz = a.Hz - a.combination_Hz;
    a.explained = std::fabs(a.residual_Hz) <= tol_Hz;
    out.push_back(a);
  }
  return out;
}

double line_power_fraction(const std::vector<double>& x, double dt, const std::vector<double>& lines_Hz,
                           double half_width_Hz) {
  const Spectrum s = periodogram(x);
  double total = 0, in = 0;
  for (std::size_t k = 1; k < s.freq.size(); ++k) {
    const double f = s.freq[k] / dt;
    total += s.power[k];
    for (double l : lines_Hz)
      if (std::fabs(f - l) <= half_width_Hz) {
        in += s.power[k];
        break;
      }
  }
  return total > 0 ? in / total : 0.0;
}

}  // namespace cvt::analysis
