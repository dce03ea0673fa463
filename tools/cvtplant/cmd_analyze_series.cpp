// The series tools of `cvtplant analyze` (docs/analysis.md#cli): ami, fnn,
// cao, lle, rqa and recurrence, test01, classify, each on one CSV column.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cmd_analyze.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/analysis/series.hpp"
#include "cvtplant/analysis/test01.hpp"

namespace cvtcli::analyze {

using namespace cvt::analysis;
using nlohmann::json;

Tool add_ami(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto lag = std::make_shared<int>(-1);
  auto bins = std::make_shared<int>(0);
  auto* c = an->add_subcommand("ami", "average mutual information and autocorrelation; delay choice");
  add_series_options(c, *a, false);
  cvtcli::add_int(c, "--max-lag", *lag, 1, 100000, "largest lag [samples] (default min(N/10, 500))");
  cvtcli::add_int(c, "--bins", *bins, 2, 4096, "histogram bins (default cbrt(N) clamped to 8..64)");
  return {c, [a, lag, bins] {
    const auto x = load(*a, 50);
    const int L = *lag > 0 ? *lag : std::min<int>(static_cast<int>(x.size() / 10), 500);
    const AmiResult r = average_mutual_information(x, L, *bins);
    json j{{"tau", r.tau}, {"method", r.method}, {"tau_ami_first_minimum", r.tau_ami},
           {"tau_acf_zero", r.tau_acf_zero}, {"bins", r.bins}, {"ami", r.ami}, {"acf", r.acf}};
    if (a->json)
      cvtcli::print_json(j);
    else
      std::printf("tau = %d (%s); first AMI minimum %d, first ACF zero %d\n", r.tau, r.method,
                  r.tau_ami, r.tau_acf_zero);
    return 0;
  }};
}

Tool add_fnn(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto o = std::make_shared<FnnOptions>();
  auto* c = an->add_subcommand("fnn", "false nearest neighbours (Kennel: Rtol=10, Atol=2)");
  add_series_options(c, *a, true);
  cvtcli::add_int(c, "--m-max", o->m_max, 1, 30, "largest dimension tested");
  cvtcli::add_real(c, "--rtol", o->rtol, {0, 1e6, true}, "Kennel criterion 1 threshold");
  cvtcli::add_real(c, "--atol", o->atol, {0, 1e6, true}, "Kennel criterion 2 threshold");
  cvtcli::add_real(c, "--threshold", o->threshold, {0, 1}, "dimension = first m with FNN fraction <= threshold");
  return {c, [a, o] {
    const auto x = load(*a, 100);
    FnnOptions fo = *o;
    fo.tau = pick_tau(*a, x);
    fo.theiler = pick_theiler(*a, x);
    if (fo.m_max < 1 || fo.m_max > 30) throw cvtcli::UsageError{"--m-max must be in 1..30"};
    const FnnResult r = false_nearest_neighbours(x, fo);
    json j{{"dimension", r.dimension}, {"reached", r.reached}, {"tau", fo.tau},
           {"theiler", r.theiler},     {"rtol", fo.rtol},      {"atol", fo.atol},
           {"threshold", fo.threshold}, {"m", r.m},            {"fraction", r.fraction},
           {"fraction_rtol", r.fraction_rtol}, {"fraction_atol", r.fraction_atol}};
    if (a->json) {
      cvtcli::print_json(j);
    } else {
      for (std::size_t i = 0; i < r.m.size(); ++i)
        std::printf("m=%2d  FNN %.4f (Rtol %.4f, Atol %.4f)\n", r.m[i], r.fraction[i],
                    r.fraction_rtol[i], r.fraction_atol[i]);
      std::printf("dimension %d%s (tau %d, Theiler %d)\n", r.dimension,
                  r.reached ? "" : " (threshold not reached)", fo.tau, r.theiler);
    }
    return 0;
  }};
}

Tool add_cao(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto o = std::make_shared<CaoOptions>();
  auto* c = an->add_subcommand("cao", "Cao's E1/E2 embedding dimension");
  add_series_options(c, *a, true);
  cvtcli::add_int(c, "--m-max", o->m_max, 1, 30, "largest dimension tested");
  cvtcli::add_real(c, "--e1-threshold", o->e1_threshold, {0, 1, true}, "dimension = first m with E1(m) >= threshold");
  return {c, [a, o] {
    const auto x = load(*a, 100);
    CaoOptions co = *o;
    co.tau = pick_tau(*a, x);
    co.theiler = pick_theiler(*a, x);
    if (co.m_max < 1 || co.m_max > 30) throw cvtcli::UsageError{"--m-max must be in 1..30"};
    const CaoResult r = cao(x, co);
    json j{{"dimension", r.dimension}, {"reached", r.reached}, {"tau", co.tau}, {"theiler", r.theiler},
           {"m", r.m}, {"E1", r.e1}, {"E2", r.e2}};
    if (a->json) {
      cvtcli::print_json(j);
    } else {
      for (std::size_t i = 0; i < r.m.size(); ++i)
        std::printf("m=%2d  E1 %.4f  E2 %.4f\n", r.m[i], r.e1[i], r.e2[i]);
      std::printf("dimension %d\n", r.dimension);
    }
    return 0;
  }};
}

Tool add_lle(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto method = std::make_shared<std::string>("rosenstein");
  auto o = std::make_shared<LleOptions>();
  auto* c = an->add_subcommand("lle", "largest Lyapunov exponent (Rosenstein or Kantz) with automatic scaling region");
  add_series_options(c, *a, true);
  c->add_option("--method", *method, "rosenstein | kantz | both")->check(CLI::IsMember({"rosenstein", "kantz", "both"}));
  cvtcli::add_int(c, "--k-max", o->k_max, 1, 1000000, "divergence horizon [samples] (default 5 mean periods)");
  cvtcli::add_real(c, "--eps", o->eps, {0, 1e3, true},
                   "Kantz radius in std units (default: median 10th-neighbour distance)");
  return {c, [a, method, o] {
    const auto x = load(*a, 100);
    LleOptions lo = *o;
    lo.dt = a->dt;
    lo.tau = pick_tau(*a, x);
    lo.theiler = pick_theiler(*a, x);
    lo.m = pick_m(*a, x, lo.tau, lo.theiler);
    json j = json::object();
    if (*method != "kantz") j["rosenstein"] = lle_json(lle_rosenstein(x, lo), "rosenstein", lo.m, lo.tau);
    if (*method != "rosenstein") j["kantz"] = lle_json(lle_kantz(x, lo), "kantz", lo.m, lo.tau);
    if (a->json) {
      cvtcli::print_json(j);
    } else {
      for (auto& [k, v] : j.items())
        std::printf("%s: lambda = %.6g +- %.2g per unit time (m %d, tau %d, Theiler %d, fit samples "
                    "%d..%d, R^2 %.4f, scaling region %s)\n",
                    k.c_str(), v["lambda"].get<double>(), v["ci95"].get<double>(), lo.m, lo.tau,
                    v["theiler"].get<int>(), v["fit"]["k_begin"].get<int>(),
                    v["fit"]["k_end"].get<int>(), v["fit"]["r2"].get<double>(),
                    v["fit"]["scaling_region"].get<bool>() ? "yes" : "no");
    }
    return 0;
  }};
}

Tool add_rqa(CLI::App* an, bool is_png) {
  auto a = std::make_shared<SeriesArgs>();
  auto o = std::make_shared<RqaOptions>();
  auto path = std::make_shared<std::string>();
  auto pixels = std::make_shared<int>(1000);
  auto* c = is_png ? an->add_subcommand("recurrence", "recurrence plot as PNG (plus the RQA measures)")
                : an->add_subcommand("rqa", "recurrence quantification: RR DET L Lmax ENTR LAM TT (streaming)");
  add_series_options(c, *a, true);
  // Up to 1e3 std units: beyond, every pair recurs (RR = 1) and the
  // streaming count becomes N^2 work for no information.
  cvtcli::add_real(c, "--eps", o->eps, {0, 1e3, true}, "recurrence radius in std units of the series (default: from --rr)");
  cvtcli::add_real(c, "--rr", o->target_rr, {0, 1, true, true}, "target recurrence rate when --eps is not given");
  cvtcli::add_int(c, "--lmin", o->lmin, 1, 1000000, "minimal diagonal line");
  cvtcli::add_int(c, "--vmin", o->vmin, 1, 1000000, "minimal vertical line");
  if (is_png) {
    c->add_option("--png", *path, "output PNG file")->required();
    cvtcli::add_int(c, "--pixels", *pixels, 16, 8192, "image side in pixels (max)");
  }
    return {c, [a, o, path, pixels, is_png] {
                     const auto x = load(*a, 100);
                     const int tau = pick_tau(*a, x);
                     const int w = a->theiler >= 0 ? a->theiler : 0;
                     if (a->theiler < -1) throw cvtcli::UsageError{"--theiler must be >= 0"};
                     const int m = pick_m(*a, x, tau, pick_theiler(*a, x));
                     RqaOptions ro = *o;
                     ro.theiler = w;
                     const Embedding e = delay_embed(x, m, tau);
                     cvtcli::Progress progress(is_png ? "recurrence" : "rqa", static_cast<double>(e.n), "rows");
                     ro.progress = [&](double done, double) { progress.update(done); };
                     const RqaResult r = rqa(e, ro);
                     progress.finish();
                     json j = rqa_json(r, m, tau, ro);
                     if (is_png) {
                       write_recurrence_png(e, r.eps, -1, *path, *pixels);
                       j["png"] = *path;
                     }
                     if (a->json) {
                       cvtcli::print_json(j);
                     } else {
                       std::printf("RR %.4f DET %.4f L %.3f Lmax %ld ENTR %.3f LAM %.4f TT %.3f (eps %.4g, m %d, tau "
                                   "%d, Theiler %d)\n",
                                   r.rr, r.det, r.l_mean, r.lmax, r.entr, r.lam, r.tt, r.eps, m, tau, w);
                       if (is_png) std::printf("wrote %s\n", path->c_str());
                     }
                     return 0;
                   }};
}

Tool add_test01(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto o = std::make_shared<Test01Options>();
  o->subsample = -1;
  auto* c = an->add_subcommand("test01", "Gottwald-Melbourne 0-1 test for chaos (K ~ 0 regular, ~ 1 chaotic or noise)");
  add_series_options(c, *a, false);
  cvtcli::add_int(c, "--subsample", o->subsample, 1, 1000000, "use every n-th sample (default: the AMI delay)");
  cvtcli::add_int(c, "--n-c", o->n_c, 1, 10000, "number of random frequencies c");
  cvtcli::add_int(c, "--max-points", o->max_points, 100, 10000000, "points used after subsampling");
  return {c, [a, o] {
    const auto x = load(*a, 100);
    Test01Options to = *o;
    if (to.subsample == -1) to.subsample = pick_tau(*a, x);
    const Test01Result r = test01(x, to);
    json j{{"K", r.k_median}, {"K_q25", r.k_q25}, {"K_q75", r.k_q75}, {"points", r.points},
           {"subsample", r.subsample}, {"n_c", to.n_c}};
    if (a->json)
      cvtcli::print_json(j);
    else
      std::printf("K = %.4f (IQR %.4f..%.4f, %d points, subsample %d)\n", r.k_median, r.k_q25,
                  r.k_q75, r.points, r.subsample);
    return 0;
  }};
}

Tool add_classify(CLI::App* an) {
  auto a = std::make_shared<SeriesArgs>();
  auto* c = an->add_subcommand("classify", "verdict: fixed_point / periodic / quasi_periodic / chaotic / inconclusive");
  add_series_options(c, *a, true);
  return {c, [a] {
    CsvColumn col = read_column(a->csv, a->column, a->caps);
    if (a->discard < 0 || static_cast<std::size_t>(a->discard) >= col.values.size())
      throw cvtcli::UsageError{"--discard must be in 0..N-1"};
    cvtcli::require_memory(kSeriesBytesPerSample * static_cast<double>(col.values.size()), a->caps,
                           cvtcli::fmt_count(static_cast<double>(col.values.size())) + " samples");
    std::vector<double> x(col.values.begin() + a->discard, col.values.end());
    ClassifyOptions co;
    co.dt = a->dt;
    co.tau = a->tau;
    co.m = a->m;
    co.theiler = a->theiler;
    const Classification r = classify(x, co);
    const json j = classification_json(r);
    if (a->json) {
      cvtcli::print_json(j);
    } else {
      std::printf("classification: %s (%s)\n", r.classification.c_str(), r.confidence.c_str());
      for (const auto& s : r.reasons) std::printf("  - %s\n", s.c_str());
    }
    return 0;
  }};
}

}  // namespace cvtcli::analyze
