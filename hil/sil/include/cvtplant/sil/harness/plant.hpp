// The plant seam of the SIL harness (docs/sil.md#harness): the harness talks
// to the plant only through the bus (SimCtrl, the output groups), so what
// varies is where the plant runs and how a real-time run is paced: a bridge
// process on a CAN interface, or a plant in this process on the loopback bus,
// serviced while the harness waits. Host only.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

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

// The SIL bridge (the scene's real-time plant) in-process on the loopback
// bus. In real time it is paced as pace_realtime does, one frame per virtual
// millisecond; `frame_cost_ns` makes each frame's work take that long (a
// plant slower than its frame overruns).
class LoopbackBridgePlant final : public PlantUnderTest {
 public:
  LoopbackBridgePlant(InProcessBus& bus, std::int64_t frame_cost_ns);
  std::function<void()> idle() override;
  RealTimeBus realtime() override;

 private:
  InProcessBus& bus_;
  std::unique_ptr<Bridge> bridge_;
  std::int64_t frame_cost_ns_, deadline_ = 0;
};

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
