// Host monotonic clock: CLOCK_MONOTONIC, absolute-deadline sleeps with
// clock_nanosleep(TIMER_ABSTIME) so a periodic loop does not drift
// (docs/can.md#port).
#pragma once

#include "cvtplant/port/clock.hpp"

namespace cvt::port {

class PosixMonotonicClock final : public Clock {
 public:
  int64_t now_ns() const noexcept override;
  void sleep_until(int64_t t_ns) noexcept override;
};

}  // namespace cvt::port
