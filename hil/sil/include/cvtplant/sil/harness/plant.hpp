// The plant seam of the SIL harness (docs/sil.md#harness): the harness talks
// to the plant only through the bus (SimCtrl, the output groups), so what
// varies is where the plant runs and how a real-time run is paced: a bridge
// process on a CAN interface, or a plant in this process on the loopback bus,
// serviced while the harness waits. Host only.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "cvtplant/port/clock.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/sil/bridge.hpp"

namespace cvt::sil::harness {

// How a real-time run is paced (docs/sil.md#ratio-realtime). On SocketCAN
// the bridge process paces itself on CLOCK_MONOTONIC and `start`/`frame`
// are empty; with the bridge in-process on the loopback bus, `frame` sleeps
// the virtual clock to the next frame's deadline and runs it
// (deterministic), `start` sets the first deadline.
struct RealTimeBus {
  cvt::port::Clock& clock;
  std::function<void()> start, frame;
  std::int64_t poll_ns;  // how long the controller waits for a frame per turn
  const char* clock_name;
};

class PlantUnderTest {
 public:
  virtual ~PlantUnderTest() = default;
  // Services an in-process plant while the harness has nothing to read;
  // empty for a plant in another process.
  virtual std::function<void()> idle() = 0;
  virtual RealTimeBus realtime() = 0;
  // What the bus cannot carry about a plant fault (PlantDiag.plant_fault
  // gives its kind): the plant's own words, where the harness can see them
  // (a plant in this process); empty otherwise (docs/sil.md#plant-faults).
  virtual std::string fault_message() const { return {}; }
};

// The in-process bus on a virtual clock (the loopback transport,
// docs/can.md#port): node 0 the plant, 1 the harness, 2 the example
// controller or the harness's port for an external one, 3 an external
// controller in this process (tests of the external-controller protocol).
struct InProcessBus {
  cvt::port::VirtualClock clock;
  cvt::port::LoopbackBus<4, 256> bus{&clock};
  cvt::port::CanTransport& plant_node() { return bus.node(0); }
  cvt::port::CanTransport& harness_node() { return bus.node(1); }
  cvt::port::CanTransport& controller_node() { return bus.node(2); }
  cvt::port::CanTransport& external_node() { return bus.node(3); }
};

// A bridge in-process on the loopback bus, with any plant behind it
// (BasicBridge<Plant>). In real time it is paced as pace_realtime does, one
// frame per virtual millisecond; `frame_cost_ns` makes each frame's work take
// that long (a plant slower than its frame overruns).
template <class BridgeT>
class LoopbackPlant : public PlantUnderTest {
 public:
  // `initial`: the scene loaded now (null: none until the first SimCtrl
  // Reset, for a plant whose start costs time); `plant_args` construct the
  // bridge's plant.
  template <class... PlantArgs>
  LoopbackPlant(InProcessBus& bus, std::int64_t frame_cost_ns,
                const cvt::Scene* initial = cvt::find_builtin_scene("tip-in"), PlantArgs&&... plant_args)
      : bus_(bus),
        bridge_(std::make_unique<BridgeT>(bus.plant_node(), bus.clock, nullptr,
                                          static_cast<PlantArgs&&>(plant_args)...)),
        frame_cost_ns_(frame_cost_ns) {
    if (initial != nullptr) bridge_->load_scene(*initial);
  }
  std::function<void()> idle() override {
    return [this] { bridge_->service(0); };
  }
  RealTimeBus realtime() override {
    return RealTimeBus{bus_.clock, [this] { deadline_ = bus_.clock.now_ns() + bridge_->frame_ns(); },
                       [this] {
                         bus_.clock.sleep_until(deadline_);
                         bridge_->realtime_frame();
                         bus_.clock.advance(frame_cost_ns_);
                         deadline_ += bridge_->frame_ns();
                         if (bus_.clock.now_ns() > deadline_) bridge_->note_overrun();
                       },
                       0, "virtual clock"};
  }
  std::string fault_message() const override {
    return bridge_->plant().faulted() ? bridge_->plant().fault_message() : "";
  }
  const BridgeT& bridge() const { return *bridge_; }
  BridgeT& bridge() { return *bridge_; }

 private:
  InProcessBus& bus_;
  std::unique_ptr<BridgeT> bridge_;
  std::int64_t frame_cost_ns_, deadline_ = 0;
};

// The SIL bridge (the scene's real-time plant) in-process on the loopback bus.
using LoopbackBridgePlant = LoopbackPlant<Bridge>;

// A plant process on a CAN interface (cvtplant-bridge): nothing to service,
// it paces itself on the wall clock, which the harness reads too.
class BusPlant final : public PlantUnderTest {
 public:
  std::function<void()> idle() override { return {}; }
  RealTimeBus realtime() override { return RealTimeBus{wall_, {}, {}, 1000000, "wall clock"}; }

 private:
  cvt::port::PosixMonotonicClock wall_;
};

}  // namespace cvt::sil::harness
