// Linux SocketCAN transport on a raw CAN socket (docs/can.md#port).
//
// - Classic CAN only: the socket never enables CAN_RAW_FD_FRAMES, so the
//   kernel does not hand FD frames up; anything that is not a classic frame
//   is counted in rx_invalid and skipped.
// - Error frames: CAN_RAW_ERR_FILTER subscribes to every error class; they
//   come back as CanIoStatus::ErrorFrame and update bus_state(), never as data.
// - ENOBUFS / EAGAIN on send (vcan's small queue): retried up to
//   `enobufs_retries` times with `enobufs_backoff_ns` between attempts, each
//   retry counted; after the bound the frame is dropped and counted.
// - Kernel receive-queue drops are read from SO_RXQ_OVFL.
#pragma once

#include <cstdint>

#include "cvtplant/port/can_transport.hpp"

namespace cvt::port {

struct SocketCanConfig {
  uint32_t enobufs_retries = 16;
  // 50 us: a few frame times at 1 Mbit/s (an 8-byte frame is ~110 bits),
  // enough for the queue to drain one frame without stalling a 1 kHz loop.
  int64_t enobufs_backoff_ns = 50000;
  bool receive_own_messages = false;   // CAN_RAW_RECV_OWN_MSGS
};

class SocketCanTransport final : public CanTransport {
 public:
  SocketCanTransport() = default;
  ~SocketCanTransport();
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  // Open and bind `ifname`. Returns 0 or the errno of the failing step;
  // error_text() names the step (e.g. "socket(AF_CAN): Address family not
  // supported by protocol" on a kernel without SocketCAN).
  int open(const char* ifname, const SocketCanConfig& cfg = {}) noexcept;
  void close() noexcept;
  bool is_open() const noexcept { return fd_ >= 0; }
  const char* error_text() const noexcept { return error_; }
  int last_errno() const noexcept { return last_errno_; }

  CanIoStatus send(const can::CanFrame& frame) noexcept override;
  CanIoStatus receive(can::CanFrame& out, int64_t timeout_ns) noexcept override;
  CanTransportCounters counters() const noexcept override { return counters_; }
  CanBusState bus_state() const noexcept override { return state_; }

 private:
  void fail(const char* step, int err) noexcept;

  int fd_ = -1;
  SocketCanConfig cfg_{};
  CanTransportCounters counters_{};
  CanBusState state_ = CanBusState::ErrorActive;
  uint32_t kernel_drops_seen_ = 0;
  int last_errno_ = 0;
  char error_[160] = {};
};

}  // namespace cvt::port
