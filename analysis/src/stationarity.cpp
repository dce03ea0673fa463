// Stationarity over consecutive windows (docs/analysis.md#stationarity).
#include "cvtplant/analysis/stationarity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/link_rates.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

Stationarity stationarity(const std::vector<double>& x, const StationarityOptions& o) {
  if (o.windows < 2) throw InputError("stationarity: at least 2 windows");
  if (!(o.dt > 0)) throw InputError("stationarity: dt must be > 0");
  const std::size_t len = x.size() / static_cast<std::size_t>(o.windows);
  if (len < 64) throw InputError("stationarity: fewer than 64 samples per window");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) throw InputError("stationarity: sample " + std::to_string(i) + " is not finite");
  Stationarity s;
  const double sd = stddev(x);
  const Lines whole = spectral_lines(x, o.dt, 1);
  s.dominant_Hz = whole.Hz.empty() ? 0.0 : whole.Hz[0];
  double mean_lo = INFINITY, mean_hi = -INFINITY, std_lo = INFINITY, std_hi = 0;
  const double bin = 1.0 / (static_cast<double>(len) * o.dt);  // a window's own resolution (not the padded bin)
  for (int w = 0; w < o.windows; ++w) {
    const auto b = x.begin() + static_cast<long>(w * len);
    const std::vector<double> part(b, b + static_cast<long>(len));
    WindowStats ws;
    ws.t_begin_s = static_cast<double>(w * len) * o.dt;
    ws.t_end_s = static_cast<double>((w + 1) * len) * o.dt;
    ws.mean = mean(part);
    ws.std = stddev(part);
    if (ws.std > 0) ws.mean_Hz = 1.0 / (mean_period_samples(part) * o.dt);
    mean_lo = std::min(mean_lo, ws.mean);
    mean_hi = std::max(mean_hi, ws.mean);
    std_lo = std::min(std_lo, ws.std);
    std_hi = std::max(std_hi, ws.std);
    if (ws.std > 0) {
      const Lines l = spectral_lines(part, o.dt, std::max(o.peaks_per_window, 20));
      for (std::size_t k = 0; k < l.Hz.size(); ++k) {
        if (static_cast<int>(k) < o.peaks_per_window) {
          ws.peaks_Hz.push_back(l.Hz[k]);
          ws.peak_power_rel.push_back(l.power_rel[k]);
        }
        // The line nearest the series' dominant one, among those with at least
        // a tenth of the window's strongest power.
        if (l.power_rel[k] >= 0.1 &&
            (ws.dominant_line_Hz == 0 || std::fabs(l.Hz[k] - s.dominant_Hz) < std::fabs(ws.dominant_line_Hz - s.dominant_Hz)))
          ws.dominant_line_Hz = l.Hz[k];
      }
    }
    s.windows.push_back(ws);
  }
  s.mean_shift = sd > 0 ? (mean_hi - mean_lo) / sd : 0.0;
  s.std_ratio = std_lo > 0 ? std_hi / std_lo : INFINITY;
  s.line_tolerance = s.dominant_Hz > 0 ? std::max(o.max_line_shift, 2.0 * bin / s.dominant_Hz) : o.max_line_shift;
  s.dominant_fraction = s.dominant_Hz > 0 ? line_power_fraction(x, o.dt, {s.dominant_Hz}, 2.0 * bin) : 0.0;
  s.line_tested = s.dominant_fraction >= o.min_line_fraction;
  for (const auto& ws : s.windows)
    if (s.dominant_Hz > 0)
      s.line_shift = std::max(s.line_shift, ws.dominant_line_Hz > 0 ? std::fabs(ws.dominant_line_Hz - s.dominant_Hz) / s.dominant_Hz
                                                                    : INFINITY);
  double f_lo = INFINITY, f_hi = 0, f_sum = 0;
  for (const auto& ws : s.windows) {
    f_lo = std::min(f_lo, ws.mean_Hz);
    f_hi = std::max(f_hi, ws.mean_Hz);
    f_sum += ws.mean_Hz;
  }
  s.mean_frequency_shift = f_sum > 0 ? (f_hi - f_lo) / (f_sum / static_cast<double>(s.windows.size())) : 0.0;
  char buf[256];
  bool ok = true;
  std::snprintf(buf, sizeof buf, "window means differ by %.3g standard deviations of the series (stationary needs <= %.3g)",
                s.mean_shift, o.max_mean_shift);
  s.reasons.push_back(buf);
  ok = ok && s.mean_shift <= o.max_mean_shift;
  std::snprintf(buf, sizeof buf, "largest over smallest window standard deviation %.3g (stationary needs <= %.3g)",
                s.std_ratio, o.max_std_ratio);
  s.reasons.push_back(buf);
  ok = ok && s.std_ratio <= o.max_std_ratio;
  if (s.line_tested) {
    std::snprintf(buf, sizeof buf,
                  "dominant line %.4g Hz (%.3g of the power) moves by up to %.3g of itself between windows (stationary "
                  "needs <= %.3g: %.3g or 2 bins of a window)",
                  s.dominant_Hz, s.dominant_fraction, s.line_shift, s.line_tolerance, o.max_line_shift);
    ok = ok && s.line_shift <= s.line_tolerance;
  } else {
    std::snprintf(buf, sizeof buf,
                  "broadband (the strongest line, %.4g Hz, carries %.3g of the power): the windows' mean frequencies "
                  "differ by %.3g of their mean (stationary needs <= %.3g)",
                  s.dominant_Hz, s.dominant_fraction, s.mean_frequency_shift, o.max_mean_frequency_shift);
    ok = ok && s.mean_frequency_shift <= o.max_mean_frequency_shift;
  }
  s.reasons.push_back(buf);
  s.stationary = ok;
  return s;
}

}  // namespace cvt::analysis
