// Separation of two runs (docs/analysis.md#separation).
#include "cvtplant/analysis/separation.hpp"

#include <algorithm>
#include <cmath>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

Separation separation_growth(const std::vector<double>& a, const std::vector<double>& b, const SeparationOptions& o) {
  if (a.size() != b.size()) throw InputError("separation: the two runs differ in length");
  if (o.block < 1 || !(o.dt > 0)) throw InputError("separation: block >= 1 and dt > 0");
  const std::size_t nb = a.size() / static_cast<std::size_t>(o.block);
  if (nb < 4) throw InputError("separation: fewer than 4 blocks");
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(a[i]) || !std::isfinite(b[i]))
      throw InputError("separation: sample " + std::to_string(i) + " is not finite");
  const double sd = stddev(a);
  if (!(sd > 0)) throw InputError("separation: the first run is constant");
  Separation s;
  s.max = -INFINITY;
  std::size_t first_block = nb;
  for (std::size_t k = 0; k < nb; ++k) {
    double d = 0;
    for (std::size_t i = k * o.block; i < (k + 1) * o.block; ++i) d = std::max(d, std::fabs(a[i] - b[i]));
    s.t_s.push_back(static_cast<double>((k + 1) * o.block - 1) * o.dt);
    const double l = d > 0 ? std::log(d / sd) : -INFINITY;
    s.log_sep.push_back(l);
    if (d > 0 && first_block == nb) first_block = k;
    if (l > s.max) s.max = l;
    if (!s.saturated && l >= std::log(0.1)) {
      s.saturated = true;
      s.t_saturated_s = s.t_s.back();
    }
  }
  if (first_block == nb) return s;  // identical runs
  s.differ = true;
  s.first = s.log_sep[first_block];
  s.last = s.log_sep.back();
  s.t_first_s = s.t_s[first_block];
  // Blocks where the runs are equal to the last bit carry no distance; the
  // curve from the first differing block on, equal blocks at the curve's
  // running level (the distance cannot be resolved below it).
  std::vector<double> y, t;
  double level = s.first;
  for (std::size_t k = first_block; k < nb; ++k) {
    if (std::isfinite(s.log_sep[k])) level = s.log_sep[k];
    y.push_back(level);
    t.push_back(s.t_s[k]);
  }
  s.exponential = fit_scaling_region(y, o.dt * o.block);
  // Both laws over the exponential fit's window.
  const std::size_t k0 = static_cast<std::size_t>(s.exponential.k_begin), k1 = static_cast<std::size_t>(s.exponential.k_end);
  if (k1 > k0 + 2) {
    std::vector<double> lt, ly;
    for (std::size_t k = k0; k <= k1; ++k) {
      lt.push_back(std::log(t[k]));
      ly.push_back(y[k]);
    }
    const LineFit pw = fit_line(lt.data(), ly.data(), lt.size());
    const LineFit ex = fit_line(t.data() + k0, y.data() + k0, k1 - k0 + 1);
    s.power_law_exponent = pw.slope;
    s.power_law_r2 = pw.r2;
    s.exponential_r2 = ex.r2;
  }
  s.exponential_growth = s.exponential.scaling_region && s.exponential.slope - s.exponential.ci95 > 0 &&
                         s.exponential_r2 >= s.power_law_r2;
  if (!s.saturated) {
    std::size_t kmax = first_block;
    for (std::size_t k = first_block; k < nb; ++k)
      if (s.log_sep[k] >= s.log_sep[kmax]) kmax = k;
    if (s.t_s[kmax] > s.t_first_s) s.rate_bound = (s.max - s.first) / (s.t_s[kmax] - s.t_first_s);
  }
  return s;
}

}  // namespace cvt::analysis
