// The example controller (hil/controller, docs/sil.md#controller) behind the
// harness's controller seam, run in-process on its own transport, with the
// faults of its link injected by the harness (docs/sil.md#fault-scenarios).
// Host only.
#pragma once

#include "cvtctl/control_schedule.hpp"
#include "cvtctl/controller_node.hpp"
#include "cvtplant/sil/harness/controller.hpp"
#include "cvtplant/sil/harness/fault_injector.hpp"

namespace cvt::sil::harness {

// The example ratio law as every harness command wires it
// (docs/sil.md#ratio-control): the production CVT's clamping calibration,
// with the fixed-ratio law's safety margin and a clamping floor on each
// pulley.
inline cvtctl::RatioLawParams example_ratio_law(const cvtctl::ClampLawParams& law,
                                                float clamp_floor_N = cvtctl::production_clamp_law().clamp_min_N) {
  cvtctl::RatioLawParams r;
  r.clamp.safety = law.safety;
  r.clamp.clamp_min_N = clamp_floor_N;
  return r;
}

class ExampleController final : public ControllerUnderTest {
 public:
  // `bus` is the controller's own transport (its own socket on SocketCAN).
  ExampleController(cvt::port::CanTransport& bus, const cvtctl::ClampLawParams& law,
                    const cvtctl::RatioLawParams& ratio_law)
      : faults_(bus), node_(faults_, law, ratio_law) {}

  bool can_run(const Scenario&, std::string&) const override { return true; }

  void begin_run(const Scenario& sc) override;
  void control_period(const Scenario& sc, int k, double t) override;
  void after_step() override;
  void end_run() override;
  Commands commands() const override;

  std::uint32_t rejected() const override { return node_.counters().rejected; }
  std::uint32_t lost_on_purpose() const override { return faults_.lost(); }
  void add_checks(const Scenario&, std::vector<Check>&) override {}

  void rt_begin(const Scenario& sc) override;
  void rt_receive(std::int64_t, std::int64_t wait_ns) override { node_.poll(wait_ns); }
  RealtimeStep rt_step(const Scenario& sc, std::int64_t now, double t) override;
  GroupView group() const override { return {node_.speeds(), node_.ratio(), node_.forces(), node_.shift()}; }
  void rt_end() override {}
  void add_realtime_checks(double periods, std::vector<Check>& c) override;

  cvtctl::ControllerNode& node() { return node_; }

 private:
  FaultInjector faults_;
  cvtctl::ControllerNode node_;
  cvtctl::ControlSchedule sched_;
  long steps_ = 0, fresh_steps_ = 0;
};

}  // namespace cvt::sil::harness
