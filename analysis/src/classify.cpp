#include "cvtplant/analysis/classify.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"
#include "fmt.hpp"

namespace cvt::analysis {
namespace {

using detail::fmt;

double quarter_std(const std::vector<double>& x, int q) {
  const std::size_t n = x.size() / 4;
  std::vector<double> part(x.begin() + static_cast<long>(q * n), x.begin() + static_cast<long>((q + 1) * n));
  return stddev(part);
}

}  // namespace

// docs/analysis.md#spectral-lines: the lines within 20 dB of the strongest
// (in cycles per sample), the lowest taken as the fundamental.
SpectralPeaks spectral_peaks(const std::vector<double>& x) {
  SpectralPeaks r;
  const Lines lines = spectral_lines(x, 1.0, 20);
  r.freq = lines.Hz;
  if (r.freq.empty()) return r;
  const double df = lines.resolution_Hz;
  r.fundamental = *std::min_element(r.freq.begin(), r.freq.end());
  // A fundamental within 3 bins of DC cannot be resolved: no verdict.
  if (r.fundamental < 3 * df) return r;
  for (double f : r.freq) {
    const double h = f / r.fundamental;
    r.worst_harmonic_error = std::max(r.worst_harmonic_error, std::abs(h - std::round(h)));
  }
  r.harmonic = r.worst_harmonic_error <= 0.05;
  return r;
}

// docs/analysis.md#classify
Classification classify(const std::vector<double>& x, const ClassifyOptions& opt) {
  validate_series(x, 500, "classify");
  if (!(opt.dt > 0)) throw InputError("classify: dt must be > 0");
  Classification c;
  // 1. Decay to a fixed point (docs/analysis.md#classify): the amplitude falls
  // monotonically by 100x or more, or it is still falling geometrically (by
  // >= 1.5x from each quarter to the next, >= 10x in all) at the end of the
  // series: a stationary motion (periodic, quasi-periodic, chaotic) keeps its
  // amplitude, and a transient towards a cycle levels off.
  const double s1 = quarter_std(x, 0), s2 = quarter_std(x, 1), s3 = quarter_std(x, 2), s4 = quarter_std(x, 3);
  c.amplitude_decay = s4 > 0 ? s1 / s4 : 1e300;
  double scale = 0;
  for (double v : x) scale = std::max(scale, std::abs(v));
  const bool geometric = s4 > 0 && s2 >= 1.5 * s3 && s1 >= 1.5 * s2 && s3 >= 1.5 * s4 && s1 >= 10 * s4;
  const bool decays = (s4 <= 1e-2 * s1 && s4 <= s3 && s3 <= s2) || s4 <= 1e-9 * scale || geometric;
  if (decays) {
    c.classification = "fixed_point";
    c.confidence = s4 <= 1e-3 * s1 ? "strong" : "weak";
    c.reasons.push_back(fmt("amplitude (std) decays %.3g-fold from the first to the last quarter", c.amplitude_decay));
    if (s4 > 0)
      c.reasons.push_back(fmt("quarter-to-quarter std ratios %.3g, %.3g, %.3g: still decaying at the end", s1 / s2,
                              s2 / s3, s3 / s4));
    if (!opt.full_evidence) return c;
  }
  const std::vector<double> z = zscore(x);
  c.theiler = opt.theiler >= 0 ? opt.theiler : default_theiler(z);
  c.ami = average_mutual_information(z, std::min<int>(static_cast<int>(z.size() / 10), 500));
  c.tau = opt.tau > 0 ? opt.tau : c.ami.tau;
  FnnOptions fo;
  fo.tau = c.tau;
  fo.m_max = opt.m_max;
  fo.theiler = c.theiler;
  c.fnn = false_nearest_neighbours(z, fo);
  c.m = opt.m > 0 ? opt.m : std::max(2, c.fnn.dimension);
  const double fnn_min = *std::min_element(c.fnn.fraction.begin(), c.fnn.fraction.end());

  const Embedding e = delay_embed(z, c.m, c.tau);
  RqaOptions& ro = c.rqa_options;
  ro.target_rr = 0.02;
  ro.theiler = c.theiler;
  ro.lmin = default_lmin(c.m, c.tau);
  ro.vmin = ro.lmin;
  c.rqa = rqa(e, ro);

  LleOptions& lo = c.lle_options;
  lo.m = c.m;
  lo.tau = c.tau;
  lo.theiler = c.theiler;
  lo.dt = opt.dt;
  c.lle = lle_rosenstein(z, lo);

  Test01Options to;
  // Subsample by the delay (oversampled flows give K ~ 0 otherwise), but keep
  // at least 1000 points for the regression over n <= N/10.
  to.subsample = opt.test01_subsample > 0
                     ? opt.test01_subsample
                     : std::max(1, std::min(c.tau, static_cast<int>(z.size() / 1000)));
  c.t01 = test01(z, to);
  c.peaks = spectral_peaks(z);

  // 2. Determinism: FNN reaches a few percent and the RP has long diagonals.
  c.deterministic = fnn_min <= 0.05 && c.rqa.det >= 0.8;
  c.reasons.push_back(fmt("FNN minimum %.3f at tau=%g (determinism needs <= 0.05)", fnn_min, c.tau));
  c.reasons.push_back(fmt("RQA DET %.3f at RR %.3f (determinism needs >= 0.8)", c.rqa.det, c.rqa.rr));
  c.reasons.push_back(fmt("0-1 test K = %.3f (IQR %.3f..%.3f)", c.t01.k_median, c.t01.k_q25, c.t01.k_q75));
  // Exponent in units of the mean period: how many e-folds per cycle.
  const double period_s = mean_period_samples(z) * opt.dt;
  c.mean_period_s = period_s;
  const double lam = c.lle.fit.slope, ci = c.lle.fit.ci95;
  c.reasons.push_back(fmt("largest exponent (Rosenstein) %.4g +- %.2g per unit time, %.3g per mean period", lam, ci,
                          lam * period_s));
  if (decays) {
    c.reasons.push_back("the decay decides: the estimators above describe the transient towards the fixed point");
    return c;
  }
  if (!c.deterministic) {
    c.classification = "inconclusive";
    c.confidence = "weak";
    c.reasons.push_back("no low-dimensional determinism: noise-like or high-dimensional; a positive exponent or K~1 "
                        "would not prove chaos here");
    return c;
  }
  const bool lle_positive = c.lle.fit.scaling_region && lam - ci > 0 && lam * period_s >= 0.05;
  const bool lle_zero = !c.lle.fit.scaling_region || lam * period_s < 0.02 || lam - ci <= 0;
  const bool k_chaos = c.t01.k_median >= 0.8;
  const bool k_regular = c.t01.k_median <= 0.2;
  if (lle_positive && k_chaos) {
    c.classification = "chaotic";
    c.confidence = "strong";
    c.reasons.push_back("positive exponent with a scaling region, K near 1 and deterministic structure agree");
  } else if (k_regular && lle_zero) {
    c.classification = c.peaks.harmonic ? "periodic" : "quasi_periodic";
    c.confidence = "strong";
    c.reasons.push_back(std::string("regular: K near 0 and no exponential divergence; spectral peaks ") +
                        (c.peaks.harmonic ? "are harmonics of one fundamental" : "are not harmonics of one fundamental") +
                        fmt(" (worst harmonic error %.3f, fundamental %.4g cycles/sample)", c.peaks.worst_harmonic_error,
                            c.peaks.fundamental));
  } else if (lle_positive || k_chaos) {
    c.classification = "inconclusive";
    c.confidence = "weak";
    c.reasons.push_back(std::string("tests disagree: ") + (lle_positive ? "exponent positive" : "exponent ~0") + ", " +
                        (k_chaos ? "K ~ 1" : "K not near 1"));
  } else {
    c.classification = "inconclusive";
    c.confidence = "weak";
    c.reasons.push_back("K between 0.2 and 0.8 or exponent ambiguous");
  }
  return c;
}

}  // namespace cvt::analysis
