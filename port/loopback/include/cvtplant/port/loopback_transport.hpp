// In-process CAN bus for unit tests (docs/can.md#port): N nodes, each with a
// fixed receive ring; a frame sent by one node is delivered to every other
// node, as on a real bus. Heap-free, single-threaded, never blocks: an
// empty receive with a timeout advances the attached VirtualClock instead.
// Test hooks inject error frames, transmit-buffer exhaustion and lost frames
// so the error paths of code above the transport can be exercised.
#pragma once

#include <cstddef>
#include <cstdint>

#include "cvtplant/can/frame.hpp"
#include "cvtplant/port/can_transport.hpp"
#include "cvtplant/port/clock.hpp"

namespace cvt::port {

template <size_t kNodes, size_t kDepth>
class LoopbackBus {
  static_assert(kNodes >= 1 && kDepth >= 1, "need at least one node and one slot");

 public:
  // Retries a node makes when its transmit path reports "no buffer"
  // (the ENOBUFS analogue) before dropping the frame.
  static constexpr uint32_t kTxRetryBound = 4;

  class Node final : public CanTransport {
   public:
    CanIoStatus send(const can::CanFrame& f) noexcept override {
      if (f.dlc > can::kMaxClassicDlc || (f.flags & can::kFrameError) ||
          f.id > ((f.flags & can::kFrameExtendedId) ? can::kExtIdMask : can::kStdIdMask)) {
        ++counters_.tx_invalid;
        return CanIoStatus::InvalidFrame;
      }
      if (state_ == CanBusState::BusOff) return CanIoStatus::BusOff;
      for (uint32_t attempt = 0;; ++attempt) {
        if (tx_fail_budget_ == 0) break;
        --tx_fail_budget_;
        if (attempt == kTxRetryBound) {
          ++counters_.tx_dropped;
          return CanIoStatus::Dropped;
        }
        ++counters_.tx_enobufs_retries;
      }
      bus_->broadcast(index_, f);
      ++counters_.tx_frames;
      return CanIoStatus::Ok;
    }

    CanIoStatus receive(can::CanFrame& out, int64_t timeout_ns) noexcept override {
      if (count_ == 0) {
        if (bus_->clock_ && timeout_ns > 0) bus_->clock_->sleep_until(bus_->clock_->now_ns() + timeout_ns);
        return CanIoStatus::Timeout;
      }
      out = ring_[head_];
      head_ = (head_ + 1) % kDepth;
      --count_;
      if (out.flags & can::kFrameError) {
        ++counters_.rx_error_frames;
        const CanBusState next = next_bus_state(state_, out);
        if (next == CanBusState::BusOff && state_ != CanBusState::BusOff) ++counters_.bus_off_events;
        state_ = next;
        return CanIoStatus::ErrorFrame;
      }
      ++counters_.rx_frames;
      return CanIoStatus::Ok;
    }

    CanTransportCounters counters() const noexcept override { return counters_; }
    CanBusState bus_state() const noexcept override { return state_; }

    // Test hook: the next n transmit attempts find no buffer.
    void fail_next_tx_attempts(uint32_t n) noexcept { tx_fail_budget_ = n; }
    size_t pending() const noexcept { return count_; }

   private:
    friend class LoopbackBus;

    void enqueue(const can::CanFrame& f) noexcept {
      if (count_ == kDepth) {
        ++counters_.rx_kernel_drops;  // receiver overrun, like a full socket buffer
        return;
      }
      ring_[(head_ + count_) % kDepth] = f;
      ++count_;
    }

    LoopbackBus* bus_ = nullptr;
    size_t index_ = 0;
    can::CanFrame ring_[kDepth] = {};
    size_t head_ = 0;
    size_t count_ = 0;
    uint32_t tx_fail_budget_ = 0;
    CanBusState state_ = CanBusState::ErrorActive;
    CanTransportCounters counters_{};
  };

  explicit LoopbackBus(Clock* clock = nullptr) noexcept : clock_(clock) {
    for (size_t i = 0; i < kNodes; ++i) {
      nodes_[i].bus_ = this;
      nodes_[i].index_ = i;
    }
  }
  LoopbackBus(const LoopbackBus&) = delete;
  LoopbackBus& operator=(const LoopbackBus&) = delete;

  Node& node(size_t i) noexcept { return nodes_[i]; }

  // Test hook: a frame lost on the wire. `drop(ctx, from_node, frame)`
  // returning true makes the frame reach no node; the sender still sees Ok
  // (CAN has no end-to-end acknowledgement). Plain function pointer and
  // context: heap-free. nullptr removes the hook.
  using DropFilter = bool (*)(void* ctx, size_t from_node, const can::CanFrame& f);
  void set_drop_filter(DropFilter drop, void* ctx = nullptr) noexcept {
    drop_ = drop;
    drop_ctx_ = ctx;
  }
  uint64_t frames_dropped() const noexcept { return frames_dropped_; }

  // Test hook: deliver an error frame (class bits in `error_class`,
  // controller detail in data[1]) to one node.
  void inject_error(size_t node_index, uint32_t error_class, uint8_t ctrl_detail = 0) noexcept {
    can::CanFrame e;
    e.flags = can::kFrameError;
    e.id = error_class;
    e.dlc = 8;
    e.data[1] = ctrl_detail;
    nodes_[node_index].enqueue(e);
  }

 private:
  void broadcast(size_t from, const can::CanFrame& f) noexcept {
    if (drop_ != nullptr && drop_(drop_ctx_, from, f)) {
      ++frames_dropped_;
      return;
    }
    for (size_t i = 0; i < kNodes; ++i)
      if (i != from) nodes_[i].enqueue(f);
  }

  Clock* clock_;
  DropFilter drop_ = nullptr;
  void* drop_ctx_ = nullptr;
  uint64_t frames_dropped_ = 0;
  Node nodes_[kNodes];
};

}  // namespace cvt::port
