// Compiled for Cortex-M4F by the hil.codec_cortex_m4 test: instantiates the
// whole codec, E2E and receive pipeline with the firmware flags, so the core's
// no-heap / no-exceptions / no-RTTI promise is checked by the compiler and by
// the undefined-symbol list of the object (hil/tests/can/check_m4_codec.sh).
#include "cvtplant/can/messages.hpp"

namespace {
cvt::can::TxChannel<cvt::can::CtrlCmd> g_tx;
cvt::can::RxBank g_rx;
cvt::can::AnyMessage g_any;
}  // namespace

extern "C" int cvt_can_m4_smoke(float force_N, float torque_Nm, cvt::can::CanFrame* frame) {
  cvt::can::CtrlCmd c;
  c.clamp_force_cmd_N = force_N;
  c.driver_torque_req_Nm = torque_Nm;
  if (g_tx.encode(c, *frame) != cvt::can::CodecStatus::Ok) return -1;
  const cvt::can::RxResult r = g_rx.receive(*frame, g_any);
  cvt::can::AnyMessage scratch;
  const cvt::can::CodecStatus st = cvt::can::decode_any(*frame, scratch);
  return (r.accepted() ? 1 : 0) + static_cast<int>(st) * 2;
}
