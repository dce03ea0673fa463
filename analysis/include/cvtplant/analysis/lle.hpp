#pragma once
// Largest Lyapunov exponent from a scalar series (docs/analysis.md#lle):
// Rosenstein et al. (1993) and Kantz (1994) divergence curves, with the
// linear (scaling) region detected automatically and the slope's uncertainty.
#include <cstddef>
#include <vector>

namespace cvt::analysis {

struct LleOptions {
  int m = 3;
  int tau = 1;
  int theiler = -1;      // -1: default_theiler(x)
  int k_max = -1;        // divergence horizon in samples; -1: from the data
  double dt = 1.0;       // sample interval; exponents are per unit of dt's unit
  // Kantz only:
  double eps = -1;       // neighbourhood radius; -1: from the data
  int max_refs = 4000;   // reference points (evenly spaced)
};

// The scaling region: the fit window [k_begin, k_end] (samples).
struct ScalingFit {
  double slope = 0;        // per unit time
  double slope_se = 0;     // OLS standard error, per unit time
  double ci95 = 0;         // half-width: 1.96*max(se, window spread/2)
  double window_spread = 0;// max-min slope over the near-best windows
  double r2 = 0;
  int k_begin = 0, k_end = 0;
  double growth_efolds = 0;  // y(k_end) - y(k_begin)
  bool scaling_region = false;  // false: the curve never grows by 1 e-fold
};
// Picks the longest window with R^2 >= 0.99 before saturation
// (docs/analysis.md#scaling-region).
ScalingFit fit_scaling_region(const std::vector<double>& y, double dt);

struct LleResult {
  std::vector<double> divergence;  // y(k) = <ln d_i(k)>, k = 0..k_max
  std::vector<int> pairs;          // number of pairs averaged at each k
  ScalingFit fit;
  int theiler = 0, k_max = 0;
  double eps = 0;                  // Kantz radius used
  double mean_neighbours = 0;      // Kantz
  std::size_t points = 0;
};

LleResult lle_rosenstein(const std::vector<double>& x, const LleOptions& opt);
LleResult lle_kantz(const std::vector<double>& x, const LleOptions& opt);
// Reference O(N^2) Rosenstein (brute-force neighbour search) for tests and the
// benchmark. Same options and output.
LleResult lle_rosenstein_naive(const std::vector<double>& x, const LleOptions& opt);

}  // namespace cvt::analysis
