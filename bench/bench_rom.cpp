// Host cost of one 1 ms frame of the reduced-order plant, per built-in scene
// and per optional feature (docs/rom.md#cost). Run: build-*/bench/bench_rom
#include <benchmark/benchmark.h>

#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

// Frames of a scene from its steady state after 1 s, so the cost is that of
// normal running, with the scene's default integrator and substeps.
template <class T, std::uint32_t F>
void frame_cost(benchmark::State& st, const char* scene_name, std::uint32_t /*unused*/, int substeps) {
  cvt::Scene s = *cvt::find_builtin_scene(scene_name);
  if (substeps > 0) s.substeps = substeps;
  cvt::RomSimConfig cfg = cvt::sim_config_of(s);
  cvt::RomSimulator<T, F> sim(s.params, cfg);
  sim.reset(s.initial, cvt::scene_inputs_at<T>(s, 0.0));
  const cvt::RomInputs<T> u = cvt::scene_inputs_at<T>(s, 1.0);
  for (int i = 0; i < 1000; ++i) sim.step_frame(u);
  for (auto _ : st) {
    sim.step_frame(u);
    benchmark::DoNotOptimize(sim.state());
  }
  if (sim.fault() != cvt::RomFault::none) st.SkipWithError("plant faulted");
}

namespace f = cvt::rom_feature;

// Each built-in scene at its default (ROS2, 2 substeps per 1 ms frame).
void BM_scene_oscillator_coulomb(benchmark::State& st) { frame_cost<double, 0>(st, "oscillator-coulomb", 0, 0); }
void BM_scene_oscillator_stribeck(benchmark::State& st) { frame_cost<double, 0>(st, "oscillator-stribeck", 0, 0); }
void BM_scene_seed_case1(benchmark::State& st) { frame_cost<double, f::axial>(st, "seed-case1", 0, 0); }
void BM_scene_seed_case2(benchmark::State& st) { frame_cost<double, f::axial>(st, "seed-case2", 0, 0); }
void BM_scene_clamp_step(benchmark::State& st) { frame_cost<double, f::axial | f::road_load>(st, "clamp-step", 0, 0); }
void BM_scene_tip_in(benchmark::State& st) { frame_cost<double, f::axial | f::road_load>(st, "tip-in", 0, 0); }
void BM_scene_gross_slip(benchmark::State& st) { frame_cost<double, 0>(st, "gross-slip", 0, 0); }
void BM_scene_seed_case1_float(benchmark::State& st) { frame_cost<float, f::axial>(st, "seed-case1", 0, 0); }
void BM_scene_gross_slip_float(benchmark::State& st) { frame_cost<float, 0>(st, "gross-slip", 0, 0); }
void BM_scene_gross_slip_fixed(benchmark::State& st) { frame_cost<cvt::q16_16, 0>(st, "gross-slip", 0, 0); }

// Features one at a time on the gross-slip parameter set (1 substep, so the
// numbers are per integrator step).
void BM_feature_core(benchmark::State& st) { frame_cost<double, 0>(st, "gross-slip", 0, 1); }
void BM_feature_axial(benchmark::State& st) { frame_cost<double, f::axial>(st, "gross-slip", 0, 1); }
void BM_feature_road_load(benchmark::State& st) { frame_cost<double, f::road_load>(st, "gross-slip", 0, 1); }
void BM_feature_deformation(benchmark::State& st) { frame_cost<double, f::deformation>(st, "gross-slip", 0, 1); }
// Chordal action excites ~380 Hz at these speeds: one 1 ms step faults
// (docs/rom.md#polygon), so these two run 4 substeps per frame.
void BM_feature_polygon_4sub(benchmark::State& st) { frame_cost<double, f::polygon>(st, "gross-slip", 0, 4); }
void BM_feature_all_4sub(benchmark::State& st) { frame_cost<double, f::all>(st, "gross-slip", 0, 4); }
void BM_feature_core_4sub(benchmark::State& st) { frame_cost<double, 0>(st, "gross-slip", 0, 4); }

}  // namespace

BENCHMARK(BM_scene_oscillator_coulomb);
BENCHMARK(BM_scene_oscillator_stribeck);
BENCHMARK(BM_scene_seed_case1);
BENCHMARK(BM_scene_seed_case2);
BENCHMARK(BM_scene_clamp_step);
BENCHMARK(BM_scene_tip_in);
BENCHMARK(BM_scene_gross_slip);
BENCHMARK(BM_scene_seed_case1_float);
BENCHMARK(BM_scene_gross_slip_float);
BENCHMARK(BM_scene_gross_slip_fixed);
BENCHMARK(BM_feature_core);
BENCHMARK(BM_feature_axial);
BENCHMARK(BM_feature_road_load);
BENCHMARK(BM_feature_deformation);
BENCHMARK(BM_feature_polygon_4sub);
BENCHMARK(BM_feature_all_4sub);
BENCHMARK(BM_feature_core_4sub);
BENCHMARK_MAIN();
