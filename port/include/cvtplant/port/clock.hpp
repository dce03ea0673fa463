// Clock seam (docs/can.md#port): host monotonic time for real-time pacing,
// a virtual clock for tests and lock-step runs. Nanoseconds in int64_t cover
// 292 years, so no wrap handling is needed.
#pragma once

#include <cstdint>

namespace cvt::port {

class Clock {
 public:
  virtual int64_t now_ns() const noexcept = 0;
  // Sleep until the absolute monotonic time t_ns (no drift from relative
  // sleeps). Returns immediately when t_ns is already past.
  virtual void sleep_until(int64_t t_ns) noexcept = 0;

 protected:
  Clock() = default;
  ~Clock() = default;
};

// Time only moves when told to: sleep_until() jumps straight to the
// deadline, so a test of timeouts takes no wall time and is deterministic.
class VirtualClock final : public Clock {
 public:
  explicit constexpr VirtualClock(int64_t start_ns = 0) noexcept : now_(start_ns) {}
  int64_t now_ns() const noexcept override { return now_; }
  void sleep_until(int64_t t_ns) noexcept override {
    if (t_ns > now_) now_ = t_ns;
  }
  void advance(int64_t dt_ns) noexcept {
    if (dt_ns > 0) now_ += dt_ns;
  }

 private:
  int64_t now_;
};

}  // namespace cvt::port
