// The C API of cvtplant_c/socketcan.h on the POSIX port's SocketCanTransport:
// one SocketCAN implementation for C and C++ programs. Built, like the port,
// without exceptions and RTTI and without the heap, it needs nothing of the
// C++ runtime: a C program links it with the C compiler driver (the template
// controller, examples/controller-c, does).
#include "cvtplant_c/socketcan.h"

#include <cstring>
#include <new>

#include "cvtplant/port/socketcan_transport.hpp"

namespace {

using cvt::port::CanIoStatus;
using cvt::port::SocketCanTransport;

static_assert(sizeof(SocketCanTransport) <= sizeof(cvt_socketcan{}.opaque.bytes), "cvt_socketcan storage too small");
static_assert(alignof(SocketCanTransport) <= 8, "cvt_socketcan storage alignment");
static_assert(static_cast<int>(CanIoStatus::IoError) == CVT_CAN_IO_ERROR &&
                  static_cast<int>(CanIoStatus::ErrorFrame) == CVT_CAN_IO_ERROR_FRAME &&
                  static_cast<int>(CanIoStatus::BusOff) == CVT_CAN_IO_BUS_OFF,
              "cvt_can_io_status must match port::CanIoStatus");
static_assert(static_cast<int>(cvt::port::CanBusState::BusOff) == CVT_CAN_BUS_OFF,
              "cvt_can_bus_state must match port::CanBusState");
static_assert(static_cast<unsigned>(cvt::can::kFrameError) == CVT_CAN_FRAME_ERROR &&
                  static_cast<unsigned>(cvt::can::kFrameRemote) == CVT_CAN_FRAME_REMOTE &&
                  static_cast<unsigned>(cvt::can::kFrameExtendedId) == CVT_CAN_FRAME_EXTENDED_ID,
              "frame flags must match");

// The transport lives in the caller's storage, built by cvt_socketcan_open.
SocketCanTransport* get(cvt_socketcan* s) { return std::launder(reinterpret_cast<SocketCanTransport*>(s->opaque.bytes)); }
const SocketCanTransport* get(const cvt_socketcan* s) {
  return std::launder(reinterpret_cast<const SocketCanTransport*>(s->opaque.bytes));
}

}  // namespace

extern "C" {

int cvt_socketcan_open(cvt_socketcan* s, const char* ifname) {
  SocketCanTransport* t = new (s->opaque.bytes) SocketCanTransport();
  return t->open(ifname);
}

void cvt_socketcan_close(cvt_socketcan* s) { get(s)->close(); }

const char* cvt_socketcan_error(const cvt_socketcan* s) { return get(s)->error_text(); }

cvt_can_io_status cvt_socketcan_send(cvt_socketcan* s, const cvt_can_frame* f) {
  cvt::can::CanFrame g;
  g.id = f->id;
  g.dlc = f->dlc;
  g.flags = f->flags;
  std::memcpy(g.data, f->data, sizeof g.data);
  return static_cast<cvt_can_io_status>(get(s)->send(g));
}

cvt_can_io_status cvt_socketcan_receive(cvt_socketcan* s, cvt_can_frame* out, int64_t timeout_ns) {
  cvt::can::CanFrame g;
  const CanIoStatus st = get(s)->receive(g, timeout_ns);
  if (st == CanIoStatus::Ok || st == CanIoStatus::ErrorFrame) {
    out->id = g.id;
    out->dlc = g.dlc;
    out->flags = g.flags;
    std::memcpy(out->data, g.data, sizeof out->data);
  }
  return static_cast<cvt_can_io_status>(st);
}

cvt_can_io_counters cvt_socketcan_counters(const cvt_socketcan* s) {
  const cvt::port::CanTransportCounters c = get(s)->counters();
  return {c.tx_frames,  c.rx_frames,       c.tx_enobufs_retries, c.tx_dropped,     c.tx_invalid,
          c.rx_error_frames, c.rx_invalid, c.rx_kernel_drops,    c.bus_off_events};
}

cvt_can_bus_state cvt_socketcan_bus_state(const cvt_socketcan* s) {
  return static_cast<cvt_can_bus_state>(get(s)->bus_state());
}

const char* cvt_can_io_status_name(cvt_can_io_status st) { return cvt::port::to_string(static_cast<CanIoStatus>(st)); }

}  // extern "C"
