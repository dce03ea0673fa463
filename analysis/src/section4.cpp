// The seed's section 4 pipeline on one plant signal (docs/analysis.md#seed-section4).
#include "cvtplant/analysis/section4.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

Section4Result section4_pipeline(const std::vector<double>& x_all, const Section4Options& opt, const std::string& label,
                                 const std::string& out_dir) {
  if (!(opt.dt > 0)) throw InputError("seed-section4: dt must be > 0");
  if (opt.discard < 0 || static_cast<std::size_t>(opt.discard) >= x_all.size())
    throw InputError("seed-section4: the transient (" + std::to_string(opt.discard) + " samples) leaves no data of " +
                     std::to_string(x_all.size()));
  Section4Result r;
  r.label = label;
  const std::vector<double> x(x_all.begin() + opt.discard, x_all.end());
  r.points = x.size();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) throw InputError(label + ": sample " + std::to_string(i) + " is not finite");
  r.mean = mean(x);
  r.stddev = stddev(x);
  r.min = *std::min_element(x.begin(), x.end());
  r.max = *std::max_element(x.begin(), x.end());
  constexpr int kStages = 5;
  auto stage = [&](int k) {
    if (opt.on_stage) opt.on_stage(k, kStages);
  };
  r.figures.push_back(run_time_history_figure(x_all, opt.dt, opt.discard, label, out_dir));
  stage(1);
  const double scale = std::max(std::abs(r.min), std::abs(r.max));
  char buf[320];
  if (r.stddev <= opt.constant_rel_std * std::max(scale, 1e-300)) {
    // A constant signal is a fixed point of whatever produces it; delay
    // embedding, FNN, exponents and RQA are undefined on it.
    r.constant = true;
    r.classification = "fixed_point";
    r.confidence = "strong";
    std::snprintf(buf, sizeof buf,
                  "constant after the transient: mean %.12g, std %.3g, peak-to-peak %.3g (%.2g of the mean; the "
                  "constant-series threshold is %.0e)",
                  r.mean, r.stddev, r.max - r.min, scale > 0 ? (r.max - r.min) / scale : 0.0, opt.constant_rel_std);
    r.evidence.push_back(buf);
    r.evidence.push_back("no delay, dimension, exponent or recurrence analysis exists for a constant series "
                         "(normalising divides by its zero standard deviation)");
    stage(kStages);
    return r;
  }
  validate_series(x, 500, label);
  ClassifyOptions co;
  co.dt = opt.dt;
  co.tau = opt.tau;
  co.m = opt.m;
  co.m_max = 10;
  co.full_evidence = true;
  r.verdict = classify(x, co);
  r.classification = r.verdict.classification;
  r.confidence = r.verdict.confidence;
  r.evidence = r.verdict.reasons;
  const Classification& c = r.verdict;
  stage(2);
  // The estimators classify does not run: Cao's dimension and Kantz's
  // and Wolf's exponents, with classify's embedding and Theiler window.
  const std::vector<double> z = zscore(x);
  CaoOptions cao_opt;
  cao_opt.tau = c.tau;
  cao_opt.m_max = 10;
  cao_opt.theiler = c.theiler;
  r.cao = cao(z, cao_opt);
  stage(3);
  try {
    r.kantz = lle_kantz(z, c.lle_options);
  } catch (const InputError& e) {
    // A transient that never returns near itself leaves Kantz without
    // neighbourhoods outside the Theiler window; the rest still stands.
    r.kantz_error = e.what();
  }
  try {
    WolfOptions wo;
    wo.m = c.m;
    wo.tau = c.tau;
    wo.theiler = c.theiler;
    wo.dt = opt.dt;
    r.wolf = lle_wolf(z, wo);
  } catch (const InputError& e) {
    r.wolf_error = e.what();
  }
  stage(4);
  const auto f = series_figures(x, opt.dt, label, out_dir, c.tau, c.m);
  r.figures.insert(r.figures.end(), f.begin(), f.end());
  stage(kStages);
  return r;
}

}  // namespace cvt::analysis
