#pragma once
// Surrogate-data test (docs/analysis.md#surrogates): iterated
// amplitude-adjusted Fourier-transform (IAAFT) surrogates, which keep a
// series' value distribution exactly and its power spectrum closely but
// destroy every other structure, and nonlinear statistics compared between
// the data and the surrogates by rank. The null hypothesis is a stationary
// linear Gaussian process seen through a static monotone function; rejecting
// it shows nonlinear structure (a limit cycle with harmonics locked in phase
// rejects it too), not chaos on its own.
#include <cstdint>
#include <string>
#include <vector>

namespace cvt::analysis {

// The sub-series [begin, begin + length) whose two ends join best when the
// series is continued periodically, as the discrete Fourier transform assumes
// (Schreiber & Schmitz 2000): mismatch = ((x_first - x_last)^2 + (slope at the
// start - slope at the end)^2) / (N var x). The length is at least
// min_fraction of the series and has no prime factor above 5 (a fast
// transform). Throws InputError for fewer than 64 points.
struct Segment {
  std::size_t begin = 0, length = 0;
  double mismatch = 0;
};
Segment end_matched_segment(const std::vector<double>& x, double min_fraction = 0.9);

// One IAAFT surrogate of x (Schreiber & Schmitz 1996): a random shuffle of x,
// then alternately the Fourier amplitudes of x imposed (phases kept) and the
// values of x imposed by rank, until the ranks stop changing or after
// max_iterations. Deterministic for a given seed. spectrum_error: the
// relative L2 difference of the surrogate's Fourier amplitudes from x's.
struct Surrogate {
  std::vector<double> x;
  int iterations = 0;
  double spectrum_error = 0;
};
Surrogate iaaft(const std::vector<double>& x, std::uint64_t seed, int max_iterations = 1000);

// Time-reversal asymmetry at `lag`: <(x_{i+lag} - x_i)^3> / <(x_{i+lag} - x_i)^2>^{3/2};
// zero in expectation for any time-reversible process (every linear Gaussian one).
double time_reversal_asymmetry(const std::vector<double>& x, int lag);

// Nonlinear prediction error: the zeroth-order (locally constant) predictor
// in the delay embedding (m, tau): x_{i+horizon} predicted by the mean of the
// `neighbours` nearest delay vectors' futures (neighbours outside the Theiler
// window), over up to max_refs evenly spaced reference points; the RMS error
// over the series' standard deviation.
struct PredictionOptions {
  int m = 3;
  int tau = 1;
  int horizon = 1;
  int neighbours = 5;
  int theiler = 0;
  int max_refs = 2000;
};
double prediction_error(const std::vector<double>& x, const PredictionOptions& opt);

// A statistic on the data and on each surrogate. rank_low / rank_high: the
// data's rank among all n + 1 values from below / from above (1 = the data is
// the smallest / the largest). p: the rank test's p-value in the statistic's
// tail ("lower": rank_low / (n + 1); "upper": rank_high / (n + 1); "two-sided":
// twice the smaller of the two, at most 1).
struct SurrogateStatistic {
  std::string name, tail;
  double data = 0;
  std::vector<double> surrogates;
  int rank_low = 0, rank_high = 0;
  double p = 1;
  bool significant = false;  // p <= alpha
};

struct SurrogateTestOptions {
  int count = 19;            // surrogates: 19 give p = 0.05 one-sided at rank 1
  std::uint64_t seed = 20260601u;
  int m = 3, tau = 1, theiler = 0;  // embedding of the prediction error and the exponent
  int horizon = 1;           // prediction horizon [samples]
  double dt = 1.0;           // sample interval (the exponent's unit)
  double alpha = 0.05;
  bool exponent = true;      // also rank the Rosenstein exponent (m, tau, theiler)
  double min_fraction = 0.9; // of the series kept by end matching
};

struct SurrogateTest {
  Segment segment;
  int count = 0;
  std::uint64_t seed = 0;
  int max_iterations_used = 0;
  double worst_spectrum_error = 0;
  std::vector<SurrogateStatistic> statistics;  // time_reversal_asymmetry, prediction_error[, rosenstein_exponent]
  // The null hypothesis is rejected by a nonlinear statistic: the prediction
  // error (lower tail) or the time-reversal asymmetry (two-sided).
  bool nonlinear = false;
};
SurrogateTest surrogate_test(const std::vector<double>& x, const SurrogateTestOptions& opt);

}  // namespace cvt::analysis
