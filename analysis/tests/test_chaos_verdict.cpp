// The verdict on chaos from its evidence (docs/analysis.md#chaos-verdict):
// synthetic series of known kind through the same machinery the seed-section4
// pipeline uses.
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/analysis/chaos_verdict.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {

// sin(2 pi f1 t) + 0.6 sin(2 pi f2 t) with f2 / f1 = sqrt(2), plus white
// noise of std `noise`: a two-frequency torus, seen through noise.
std::vector<double> torus(std::size_t n, double dt, double noise, unsigned seed) {
  const std::vector<double> e = testsig::white_noise(n, seed);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    x[i] = std::sin(2 * M_PI * 3.1 * t) + 0.6 * std::sin(2 * M_PI * 3.1 * std::sqrt(2.0) * t + 1) + noise * e[i];
  }
  return x;
}

}  // namespace

TEST_CASE("chaos verdict: a noisy two-frequency torus is not called chaotic") {
  for (unsigned seed : {1u, 2u}) {
    EvidenceOptions o;
    o.dt = 0.01;
    o.surrogates = seed == 1 ? 19 : 0;
    const SeriesEvidence se = gather_evidence(torus(6000, 0.01, 0.05, seed), o);
    const ChaosVerdict v = chaos_verdict(se.evidence);
    CHECK(v.verdict != "chaotic");
    CHECK(se.evidence.stationarity.stationary);
    // Given the two frequencies, the line spectrum decides: a torus.
    EvidenceOptions b = o;
    b.bases_Hz = {3.1, 3.1 * std::sqrt(2.0)};
    b.surrogates = 0;
    const ChaosVerdict vb = chaos_verdict(gather_evidence(torus(6000, 0.01, 0.05, seed), b).evidence);
    CHECK(vb.verdict == "regular");
    CHECK(vb.kind == "quasi_periodic");
  }
}

TEST_CASE("chaos verdict: Lorenz x is chaotic, and nonlinear against its surrogates") {
  EvidenceOptions o;
  o.dt = 0.01;
  o.surrogates = 19;
  const SeriesEvidence se = gather_evidence(testsig::lorenz_x(10000), o);
  const ChaosVerdict v = chaos_verdict(se.evidence);
  CHECK(v.verdict == "chaotic");
  CHECK(se.evidence.surrogates.nonlinear);
  CHECK(se.evidence.classification.classification == "chaotic");
}

TEST_CASE("chaos verdict: a sweeping line is not stationary and decides nothing") {
  std::vector<double> chirp(6000);
  for (std::size_t i = 0; i < chirp.size(); ++i) {
    const double t = i * 1e-3;
    chirp[i] = std::sin(2 * M_PI * (50 * t + 5 * t * t));
  }
  EvidenceOptions o;
  o.dt = 1e-3;
  o.surrogates = 0;
  const ChaosVerdict v = chaos_verdict(gather_evidence(chirp, o).evidence);
  CHECK(v.verdict == "undecided");
  CHECK(judge_claim("chaotic", v).verdict == "cannot be decided");
}

TEST_CASE("chaos verdict: a sharp periodic pulse train sampled at 1 kHz breaks its recurrence diagonals, yet is periodic") {
  // 103.19 Hz pulses, as the chain's link passages at 60 rad/s: 9.69 samples
  // per period. The recurrence plot's diagonals break where the orbit is
  // steep (DET below classify's determinism bar), the seed's Fig. 22
  // "discontinuities", for a motion that is strictly periodic.
  const double f = 103.19, dt = 1e-3;
  std::vector<double> x(4000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double ph = std::fmod(i * dt * f, 1.0), d = std::min(ph, 1 - ph) / 0.06;
    x[i] = std::exp(-d * d);
  }
  EvidenceOptions o;
  o.dt = dt;
  o.tau = 1;
  o.m = 3;
  o.surrogates = 0;
  o.bases_Hz = {f};
  const SeriesEvidence se = gather_evidence(x, o);
  CHECK(se.evidence.classification.rqa.det < 0.8);
  CHECK(se.evidence.classification.classification == "inconclusive");
  CHECK(se.evidence.classification.t01.k_median < 0.2);
  const ChaosVerdict v = chaos_verdict(se.evidence);
  CHECK(v.verdict == "regular");
  CHECK(v.kind == "periodic");
  CHECK(judge_claim("mildly chaotic", v).verdict == "does not hold");
  CHECK(judge_claim("periodic", v).verdict == "holds");
}

TEST_CASE("chaos verdict: an exponent from the equations overrules the series") {
  ChaosEvidence e;
  e.classification.classification = "periodic";
  e.classification.mean_period_s = 0.01;
  e.equation_exponents.push_back({"Benettin", 5.0, 1.0, 0.2});
  CHECK(chaos_verdict(e).verdict == "chaotic");
  e.classification.classification = "chaotic";
  e.equation_exponents = {{"Benettin", 0.01, 0.1, 0.2}};  // within the band
  const ChaosVerdict r = chaos_verdict(e);
  CHECK(r.verdict == "regular");
  // Straddling the band: not resolved, the series decides (chaotic, no surrogates: undecided).
  e.equation_exponents = {{"Benettin", 0.5, 1.0, 0.2}};
  CHECK(chaos_verdict(e).verdict == "undecided");
  e.classification.classification = "periodic";
  CHECK(chaos_verdict(e).verdict == "regular");
  e.equation_exponents = {{"Benettin", 5.0, 1.0, 0.2}, {"Benettin, other settings", -1.0, 0.5, 0.2}};
  CHECK(chaos_verdict(e).verdict == "undecided");
  // Chaotic against a regular alternative is a contradiction; inconclusive is not.
  ChaosEvidence a;
  a.classification.classification = "periodic";
  a.alternatives.push_back({"another embedding", "inconclusive", ""});
  CHECK(chaos_verdict(a).verdict == "regular");
  a.alternatives.push_back({"a tighter tolerance", "chaotic", ""});
  CHECK(chaos_verdict(a).verdict == "undecided");
  CHECK_THROWS(judge_claim("wild", chaos_verdict(a)));
}
