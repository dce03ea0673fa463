// docs/analysis.md#chaos-verdict
#include "cvtplant/analysis/chaos_verdict.hpp"

#include <cmath>
#include <cstdio>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"
#include "fmt.hpp"

namespace cvt::analysis {

namespace {

using detail::fmt;

bool regular_kind(const std::string& k) { return k == "periodic" || k == "quasi_periodic" || k == "fixed_point"; }

}  // namespace

ChaosVerdict chaos_verdict(const ChaosEvidence& e) {
  ChaosVerdict v;
  const Classification& c = e.classification;
  v.kind = c.classification;
  v.reasons.push_back("series: " + c.classification + " (" + c.confidence + ")");
  // 1. Stationarity.
  if (e.has_stationarity && !e.stationarity.stationary) {
    v.verdict = "undecided";
    v.reasons.push_back("the series is not stationary over the record; the estimators assume one invariant set");
    for (const auto& r : e.stationarity.reasons) v.reasons.push_back("  " + r);
    return v;
  }
  // 2. Robustness to the embedding and the numerics: chaos against a
  // regular kind is a contradiction; an inconclusive alternative only lacks
  // evidence.
  for (const auto& a : e.alternatives) {
    const std::string& base = a.against.empty() ? c.classification : a.against;
    if ((a.kind == "chaotic" && regular_kind(base)) || (base == "chaotic" && regular_kind(a.kind))) {
      v.verdict = "undecided";
      v.reasons.push_back("the classification changes with " + a.label + ": " + a.kind + " against " + base);
      return v;
    }
    v.reasons.push_back("with " + a.label + ": " + a.kind + (a.kind == base ? " as well" : " (against " + base + ")"));
  }
  // 3. Exponents from the equations, each against its own zero band.
  int positive = 0, regular = 0;
  for (const auto& x : e.equation_exponents) {
    const bool pos = x.lambda - x.ci95 > x.zero_band;
    const bool reg = x.lambda + x.ci95 <= x.zero_band;
    v.reasons.push_back(x.source + fmt(": largest exponent %.4g +- %.2g 1/s (zero band %.3g 1/s)", x.lambda, x.ci95, x.zero_band) +
                        (pos ? ", positive" : reg ? ", not positive" : ", not resolved from zero"));
    positive += pos;
    regular += reg;
  }
  if (positive > 0 && regular > 0) {
    v.verdict = "undecided";
    v.reasons.push_back("the exponents from the equations contradict each other");
    return v;
  }
  if (positive > 0) {
    v.verdict = "chaotic";
    v.reasons.push_back("a positive largest exponent of the equations: chaotic whatever the series estimators say");
    return v;
  }
  if (regular > 0) {
    v.verdict = "regular";
    if (c.classification == "chaotic")
      v.reasons.push_back("the series estimators' chaos is not in the equations: their positive exponent is an "
                          "artefact of the finite, sampled record");
    v.reasons.push_back("no positive largest exponent of the equations: regular");
    return v;
  }
  // 4. A line spectrum.
  if (e.has_lines) {
    v.reasons.push_back(fmt("%.4g %% of the power in spectral lines (a line spectrum needs >= %.4g %%)",
                            100 * e.line_power_fraction, 100 * e.min_line_power_fraction) +
                        (e.lines_explained ? ", every line a combination of " + std::to_string(e.line_bases) +
                                                 (e.line_bases == 1 ? " base frequency" : " base frequencies")
                                           : std::string(", not every line a combination of the base frequencies")));
    if (e.line_power_fraction >= e.min_line_power_fraction && e.lines_explained) {
      if (c.classification == "chaotic" || c.t01.k_median >= 0.8) {
        v.verdict = "undecided";
        v.reasons.push_back("a line spectrum, but the series estimators say chaos");
        return v;
      }
      v.verdict = "regular";
      v.kind = e.line_bases == 1 ? "periodic" : "quasi_periodic";
      v.reasons.push_back("a line spectrum of " + std::string(e.line_bases == 1 ? "one frequency and its harmonics"
                                                                                : "incommensurate frequencies") +
                          fmt(" (0-1 test K = %.3f): ", c.t01.k_median) + v.kind);
      return v;
    }
  }
  // 5. The series alone.
  if (c.classification == "chaotic") {
    if (!e.has_surrogates) {
      v.verdict = "undecided";
      v.reasons.push_back("chaotic by the series estimators, but no surrogate test was run");
      return v;
    }
    if (!e.surrogates.nonlinear) {
      v.verdict = "undecided";
      v.reasons.push_back("chaotic by the series estimators, but no nonlinear statistic tells the series from its "
                          "linear surrogates");
      return v;
    }
    v.verdict = "chaotic";
    v.reasons.push_back("chaotic by the series estimators, and nonlinear against its surrogates");
    return v;
  }
  if (regular_kind(c.classification)) {
    v.verdict = "regular";
    v.reasons.push_back("the series estimators find " + c.classification + " motion");
    return v;
  }
  v.verdict = "undecided";
  v.reasons.push_back("the series estimators disagree or find no low-dimensional determinism");
  return v;
}

SeriesEvidence gather_evidence(const std::vector<double>& x, const EvidenceOptions& o) {
  validate_series(x, 500, "evidence");
  if (!(o.dt > 0)) throw InputError("evidence: dt must be > 0");
  SeriesEvidence r;
  ChaosEvidence& e = r.evidence;
  StationarityOptions so = o.stationarity;
  so.dt = o.dt;
  e.has_stationarity = true;
  e.stationarity = stationarity(x, so);
  ClassifyOptions co;
  co.dt = o.dt;
  co.tau = o.tau;
  co.m = o.m;
  co.m_max = o.m_max;
  co.full_evidence = true;
  e.classification = classify(x, co);
  co.tau = -1;
  co.m = -1;
  r.data_embedding = classify(x, co);
  e.alternatives.push_back({"the embedding from AMI and FNN (d = " + std::to_string(r.data_embedding.tau) + ", m = " +
                                std::to_string(r.data_embedding.m) + ")",
                            r.data_embedding.classification, ""});
  r.lines = spectral_lines(x, o.dt, o.lines);
  r.line_resolution_Hz = 1.0 / (static_cast<double>(x.size()) * o.dt);
  if (!o.bases_Hz.empty()) {
    const int order = o.bases_Hz.size() == 1 ? 50 : 8;
    r.attribution = attribute_lines(r.lines, o.bases_Hz, order, 2 * r.line_resolution_Hz, o.aliases ? 1.0 / o.dt : 0.0);
    e.has_lines = true;
    e.line_bases = static_cast<int>(o.bases_Hz.size());
    e.line_power_fraction = line_power_fraction(x, o.dt, r.lines.Hz, 2 * r.line_resolution_Hz);
    e.lines_explained = !r.attribution.empty();
    for (const auto& a : r.attribution) e.lines_explained = e.lines_explained && a.explained;
  }
  if (o.surrogates > 0) {
    const Classification& c = e.classification;
    SurrogateTestOptions st;
    st.count = o.surrogates;
    st.seed = o.surrogate_seed;
    st.m = c.m;
    st.tau = c.tau;
    st.theiler = c.theiler;
    st.horizon = c.tau;
    st.dt = o.dt;
    e.has_surrogates = true;
    e.surrogates = surrogate_test(x, st);
  }
  return r;
}

ClaimVerdict judge_claim(const std::string& claim, const ChaosVerdict& v) {
  ClaimVerdict r;
  r.claim = claim;
  const bool says_chaos = claim == "chaotic" || claim == "mildly chaotic";
  if (!says_chaos && claim != "periodic") throw InputError("judge_claim: unknown claim '" + claim + "'");
  if (v.verdict == "undecided") {
    r.verdict = "cannot be decided";
    r.why = v.reasons.empty() ? "undecided" : v.reasons.back();
    for (const auto& x : v.reasons)
      if (x.find("not stationary") != std::string::npos || x.find("changes with") != std::string::npos ||
          x.find("contradict") != std::string::npos)
        r.why = x;
    return r;
  }
  const bool chaotic = v.verdict == "chaotic";
  const bool periodic_ok = v.kind == "periodic" || v.kind == "fixed_point";
  if (says_chaos)
    r.verdict = chaotic ? "holds" : "does not hold";
  else
    r.verdict = !chaotic && periodic_ok ? "holds" : "does not hold";
  r.why = "the verdict is " + v.verdict + " (" + v.kind + ")";
  return r;
}

}  // namespace cvt::analysis
