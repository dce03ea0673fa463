#pragma once
// Link-passing analysis (docs/analysis.md#link-rates): the rate at which a
// chain's links enter each pulley's wrap, the ratio of two such rates and how
// close it is to a ratio of small integers, and the spectral lines of a signal
// explained as integer combinations of given base frequencies. Two
// incommensurate forcing rates make a quasi-periodic response (a torus) whose
// spectrum and recurrence plot look irregular without any chaos; a signal
// whose strong lines are all such combinations, with little broadband power,
// is of that kind.
#include <vector>

#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

// Events per unit time over [t0, t1): (count - 1) / (last - first) of the
// sorted event times in the window (a mean rate between the first and the
// last event, free of where the window's ends fall). 0 with fewer than 2.
struct EventRate {
  double Hz = 0;
  std::size_t events = 0;
  double resolution_Hz = 0;  // from the events' time quantum: 2 quantum / (last - first) of the rate
};
EventRate event_rate(const std::vector<double>& sorted_times_s, double t0_s, double t1_s, double quantum_s);

// The best rational approximation p/q (q <= q_max) of `ratio` by continued
// fractions, and whether the ratio is indistinguishable from it at the
// relative resolution given.
struct RationalRatio {
  double ratio = 0;
  long p = 0, q = 1;
  double error_rel = 0;        // |ratio - p/q| / ratio
  double resolution_rel = 0;
  bool rational = false;       // error_rel <= resolution_rel
};
RationalRatio rational_ratio(double ratio, double resolution_rel, long q_max = 20);

// One spectral line as the combination sum n_k base_k (sum |n_k| <= max_order,
// the combination positive) nearest to it. With sample_Hz > 0 each
// combination is first folded into [0, sample_Hz / 2], where sampling puts
// it (a sharp periodic pulse sampled at 1 kHz shows its harmonics above
// 500 Hz as aliases below).
struct LineAttribution {
  double Hz = 0, power_rel = 0;
  std::vector<int> coefficients;  // n_k per base
  double combination_Hz = 0, residual_Hz = 0;  // where the combination is seen (folded), and the line's distance from it
  bool explained = false;         // |residual| <= tol_Hz
};
std::vector<LineAttribution> attribute_lines(const Lines& lines, const std::vector<double>& base_Hz, int max_order,
                                             double tol_Hz, double sample_Hz = 0);

// A frequency as sampling at sample_Hz shows it: folded into [0, sample_Hz / 2].
double alias_Hz(double f_Hz, double sample_Hz);

// Fraction of the periodogram's power (the mean removed) within +-half_width_Hz
// of the given lines: near 1 for a line spectrum (periodic, quasi-periodic),
// well below for broadband motion (noise, chaos).
double line_power_fraction(const std::vector<double>& x, double dt, const std::vector<double>& lines_Hz,
                           double half_width_Hz);

}  // namespace cvt::analysis
