// The in-process rig of the external-controller tests (docs/sil.md#external-lockstep):
// the bridge, the harness, the harness's port for an external controller and
// a controller of its own on node 3 of the loopback bus, whose link may
// misbehave. Shared by test_external_controller.cpp and
// test_template_controller.cpp.
#pragma once

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

namespace sil_test {

using namespace cvt::sil::harness;
using cvt::can::CanFrame;
using cvt::port::CanIoStatus;

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

// One turn of a controller on node 3: what arrived, then its control step
// when the harness's demand is in. Defined by each controller's test.
using ControllerTurn = std::function<void(cvt::port::CanTransport& node)>;

// The example controller (hil/controller) as a node of its own.
inline ControllerTurn example_turn() {
  auto ctl = std::make_shared<std::unique_ptr<cvtctl::ControllerNode>>();
  return [ctl](cvt::port::CanTransport& node) {
    if (!*ctl) *ctl = std::make_unique<cvtctl::ControllerNode>(node);
    cvtctl::ControllerNode& c = **ctl;
    c.poll(0);
    c.take_new_run();
    if (c.demand_pending()) c.control_step_demand();
  };
}

// The bus, the bridge, the harness and the external controller's port, and a
// controller on node 3 answering HarnessDemand through a link that may
// misbehave.
struct Rig {
  InProcessBus bus;
  LoopbackBridgePlant plant{bus, 0};
  Misbehaving link;
  ControllerTurn turn;
  FaultInjector hf{bus.harness_node()};
  std::function<void()> plant_idle = plant.idle();
  void controller_turn() { turn(link); }
  HarnessNode h{hf, 20000000, [this] {
                  plant_idle();
                  controller_turn();
                }};
  ExternalController ext;

  Rig(Fault f = Fault::None, int from = 0, ExternalOptions o = options(), ControllerTurn t = example_turn())
      : link(bus.external_node(), f, from),
        turn(std::move(t)),
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

inline const Scenario& scenario(const char* name) {
  static const std::vector<Scenario> all = scenarios();
  for (const Scenario& s : all)
    if (std::strcmp(s.name, name) == 0) return s;
  FAIL("no scenario ", name);
  return all.front();
}

inline const Check& check(const ScenarioResult& r, const char* name) {
  for (const Check& c : r.checks)
    if (c.name == name) return c;
  FAIL("no check ", name);
  return r.checks.front();
}

inline std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline std::string out_dir(const char* name) {
  const std::string d = std::string("external-out/") + name;
  std::filesystem::create_directories(d);
  return d;
}


}  // namespace sil_test
