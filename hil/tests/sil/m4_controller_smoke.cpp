// Compiled for Cortex-M4F by the hil.sil_controller_cortex_m4 test
// (hil/tests/can/check_m4_codec.sh): the example controller's law and CAN node
// on a stand-in for an MCU CAN driver, with the firmware flags. Any heap,
// exception or RTTI reference fails the test (docs/sil.md#controller).
#include "cvtctl/control_schedule.hpp"
#include "cvtctl/controller_node.hpp"

namespace {

// What an ECU's CAN driver would provide: a fixed mailbox, no OS.
class MailboxCan final : public cvt::port::CanTransport {
 public:
  cvt::port::CanIoStatus send(const cvt::can::CanFrame& f) noexcept override {
    last_tx = f;
    ++counters_.tx_frames;
    return cvt::port::CanIoStatus::Ok;
  }
  cvt::port::CanIoStatus receive(cvt::can::CanFrame& out, int64_t) noexcept override {
    if (!rx_full) return cvt::port::CanIoStatus::Timeout;
    out = rx;
    rx_full = false;
    ++counters_.rx_frames;
    return cvt::port::CanIoStatus::Ok;
  }
  cvt::port::CanTransportCounters counters() const noexcept override { return counters_; }
  cvt::port::CanBusState bus_state() const noexcept override { return cvt::port::CanBusState::ErrorActive; }

  cvt::can::CanFrame rx{}, last_tx{};
  bool rx_full = false;

 private:
  cvt::port::CanTransportCounters counters_{};
};

MailboxCan g_can;
cvtctl::ControllerNode g_node(g_can);
cvtctl::ControlSchedule g_schedule;

}  // namespace

// One frame in at now_ns; a control step when the schedule says so; returns
// the clamping command [N].
extern "C" float cvt_controller_m4_smoke(const cvt::can::CanFrame* in, float demand_Nm, int64_t now_ns) {
  g_can.rx = *in;
  g_can.rx_full = true;
  g_node.poll(0);
  if (g_schedule.due(now_ns, g_node.fresh_group())) {
    g_node.control_step(demand_Nm);
    g_schedule.ran(now_ns);
  }
  return g_node.last_output().clamp_force_cmd_N;
}

// The same with ratio control (docs/sil.md#ratio-control): both clamping
// commands from RatioLaw; returns the driven one [N].
extern "C" float cvt_controller_m4_ratio_smoke(const cvt::can::CanFrame* in, float demand_Nm, float ratio_target,
                                               int64_t now_ns) {
  g_can.rx = *in;
  g_can.rx_full = true;
  g_node.poll(0);
  if (g_schedule.due(now_ns, g_node.fresh_group())) {
    g_node.control_step_ratio(demand_Nm, ratio_target);
    g_schedule.ran(now_ns);
  }
  return g_node.last_ratio_output().driven_clamp_cmd_N;
}
