// A reference that fails mid-scenario (docs/sil.md#plant-faults): the plant
// fault on the bus (PlantStatus Fault and fault_watchdog, PlantDiag.plant_fault
// with its kind), the scenario failing with the reason in its criteria and
// in the JUnit file, the run ending there and nothing waiting on it; then a
// Reset starts clean. Failures detected by the reference itself (the ledger
// bound, the step cap) and the test hook for each kind.
// Cost: under a second of CPU after the release state of tip-in is made.
#include <doctest/doctest.h>

#include <fstream>
#include <stdexcept>
#include <sstream>
#include <string>

#include "cosim_rig.hpp"
#include "cvtplant/sil/harness/report.hpp"

using namespace cosim_test;
using cvt::can::PlantFault;
using cvt::mbd::StepFault;

namespace {

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs tip-in for up to 0.3 s against a reference with options `o`; checks
// that it stopped with `code` and whose own words contain `says`.
void expect_fault(const cvt::cosim::ReferenceOptions& o, PlantFault code, const std::string& says,
                  double by_s = 0.3) {
  Rig rig(o);
  const auto r = rig.run(short_scenario("tip-in", 0.3));
  CHECK(!r.pass());
  // The bus: the status that ended the run shows the fault, PlantDiag its kind.
  CHECK(rig.node.status().plant_mode == cvt::can::PlantMode::Fault);
  CHECK(rig.node.status().fault_watchdog);
  CHECK(rig.node.diag().plant_fault == code);
  // The criteria: the run stopped at the fault, the reason in no_watchdog_fault.
  const auto* w = find(r, "no_watchdog_fault");
  REQUIRE(w != nullptr);
  CHECK(!w->pass);
  CHECK_MESSAGE(w->detail.find(std::string(cvt::can::to_string(code)) + " (PlantDiag.plant_fault)") !=
                    std::string::npos,
                w->detail);
  CHECK_MESSAGE(w->detail.find(says) != std::string::npos, w->detail);
  MESSAGE(w->detail);
  const auto* answered = find(r, "bridge_answered_every_step");
  REQUIRE(answered != nullptr);
  CHECK_MESSAGE(answered->pass, answered->detail);
  CHECK(answered->detail.find("the run stopped at the plant fault") != std::string::npos);
  CHECK(find(r, "lockstep_time_exact")->pass);
  REQUIRE(!r.trace.empty());
  CHECK(r.trace.back().watchdog);
  CHECK(r.trace.back().t_s <= by_s + 1e-9);
  // The JUnit file: a <failure> carrying the reason.
  REQUIRE(cvt::sil::harness::write_junit("faults-junit.xml", {r}));
  const std::string junit = read_file("faults-junit.xml");
  const std::size_t at = junit.find("name=\"no_watchdog_fault\"");
  REQUIRE(at != std::string::npos);
  const std::size_t failure = junit.find("<failure", at);
  REQUIRE(failure != std::string::npos);
  CHECK(junit.find(std::string(cvt::can::to_string(code)), failure) != std::string::npos);
  // A Reset starts the scene again from its release state: no fault.
  REQUIRE(rig.node.request(cvt::can::SimRequest::Reset, 0, cvt::can::SceneId::TipIn));
  CHECK(rig.node.status().plant_mode == cvt::can::PlantMode::Ready);
  CHECK(!rig.node.status().fault_watchdog);
  CHECK(rig.node.diag().plant_fault == PlantFault::None);
}

}  // namespace

TEST_CASE("a reference that fails mid-scenario: detected by the reference") {
  SUBCASE("the energy ledger beyond its bound") {
    cvt::cosim::ReferenceOptions o;
    o.stepper.ledger_tol = 1e-13;
    expect_fault(o, PlantFault::EnergyCheck, "energy ledger residual");
  }
  SUBCASE("the step cap of a frame") {
    cvt::cosim::ReferenceOptions o;
    o.stepper.max_steps_per_frame = 3;
    expect_fault(o, PlantFault::StepCap, "step cap");
  }
}

TEST_CASE("a reference that fails mid-scenario: each kind through the test hook") {
  const struct {
    StepFault kind;
    PlantFault code;
  } kinds[] = {{StepFault::ledger, PlantFault::EnergyCheck},  {StepFault::torn_chain, PlantFault::TornChain},
               {StepFault::runaway, PlantFault::SpeedOutOfRange}, {StepFault::step_cap, PlantFault::StepCap},
               {StepFault::solver, PlantFault::SolverFailed},  {StepFault::state, PlantFault::StateInvalid}};
  for (const auto& k : kinds) {
    CAPTURE(cvt::mbd::step_fault_name(k.kind));
    cvt::cosim::ReferenceOptions o;
    o.inject = {k.kind, 0.105};
    // The frame ending at 0.105 s: the group of 0.11 s shows it.
    expect_fault(o, k.code, "at t = 0.105 s: " + std::string(cvt::mbd::step_fault_name(k.kind)) + " injected", 0.11);
  }
}

TEST_CASE("the test hook's names") {
  CHECK(cvt::cosim::step_fault_by_name("torn_chain") == StepFault::torn_chain);
  CHECK_THROWS_AS(cvt::cosim::step_fault_by_name("torn-chain"), std::invalid_argument);
  for (StepFault f : {StepFault::input, StepFault::ledger, StepFault::torn_chain, StepFault::runaway,
                      StepFault::step_cap, StepFault::solver, StepFault::state})
    CHECK(cvt::cosim::plant_fault_code(f) != PlantFault::None);
  CHECK(cvt::cosim::plant_fault_code(StepFault::none) == PlantFault::None);
}
