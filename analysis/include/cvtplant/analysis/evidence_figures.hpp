#pragma once
// The figures of the seed's section 4 and of the evidence behind a chaos
// verdict (docs/analysis.md#evidence-figures), drawn by gnuplot from data
// files written next to them: the window's time history, delay
// reconstructions at given delays (seed Figs. 15-16), AMI, FNN with Cao
// (Fig. 17), divergence curves (Figs. 18-20), the recurrence plot (Figs.
// 21-22), the spectrum with marked frequencies, the surrogate statistics,
// the separation of runs that differ only in their numerics and the running
// estimate of the equations' largest exponent.
#include <string>
#include <utility>
#include <vector>

#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/separation.hpp"
#include "cvtplant/analysis/surrogates.hpp"

namespace cvt::analysis {

struct EvidenceFigures {
  std::string label;       // names the signal and the run in every title
  std::vector<double> x;   // the analysed window (raw units)
  double dt = 1e-3;        // [s]
  std::string unit;        // of x
  std::vector<int> delays;  // delay reconstructions, one panel each (up to 4)
  AmiResult ami;
  int seed_tau = 1;         // marked on the AMI figure
  FnnResult fnn;
  CaoResult cao;
  // Divergence curves: a legend label and the estimate.
  std::vector<std::pair<std::string, LleResult>> divergence;
  int rp_m = 3, rp_tau = 1;  // recurrence plot embedding (z-scored series)
  double rp_rr = 0.02;       // its radius gives this recurrence rate
  std::vector<std::pair<std::string, double>> marks_Hz;  // frequencies marked on the spectrum
  bool has_surrogates = false;
  SurrogateTest surrogates;
  std::vector<std::pair<std::string, Separation>> separations;
  // The largest exponent of the equations as it accumulated (two
  // trajectories): running estimate against time, with its final value and CI.
  bool has_exponent = false;
  std::vector<double> exponent_t_s, exponent_running;
  double exponent = 0, exponent_ci95 = 0;
};

// Writes the PNGs into out_dir (created) and returns their paths.
std::vector<std::string> evidence_figures(const EvidenceFigures& f, const std::string& out_dir);

}  // namespace cvt::analysis
