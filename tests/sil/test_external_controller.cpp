// The external-controller protocol of the SIL harness on the loopback bus
// (docs/sil.md#external-lockstep, #external-realtime, #misbehaviour): the
// harness, the bridge and a controller of its own in one process, the
// controller answering HarnessDemand as a separate ECU would. A controller
// that behaves gives the trace of the example controller run by the harness;
// one that is silent, late, sends a wrong CRC, repeats its counter or a value
// outside the DBC range fails the named criterion with the period it began.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include "cvtctl/controller_node.hpp"
#include "cvtplant/sil/harness/example_controller.hpp"
#include "cvtplant/sil/harness/external_controller.hpp"
#include "cvtplant/sil/harness/report.hpp"
#include "cvtplant/sil/harness/runner.hpp"

using namespace cvt::sil::harness;
using cvt::can::CanFrame;
using cvt::port::CanIoStatus;

namespace {

// What the controller's link does wrong, from the `from`-th HarnessDemand on
// (0 = the first demand of the run).
enum class Fault { None, Silent, Late, BadCrc, RepeatCounter, OutOfRange };

// The controller's transport with a fault: frames are changed, held or
// dropped on their way to the bus.
class Misbehaving final : public cvt::port::CanTransport {
 public:
  Misbehaving(cvt::port::CanTransport& inner, Fault f, int from) : inner_(inner), fault_(f), from_(from) {}
  int demands = 0;  // HarnessDemand frames seen by the controller

  CanIoStatus send(const CanFrame& f) noexcept override {
    const bool cmd = f.id == cvt::can::CtrlCmd::kId || f.id == cvt::can::CtrlShiftCmd::kId;
    const bool active = cmd && demands - 1 >= from_;
    CanFrame g = f;
    if (active) {
      switch (fault_) {
        case Fault::None: break;
        case Fault::Silent: return CanIoStatus::Ok;  // lost: the sender sees Ok, as on CAN
        case Fault::Late:
          held_[held_n_++] = f;  // sent when the next demand has arrived
          return CanIoStatus::Ok;
        case Fault::BadCrc:
          if (demands - 1 == from_ && f.id == cvt::can::CtrlCmd::kId) g.data[0] ^= 0x5A;
          break;
        case Fault::RepeatCounter:
          // The previous CtrlCmd's bytes again: same counter, same CRC.
          if (demands - 1 == from_ && f.id == cvt::can::CtrlCmd::kId) g = last_cmd_;
          break;
        case Fault::OutOfRange:
          if (demands - 1 == from_ && f.id == cvt::can::CtrlCmd::kId) {
            // clamp_force_cmd_N raw 65000 > the DBC's 60000, CRC made valid.
            g.data[2] = 65000 & 0xFF;
            g.data[3] = 65000 >> 8;
            std::uint8_t (&d)[8] = g.data;
            d[0] = cvt::can::e2e_crc(cvt::can::CtrlCmd::kE2eDataId, d);
          }
          break;
      }
    }
    if (f.id == cvt::can::CtrlCmd::kId) last_cmd_ = f;
    return inner_.send(g);
  }
  CanIoStatus receive(CanFrame& out, std::int64_t timeout_ns) noexcept override {
    const CanIoStatus st = inner_.receive(out, timeout_ns);
    if (st == CanIoStatus::Ok && out.id == cvt::can::HarnessDemand::kId) {
      ++demands;
      for (int i = 0; i < held_n_; ++i) inner_.send(held_[i]);
      held_n_ = 0;
    }
    return st;
  }
  cvt::port::CanTransportCounters counters() const noexcept override { return inner_.counters(); }
  cvt::port::CanBusState bus_state() const noexcept override { return inner_.bus_state(); }

 private:
  cvt::port::CanTransport& inner_;
  Fault fault_;
  int from_;
  CanFrame held_[4]{}, last_cmd_{};
  int held_n_ = 0;
};

// The bus, the bridge, the harness and the external controller's port, and
// the example controller's node on node 3 answering HarnessDemand.
struct Rig {
  InProcessBus bus;
  LoopbackBridgePlant plant{bus, 0};
  Misbehaving link;
  cvtctl::ControllerNode ctl;
  FaultInjector hf{bus.harness_node()};
  std::function<void()> plant_idle = plant.idle();
  // One turn of the controller: whatever arrived, then a control step when
  // the harness's demand is in.
  void controller_turn() {
    ctl.poll(0);
    ctl.take_new_run();
    if (ctl.demand_pending()) ctl.control_step_demand();
  }
  HarnessNode h{hf, 20000000, [this] {
                  plant_idle();
                  controller_turn();
                }};
  ExternalController ext;

  Rig(Fault f = Fault::None, int from = 0, ExternalOptions o = options())
      : link(bus.external_node(), f, from),
        ctl(link),
        ext(bus.controller_node(), o,
            [this] {
              plant_idle();
              controller_turn();
            },
            [this] { controller_turn(); }) {
    REQUIRE(h.sync());
  }
  static ExternalOptions options() {
    ExternalOptions o;
    o.answer_timeout_ns = 200000000;  // wall time; the in-process controller answers at once
    o.start_timeout_ns = 200000000;
    o.silent_wait_ns = 2000000;
    return o;
  }
};

const Scenario& scenario(const char* name) {
  static const std::vector<Scenario> all = scenarios();
  for (const Scenario& s : all)
    if (std::strcmp(s.name, name) == 0) return s;
  FAIL("no scenario ", name);
  return all.front();
}

const Check& check(const ScenarioResult& r, const char* name) {
  for (const Check& c : r.checks)
    if (c.name == name) return c;
  FAIL("no check ", name);
  return r.checks.front();
}

std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string out_dir(const char* name) {
  const std::string d = std::string("external-out/") + name;
  std::filesystem::create_directories(d);
  return d;
}

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
  CHECK(check(r, "controller_answered").detail.find("all 550 periods answered") != std::string::npos);
  CHECK(check(r, "commands_e2e_valid").detail.find("550 CtrlCmd and 550 CtrlShiftCmd frames checked") !=
        std::string::npos);
  REQUIRE(inproc.size() > 10000);
  CHECK(slurp(cfg.out_dir + "/sil-kick-down.csv") == inproc);
  // A second run on the same controller: its laws start again on the Reset.
  const ScenarioResult r2 = run_lockstep(scenario("kick-down"), rig.h, rig.hf, rig.ext, cfg);
  CHECK(r2.pass());
  CHECK(slurp(cfg.out_dir + "/sil-kick-down.csv") == inproc);
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
  cvt::port::PosixMonotonicClock wall;
  const std::int64_t t0 = wall.now_ns();
  const ScenarioResult r = run_lockstep(scenario("tip-in"), rig.h, rig.hf, rig.ext, cfg);
  // One answer timeout (0.2 s), then the 2 ms silent wait per period: 200 periods.
  CHECK(static_cast<double>(wall.now_ns() - t0) * 1e-9 < 0.2 + 200 * 0.003 + 1.0);
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
      expect_failure(r, "controller_on_time", "150 CtrlCmd (549 10 ms periods)", "external-out/rt-silent");
      CHECK(check(r, "controller_on_time").detail.find("1 at or beyond the plant's 50 ms deadline") !=
            std::string::npos);
      CHECK_FALSE(check(r, "no_cmd_timeout").pass);
    }
  }
}
