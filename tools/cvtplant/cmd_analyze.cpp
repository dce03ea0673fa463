// `cvtplant analyze <tool>`: nonlinear time-series analysis of one CSV column
// (docs/analysis.md): ami, fnn, cao, lle, rqa, recurrence, test01, classify;
// plus sweep / merge / figures / trajectory / seed-section4 / ripple for
// scene studies. This file registers the tools and holds what the series
// tools share; each tool is one function (cmd_analyze.hpp).
#include "cmd_analyze.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "guarded.hpp"
#include "io_util.hpp"
#include "registry.hpp"
#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"
#include "cvtplant/analysis/test01.hpp"

namespace cvtcli::analyze {

using namespace cvt::analysis;
using nlohmann::json;

void add_series_options(CLI::App* c, SeriesArgs& a, bool embedding) {
  c->add_option("--csv", a.csv, "input CSV with a header row")->required();
  c->add_option("--column", a.column, "column name")->required();
  cvtcli::add_real(c, "--dt", a.dt, {0, 1e6, true}, "sample interval [s] (exponents are per second)");
  cvtcli::add_int(c, "--discard", a.discard, 0, 1000000000000LL, "drop this many leading samples (transient)");
  c->add_flag("--json", a.json, "machine-readable output");
  if (embedding) {
    cvtcli::add_int(c, "--tau", a.tau, 1, 100000, "delay [samples] (default: first AMI minimum)");
    cvtcli::add_int(c, "--m", a.m, 1, 30, "embedding dimension (default: FNN)");
    cvtcli::add_int(c, "--theiler", a.theiler, 0, 1000000000,
                    "Theiler window w [samples], pairs |i-j| <= w excluded (default: mean period)");
  }
  add_caps(c, a.caps, false, true);
}

CsvColumn read_column(const std::string& path, const std::string& column, const cvtcli::Caps& caps) {
  try {
    return read_csv_column(path, column, cvtcli::memory_cap_bytes(caps));
  } catch (const LimitError& e) {
    throw cvtcli::UsageError{std::string(e.what()) + "; raise it with --max-memory-mb"};
  }
}

std::vector<double> load(const SeriesArgs& a, std::size_t min_points) {
  if (!(a.dt > 0) || !std::isfinite(a.dt)) throw cvtcli::UsageError{"--dt must be a positive number"};
  if (a.discard < 0) throw cvtcli::UsageError{"--discard must be >= 0"};
  CsvColumn c = read_column(a.csv, a.column, a.caps);
  if (static_cast<std::size_t>(a.discard) >= c.values.size())
    throw cvtcli::UsageError{"--discard " + std::to_string(a.discard) + " removes all " + std::to_string(c.values.size()) +
                             " samples"};
  cvtcli::require_memory(kSeriesBytesPerSample * static_cast<double>(c.values.size()), a.caps,
                         cvtcli::fmt_count(static_cast<double>(c.values.size())) + " samples");
  std::vector<double> x(c.values.begin() + a.discard, c.values.end());
  validate_series(x, min_points, "column '" + a.column + "'");
  return zscore(x);
}

int pick_tau(const SeriesArgs& a, const std::vector<double>& x) {
  if (a.tau > 0) return a.tau;
  if (a.tau == 0 || a.tau < -1) throw cvtcli::UsageError{"--tau must be >= 1"};
  return average_mutual_information(x, std::min<int>(static_cast<int>(x.size() / 10), 500)).tau;
}
int pick_theiler(const SeriesArgs& a, const std::vector<double>& x) {
  if (a.theiler < -1) throw cvtcli::UsageError{"--theiler must be >= 0"};
  return a.theiler >= 0 ? a.theiler : default_theiler(x);
}
int pick_m(const SeriesArgs& a, const std::vector<double>& x, int tau, int w) {
  if (a.m > 0) return a.m;
  if (a.m == 0 || a.m < -1) throw cvtcli::UsageError{"--m must be >= 1"};
  FnnOptions fo;
  fo.tau = tau;
  fo.theiler = w;
  return std::max(2, false_nearest_neighbours(x, fo).dimension);
}

namespace {

json fit_json(const ScalingFit& f) {
  return {{"slope", f.slope},          {"ci95", f.ci95},         {"slope_se", f.slope_se},
          {"window_spread", f.window_spread}, {"r2", f.r2},      {"k_begin", f.k_begin},
          {"k_end", f.k_end},          {"growth_efolds", f.growth_efolds}, {"scaling_region", f.scaling_region}};
}
}  // namespace

json lle_json(const LleResult& r, const char* method, int m, int tau) {
  return {{"method", method}, {"lambda", r.fit.slope}, {"ci95", r.fit.ci95}, {"fit", fit_json(r.fit)},
          {"m", m},           {"tau", tau},            {"theiler", r.theiler}, {"k_max", r.k_max},
          {"eps", r.eps},     {"mean_neighbours", r.mean_neighbours}, {"points", r.points},
          {"divergence", r.divergence}};
}
json rqa_json(const RqaResult& r, int m, int tau, const RqaOptions& o) {
  return {{"RR", r.rr},   {"DET", r.det},   {"L", r.l_mean},    {"Lmax", r.lmax}, {"ENTR", r.entr},
          {"LAM", r.lam}, {"TT", r.tt},     {"Vmax", r.vmax},   {"eps", r.eps},   {"theiler", r.theiler},
          {"lmin", o.lmin}, {"vmin", o.vmin}, {"m", m},          {"tau", tau},     {"points", r.n},
          {"rule", "||y_i - y_j||_2 <= eps on the z-scored series; pairs |i-j| <= theiler excluded (line of identity never counted)"}};
}

// The estimators are present whenever classify ran them (tau > 0).
json classification_json(const Classification& r) {
  json j{{"classification", r.classification}, {"confidence", r.confidence}, {"evidence", r.reasons}};
  if (r.classification != "fixed_point" || r.tau > 0) {
    j["tau"] = r.tau;
    j["m"] = r.m;
    j["theiler"] = r.theiler;
    j["deterministic"] = r.deterministic;
    j["fnn"] = {{"m", r.fnn.m}, {"fraction", r.fnn.fraction}};
    j["rqa"] = {{"RR", r.rqa.rr}, {"DET", r.rqa.det}, {"LAM", r.rqa.lam}, {"L", r.rqa.l_mean}, {"ENTR", r.rqa.entr}};
    j["lle"] = {{"lambda", r.lle.fit.slope}, {"ci95", r.lle.fit.ci95}, {"fit", fit_json(r.lle.fit)}};
    j["test01"] = {{"K", r.t01.k_median}, {"K_q25", r.t01.k_q25}, {"K_q75", r.t01.k_q75}, {"subsample", r.t01.subsample}};
    j["spectrum"] = {{"fundamental_cycles_per_sample", r.peaks.fundamental},
                     {"harmonic", r.peaks.harmonic},
                     {"worst_harmonic_error", r.peaks.worst_harmonic_error},
                     {"peaks_cycles_per_sample", r.peaks.freq}};
  }
  j["amplitude_decay"] = r.amplitude_decay;
  return j;
}

}  // namespace cvtcli::analyze

namespace {

cvtcli::Action register_analyze(CLI::App& app) {
  using namespace cvtcli::analyze;
  auto* an = app.add_subcommand("analyze", "nonlinear time-series analysis of a CSV column, sweeps and figures");
  an->require_subcommand(1);
  const std::vector<Tool> tools = {add_ami(an),        add_fnn(an),        add_cao(an),
                                   add_lle(an),        add_rqa(an, false), add_rqa(an, true),
                                   add_test01(an),     add_classify(an),   add_trajectory(an),
                                   add_sweep(an),      add_merge(an),      add_figures(an),
                                   add_seed_section4(an), add_ripple(an)};
  return [tools]() -> int {
    for (const Tool& t : tools)
      if (t.app->parsed()) return cvtcli::guarded(t.run);
    throw cvtcli::UsageError{"choose a tool (see cvtplant analyze --help)"};
  };
}

const bool registered = cvtcli::add_registrar(&register_analyze);

}  // namespace
