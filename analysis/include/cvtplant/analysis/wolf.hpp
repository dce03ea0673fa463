#pragma once
// Largest Lyapunov exponent from a scalar series by Wolf, Swift, Swinney and
// Vastano (1985), the fixed-evolution-time algorithm (docs/analysis.md#wolf):
// one neighbour of the reference orbit is followed for a fixed time, its
// stretching logged, and when it has left the small scales it is replaced by
// a nearby point in the direction of the old separation.
#include <cstddef>
#include <vector>

namespace cvt::analysis {

struct WolfOptions {
  int m = 3;
  int tau = 1;
  int theiler = -1;          // -1: default_theiler(x)
  int evolve = -1;           // evolution time [samples]; -1: a quarter of the mean period, at least 1
  double scale_min = -1;     // smallest separation [series units]; -1: 1e-3 of the series' extent
  double scale_max = -1;     // separation at which the neighbour is replaced; -1: 0.1 of the extent
  double max_angle_rad = 0.3;  // a replacement's largest angle to the old separation (Wolf et al.'s 0.3)
  int batches = 10;          // batch means for the confidence interval
  double dt = 1.0;           // sample interval; the exponent is per unit of dt's unit
};

struct WolfResult {
  double lambda = 0;         // per unit time
  double ci95 = 0;           // half-width from the batch means (Student t)
  std::vector<double> batch_lambda;
  std::vector<double> running;  // the estimate after each evolution step
  int m = 0, tau = 0, theiler = 0, evolve = 0;
  double scale_min = 0, scale_max = 0, max_angle_rad = 0;
  std::size_t points = 0;    // delay vectors
  int steps = 0;             // evolution steps averaged
  int kept = 0;              // steps whose neighbour stayed within the scales
  int replaced = 0;          // replacements within max_angle and scale_max
  int relaxed = 0;           // replacements that needed a wider radius or angle
  int unreplaced = 0;        // no candidate at all: the evolved neighbour was kept
  int collapsed = 0;         // steps whose pair met exactly (repeated samples): not averaged
  double mean_angle_rad = 0; // over the replacements
  double mean_log_scale = 0; // <ln d> at the steps' starts
};

// Throws InputError for bad options or a series too short for them.
WolfResult lle_wolf(const std::vector<double>& x, const WolfOptions& opt);

}  // namespace cvt::analysis
