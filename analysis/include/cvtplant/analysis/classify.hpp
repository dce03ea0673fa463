#pragma once
// A verdict from a scalar series with the evidence behind it
// (docs/analysis.md#classify): fixed_point, periodic, quasi_periodic, chaotic
// or inconclusive. Every estimator's number is returned so a user can disagree.
#include <string>
#include <vector>

#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/rqa.hpp"
#include "cvtplant/analysis/test01.hpp"

namespace cvt::analysis {

struct ClassifyOptions {
  double dt = 1.0;          // sample interval
  int tau = -1;             // -1: AMI
  int m = -1;               // -1: FNN
  int theiler = -1;         // -1: default_theiler
  int m_max = 8;
  int test01_subsample = -1;  // -1: tau
  // Compute every estimator even when step 1 already decides fixed_point
  // (the seed-section4 pipeline reports delay, dimension, exponent and RQA
  // whatever the verdict).
  bool full_evidence = false;
};

struct SpectralPeaks {
  std::vector<double> freq;   // cycles/sample, interpolated, strongest first
  double fundamental = 0;     // lowest significant peak
  double worst_harmonic_error = 0;  // max |f/f0 - round(f/f0)|
  bool harmonic = false;      // all significant peaks are harmonics of f0
};
SpectralPeaks spectral_peaks(const std::vector<double>& x);

struct Classification {
  std::string classification;  // fixed_point | periodic | quasi_periodic | chaotic | inconclusive
  std::string confidence;      // strong | weak
  std::vector<std::string> reasons;
  // Evidence
  AmiResult ami;
  FnnResult fnn;
  int tau = 0, m = 0, theiler = 0;
  RqaResult rqa;
  RqaOptions rqa_options;  // as used (RR 2 %, Theiler, lmin = vmin from the embedding)
  LleResult lle;
  LleOptions lle_options;  // as used (m, tau, Theiler, dt)
  Test01Result t01;
  SpectralPeaks peaks;
  double amplitude_decay = 0;  // std(first quarter)/std(last quarter)
  double mean_period_s = 0;    // Rosenstein's mean period times dt (the exponent's per-period scale)
  bool deterministic = false;
};

Classification classify(const std::vector<double>& x, const ClassifyOptions& opt);

}  // namespace cvt::analysis
