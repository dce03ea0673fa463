#pragma once
// Gottwald-Melbourne 0-1 test for chaos, correlation method with the
// oscillatory term removed (docs/analysis.md#test01). K ~ 0: regular
// (periodic or quasi-periodic); K ~ 1: chaotic OR stochastic (noise also gives
// K ~ 1, so K alone never proves determinism).
#include <vector>

namespace cvt::analysis {

struct Test01Options {
  int subsample = 1;     // use every `subsample`-th point (oversampled flows need > 1)
  int n_c = 100;         // number of random frequencies c in (pi/5, 4pi/5)
  int max_points = 5000; // after subsampling, the first max_points are used
  unsigned seed = 20240601u;
};
struct Test01Result {
  double k_median = 0;
  double k_q25 = 0, k_q75 = 0;  // spread over c
  int points = 0;
  int subsample = 1;
};
Test01Result test01(const std::vector<double>& x, const Test01Options& opt);

}  // namespace cvt::analysis
