// Speed and memory of the time-series estimators against O(N^2) references
// (docs/analysis.md#benchmarks). Peak RSS is process-wide, so measure memory
// with one benchmark per process: --benchmark_filter=BM_Rqa_stream/100000.
// bench/analysis-1e6.sh runs the 10^6-sample cases that way.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/rqa.hpp"
#include "cvtplant/analysis/series.hpp"
#include "cvtplant/analysis/systems.hpp"

using namespace cvt::analysis;

namespace {

// Lorenz x sampled every 0.01 after a transient of 50, z-scored.
const std::vector<double>& lorenz(std::size_t n) {
  static std::vector<double> cache;
  if (cache.size() < n) {
    const Model& s = find_model("lorenz");
    const auto rows = s.trajectory(s.default_params, s.default_x0, 0.005, 50, static_cast<double>(n) * 0.01, 0.01);
    cache.clear();
    for (std::size_t i = 0; i < rows.size(); i += 3) cache.push_back(rows[i]);
    cache = zscore(cache);
  }
  static std::vector<double> out;
  out.assign(cache.begin(), cache.begin() + static_cast<long>(n));
  return out;
}

double peak_rss_MB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

LleOptions lle_opts() {
  LleOptions o;
  o.m = 5;
  o.tau = 18;
  o.dt = 0.01;
  o.theiler = 100;
  o.k_max = 400;
  return o;
}

void BM_Rosenstein_kdtree(benchmark::State& st) {
  const auto x = lorenz(static_cast<std::size_t>(st.range(0)));
  double lam = 0;
  for (auto _ : st) lam = lle_rosenstein(x, lle_opts()).fit.slope;
  st.counters["lambda"] = lam;
  st.counters["peak_rss_MB"] = peak_rss_MB();
}
BENCHMARK(BM_Rosenstein_kdtree)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_Rosenstein_naive(benchmark::State& st) {
  const auto x = lorenz(static_cast<std::size_t>(st.range(0)));
  double lam = 0;
  for (auto _ : st) lam = lle_rosenstein_naive(x, lle_opts()).fit.slope;
  st.counters["lambda"] = lam;
}
BENCHMARK(BM_Rosenstein_naive)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1);

// Kennel FNN as `cvtplant analyze fnn` runs it: m = 1..10, tau 18 (the AMI
// minimum of this series), Theiler window = mean period.
void BM_Fnn(benchmark::State& st) {
  const auto x = lorenz(static_cast<std::size_t>(st.range(0)));
  FnnOptions o;
  o.tau = 18;
  FnnResult r;
  for (auto _ : st) r = false_nearest_neighbours(x, o);
  st.counters["dimension"] = r.dimension;
  st.counters["peak_rss_MB"] = peak_rss_MB();
}
BENCHMARK(BM_Fnn)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);

RqaOptions rqa_opts() {
  RqaOptions o;
  o.eps = 0.1;  // z-scored Lorenz, m=3: RR ~ 0.23%
  o.theiler = 1;
  return o;
}
// The command line's default: eps for RR = 2 %, Theiler window 0.
RqaOptions rqa_opts_rr2() {
  RqaOptions o;
  o.target_rr = 0.02;
  o.theiler = 0;
  return o;
}

template <RqaResult (*F)(const Embedding&, const RqaOptions&), RqaOptions (*O)()>
void BM_Rqa(benchmark::State& st) {
  const Embedding e = delay_embed(lorenz(static_cast<std::size_t>(st.range(0))), 3, 18);
  RqaResult r;
  for (auto _ : st) r = F(e, O());
  st.counters["RR"] = r.rr;
  st.counters["DET"] = r.det;
  st.counters["LAM"] = r.lam;
  st.counters["peak_rss_MB"] = peak_rss_MB();
}
// The streaming grid method (rqa), the k-d tree method it replaced
// (rqa_kdtree) and the brute force (rqa_naive): identical measures.
BENCHMARK(BM_Rqa<rqa, rqa_opts>)
    ->Name("BM_Rqa_stream")
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_Rqa<rqa_kdtree, rqa_opts>)
    ->Name("BM_Rqa_kdtree")
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_Rqa<rqa_naive, rqa_opts>)->Name("BM_Rqa_naive")->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Rqa<rqa, rqa_opts_rr2>)
    ->Name("BM_Rqa_stream_rr2")
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_Rqa<rqa_kdtree, rqa_opts_rr2>)
    ->Name("BM_Rqa_kdtree_rr2")
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
