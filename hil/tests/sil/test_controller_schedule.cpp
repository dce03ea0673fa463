// The example controller's schedule on a real-time bus
// (docs/sil.md#controller-schedule): how many control steps see a fresh plant
// output group, with the controller on its own 10 ms clock and with
// ControlSchedule, against the real-time bridge on the loopback bus. Both
// sides wake up late by a deterministic pseudo-random jitter, and the plant
// stalls now and then and catches up, as processes on a loaded host do.
#include <doctest/doctest.h>

#include <cstdint>

#include "cvtctl/control_schedule.hpp"
#include "cvtctl/controller_node.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/sil/bridge.hpp"

using namespace cvt;

namespace {

constexpr std::int64_t kMs = 1000000;
constexpr std::int64_t kTick = 100000;  // simulation resolution: 0.1 ms

// Park-Miller minimal standard generator: reproducible on every platform.
struct Lcg {
  std::uint32_t s;
  std::uint32_t next() {
    s = static_cast<std::uint32_t>((static_cast<std::uint64_t>(s) * 48271u) % 2147483647u);
    return s;
  }
  // Uniform in [0, n) ticks.
  std::int64_t ticks(std::int64_t n) { return static_cast<std::int64_t>(next() % static_cast<std::uint32_t>(n)); }
};

// Wake-up lateness of a process: mostly under 0.5 ms, one in ten 1-6 ms.
std::int64_t wake_jitter(Lcg& r) {
  std::int64_t j = r.ticks(5) * kTick;
  if (r.next() % 10 == 0) j += (10 + r.ticks(50)) * kTick;
  return j;
}

struct Result {
  std::uint32_t steps = 0, fresh = 0;
  // Stale steps although the plant's last group was less than 15 ms old:
  // the plant was on time, the controller looked at the wrong moment.
  std::uint32_t stale_plant_on_time = 0;
  double fraction() const { return steps == 0 ? 0.0 : static_cast<double>(fresh) / steps; }
};

// Runs the bridge in real time and the controller for `seconds` of virtual
// time. aligned: ControlSchedule; otherwise a fixed 10 ms clock started at
// `phase`.
Result run(bool aligned, std::int64_t phase, std::uint32_t seed, int seconds) {
  port::VirtualClock clock;
  port::LoopbackBus<2, 256> bus(&clock);
  sil::Bridge bridge(bus.node(0), clock);
  REQUIRE(bridge.load_scene(*find_builtin_scene("tip-in")));
  bridge.start_realtime();
  cvtctl::ControllerNode ctl(bus.node(1));
  cvtctl::ControlSchedule sched;
  Lcg rng{seed};

  std::int64_t bridge_deadline = kMs, bridge_wake = kMs;  // the bridge's next frame and when it wakes for it
  std::int64_t fixed_deadline = phase;                   // the fixed-clock controller's next period
  std::int64_t ctl_wake = -1;                            // when the controller's pending step runs
  std::int64_t last_group_t = -1;
  std::uint64_t groups = 0;
  Result r;
  const std::int64_t end = seconds * 1000 * kMs;
  for (std::int64_t t = 0; t < end; t += kTick) {
    clock.advance(t - clock.now_ns());
    // Bridge: wakes late, then runs every frame whose deadline has passed
    // (catch-up after a stall, docs/sil.md#real-time).
    if (t >= bridge_wake) {
      while (bridge_deadline <= t) {
        bridge.realtime_frame();
        bridge_deadline += kMs;
      }
      if (bridge.groups_sent() != groups) {
        groups = bridge.groups_sent();
        last_group_t = t;
      }
      // One frame in 300 the process is descheduled for 5-25 ms.
      const std::int64_t stall = rng.next() % 300 == 0 ? (50 + rng.ticks(200)) * kTick : 0;
      bridge_wake = bridge_deadline + wake_jitter(rng) + stall;
    }
    // Controller.
    ctl.poll(0);
    if (ctl_wake < 0) {
      const bool due = aligned ? sched.due(t, ctl.fresh_group()) : t >= fixed_deadline;
      if (due) ctl_wake = t + wake_jitter(rng);
    }
    if (ctl_wake >= 0 && t >= ctl_wake) {
      ctl.poll(0);
      const std::uint32_t fresh_before = ctl.counters().fresh_periods;
      ctl.control_step(80.0f);
      if (ctl.counters().fresh_periods == fresh_before && last_group_t >= 0 && t - last_group_t < 15 * kMs)
        ++r.stale_plant_on_time;
      sched.ran(t);
      fixed_deadline += 10 * kMs;
      ctl_wake = -1;
    }
  }
  r.steps = ctl.counters().fresh_periods + ctl.counters().invalid_periods;
  r.fresh = ctl.counters().fresh_periods;
  CHECK(bridge.cmd_timeouts() <= 1);  // the start, before the first command
  return r;
}

}  // namespace

