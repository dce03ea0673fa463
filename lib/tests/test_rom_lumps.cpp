// The two link lumps are the entry and the exit of the driver wrap
// (docs/rom.md#lump-load-split): in the drive-train scenes they carry
// different shares of the wrap's normal load, so they move apart and the
// coupling k2, c2 between them acts. With an even split they are one lump.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

struct LumpRun {
  double max_split_m = 0;    // max |x1 - x2|
  double max_x1_m = 0;       // max |x1|
  double torque_mean_Nm = 0;  // torque on the driver, mean over 0.5-1 s
};

LumpRun run_lumps(const cvt::Scene& s) {
  constexpr std::uint32_t F = cvt::rom_feature::axial;
  using L = cvt::RomLayout<F>;
  cvt::Scene one_s = s;
  one_s.t_end_s = 1.0;
  LumpRun r;
  long n = 0;
  const cvt::RomFault fault = cvt::run_scene<double, F>(
      one_s, cvt::sim_config_of(one_s), [&](long, double t, const cvt::RomSimulator<double, F>& sim) {
        const auto x = sim.state_si();
        r.max_split_m = std::max(r.max_split_m, std::fabs(x(L::kX1) - x(L::kX2)));
        r.max_x1_m = std::max(r.max_x1_m, std::fabs(x(L::kX1)));
        if (t >= 0.5) {
          r.torque_mean_Nm += sim.outputs().torque_transmitted_Nm;
          ++n;
        }
        return true;
      });
  REQUIRE(fault == cvt::RomFault::none);
  r.torque_mean_Nm /= static_cast<double>(n);
  return r;
}

}  // namespace

TEST_CASE("the lumps are the wrap's entry and exit: they move apart and k2 changes the transmitted torque") {
  // seed-case1's calibrated wrap and inputs on the axial plant: the seed
  // case under its clamping actuator (tools/scenes/seed-case1-clamped.toml).
  cvt::Scene seed = *cvt::find_builtin_scene("seed-case1");
  seed.features = cvt::rom_feature::axial;
  REQUIRE(seed.params.entry_load_share == 0.705);
  cvt::Scene soft = seed;
  soft.params.k2_N_m = 0.1 * seed.params.k2_N_m;
  soft.params.c2_Ns_m = 0.1 * seed.params.c2_Ns_m;
  const LumpRun a = run_lumps(seed), b = run_lumps(soft);
  MESSAGE("max |x1 - x2| " << a.max_split_m << " m of max |x1| " << a.max_x1_m << " m; torque on the driver "
                           << a.torque_mean_Nm << " N m, with k2, c2 / 10: " << b.torque_mean_Nm << " N m");
  // The lumps differ by more than 0.1 % of their travel...
  CHECK(a.max_split_m > 1e-3 * a.max_x1_m);
  // ...and the coupling between them shows in what the driver feels: a
  // tenth of k2 and c2 moves the mean torque of 0.5-1 s by more than 0.5 %.
  CHECK(std::fabs(b.torque_mean_Nm - a.torque_mean_Nm) > 5e-3 * std::fabs(a.torque_mean_Nm));

  // The same measures on an even split: the two lumps are one (x1 = x2 but
  // for rounding) and k2, c2 change nothing, which is what the checks above
  // rule out for the built-in scenes.
  cvt::Scene even = seed, even_soft = soft;
  even.params.entry_load_share = 0.5;
  even_soft.params.entry_load_share = 0.5;
  const LumpRun e = run_lumps(even), es = run_lumps(even_soft);
  MESSAGE("even split: max |x1 - x2| " << e.max_split_m << " m; torque " << e.torque_mean_Nm << " N m, with k2, c2 / 10: "
                                      << es.torque_mean_Nm << " N m");
  CHECK(e.max_split_m < 1e-12 * e.max_x1_m);
  CHECK(std::fabs(es.torque_mean_Nm - e.torque_mean_Nm) < 1e-9 * std::fabs(e.torque_mean_Nm));
}
