// Host cost of one 1 ms frame of the reduced-order plant for every row of the
// cost table (bench/cost_cases.hpp, docs/rom.md#cost),
// in float (the Cortex-M4F's type, whose instruction counts the target test
// prints for the same frames) and in double. Benchmarks are named
// "<scalar>/<row label>", e.g. float/scene/seed-case1.
// Run: build-*/bench/bench_rom; the table: bench/rom-cost-table.sh
#include <benchmark/benchmark.h>

#include <string>

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
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
