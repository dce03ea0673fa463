// When the example controller runs its control step on a real-time bus
// (docs/sil.md#controller-schedule). Heap-free, integer nanoseconds.
//
// A controller that runs on its own 10 ms clock samples the plant's 10 ms
// output groups at a phase that jitter and drift move across the groups'
// arrival: some periods see two groups, the next none, and run on stale
// inputs. Here the step follows the plant instead: it runs as soon as a
// fresh group is complete, but never sooner than min_gap after the previous
// step (a burst of groups, e.g. a plant catching up, gives one step on the
// newest), and runs anyway max_wait after the previous step when no fresh
// group came (stale inputs, handled by the law; CtrlCmd keeps coming well
// inside the plant's 50 ms deadline).
#pragma once

#include <cstdint>

namespace cvtctl {

struct ControlScheduleParams {
  std::int64_t min_gap_ns = 5000000;    // half the CtrlCmd cycle
  std::int64_t max_wait_ns = 15000000;  // 1.5 CtrlCmd cycles
};

class ControlSchedule {
 public:
  explicit constexpr ControlSchedule(const ControlScheduleParams& p = {}) : p_(p) {}

  // Until when the caller may wait for a fresh group (absolute, ns).
  constexpr std::int64_t wait_until_ns() const { return started_ ? last_ns_ + p_.max_wait_ns : 0; }
  // Earliest time a fresh group may start the next step.
  constexpr std::int64_t earliest_ns() const { return started_ ? last_ns_ + p_.min_gap_ns : 0; }
  constexpr bool due(std::int64_t now_ns, bool fresh_group) const {
    return now_ns >= (fresh_group ? earliest_ns() : wait_until_ns());
  }
  constexpr void ran(std::int64_t now_ns) {
    last_ns_ = now_ns;
    started_ = true;
  }
  constexpr const ControlScheduleParams& params() const { return p_; }

 private:
  ControlScheduleParams p_;
  std::int64_t last_ns_ = 0;
  bool started_ = false;
};

}  // namespace cvtctl
