// The external-controller protocol of the SIL harness on the loopback bus
// (docs/sil.md#external-lockstep, #external-realtime, #misbehaviour): the
// harness, the bridge and a controller of its own in one process, the
// controller answering HarnessDemand as a separate ECU would. A controller
// that behaves gives the trace of the example controller run by the harness;
// one that is silent, late, sends a wrong CRC, repeats its counter or a value
// outside the DBC range fails the named criterion with the period it began.
#include <doctest/doctest.h>

#include "external_rig.hpp"

using namespace sil_test;

namespace {

// A misbehaviour shows as its criterion failing, with the period it began,
// in the JUnit file.
void expect_failure(const ScenarioResult& r, const char* name, const std::string& text, const char* dir) {
  const Check& c = check(r, name);
  CHECK_MESSAGE(!c.pass, name);
  CHECK_MESSAGE(c.detail.find(text) != std::string::npos, c.detail);
  const std::string junit = std::string(dir) + "/junit.xml";
  REQUIRE(write_junit(junit, {r}));
  const std::string x = slurp(junit);
  const std::string tc = std::string("name=\"") + name + "\" time=\"0\">\n      <failure message=\"";
  const std::size_t at = x.find(tc);
  REQUIRE_MESSAGE(at != std::string::npos, x);
  CHECK(x.find(text, at) < x.find("</testcase>", at));
}

// tip-in (300 periods) against a controller with `f` from period `from`;
// the traces and JUnit file into external-out/<dir>.
ScenarioResult misbehaving_run(Fault f, int from, const char* dir) {
  Rig rig(f, from);
  RunConfig cfg;
  cfg.out_dir = out_dir(dir);
  return run_lockstep(scenario("tip-in"), rig.h, rig.hf, rig.ext, cfg);
}

}  // namespace

TEST_CASE("external controller, lock-step: the protocol gives the example controller's own trace, every check passes") {
  // The example controller run by the harness ...
  std::string inproc;
  {
    InProcessBus bus;
    LoopbackBridgePlant plant(bus, 0);
    FaultInjector hf(bus.harness_node());
    HarnessNode h(hf, 20000000, plant.idle());
    REQUIRE(h.sync());
    ExampleController ex(bus.controller_node(), {}, {});
    RunConfig cfg;
    cfg.out_dir = out_dir("inproc");
    const ScenarioResult r = run_lockstep(scenario("kick-down"), h, hf, ex, cfg);
    CHECK(r.pass());
    inproc = slurp(cfg.out_dir + "/sil-kick-down.csv");
  }
  // ... and the same law as another node, driven through HarnessDemand.
  Rig rig;
  RunConfig cfg;
  cfg.out_dir = out_dir("external");
  const ScenarioResult r = run_lockstep(scenario("kick-down"), rig.h, rig.hf, rig.ext, cfg);
  for (const Check& c : r.checks) CHECK_MESSAGE(c.pass, c.name, ": ", c.detail);
  CHECK(check(r, "controller_answered").detail.find("all 600 periods answered") != std::string::npos);
  CHECK(check(r, "commands_e2e_valid").detail.find("600 CtrlCmd and 600 CtrlShiftCmd frames checked") !=
        std::string::npos);
  REQUIRE(inproc.size() > 10000);
  CHECK(slurp(cfg.out_dir + "/sil-kick-down.csv") == inproc);
  // A second run on the same controller: its laws start again on the Reset.
  const ScenarioResult r2 = run_lockstep(scenario("kick-down"), rig.h, rig.hf, rig.ext, cfg);
  CHECK(r2.pass());
  CHECK(slurp(cfg.out_dir + "/sil-kick-down.csv") == inproc);
}

TEST_CASE("external controller: the harness waits for the controller to come on the bus, and gives up on a silent one") {
  Rig ready;
  CHECK(ready.ext.wait_ready());
  Rig silent(Fault::Silent, 0);
  CHECK_FALSE(silent.ext.wait_ready());  // after start_timeout (0.2 s here)
}

TEST_CASE("external controller, lock-step: scenarios with faults inside the controller are refused with the reason") {
  std::string why;
  CHECK(ExternalController::accepts(scenario("ratio-sweep"), why));
  CHECK(ExternalController::accepts(scenario("slip-recovery"), why));
  CHECK(ExternalController::accepts(scenario("load-step"), why));
  for (const char* n : {"clamp-loss", "lost-frames", "frozen-controller", "controller-restart", "controller-flood"}) {
    CHECK_FALSE(ExternalController::accepts(scenario(n), why));
    CHECK(why.find("example controller") != std::string::npos);
  }
}

