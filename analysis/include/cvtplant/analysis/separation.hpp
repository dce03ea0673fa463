#pragma once
// Growth of the distance between two runs of one system that differ only in
// their numerics (a tighter tolerance, another integrator)
// (docs/analysis.md#separation). Their difference starts at the numerical
// error and is fed by it all along; on a chaotic attractor it grows
// exponentially at the largest exponent until it saturates at the
// attractor's size, on a regular one at most like a power of time (a phase
// drift along a cycle or a torus). A run whose difference stays small over
// the record bounds the largest exponent from above.
#include <vector>

#include "cvtplant/analysis/lle.hpp"

namespace cvt::analysis {

struct SeparationOptions {
  double dt = 1.0;   // sample interval [s]
  int block = 10;    // samples per point of the curve: the largest |a - b| over the block
};

struct Separation {
  std::vector<double> t_s;      // the block's end time
  std::vector<double> log_sep;  // ln(max over the block |a - b| / std(a)); -inf where equal
  double first = 0, last = 0, max = 0;  // log_sep of the first block that differs, the last, the largest
  double t_first_s = 0;         // end of the first block where the runs differ
  bool differ = false;          // the runs differ at all
  bool saturated = false;       // the separation reached a tenth of std(a)
  double t_saturated_s = -1;
  // The scaling region of log_sep against t from the first differing block
  // (docs/analysis.md#scaling-region): an exponential rate [1/s] with its CI.
  ScalingFit exponential;
  // The same window fitted against ln t (t from the release): the exponent of
  // a power law, and R^2 of both fits over that window.
  double power_law_exponent = 0, power_law_r2 = 0, exponential_r2 = 0;
  // exponential growth: a scaling region, a rate whose CI excludes 0, and the
  // exponential fitting the window at least as well as the power law.
  bool exponential_growth = false;
  // Upper bound on the largest exponent when the runs never saturate:
  // (max - first) / (t at max - t_first) [1/s]; 0 otherwise.
  double rate_bound = 0;
};

// a and b sampled on the same grid from the same start. Throws InputError for
// different lengths, fewer than 4 blocks, a non-finite value or a constant a.
Separation separation_growth(const std::vector<double>& a, const std::vector<double>& b, const SeparationOptions& opt);

}  // namespace cvt::analysis
