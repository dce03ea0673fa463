// docs/analysis.md#ripple: detrend, spread and dominant frequency of a window.
#include "cvtplant/analysis/ripple.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

RippleWindow ripple_window(const std::vector<double>& t_s, const std::vector<double>& y, double t_begin_s,
                           double t_end_s, const RippleOptions& o) {
  if (t_s.size() != y.size()) throw InputError{"ripple: time and value columns differ in length"};
  if (!(t_end_s > t_begin_s)) throw InputError{"ripple: a window must end after it begins"};
  if (!(o.min_hz >= 0) || !(o.band > 0) || !std::isfinite(o.min_hz) || !std::isfinite(o.band))
    throw InputError{"ripple: min_hz must be >= 0 and band > 0"};
  std::size_t first = t_s.size(), last = 0;
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!std::isfinite(t_s[i]) || !std::isfinite(y[i]))
      throw InputError{"ripple: non-finite value at sample " + std::to_string(i)};
    if (t_s[i] >= t_begin_s && t_s[i] < t_end_s) {
      first = std::min(first, i);
      last = i;
    }
  }
  if (first >= t_s.size() || last - first + 1 < 16)
    throw InputError{"ripple: fewer than 16 samples in the window [" + std::to_string(t_begin_s) + ", " +
                     std::to_string(t_end_s) + ") s"};
  const std::size_t n = last - first + 1;
  const double dt = (t_s[last] - t_s[first]) / static_cast<double>(n - 1);
  for (std::size_t i = first + 1; i <= last; ++i)
    if (!(std::fabs(t_s[i] - t_s[i - 1] - dt) <= 1e-3 * dt))
      throw InputError{"ripple: the time column must increase with a uniform step (sample " + std::to_string(i) + ")"};
  RippleWindow r;
  r.t_begin_s = t_begin_s;
  r.t_end_s = t_end_s;
  r.samples = n;
  const std::vector<double> t(t_s.begin() + static_cast<long>(first), t_s.begin() + static_cast<long>(last) + 1);
  std::vector<double> d(y.begin() + static_cast<long>(first), y.begin() + static_cast<long>(last) + 1);
  r.mean = mean(d);
  const LineFit f = fit_line(t.data(), d.data(), n);
  for (std::size_t i = 0; i < n; ++i) d[i] -= f.intercept + f.slope * t[i];
  r.std = stddev(d);
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  r.peak_to_peak = *hi - *lo;
  const Spectrum s = periodogram(d);
  const double fs = 1.0 / dt;
  std::size_t peak = s.freq.size();
  double total = 0;
  for (std::size_t k = 0; k < s.freq.size(); ++k) {
    total += s.power[k];
    if (s.freq[k] * fs >= o.min_hz && (peak == s.freq.size() || s.power[k] > s.power[peak])) peak = k;
  }
  if (peak == s.freq.size() || !(total > 0))
    throw InputError{"ripple: no frequency between min_hz and the Nyquist frequency, or a constant window"};
  r.peak_hz = s.freq[peak] * fs;
  double band = 0;
  for (std::size_t k = 0; k < s.freq.size(); ++k) {
    const double fk = s.freq[k] * fs;
    if (fk >= r.peak_hz / (1.0 + o.band) && fk <= r.peak_hz * (1.0 + o.band)) band += s.power[k];
  }
  r.line_amplitude = std::sqrt(2.0 * band / total) * r.std;
  return r;
}

}  // namespace cvt::analysis