TEST_CASE("misbehaving controller: silent from period 100 is controller_answered failing at period 100, not a hang") {
  Rig rig(Fault::Silent, 100);
  RunConfig cfg;
  cfg.out_dir = out_dir("silent");
  const ScenarioResult r = run_lockstep(scenario("tip-in"), rig.h, rig.hf, rig.ext, cfg);
  // Not a hang: one full answer timeout, then the short wait per silent period.
  CHECK(rig.ext.full_timeouts() == 1);
  CHECK(rig.ext.short_timeouts() == 199);
  expect_failure(r, "controller_answered", "silent in 200 of 300 periods, first: no CtrlCmd at period 100 (t = 1.00 s)",
                 "external-out/silent");
  // The plant saw it too: its command deadline expired.
  CHECK_FALSE(check(r, "no_cmd_timeout").pass);
  CHECK(check(r, "commands_on_time").pass);
  CHECK(check(r, "commands_e2e_valid").pass);
  CHECK(check(r, "bridge_answered_every_step").pass);
}

TEST_CASE("misbehaving controller: one period late from period 40 is commands_on_time failing at period 40") {
  const ScenarioResult r = misbehaving_run(Fault::Late, 40, "late");
  expect_failure(r, "commands_on_time", "first: CtrlCmd for period 40 arrived after its deadline at period 40 (t = 0.40 s)",
                 "external-out/late");
  CHECK(check(r, "commands_on_time").detail.find("259 answers after") != std::string::npos);
  // Only the last period's answer never came (held until a next demand).
  expect_failure(r, "controller_answered", "silent in 1 of 300 periods, first: no CtrlCmd at period 299",
                 "external-out/late");
  CHECK(check(r, "commands_e2e_valid").pass);
}

TEST_CASE("misbehaving controller: a wrong CRC at period 50 is commands_e2e_valid failing at period 50") {
  const ScenarioResult r = misbehaving_run(Fault::BadCrc, 50, "crc");
  expect_failure(r, "commands_e2e_valid", "first: CtrlCmd CRC wrong (counter 5) at period 50 (t = 0.50 s)",
                 "external-out/crc");
  // The plant refused it too, and the period had no usable command.
  CHECK_FALSE(check(r, "controller_answered").pass);
  CHECK(check(r, "commands_in_range").pass);
}

TEST_CASE("misbehaving controller: a repeated counter at period 60 is commands_e2e_valid failing at period 60") {
  const ScenarioResult r = misbehaving_run(Fault::RepeatCounter, 60, "repeat");
  expect_failure(r, "commands_e2e_valid", "first: CtrlCmd counter 14 repeated at period 60 (t = 0.60 s)",
                 "external-out/repeat");
}

TEST_CASE("misbehaving controller: a command outside the DBC range at period 70 is commands_in_range failing at period 70") {
  const ScenarioResult r = misbehaving_run(Fault::OutOfRange, 70, "range");
  expect_failure(r, "commands_in_range", "first: CtrlCmd OUT_OF_RANGE at period 70 (t = 0.70 s)", "external-out/range");
  CHECK(check(r, "commands_e2e_valid").pass);
}

TEST_CASE("external controller, real time on the virtual clock: paced, on time; a silent controller fails controller_on_time") {
  for (const bool silent : {false, true}) {
    CAPTURE(silent);
    Rig rig(silent ? Fault::Silent : Fault::None, 150);
    RunConfig cfg;
    cfg.out_dir = out_dir(silent ? "rt-silent" : "rt");
    Scenario sc = scenario("kick-down");
    const ScenarioResult r = run_realtime(sc, rig.h, rig.ext, cfg, rig.plant.realtime());
    CHECK(check(r, "realtime_paced").pass);
    CHECK(check(r, "realtime_paced").detail.find("kept time") != std::string::npos);
    CHECK(check(r, "commands_e2e_valid").pass);
    CHECK(check(r, "commands_in_range").pass);
    if (!silent) {
      for (const Check& c : r.checks) CHECK_MESSAGE(c.pass, c.name, ": ", c.detail);
      CHECK(check(r, "controller_on_time").detail.find("0 later than 15 ms") != std::string::npos);
    } else {
      // 150 commands, then silence to the end: one gap beyond the deadline.
      expect_failure(r, "controller_on_time", "150 CtrlCmd (599 10 ms periods)", "external-out/rt-silent");
      CHECK(check(r, "controller_on_time").detail.find("1 at or beyond the plant's 50 ms deadline") !=
            std::string::npos);
      CHECK_FALSE(check(r, "no_cmd_timeout").pass);
    }
  }
}
