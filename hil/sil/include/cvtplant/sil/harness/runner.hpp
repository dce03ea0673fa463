// The SIL runner (docs/sil.md#scenarios): one scenario in lock-step (the
// harness steps the plant, 10 frames per 10 ms control period) or in real
// time (the plant paced at 1 kHz, the harness watching), against any
// controller and any plant behind the harness's seams. Host only.
#pragma once

#include <functional>
#include <string>

#include "cvtctl/controller_node.hpp"
#include "cvtplant/sil/harness/controller.hpp"
#include "cvtplant/sil/harness/criteria.hpp"
#include "cvtplant/sil/harness/fault_injector.hpp"
#include "cvtplant/sil/harness/harness_node.hpp"
#include "cvtplant/sil/harness/plant.hpp"
#include "cvtplant/sil/harness/scenario.hpp"

namespace cvt::sil::harness {

struct RunConfig {
  std::string out_dir = ".";  // the CSV traces
  // The plant under test, for what the bus cannot carry about a fault (its
  // message, PlantUnderTest::fault_message); may be null.
  const PlantUnderTest* plant = nullptr;
  // Called after every lock-step period with its simulated time (progress of
  // a slow plant); may be empty.
  std::function<void(double t_s)> on_period;
};

// `harness_faults` is the harness's own transport wrapper, which the fault
// scenarios arm; the harness node sends and receives through it.
ScenarioResult run_lockstep(const Scenario& sc, HarnessNode& h, FaultInjector& harness_faults,
                            ControllerUnderTest& ctl, const RunConfig& cfg);

// A ratio scenario in real time: the plant paced at 1 kHz, the controller on
// every fresh group, the harness only watching. Same criteria as in
// lock-step where the run is comparable (docs/sil.md#ratio-realtime).
ScenarioResult run_realtime(const Scenario& sc, HarnessNode& h, ControllerUnderTest& ctl, const RunConfig& cfg,
                            const RealTimeBus& bus);

// `cvtplant-sil bench`: lock-step round trips per second, with a CtrlCmd
// from `ctl` before each Step when it is given. Prints one JSON line.
int bench(HarnessNode& h, cvtctl::ControllerNode* ctl, long steps);

}  // namespace cvt::sil::harness
