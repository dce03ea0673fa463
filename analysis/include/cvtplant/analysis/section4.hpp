#pragma once
// The seed's section 4 pipeline on one sampled plant signal
// (docs/analysis.md#seed-section4): transient removed, normalised, delay from
// AMI, dimension from FNN (and Cao), largest exponent (Rosenstein, Kantz and Wolf),
// recurrence plot and RQA, 0-1 test, and the classify verdict, with figures.
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/wolf.hpp"

namespace cvt::analysis {

struct Section4Options {
  double dt = 1e-3;     // sample interval [s] (the seed: 1 ms)
  long discard = 0;     // leading samples removed (the transient)
  int tau = -1;         // -1: AMI
  int m = -1;           // -1: FNN
  // A series whose std is at most this fraction of its largest magnitude is
  // constant: no delay, dimension or exponent exists (z-scoring divides by 0).
  double constant_rel_std = 1e-9;
  // Called as each stage ends with (stages done, stages): the time history,
  // the classification (AMI, FNN, RQA, exponent, 0-1 test), Cao, Kantz and
  // the figures. Empty: not called.
  std::function<void(int done, int total)> on_stage;
};

struct Section4Result {
  std::string label;
  std::size_t points = 0;  // after the transient
  double mean = 0, stddev = 0, min = 0, max = 0;
  bool constant = false;
  std::string classification, confidence;
  std::vector<std::string> evidence;
  // Estimators (only when !constant). `verdict` holds tau, m, theiler, AMI,
  // FNN, RQA (RR 2 %), Rosenstein and the 0-1 test, with their options.
  Classification verdict;
  CaoResult cao;
  LleResult kantz;
  std::string kantz_error;  // set when Kantz's estimator cannot run on this series (e.g. no recurrence)
  WolfResult wolf;          // Wolf et al.'s estimate at the same embedding (docs/analysis.md#wolf)
  std::string wolf_error;   // set when it cannot run (e.g. no neighbour outside the Theiler window)
  std::vector<std::string> figures;  // PNG paths
};

// `x` is the whole run sampled every opt.dt; the first opt.discard samples are
// the transient (drawn, not analysed). Figures go to out_dir (created).
Section4Result section4_pipeline(const std::vector<double>& x, const Section4Options& opt, const std::string& label,
                                 const std::string& out_dir);

}  // namespace cvt::analysis
