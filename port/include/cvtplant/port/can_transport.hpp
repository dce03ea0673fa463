// Abstract CAN transport (docs/can.md#port). One interface for the SocketCAN
// implementation (port/posix), the in-process loopback used by unit tests
// (port/loopback) and, later, an MCU CAN driver. Classic CAN only.
//
// Heap-free and exception-free so firmware can implement it; the destructor
// is protected and non-virtual so no deleting destructor (operator delete)
// is ever referenced on a bare-metal target.
#pragma once

#include <cstdint>

#include "cvtplant/can/frame.hpp"

namespace cvt::port {

enum class CanIoStatus : uint8_t {
  Ok,            // data frame sent / received
  ErrorFrame,    // received an error frame: reported in `out`, never data
  Timeout,       // nothing arrived before the deadline (0 = poll)
  Dropped,       // send gave up after the bounded ENOBUFS retries
  InvalidFrame,  // refused locally: DLC > 8, FD, bad ID, error/remote flags on send
  BusOff,        // controller is bus-off; sending is impossible until restart
  IoError,       // any other OS/driver error (see last_errno())
};

constexpr const char* to_string(CanIoStatus s) noexcept {
  switch (s) {
    case CanIoStatus::Ok: return "OK";
    case CanIoStatus::ErrorFrame: return "ERROR_FRAME";
    case CanIoStatus::Timeout: return "TIMEOUT";
    case CanIoStatus::Dropped: return "DROPPED";
    case CanIoStatus::InvalidFrame: return "INVALID_FRAME";
    case CanIoStatus::BusOff: return "BUS_OFF";
    case CanIoStatus::IoError: return "IO_ERROR";
  }
  return "?";
}

enum class CanBusState : uint8_t { ErrorActive, ErrorWarning, ErrorPassive, BusOff };

// Monotonic counters; never reset by the transport itself.
struct CanTransportCounters {
  uint64_t tx_frames = 0;          // data frames handed to the bus
  uint64_t rx_frames = 0;          // data frames delivered to the caller
  uint64_t tx_enobufs_retries = 0; // individual retries after ENOBUFS / full queue
  uint64_t tx_dropped = 0;         // frames given up after the retry bound
  uint64_t tx_invalid = 0;         // frames refused locally (InvalidFrame)
  uint64_t rx_error_frames = 0;    // error frames received (reported, not data)
  uint64_t rx_invalid = 0;         // malformed/FD/remote frames discarded on receive
  uint64_t rx_kernel_drops = 0;    // frames the OS dropped before we read them
  uint64_t bus_off_events = 0;     // transitions into bus-off
};

class CanTransport {
 public:
  // Queue one classic data frame. Never blocks longer than the transport's
  // documented retry bound.
  virtual CanIoStatus send(const can::CanFrame& frame) noexcept = 0;

  // Wait up to timeout_ns (0 = poll) for the next frame. Ok: a data frame in
  // `out`. ErrorFrame: `out` carries the error (flags = kFrameError, id =
  // error class bits, data = details); callers must not decode it as data.
  virtual CanIoStatus receive(can::CanFrame& out, int64_t timeout_ns) noexcept = 0;

  virtual CanTransportCounters counters() const noexcept = 0;
  virtual CanBusState bus_state() const noexcept = 0;

 protected:
  CanTransport() = default;
  CanTransport(const CanTransport&) = default;
  CanTransport& operator=(const CanTransport&) = default;
  ~CanTransport() = default;
};

// Error-class bits carried in CanFrame::id of an error frame. They are the
// Linux SocketCAN CAN_ERR_* values so the posix transport passes them
// through unchanged; other transports map their controller's errors to them.
namespace can_err {
inline constexpr uint32_t kTxTimeout = 0x001u;
inline constexpr uint32_t kLostArbitration = 0x002u;
inline constexpr uint32_t kController = 0x004u;
inline constexpr uint32_t kProtocol = 0x008u;
inline constexpr uint32_t kTransceiver = 0x010u;
inline constexpr uint32_t kNoAck = 0x020u;
inline constexpr uint32_t kBusOff = 0x040u;
inline constexpr uint32_t kBusError = 0x080u;
inline constexpr uint32_t kRestarted = 0x100u;
// data[1] bits when kController is set.
inline constexpr uint8_t kCtrlRxWarning = 0x04u;
inline constexpr uint8_t kCtrlTxWarning = 0x08u;
inline constexpr uint8_t kCtrlRxPassive = 0x10u;
inline constexpr uint8_t kCtrlTxPassive = 0x20u;
inline constexpr uint8_t kCtrlActive = 0x40u;
}  // namespace can_err

// Bus state after an error frame, shared by all transports so they agree.
constexpr CanBusState next_bus_state(CanBusState prev, const can::CanFrame& err) noexcept {
  if (err.id & can_err::kBusOff) return CanBusState::BusOff;
  if (err.id & can_err::kRestarted) return CanBusState::ErrorActive;
  if (err.id & can_err::kController) {
    const uint8_t c = err.data[1];
    if (c & (can_err::kCtrlRxPassive | can_err::kCtrlTxPassive)) return CanBusState::ErrorPassive;
    if (c & (can_err::kCtrlRxWarning | can_err::kCtrlTxWarning)) return CanBusState::ErrorWarning;
    if (c & can_err::kCtrlActive) return CanBusState::ErrorActive;
  }
  return prev;
}

}  // namespace cvt::port
