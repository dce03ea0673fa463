#pragma once
// A verdict on chaos that a referee can check (docs/analysis.md#chaos-verdict):
// the series classification (classify) is only believed where the series is
// stationary, the same at tighter tolerances and with other embeddings, and
// where its nonlinear structure survives a surrogate-data test; a largest
// exponent from the equations, where there is one, overrules the estimates
// from the series. The verdict is then held against a claim.
#include <string>
#include <vector>

#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/link_rates.hpp"
#include "cvtplant/analysis/stationarity.hpp"
#include "cvtplant/analysis/surrogates.hpp"

namespace cvt::analysis {

// A largest exponent with its 95 % half-width, and where it comes from.
// zero_band: the rate below which the estimate cannot tell a positive
// exponent from a neutral one over the time it was accumulated (a cycle's
// or a torus' neutral exponent decays like 1 / T), e.g. 1 / T.
struct ExponentEstimate {
  std::string source;  // e.g. "two trajectories on the reference's equations"
  double lambda = 0, ci95 = 0, zero_band = 0;  // [1/s]
};

struct ChaosEvidence {
  Classification classification;            // the series at the chosen embedding
  // The same series classified otherwise (another embedding, a tighter
  // tolerance, another integrator). They contradict where one says chaotic
  // and the other a regular kind (periodic, quasi_periodic, fixed_point);
  // `against` is what the alternative is compared with (empty: the
  // classification above; else e.g. the base run on the alternative's own
  // window).
  struct Alternative {
    std::string label, kind, against;
  };
  std::vector<Alternative> alternatives;
  bool has_stationarity = false;
  Stationarity stationarity;
  bool has_surrogates = false;
  SurrogateTest surrogates;
  // The spectrum (docs/analysis.md#link-rates): the fraction of the power
  // in its lines, whether every line is an integer combination of the base
  // frequencies (aliases included), and how many incommensurate bases.
  bool has_lines = false;
  double line_power_fraction = 0;
  bool lines_explained = false;
  int line_bases = 0;
  double min_line_power_fraction = 0.99;  // a line spectrum: at least this much of the power in its lines
  // Exponents from the equations (two trajectories, Benettin).
  std::vector<ExponentEstimate> equation_exponents;
};

struct ChaosVerdict {
  std::string verdict;  // chaotic | regular | undecided
  std::string kind;     // the classification behind it (periodic, quasi_periodic, fixed_point, chaotic, inconclusive)
  std::vector<std::string> reasons;
};

// Rules, in order (docs/analysis.md#chaos-verdict):
// 1. a non-stationary series: undecided;
// 2. an alternative that contradicts (chaotic against a regular kind): undecided;
// 3. an exponent from the equations decides where its CI clears its zero
//    band (above: chaotic; at or below: regular); one that straddles it is
//    listed and the next rules decide; exponents that contradict each other:
//    undecided;
// 4. a line spectrum (at least min_line_power_fraction of the power in
//    lines, every line a combination of the bases) is regular: periodic with
//    one base, quasi-periodic with more, unless the 0-1 test or the
//    classification says chaos (then undecided);
// 5. otherwise the series: chaotic needs the classification chaotic and the
//    surrogate test's nonlinear statistic significant; periodic,
//    quasi-periodic and fixed point are regular; anything else is undecided.
ChaosVerdict chaos_verdict(const ChaosEvidence& e);

// The evidence a series alone gives (docs/analysis.md#chaos-verdict): its
// stationarity over windows, its classification at the given embedding and
// at the one AMI and FNN choose (an alternative), its spectral lines against
// the base frequencies (when given), and the surrogate test at the
// embedding (prediction horizon = the delay). Exponents from the equations
// and runs at other numerics are the caller's to add.
struct EvidenceOptions {
  double dt = 1.0;                // sample interval [s]
  int tau = -1, m = -1;           // -1: from AMI / FNN
  int m_max = 10;
  StationarityOptions stationarity;  // its dt is set from dt
  int surrogates = 19;            // 0: no test
  std::uint64_t surrogate_seed = 20260601u;
  std::vector<double> bases_Hz;   // the forcing frequencies the lines are explained by; empty: no line evidence
  bool aliases = true;            // harmonics above the Nyquist frequency seen folded
  int lines = 12;                 // spectral lines examined (within 20 dB of the strongest)
};
struct SeriesEvidence {
  ChaosEvidence evidence;
  Classification data_embedding;  // the classification at AMI's delay and FNN's dimension
  Lines lines;
  std::vector<LineAttribution> attribution;  // per line, when bases are given
  double line_resolution_Hz = 0;  // the window's 1 / (N dt); lines match within 2 of it
};
SeriesEvidence gather_evidence(const std::vector<double>& x, const EvidenceOptions& opt);

// The seed's words against a verdict: "chaotic" and "mildly chaotic" hold for
// a chaotic verdict and do not for a regular one; "periodic" the reverse.
// An undecided verdict: cannot be decided.
struct ClaimVerdict {
  std::string claim, verdict;  // holds | does not hold | cannot be decided
  std::string why;
};
ClaimVerdict judge_claim(const std::string& claim, const ChaosVerdict& v);

}  // namespace cvt::analysis
