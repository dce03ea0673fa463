#pragma once
// The error measures of the plant against the reference
// (docs/validation.md#measures): relative RMS errors, steady-state means,
// the axial force's ripple and the time to gross slip.
#include <cstddef>
#include <string>
#include <vector>

#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// Slip speed of the whole driver wrap above which it is in gross slip [m/s].
inline constexpr double kGrossSlip_m_s = 1.0;

// The relative RMS error of one quantity, the one definition `validate`'s
// tables and `calibrate`'s cost share: over the samples where both plant
// and reference are finite (a NaN marks a missing value: the reference's
// wrap slip with no bolt in the wrap),
//   sqrt(sum (plant - reference)^2 / sum reference^2),
// or the absolute RMS of the difference where the reference is 0 throughout;
// NaN where no sample has both (a quantity one model does not have).
double rel_rms(const std::vector<double>& plant, const std::vector<double>& reference);

// The reference's side of rel_rms, for a fit whose reference is fixed while
// the plant moves: the RMS of the reference over its finite samples (1 if
// it is 0 throughout) and their count.
struct ReferenceScale {
  double rms = 1;
  std::size_t used = 0;
};
ReferenceScale reference_scale(const std::vector<double>& reference);

// Writes the residuals of plant against reference into out[0, n) (n the
// reference's length; the plant must have as many samples): (plant -
// reference) / (rms sqrt(used)) where both are finite, 0 where either is
// not. For a finite plant (a plant that faults is not compared) their sum
// of squares is rel_rms(plant, reference)^2.
void relative_residuals(const std::vector<double>& plant, const std::vector<double>& reference,
                        const ReferenceScale& scale, double* out);

// Error of one quantity: relative RMS over the run, and the mean of each
// model over the steady-state window.
struct ErrorRow {
  std::string quantity, unit;
  double rel_rms = 0;
  double plant_ss = 0, reference_ss = 0, ss_rel = 0;  // ss_rel = (plant - ref) / |ref|
};

struct Comparison {
  std::vector<ErrorRow> rows;
  double compared_s = 0;  // the samples compared: t in [0, compared_s]
  double window_s = 0;  // steady-state window: the last second (or the last half of a shorter run)
  double ripple_plant_N = 0, ripple_reference_N = 0;  // F_ax1 peak to peak over the window
  // Time of the first sample at which the whole driver wrap slides by more
  // than kGrossSlip_m_s (|wrap_slip_m_s|; negative: never).
  double gross_slip_plant_s = -1, gross_slip_reference_s = -1;
};

// plant and reference must share the grid (same t_s) over the first n
// samples of each; the comparison uses those n samples. Throws RunError if
// they have fewer than n (or n < 2) samples or different sample times.
Comparison compare(const Series& plant, const Series& reference, std::size_t n);

}  // namespace cvt::validation
