// Host cost of one 1 ms frame of the reduced-order plant for every row of the
// cost table (bench/cost_cases.hpp, docs/rom.md#cost),
// in float (the Cortex-M4F's type, whose instruction counts the target test
// prints for the same frames) and in double. Benchmarks are named
// "<scalar>/<row label>", e.g. float/scene/seed-case1.
// Run: build-*/bench/bench_rom; the table: bench/rom-cost-table.sh
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "cost_cases.hpp"

namespace {

// Steps the same start-of-frame state every iteration, as the target test
// does, so the host and target columns measure the same work.
template <class T, std::uint32_t F>
void frame_cost(benchmark::State& st, cvt::rom_cost::Case c) {
  cvt::rom_cost::Frame<T, F> fr(c);
  const cvt::RomSimulator<T, F> start = fr.sim;
  cvt::RomSimulator<T, F> sim = start;
  for (auto _ : st) {
    sim = start;
    sim.step_frame(fr.next);
    benchmark::DoNotOptimize(sim.state());
  }
  if (sim.fault() != cvt::RomFault::none) st.SkipWithError("plant faulted");
}

// The spread of a frame's cost over a run (docs/rom.md#cost): the scene's
// frames one after the other from t = kWarmup_s, inputs changing every frame
// as the scene's profiles give them, each frame timed on its own
// (steady_clock; the clock's own cost, measured on empty intervals, is taken
// off). Counters: median, p99, p99.9 and max ns per frame, and max / median.
// On a shared host the tail includes preemption; read it with the load.
template <class T, std::uint32_t F>
void frame_spread(benchmark::State& st, cvt::rom_cost::Case c) {
  using Clock = std::chrono::steady_clock;
  constexpr long kFrames = 20000;
  const cvt::Scene s = cvt::rom_cost::Frame<T, F>::scene_of(c);
  std::vector<double> ns(kFrames), empty(kFrames);
  for (auto _ : st) {
    cvt::rom_cost::Frame<T, F> fr(c);
    const long n0 = static_cast<long>(cvt::rom_cost::kWarmup_s / s.frame_s + 0.5);
    for (long i = 0; i < kFrames; ++i) {
      const cvt::RomInputs<T> u = cvt::scene_inputs_at<T>(s, static_cast<double>(n0 + i) * s.frame_s);
      const Clock::time_point t0 = Clock::now();
      fr.sim.step_frame(u);
      const Clock::time_point t1 = Clock::now();
      benchmark::DoNotOptimize(fr.sim.state());
      const Clock::time_point t2 = Clock::now();
      ns[i] = std::chrono::duration<double, std::nano>(t1 - t0).count();
      empty[i] = std::chrono::duration<double, std::nano>(t2 - t1).count();
    }
    if (fr.sim.fault() != cvt::RomFault::none) st.SkipWithError("plant faulted");
  }
  std::sort(empty.begin(), empty.end());
  const double clock_ns = empty[kFrames / 2];
  for (double& v : ns) v -= clock_ns;
  std::sort(ns.begin(), ns.end());
  auto at = [&](double q) { return ns[static_cast<std::size_t>(q * (kFrames - 1))]; };
  st.counters["median_ns"] = at(0.5);
  st.counters["p99_ns"] = at(0.99);
  st.counters["p999_ns"] = at(0.999);
  st.counters["max_ns"] = ns.back();
  st.counters["max_over_median"] = ns.back() / at(0.5);
  st.counters["p999_over_median"] = at(0.999) / at(0.5);
}

template <class T>
struct RegisterSpread {
  const char* scalar;
  template <std::uint32_t F>
  void visit(const cvt::rom_cost::Case& c) {
    if (c.label[0] != 's') return;  // the scene rows
    benchmark::RegisterBenchmark((std::string("spread/") + scalar + "/" + c.label).c_str(), &frame_spread<T, F>, c)
        ->Iterations(1);
  }
};

template <class T>
struct Register {
  const char* scalar;
  template <std::uint32_t F>
  void visit(const cvt::rom_cost::Case& c) {
    benchmark::RegisterBenchmark((std::string(scalar) + "/" + c.label).c_str(), &frame_cost<T, F>, c);
  }
};

}  // namespace

int main(int argc, char** argv) {
  cvt::rom_cost::for_each_case(Register<float>{"float"});
  cvt::rom_cost::for_each_case(Register<double>{"double"});
  cvt::rom_cost::for_each_case(RegisterSpread<double>{"double"});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
