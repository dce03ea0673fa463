// The in-process rig of the cosim tests: the multibody reference behind its
// bridge on the loopback bus, the harness and the example controller, wired
// as cvtplant-sil run --loopback --plant reference wires them.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "cvtplant/cosim/reference_plant.hpp"
#include "cvtplant/sil/harness/example_controller.hpp"
#include "cvtplant/sil/harness/fault_injector.hpp"
#include "cvtplant/sil/harness/harness_node.hpp"
#include "cvtplant/sil/harness/plant.hpp"
#include "cvtplant/sil/harness/runner.hpp"

namespace cosim_test {

namespace h = cvt::sil::harness;
using ReferenceBridge = cvt::sil::BasicBridge<cvt::cosim::ReferencePlant>;
using LoopbackReference = h::LoopbackPlant<ReferenceBridge>;

// A scenario of the table cut at t_end_s (below its shortest judged run:
// the criteria that need more are not judged, as with --allow-partial).
inline h::Scenario short_scenario(const char* name, double t_end_s) {
  for (const h::Scenario& s : h::scenarios())
    if (std::string(s.name) == name) {
      h::Scenario c = s;
      c.t_end_s = t_end_s;
      return c;
    }
  FAIL("no scenario " << name);
  return h::scenarios().front();
}

inline const h::Check* find(const h::ScenarioResult& r, const std::string& name) {
  for (const h::Check& c : r.checks)
    if (c.name == name) return &c;
  return nullptr;
}

struct Rig {
  explicit Rig(const cvt::cosim::ReferenceOptions& o = {})
      : plant(bus, 0, nullptr, o), faults(bus.harness_node()), node(faults, 20000000, plant.idle()),
        ctl(bus.controller_node(), law, ratio_law) {
    REQUIRE(node.sync());
  }
  h::ScenarioResult run(const h::Scenario& sc, const std::string& out_dir = ".") {
    h::RunConfig cfg;
    cfg.out_dir = out_dir;
    cfg.plant = &plant;
    return h::run_lockstep(sc, node, faults, ctl, cfg);
  }
  ReferenceBridge& bridge() { return plant.bridge(); }
  cvt::cosim::ReferencePlant& reference() { return plant.bridge().plant(); }

  h::InProcessBus bus;
  LoopbackReference plant;
  h::FaultInjector faults;
  h::HarnessNode node;
  cvtctl::ClampLawParams law;
  cvtctl::RatioLawParams ratio_law;
  h::ExampleController ctl;
};

}  // namespace cosim_test
