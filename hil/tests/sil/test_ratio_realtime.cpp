// Ratio control in real time (docs/sil.md#ratio-scenarios): the bridge paces
// the variable-ratio plant at 1 kHz on a virtual clock, the example
// controller's RatioLaw runs on every fresh group and drives the chain onto
// the underdrive stop, then onto the overdrive stop. The end stop must stay
// resolved (energy ledger closed), nothing may fault or time out.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "cvtctl/controller_node.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/sil/bridge.hpp"

using namespace cvt;

TEST_CASE("real time, ratio control onto both end stops: no fault, no timeout, slip bounded, ledger closed") {
  constexpr std::int64_t kMs = 1000000;
  port::VirtualClock clock;
  port::LoopbackBus<2, 256> bus(&clock);
  sil::Bridge bridge(bus.node(0), clock);
  REQUIRE(bridge.load_scene(*find_builtin_scene("ratio-control")));
  bridge.start_realtime();
  cvtctl::ControllerNode ctl(bus.node(1));
  const cvtctl::ThrustMap map;
  // 1.5, then beyond the underdrive stop (2.65), then beyond the overdrive
  // stop (0.89), then 1.5 again.
  auto target = [](double t) { return t < 0.5 ? 1.5f : t < 5.0 ? 2.9f : t < 10.0 ? 0.8f : 1.5f; };
  bool under = false, over = false;
  double max_slip = 0, max_err_settled = 0, changed_s = 0;
  float last_target = 1.5f;
  int steps = 0, settled = 0;
  for (int k = 1; k <= 14000; ++k) {
    clock.advance(k * kMs - clock.now_ns());
    bridge.realtime_frame();
    ctl.poll(0);
    if (!ctl.fresh_group()) continue;
    const double t = static_cast<double>(k) * 1e-3;
    const float r_set = target(t);
    if (r_set != last_target) {
      last_target = r_set;
      changed_s = t;
    }
    ctl.control_step_ratio(60.0f, r_set);
    ++steps;
    under = under || ctl.shift().end_stop_underdrive;
    over = over || ctl.shift().end_stop_overdrive;
    max_slip = std::fmax(max_slip, std::fabs(static_cast<double>(ctl.ratio().slip)));
    // The last set-point, reachable, judged 2 s after its step (2.9 -> 1.5
    // at 0.6 ratio/s takes 1.9 s).
    if (r_set >= map.ratio[0] && r_set <= map.ratio[4] && t - changed_s >= 2.5 && changed_s > 0) {
      max_err_settled = std::fmax(max_err_settled, std::fabs(static_cast<double>(ctl.ratio().geometric_ratio) - r_set));
      ++settled;
    }
  }
  const double ledger = bridge.plant().energy_residual_rel();
  MESSAGE("real-time ratio control, 14 s at 1 kHz (virtual clock): ", steps, " control steps, max |slip| ", max_slip,
          ", settled |r - r*| ", max_err_settled, " over ", settled, " samples, ", bridge.plant().stop_refined_frames(),
          " frames refined at the stops, ledger residual / flows ", ledger);
  CHECK(bridge.plant().fault() == RomFault::none);
  CHECK(bridge.mode() == can::PlantMode::RealTime);
  CHECK(bridge.rt_overruns() == 0);
  CHECK(bridge.cmd_timeouts() == 0);
  CHECK(bridge.shift_timeouts() == 0);
  CHECK(ctl.counters().rejected == 0);
  CHECK(steps >= 1390);  // one per 10 ms group
  CHECK(under);
  CHECK(over);
  CHECK(bridge.plant().stop_refined_frames() > 0);
  CHECK(max_slip <= 0.10);
  CHECK(settled >= 100);
  CHECK(max_err_settled <= 0.05);
  CHECK(ledger < 1e-5);
}
