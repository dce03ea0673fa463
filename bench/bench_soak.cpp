// Soak of the real-time plant (docs/rom.md#soak): the tip-in scene (road
// load, so the speeds settle where the load takes the input torque) run for
// many frames at the real-time default, in double and in float, one
// benchmark iteration per run. Reported as counters: the energy ledger's
// residual relative to the flows at each decade of frames and its worst value
// (the ledger must not drift however long the run), the largest speed (the
// speeds stay bounded), the fault code, the growth of the heap in use and of
// the resident set from 1 % of the run to its end (the plant is heap-free:
// the heap must not grow at all) and the host time per frame.
//
//   bench_soak --frames=100000000        the soak of docs/rom.md#soak
//   bench_soak                           100,000 frames (the CI smoke run)
//
// Not a timed test: nothing here asserts a time. The exit status is 1 if a
// run faulted, its ledger residual is not finite or the heap in use grew,
// so a smoke run still catches a broken plant.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

long g_frames = 100000;
bool g_failed = false;

// Bytes the C heap has handed out and not taken back (glibc's mallinfo2:
// operator new and Eigen's allocator both come here).
double heap_in_use_B() { return static_cast<double>(mallinfo2().uordblks); }

// Resident set size [kB] from /proc/self/statm (pages in use now, not the peak).
double rss_kB() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  long size = 0, resident = 0;
  const int got = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return got == 2 ? static_cast<double>(resident) * 4.0 : 0.0;
}

constexpr std::uint32_t kSoakFeatures = cvt::rom_feature::axial | cvt::rom_feature::road_load;

template <class T>
void soak(benchmark::State& st) {
  cvt::Scene s = *cvt::find_builtin_scene("tip-in");
  if (s.features != kSoakFeatures) {
    st.SkipWithError("tip-in no longer has the soak's features");
    g_failed = true;
    return;
  }
  s.t_end_s = static_cast<double>(g_frames) * s.frame_s;
  double worst = 0, speed_max = 0, rss_start = 0, rss_end = 0, heap_start = 0, heap_end = 0, resid_end = 0;
  double at_decade[9] = {};
  cvt::RomFault fault = cvt::RomFault::none;
  // The first read of /proc allocates stdio's buffers for good; read once
  // before the run so that the measurement does not see its own allocation.
  rss_kB();
  for (auto _ : st) {
    cvt::RomSimulator<T, kSoakFeatures> sim(s.params, cvt::sim_config_of(s));
    auto on_frame = [&](long i, double, const cvt::RomSimulator<T, kSoakFeatures>& v) {
      const auto& e = v.energy();
      const double scale = static_cast<double>(e.scale_J());
      const double rel = scale > 0 ? static_cast<double>(e.residual_J()) / scale : 0.0;
      if (scale > 10.0 && std::fabs(rel) > worst) worst = std::fabs(rel);
      const auto o = v.outputs();
      speed_max = std::fmax(speed_max, std::fabs(static_cast<double>(o.omega1_rad_s)));
      speed_max = std::fmax(speed_max, std::fabs(static_cast<double>(o.omega2_rad_s)));
      // After the first 1 % of the run every page the run needs is touched.
      if (i == g_frames / 100) {
        rss_start = rss_kB();
        heap_start = heap_in_use_B();
      }
      long d = 1000;
      for (int k = 3; k <= 8; ++k, d *= 10)
        if (i == d) at_decade[k] = rel;
      resid_end = rel;
      return true;
    };
    fault = cvt::run_frames(sim, s, s.frame_s, on_frame);
    rss_end = rss_kB();
    heap_end = heap_in_use_B();
  }
  st.counters["frames"] = static_cast<double>(g_frames);
  st.counters["fault"] = static_cast<double>(static_cast<int>(fault));
  st.counters["resid_rel_end"] = resid_end;
  st.counters["resid_rel_worst"] = worst;
  for (int k = 3; k <= 8; ++k)
    if (std::pow(10.0, k) <= static_cast<double>(g_frames))
      st.counters["resid_rel_1e" + std::to_string(k)] = at_decade[k];
  st.counters["speed_max_rad_s"] = speed_max;
  st.counters["rss_growth_kB"] = rss_start > 0 ? rss_end - rss_start : 0.0;
  st.counters["heap_growth_B"] = heap_end - heap_start;
  st.counters["ns_per_frame"] =
      benchmark::Counter(static_cast<double>(g_frames), benchmark::Counter::kIsIterationInvariantRate |
                                                            benchmark::Counter::kInvert);
  if (fault != cvt::RomFault::none || !std::isfinite(resid_end)) {
    g_failed = true;
    st.SkipWithError(("the plant faulted: " + std::string(cvt::rom_fault_name(fault))).c_str());
  } else if (heap_end != heap_start) {
    g_failed = true;
    st.SkipWithError("the heap in use grew during the run (the plant is heap-free)");
  }
}

}  // namespace

int main(int argc, char** argv) {
  // --frames=N is ours; everything else goes to Google Benchmark.
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--frames=", 9) == 0) {
      char* end = nullptr;
      const double v = std::strtod(argv[i] + 9, &end);
      if (*end != '\0' || !(v >= 1000 && v <= 1e8)) {
        std::fprintf(stderr, "bench_soak: error: --frames must be in 1000..1e8\n");
        return 2;
      }
      g_frames = static_cast<long>(v);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  benchmark::RegisterBenchmark("soak/tip-in/double", &soak<double>)->Iterations(1)->Unit(benchmark::kSecond);
  benchmark::RegisterBenchmark("soak/tip-in/float", &soak<float>)->Iterations(1)->Unit(benchmark::kSecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return g_failed ? 1 : 0;
}
