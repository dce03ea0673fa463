// The controller seam of the SIL harness (docs/sil.md#harness): the runner
// plays a scenario against any controller behind this interface, the
// example controller run in-process or a controller of the user's own on
// the bus. Host only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cvtplant/sil/harness/criteria.hpp"
#include "cvtplant/sil/harness/scenario.hpp"

namespace cvt::sil::harness {

// What a real-time turn of the controller did.
struct RealtimeStep {
  bool ran = false;    // a control step ran in this turn
  bool fresh = false;  // ... on a fresh plant group
};

class ControllerUnderTest {
 public:
  virtual ~ControllerUnderTest() = default;

  // Whether the controller can take part in `sc`; `why` says why not.
  virtual bool can_run(const Scenario& sc, std::string& why) const = 0;

  // ---- lock-step (docs/sil.md#lock-step) ----
  // The plant was reset for a new run: a new run starts its E2E counters at 0.
  virtual void begin_run(const Scenario& sc) = 0;
  // Period k at time t: on return the controller's commands of the period
  // are on the bus, before the harness's Step.
  virtual void control_period(const Scenario& sc, int k, double t) = 0;
  // The period's Step was answered: the controller takes the new group.
  virtual void after_step() = 0;
  virtual void end_run() = 0;
  // The commands of the last period, for the trace.
  virtual Commands commands() const = 0;

  // ---- counters the criteria read (growth over a run) ----
  // Plant frames the controller rejected.
  virtual std::uint32_t rejected() const = 0;
  // Commands the harness lost on purpose on the controller's link.
  virtual std::uint32_t lost_on_purpose() const = 0;
  // The controller's own criteria, appended to a lock-step run's; in real
  // time those judged whether or not the plant kept time.
  virtual void add_checks(const Scenario& sc, std::vector<Check>& c) = 0;
  // Plant frames the controller rejected cannot always be observed (a
  // controller in another process).
  virtual bool observes_rejections() const { return true; }

  // ---- real time (docs/sil.md#ratio-realtime) ----
  virtual void rt_begin(const Scenario& sc) = 0;
  // Takes what the bus delivered at `now` (the pacing clock, ns), waiting up
  // to wait_ns for the first frame.
  virtual void rt_receive(std::int64_t now, std::int64_t wait_ns) = 0;
  // A control step when one is due at `now` (the pacing clock, ns).
  virtual RealtimeStep rt_step(const Scenario& sc, std::int64_t now, double t) = 0;
  // The plant group the last control step used.
  virtual GroupView group() const = 0;
  virtual void rt_end() = 0;
  // Criteria judged when the plant kept time; `periods` is the number of
  // 10 ms periods the run had a control step due in.
  virtual void add_realtime_checks(double periods, std::vector<Check>& c) = 0;
};

}  // namespace cvt::sil::harness