TEST_CASE("controller schedule: fraction of control steps with fresh plant data, fixed 10 ms clock vs ControlSchedule") {
  double fixed_sum = 0, fixed_min = 1, fixed_max = 0, aligned_min = 1;
  std::uint32_t fixed_on_time = 0;
  std::uint32_t aligned_steps = 0, aligned_fresh = 0;
  for (int phase_ms = 0; phase_ms < 10; ++phase_ms) {
    CAPTURE(phase_ms);
    const auto seed = static_cast<std::uint32_t>(12345 + phase_ms);
    const Result fixed = run(false, phase_ms * kMs + 5 * kTick, seed, 5);
    const Result aligned = run(true, 0, seed, 5);
    fixed_sum += fixed.fraction();
    fixed_min = fixed.fraction() < fixed_min ? fixed.fraction() : fixed_min;
    fixed_max = fixed.fraction() > fixed_max ? fixed.fraction() : fixed_max;
    aligned_min = aligned.fraction() < aligned_min ? aligned.fraction() : aligned_min;
    aligned_steps += aligned.steps;
    aligned_fresh += aligned.fresh;
    // About one step per group either way (the plant sends 500 in 5 s).
    CHECK(fixed.steps >= 495);
    CHECK(aligned.steps >= 450);
    CHECK(aligned.steps <= 520);
    // ControlSchedule runs on stale inputs only when the plant is late.
    CHECK(aligned.stale_plant_on_time == 0);
    fixed_on_time += fixed.stale_plant_on_time;
  }
  const double fixed_mean = fixed_sum / 10.0;
  MESSAGE("fresh fraction, fixed 10 ms clock: mean " << fixed_mean << ", phases from " << fixed_min << " to "
                                                       << fixed_max
                                                       << "; ControlSchedule: overall "
                                                       << static_cast<double>(aligned_fresh) / aligned_steps
                                                       << ", worst " << aligned_min
                                                       << "; fixed-clock stale steps with the plant on time: "
                                                       << fixed_on_time);
  // The stale steps left with ControlSchedule are the plant's stalls.
  CHECK(aligned_min >= 0.95);
  CHECK(fixed_mean <= 0.95);
  CHECK(aligned_min > fixed_min + 0.05);
  CHECK(fixed_on_time > 0);
}

TEST_CASE("controller node: a group the plant sent again is not fresh; a tag coming round after 16 samples is") {
  port::VirtualClock clock;
  port::LoopbackBus<3, 256> bus(&clock);  // bridge, harness, controller
  sil::Bridge bridge(bus.node(0), clock);
  REQUIRE(bridge.load_scene(*find_builtin_scene("tip-in")));
  cvtctl::ControllerNode ctl(bus.node(2));
  can::TxChannel<can::SimCtrl> sim;
  std::uint8_t seq = 0;
  auto request = [&](bool again) {
    can::SimCtrl m;
    m.sim_request = can::SimRequest::Step;
    m.step_count = 10;
    if (!again) seq = static_cast<std::uint8_t>((seq + 1) & 0x0F);
    m.step_seq = seq;
    can::CanFrame f;
    REQUIRE(sim.encode(m, f) == can::CodecStatus::Ok);
    REQUIRE(bus.node(1).send(f) == port::CanIoStatus::Ok);
    bridge.service(0);
    ctl.poll(0);
  };
  request(false);
  REQUIRE(ctl.fresh_group());
  const std::uint8_t used = ctl.speeds().sample_tag;
  ctl.control_step(50.0f);
  CHECK(ctl.counters().fresh_periods == 1);
  request(true);  // the harness sends the same request again: same group
  CHECK(ctl.group_complete());
  CHECK(ctl.speeds().sample_tag == used);
  CHECK_FALSE(ctl.fresh_group());
  ctl.control_step(50.0f);
  CHECK(ctl.counters().invalid_periods == 1);
  // The controller misses 16 steps (a lock-step harness that does not run
  // it, or a stalled ECU): the 16th new sample has the used tag again.
  for (int i = 0; i < 16; ++i) request(false);
  CHECK(ctl.speeds().sample_tag == used);
  CHECK(ctl.fresh_group());
}
