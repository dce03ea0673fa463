// The error measures of the plant against the reference (docs/validation.md#measures).
#include "cvtplant/validation/compare.hpp"

#include <algorithm>
#include <cmath>

#include "cvtplant/validation/errors.hpp"

namespace cvt::validation {

namespace {

bool both_finite(double a, double b) { return std::isfinite(a) && std::isfinite(b); }

}  // namespace

double rel_rms(const std::vector<double>& plant, const std::vector<double>& reference) {
  double d2 = 0, r2 = 0;
  std::size_t used = 0;
  const std::size_t n = std::min(plant.size(), reference.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!both_finite(plant[i], reference[i])) continue;
    d2 += (plant[i] - reference[i]) * (plant[i] - reference[i]);
    r2 += reference[i] * reference[i];
    ++used;
  }
  // No sample to compare (a quantity one model does not have): no error, not 0.
  if (used == 0) return std::nan("");
  return r2 > 0 ? std::sqrt(d2 / r2) : std::sqrt(d2 / static_cast<double>(used));
}

ReferenceScale reference_scale(const std::vector<double>& reference) {
  double r2 = 0;
  ReferenceScale s;
  for (const double r : reference)
    if (std::isfinite(r)) {
      r2 += r * r;
      ++s.used;
    }
  if (r2 > 0) s.rms = std::sqrt(r2 / static_cast<double>(s.used));
  return s;
}

void relative_residuals(const std::vector<double>& plant, const std::vector<double>& reference,
                        const ReferenceScale& scale, double* out) {
  // (plant - reference) / (rms sqrt(used)): summed in squares, sum d^2 /
  // sum r^2, rel_rms squared (or sum d^2 / used where rms is 1).
  const double w = 1.0 / std::sqrt(static_cast<double>(std::max<std::size_t>(1, scale.used)));
  for (std::size_t i = 0; i < reference.size(); ++i)
    out[i] = both_finite(plant[i], reference[i]) ? w * (plant[i] - reference[i]) / scale.rms : 0.0;
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
    throw RunError("plant and reference have too few common samples to compare");
  const Series plant = plant_all.select(n), ref = ref_all.select(n);
  for (std::size_t i = 0; i < plant.size(); ++i)
    if (std::fabs(plant.t_s[i] - ref.t_s[i]) > 1e-9) throw RunError("plant and reference have different sample times");
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
  row("geometric ratio r2/r1", "-", plant.ratio_geom, ref.ratio_geom, from);
  row("F_ax2 (mean)", "N", plant.F_ax2_N, ref.F_ax2_N, from);
  c.ripple_plant_N = peak_to_peak_from(plant.F_ax1_N, from);
  c.ripple_reference_N = peak_to_peak_from(ref.F_ax1_N, from);
  c.gross_slip_plant_s = first_gross_slip(plant, kGrossSlip_m_s);
  c.gross_slip_reference_s = first_gross_slip(ref, kGrossSlip_m_s);
  return c;
}

}  // namespace cvt::validation
