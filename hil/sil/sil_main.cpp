// cvtplant-sil: the SIL harness (docs/sil.md#scenarios). It plays two nodes
// on the bus, each with its own socket: the Harness (SimCtrl lock-step
// requests, HarnessLoad) and the example Controller (hil/controller). For
// each scenario it resets the bridge, runs the closed loop in 10 ms
// lock-step periods (the ratio scenarios also in real time, the bridge
// pacing the plant), checks the pass/fail criteria and writes a CSV trace;
// all results go to one JUnit XML file. `bench` measures lock-step round
// trips per second.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cvtctl/control_schedule.hpp"
#include "cvtctl/controller_node.hpp"
#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/sil/bridge.hpp"
#include "cvtplant/sil/latency_stats.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/port/socketcan_transport.hpp"

namespace {

using cvt::can::CanFrame;
using cvt::port::CanIoStatus;

constexpr int kFramesPerPeriod = 10;  // 10 ms control period = CtrlCmd cycle, 1 ms plant frames
constexpr double kPeriod_s = 0.01;
// A hang guard, not a criterion: the starved TCG micro-VM has shown single
// round trips of 1.6 s (docs/sil.md#figures).
constexpr std::int64_t kReplyTimeout_ns = 10000000000;

const char kUsage[] =
    "usage: cvtplant-sil run   [--iface NAME|--loopback] [--scenario NAME|all] [--out DIR] [--junit FILE] [--safety X]\n"
    "                          [--reply-timeout-ms T] [--mode lockstep|realtime|both]\n"
    "                          [--loopback-frame-cost-us US]\n"
    "       cvtplant-sil bench [--iface NAME|--loopback] [--steps N] [--with-controller] [--reply-timeout-ms T]\n"
    "Drives cvtplant-bridge with the example controller over SocketCAN.\n"
    "  --iface NAME        interface (default vcan0)\n"
    "  --loopback          no SocketCAN: the bridge runs in-process on the loopback bus\n"
    "  --scenario NAME     ratio-sweep, kick-down, slip-recovery, tip-in, load-step, clamp-loss,\n"
    "                      lost-frames, frozen-controller, controller-restart, controller-flood\n"
    "                      or all (default all)\n"
    "  --mode M            lockstep (default): the harness steps the plant; realtime: the ratio\n"
    "                      scenarios with the bridge pacing the plant at 1 kHz (on the wall clock;\n"
    "                      with --loopback on a virtual clock); both: each scenario in lock-step,\n"
    "                      a ratio scenario then again in real time. A real-time run whose plant\n"
    "                      overran more than 1 % of its frames reports the motion criteria as skipped\n"
    "  --loopback-frame-cost-us US  real time on the loopback bus: each plant frame's work takes US us\n"
    "                      of virtual time (default 0; above 1000 the plant cannot keep time)\n"
    "  --reply-timeout-ms T  send a request again when its answer is not complete after T ms\n"
    "                      (default 1000; 20 with --loopback, whose answers are immediate)\n"
    "  --out DIR           per-scenario CSV traces (default .)\n"
    "  --junit FILE        JUnit XML report of every criterion\n"
    "  --safety X          override the controller's safety factor (default 1.3)\n"
    "  --steps N           bench: lock-step round trips (default 5000)\n"
    "  --with-controller   bench: a CtrlCmd from the controller before each Step\n"
    "Exit status: 0 all criteria passed, 1 a criterion failed or the bridge did not answer, 2 bad command line.\n";

[[noreturn]] void bad_usage(const std::string& msg) {
  std::fprintf(stderr, "cvtplant-sil: %s (see --help)\n", msg.c_str());
  std::exit(2);
}

// ---- Fault injection ------------------------------------------------------

// Wraps a node's transport to lose frames on purpose (docs/sil.md#lost-frames):
// the next sent frame with an ID (lost on the wire: the sender sees Ok, as
// on CAN), the next received frame with an ID (lost to this receiver, e.g. a
// queue overflow), and a frozen mode in which every send repeats the last
// frame sent before the freeze (a hung ECU whose CAN driver keeps sending
// its mailbox). Works on any transport, so the scenarios run the same on
// vcan and on the loopback bus.
class FaultInjector final : public cvt::port::CanTransport {
 public:
  explicit FaultInjector(cvt::port::CanTransport& inner) : inner_(inner) {}

  void lose_next_sent(std::uint32_t id) { lose_tx_ = static_cast<std::int64_t>(id); }
  void lose_next_received(std::uint32_t id) { lose_rx_ = static_cast<std::int64_t>(id); }
  void freeze(bool on) { frozen_ = on && have_last_; }
  // Scales both clamping commands on the wire (CtrlCmd, CtrlShiftCmd) by
  // `s`, counter kept and CRC recomputed: the actuators' supply pressure
  // dropping to a fraction, which the controller sees only as slip.
  void scale_clamp(float s) { clamp_scale_ = s; }
  std::uint32_t lost() const { return lost_; }

  CanIoStatus send(const CanFrame& f) noexcept override {
    if (lose_tx_ == static_cast<std::int64_t>(f.id)) {
      lose_tx_ = -1;
      ++lost_;
      return CanIoStatus::Ok;
    }
    if (frozen_) return inner_.send(last_);
    last_ = f;
    have_last_ = true;
    if (clamp_scale_ != 1.0f && f.dlc == 8 && (f.id == cvt::can::CtrlCmd::kId || f.id == cvt::can::CtrlShiftCmd::kId)) {
      CanFrame g = f;
      if (f.id == cvt::can::CtrlCmd::kId) rescale<cvt::can::CtrlCmd>(g, [this](cvt::can::CtrlCmd& m) {
          m.clamp_force_cmd_N *= clamp_scale_;
        });
      else rescale<cvt::can::CtrlShiftCmd>(g, [this](cvt::can::CtrlShiftCmd& m) {
          m.driven_clamp_force_cmd_N *= clamp_scale_;
        });
      return inner_.send(g);
    }
    return inner_.send(f);
  }
  CanIoStatus receive(CanFrame& out, std::int64_t timeout_ns) noexcept override {
    CanIoStatus st = inner_.receive(out, timeout_ns);
    if (st == CanIoStatus::Ok && lose_rx_ == static_cast<std::int64_t>(out.id)) {
      lose_rx_ = -1;
      ++lost_;
      st = inner_.receive(out, 0);
    }
    return st;
  }
  cvt::port::CanTransportCounters counters() const noexcept override { return inner_.counters(); }
  cvt::port::CanBusState bus_state() const noexcept override { return inner_.bus_state(); }

 private:
  template <class Msg, class Edit>
  static void rescale(CanFrame& g, Edit edit) {
    Msg m;
    if (cvt::can::unpack(g.data, m) != cvt::can::CodecStatus::Ok) return;
    edit(m);
    std::uint8_t q[8];
    if (cvt::can::pack(m, q) != cvt::can::CodecStatus::Ok) return;
    q[1] = static_cast<std::uint8_t>((q[1] & 0xF0u) | (g.data[1] & 0x0Fu));
    q[0] = cvt::can::e2e_crc(Msg::kE2eDataId, q);
    std::memcpy(g.data, q, 8);
  }

  cvt::port::CanTransport& inner_;
  float clamp_scale_ = 1.0f;
  std::int64_t lose_tx_ = -1, lose_rx_ = -1;
  bool frozen_ = false, have_last_ = false;
  CanFrame last_{};
  std::uint32_t lost_ = 0;
};

// ---- Harness node ----------------------------------------------------------

class Harness {
 public:
  // on_idle runs whenever the bus has nothing for the harness: with the
  // bridge in-process on the loopback bus (--loopback) it services the bridge.
  Harness(cvt::port::CanTransport& bus, std::int64_t reply_timeout_ns, std::function<void()> on_idle = {})
      : bus_(bus), reply_timeout_ns_(reply_timeout_ns), on_idle_(std::move(on_idle)) {}

  // One request and its complete answer (docs/sil.md#lost-frames): when no
  // PlantStatus acknowledging it arrives within the reply timeout, or the
  // group around it is incomplete, the same request (same step_seq, next
  // E2E counter) is sent again, up to kMaxResends times. The bridge
  // executes a step_seq once and answers a repeat with the same group.
  bool request(cvt::can::SimRequest r, std::uint16_t steps, cvt::can::SceneId scene) {
    cvt::can::SimCtrl m;
    m.sim_request = r;
    m.step_count = steps;
    m.scene_id = scene;
    m.step_seq = seq_;
    bool ok = false;
    const std::int64_t t_first = clock_.now_ns();
    int attempt = 0;
    for (; attempt <= kMaxResends && !ok; ++attempt) {
      if (attempt > 0) ++resends_;
      CanFrame f;
      if (sim_.encode(m, f) != cvt::can::CodecStatus::Ok || bus_.send(f) != CanIoStatus::Ok) break;
      // The last attempt waits as long as the hang guard allows.
      const Reply rep = wait_status(seq_, attempt == kMaxResends ? kReplyTimeout_ns : reply_timeout_ns_);
      if (rep == Reply::Complete) ok = true;
      else if (rep == Reply::Partial) ++partial_groups_;
      else ++no_reply_;
    }
    // Wall time from the first send to the complete answer of a request
    // that had to be sent again: what a lost frame costs the harness.
    if (ok && attempt > 1) {
      const std::int64_t took = clock_.now_ns() - t_first;
      max_recovery_ns_ = took > max_recovery_ns_ ? took : max_recovery_ns_;
    }
    seq_ = static_cast<std::uint8_t>((seq_ + 1) & 0x0F);
    return ok;
  }

  // The bridge may still hold another harness's last SimCtrl counter and
  // step_seq, which ours could repeat: a None request that is answered
  // (executing nothing either way) proves the next counter and step_seq
  // are taken as new (docs/can.md#e2e-checker, docs/sil.md#lost-frames).
  bool sync() {
    for (int i = 0; i < 5; ++i) {
      cvt::can::SimCtrl m;
      m.step_seq = seq_;
      CanFrame f;
      if (sim_.encode(m, f) != cvt::can::CodecStatus::Ok || bus_.send(f) != CanIoStatus::Ok) return false;
      const bool answered = wait_status(seq_, 1000000000) != Reply::None;
      seq_ = static_cast<std::uint8_t>((seq_ + 1) & 0x0F);
      if (answered) return true;
    }
    return false;
  }

  // Real time (docs/sil.md#ratio-realtime): SimCtrl RunRealTime, which the
  // bridge does not answer; it paces its frames from then on.
  bool start_realtime() {
    cvt::can::SimCtrl m;
    m.sim_request = cvt::can::SimRequest::RunRealTime;
    m.step_seq = seq_;
    seq_ = static_cast<std::uint8_t>((seq_ + 1) & 0x0F);
    CanFrame f;
    if (sim_.encode(m, f) != cvt::can::CodecStatus::Ok || bus_.send(f) != CanIoStatus::Ok) return false;
    if (on_idle_) on_idle_();
    return true;
  }

  // Back to Ready with the closing diagnostics. A real-time PlantStatus
  // acknowledges step_seq 0, so the Pause never uses 0: the answer cannot
  // be mistaken for a cyclic status still on its way (skipping a value is
  // not a repeat for the bridge).
  bool pause() {
    if (seq_ == 0) seq_ = 1;
    return request(cvt::can::SimRequest::Pause, 0, cvt::can::SceneId::Keep);
  }

  // Reads every frame already queued (a real-time run's cyclic frames).
  void drain() {
    CanFrame f;
    for (CanIoStatus st = bus_.receive(f, 0); st != CanIoStatus::Timeout; st = bus_.receive(f, 0))
      if (st == CanIoStatus::Ok) take(f);
  }
  std::uint32_t realtime_statuses() const { return realtime_statuses_; }

  bool send_load(bool active, float torque_Nm) {
    cvt::can::HarnessLoad m;
    m.load_override_active = active;
    m.load_torque_override_Nm = torque_Nm;
    CanFrame f;
    return load_.encode(m, f) == cvt::can::CodecStatus::Ok && bus_.send(f) == CanIoStatus::Ok;
  }

  const cvt::can::PlantStatus& status() const { return status_; }
  const cvt::can::PlantForces& forces() const { return forces_; }
  const cvt::can::PlantShift& shift() const { return shift_; }
  // A variable-ratio scene's groups also carry PlantShift (docs/can.md#layout).
  void expect_shift(bool on) { expect_shift_ = on; }
  const cvt::can::PlantSpeeds& speeds() const { return speeds_; }
  const cvt::can::PlantRatio& ratio() const { return ratio_; }
  const cvt::can::PlantDiag& diag() const { return diag_; }
  const cvt::can::PlantCmdDiag& cmd_diag() const { return cmd_diag_; }
  const cvt::can::PlantBusDiag& bus_diag() const { return bus_diag_; }
  std::uint32_t rejected() const { return rejected_; }
  std::uint32_t mixed_groups() const { return mixed_groups_; }
  std::uint32_t resends() const { return resends_; }
  std::uint32_t no_reply() const { return no_reply_; }
  std::uint32_t partial_groups() const { return partial_groups_; }
  std::int64_t max_recovery_ns() const { return max_recovery_ns_; }
  void clear_recovery() { max_recovery_ns_ = 0; }

 private:
  static constexpr int kMaxResends = 3;
  enum class Reply { None, Partial, Complete };

  // Reads the bus until the PlantStatus acknowledging `seq` (the end of the
  // group), checking every plant frame through the E2E receive pipeline.
  // Complete: the three state frames before it carry its sample_tag.
  Reply wait_status(std::uint8_t seq, std::int64_t timeout_ns) {
    const std::int64_t end = clock_.now_ns() + timeout_ns;
    for (;;) {
      const std::int64_t left = end - clock_.now_ns();
      if (left <= 0) return Reply::None;
      CanFrame f;
      const CanIoStatus st = bus_.receive(f, on_idle_ ? 0 : left);
      if (st == CanIoStatus::Timeout && on_idle_) on_idle_();
      if (st != CanIoStatus::Ok || !take(f)) continue;
      if (status_.step_seq_ack != seq) continue;
      if (speeds_.sample_tag != status_.sample_tag || ratio_.sample_tag != status_.sample_tag ||
          forces_.sample_tag != status_.sample_tag || (expect_shift_ && shift_.sample_tag != status_.sample_tag))
        return Reply::Partial;
      return Reply::Complete;
    }
  }

  // One received frame through the E2E receive pipeline into the latest
  // plant state; true when it was an accepted PlantStatus.
  bool take(const CanFrame& f) {
    if (f.id < cvt::can::PlantSpeeds::kId) return false;  // SimCtrl/CtrlCmd/HarnessLoad from other nodes
    cvt::can::AnyMessage a;
    if (!rx_.receive(f, a).accepted()) {
      ++rejected_;
      return false;
    }
    switch (a.which) {
      case cvt::can::MessageId::PlantSpeeds: speeds_ = a.plant_speeds; break;
      case cvt::can::MessageId::PlantRatio: ratio_ = a.plant_ratio; break;
      case cvt::can::MessageId::PlantForces: forces_ = a.plant_forces; break;
      case cvt::can::MessageId::PlantShift: shift_ = a.plant_shift; break;
      case cvt::can::MessageId::PlantDiag: diag_ = a.plant_diag; break;
      case cvt::can::MessageId::PlantBusDiag: bus_diag_ = a.plant_bus_diag; break;
      case cvt::can::MessageId::PlantCmdDiag: cmd_diag_ = a.plant_cmd_diag; break;
      case cvt::can::MessageId::PlantStatus:
        status_ = a.plant_status;
        if (status_.plant_mode == cvt::can::PlantMode::RealTime) ++realtime_statuses_;
        break;
      default: break;
    }
    return a.which == cvt::can::MessageId::PlantStatus;
  }

  cvt::port::CanTransport& bus_;
  std::int64_t reply_timeout_ns_;
  std::function<void()> on_idle_;
  cvt::port::PosixMonotonicClock clock_;
  std::int64_t max_recovery_ns_ = 0;
  cvt::can::TxChannel<cvt::can::SimCtrl> sim_;
  cvt::can::TxChannel<cvt::can::HarnessLoad> load_;
  cvt::can::RxBank rx_;
  std::uint8_t seq_ = 0;
  cvt::can::PlantStatus status_{};
  cvt::can::PlantSpeeds speeds_{};
  cvt::can::PlantRatio ratio_{};
  cvt::can::PlantForces forces_{};
  cvt::can::PlantShift shift_{};
  bool expect_shift_ = false;
  cvt::can::PlantDiag diag_{};
  cvt::can::PlantBusDiag bus_diag_{};
  cvt::can::PlantCmdDiag cmd_diag_{};
  std::uint32_t rejected_ = 0, mixed_groups_ = 0, resends_ = 0, no_reply_ = 0, partial_groups_ = 0;
  std::uint32_t realtime_statuses_ = 0;
};

// ---- Scenarios -------------------------------------------------------------

// Faults a scenario injects on purpose (docs/sil.md#fault-scenarios). Periods
// are 10 ms control periods; -1 = none.
struct Faults {
  std::vector<int> lost_cmd_periods;  // the controller's CtrlCmd lost on the wire
  int lost_step_period = -1;          // the harness's Step request lost on the wire
  int lost_status_period = -1;        // PlantStatus lost to the harness
  int lost_speeds_period = -1;        // PlantSpeeds lost to the harness (a partial group)
  double freeze_start_s = -1, freeze_end_s = -1;  // controller hung, its driver repeating the last frame
  double reboot_s = -1;                           // controller restarts, counter from 0
  double flood_start_s = -1, flood_end_s = -1;    // controller sends flood_frames CtrlCmd per period
  int flood_frames = 0;
  int lost_requests() const {
    return (lost_step_period >= 0) + (lost_status_period >= 0) + (lost_speeds_period >= 0);
  }
};

struct Scenario {
  const char* name;
  const char* what;
  double t_end_s;
  std::function<float(double)> demand_Nm;
  bool load_override = false;
  std::function<float(double)> load_Nm = [](double) { return 0.0f; };
  double link_loss_start_s = -1, link_loss_end_s = -1;  // controller silent in [start, end)
  Faults faults{};
  // Ratio control (docs/sil.md#ratio-scenarios): the variable-ratio scene,
  // the controller's RatioLaw on this set-point; empty = the ClampLaw alone.
  cvt::can::SceneId scene = cvt::can::SceneId::TipIn;
  std::function<float(double)> ratio_target;
  double track_bound = 0;       // |ratio - set-point| once the set-point has held for settle_s
  double settle_s = 1.0;
  double slip_bound = 0.10;     // max |slip| outside the clamping drop
  double clamp_drop_start_s = -1, clamp_drop_end_s = -1;  // supply pressure at clamp_drop_factor
  float clamp_drop_factor = 1.0f;
  bool expect_end_stop = false;  // the sweep drives the chain onto the underdrive and overdrive stops
};

float ramp(double t, double t0, double t1, float a, float b) {
  if (t <= t0) return a;
  if (t >= t1) return b;
  return a + (b - a) * static_cast<float>((t - t0) / (t1 - t0));
}

// docs/sil.md#ratio-scenarios: the three ratio-control scenarios on the
// variable-ratio scene (ratio-control: wedging, 60 N m, road load).
void add_ratio_scenarios(std::vector<Scenario>& v) {
  Scenario sw{"ratio-sweep",
              "60 N m; set-point 1.5 -> 2.3 (low) -> 1.0 (overdrive) -> 1.5 in ramps, then beyond both end stops", 0,
              [](double) { return 60.0f; }};
  sw.scene = cvt::can::SceneId::RatioControl;
  sw.ratio_target = [](double t) {
    if (t < 4.0) return ramp(t, 0.5, 2.5, 1.5f, 2.3f);
    if (t < 9.0) return ramp(t, 4.0, 7.0, 2.3f, 1.0f);
    if (t < 12.0) return ramp(t, 9.0, 10.0, 1.0f, 1.5f);
    if (t < 14.0) return 2.9f;  // beyond the underdrive stop (2.65)
    return 0.8f;                // beyond the overdrive stop (0.89)
  };
  sw.t_end_s = 17.5;
  sw.track_bound = 0.05;
  sw.expect_end_stop = true;
  v.push_back(sw);
  Scenario kd{"kick-down", "ratio 1.0 at 40 N m; at 2 s tip-in to 120 N m over 0.2 s and set-point 1.0 -> 2.0", 5.5,
              [](double t) { return ramp(t, 2.0, 2.2, 40.0f, 120.0f); }};
  kd.scene = cvt::can::SceneId::RatioControl;
  kd.ratio_target = [](double t) { return t < 0.5 ? 1.5f : (t < 2.0 ? 1.0f : 2.0f); };
  kd.track_bound = 0.05;
  kd.settle_s = 2.0;
  v.push_back(kd);
  Scenario sr{"slip-recovery", "ratio 1.5 at 100 N m; the clamping supply drops to 20 % for 500 ms at 1 s, then back",
              3.5, [](double) { return 100.0f; }};
  sr.scene = cvt::can::SceneId::RatioControl;
  sr.ratio_target = [](double) { return 1.5f; };
  sr.track_bound = 0.05;
  sr.clamp_drop_start_s = 1.0;
  sr.clamp_drop_end_s = 1.5;
  sr.clamp_drop_factor = 0.2f;
  v.push_back(sr);
}

std::vector<Scenario> scenarios() {
  std::vector<Scenario> v;
  add_ratio_scenarios(v);
  v.push_back({"tip-in", "driver demand 20 -> 120 N m over 0.2 s at 1 s", 3.0,
               [](double t) { return ramp(t, 1.0, 1.2, 20.0f, 120.0f); }});
  Scenario ls{"load-step", "80 N m demand; harness load override 0 -> 100 N m at 1 s", 3.0,
              [](double) { return 80.0f; }};
  ls.load_override = true;
  ls.load_Nm = [](double t) { return t < 1.0 ? 0.0f : 100.0f; };
  v.push_back(ls);
  Scenario cl{"clamp-loss", "100 N m; the controller's CtrlCmd is lost for 200 ms at 1 s", 2.5,
              [](double) { return 100.0f; }};
  cl.link_loss_start_s = 1.0;
  cl.link_loss_end_s = 1.2;
  v.push_back(cl);
  Scenario lf{"lost-frames",
              "100 N m; two CtrlCmd lost at 0.5 s, a Step request at 0.8 s, a PlantStatus at 1.0 s, a PlantSpeeds at "
              "1.2 s",
              1.5, [](double) { return 100.0f; }};
  lf.faults.lost_cmd_periods = {50, 51};
  lf.faults.lost_step_period = 80;
  lf.faults.lost_status_period = 100;
  lf.faults.lost_speeds_period = 120;
  v.push_back(lf);
  Scenario fz{"frozen-controller", "100 N m; the controller hangs at 1 s for 300 ms, its CAN driver repeating its last frame",
              2.0, [](double) { return 100.0f; }};
  fz.faults.freeze_start_s = 1.0;
  fz.faults.freeze_end_s = 1.3;
  v.push_back(fz);
  Scenario rb{"controller-restart", "100 N m; the controller restarts at 1 s, its E2E counter from 0", 1.5,
              [](double) { return 100.0f; }};
  rb.faults.reboot_s = 1.0;
  v.push_back(rb);
  Scenario fl{"controller-flood", "100 N m; for 100 ms at 1 s the controller sends 20 CtrlCmd per 10 ms period", 1.5,
              [](double) { return 100.0f; }};
  fl.faults.flood_start_s = 1.0;
  fl.faults.flood_end_s = 1.1;
  fl.faults.flood_frames = 20;
  v.push_back(fl);
  return v;
}

std::string scenario_names() {
  std::string n;
  for (const Scenario& s : scenarios()) n += std::string(n.empty() ? "" : ", ") + s.name;
  return n + " or all";
}

struct Check {
  std::string name;
  bool pass;
  std::string detail;
  // false: reported, not judged (a real-time run whose plant did not keep
  // time, docs/sil.md#ratio-realtime); JUnit <skipped>, never a failure.
  bool judged = true;
};

struct Sample {
  double t_s;
  float demand_Nm, clamp_cmd_N, axial_N, torque_Nm, slip, omega1, omega2, safety;
  bool cmd_timeout, watchdog;
  float ratio_target, geometric_ratio, driven_cmd_N, driven_axial_N, radius1_m;
  bool stop_under, stop_over;
};

struct ScenarioResult {
  std::string name;
  std::string what;  // the scenario in one line (JUnit property "description")
  double wall_s = 0;
  std::vector<Check> checks;
  bool pass() const {
    for (const Check& c : checks)
      if (c.judged && !c.pass) return false;
    return true;
  }
};

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[240];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

bool in_window(double t, double start, double end) { return start >= 0 && t >= start - 1e-9 && t < end - 1e-9; }

// slip-recovery: the time after the supply is back within which the slip
// must be small again; the common slip criteria skip the drop and this time.
constexpr double kRecovery_s = 1.0;

// Counter growth between two PlantDiag-family readings, modulo 2^16.
double grew(std::uint16_t now, std::uint16_t then) { return static_cast<std::uint16_t>(now - then); }

// docs/sil.md#ratio-scenarios: settled tracking, the slip excursion of a
// clamping drop and its recovery, the end stops.
void ratio_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c) {
  double max_err = 0, max_err_t = 0, since = 0, sum_sq = 0;
  float held = -1.0f;
  int judged = 0;
  bool under = false, over = false;
  // Over the whole run (steps and ramps of the set-point included): the
  // lag of the bounded shift speed, reported beside the settled figures.
  double run_max = 0, run_sum_sq = 0;
  int run_n = 0;
  for (const Sample& s : trace) {
    if (s.ratio_target != held) {
      held = s.ratio_target;
      since = s.t_s;
    }
    under = under || s.stop_under;
    over = over || s.stop_over;
    // Set-points beyond the stops cannot be reached: not tracking targets.
    if (s.ratio_target > 2.65f || s.ratio_target < 0.89f) continue;
    const double e = std::fabs(s.geometric_ratio - s.ratio_target);
    run_max = std::fmax(run_max, e);
    run_sum_sq += e * e;
    ++run_n;
    if (s.t_s - since < sc.settle_s - 1e-9) continue;
    if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s)) continue;
    ++judged;
    sum_sq += e * e;
    if (e > max_err) {
      max_err = e;
      max_err_t = s.t_s;
    }
  }
  const double rms = judged > 0 ? std::sqrt(sum_sq / judged) : 0.0;
  const double run_rms = run_n > 0 ? std::sqrt(run_sum_sq / run_n) : 0.0;
  c.push_back({"ratio_tracked", judged > 0 && max_err <= sc.track_bound,
               fmt("max |ratio - set-point| %.4f at t = %.2f s, ", max_err, max_err_t) +
                   fmt("RMS %.4f over %.0f settled samples (limit ", rms, judged) +
                   fmt("%.3f, set-point held >= %.1f s); ", sc.track_bound, sc.settle_s) +
                   fmt("whole run max %.4f RMS %.4f", run_max, run_rms)});
  if (sc.expect_end_stop) {
    c.push_back({"end_stops_reached", under && over,
                 fmt("PlantShift end_stop_underdrive seen %.0f, end_stop_overdrive seen %.0f", under, over)});
  }
  if (sc.clamp_drop_start_s >= 0) {
    double peak = 0, recovered = -1;
    for (const Sample& s : trace) {
      if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s))
        peak = std::fmax(peak, std::fabs(s.slip));
      if (s.t_s >= sc.clamp_drop_end_s && recovered < 0 && std::fabs(s.slip) <= 0.02) recovered = s.t_s;
    }
    c.push_back({"slip_seen_in_drop", peak > 0.02,
                 fmt("max |slip| %.4f in the drop and the %.1f s after it (the drop must be felt: > 0.02)", peak,
                     kRecovery_s)});
    c.push_back({"slip_bounded_in_drop", peak <= 0.30, fmt("max |slip| %.4f (limit 0.30)", peak)});
    c.push_back({"slip_recovered", recovered >= 0 && recovered <= sc.clamp_drop_end_s + kRecovery_s,
                 fmt("|slip| <= 0.02 again at %.2f s (supply back at %.2f s, limit + ", recovered,
                     sc.clamp_drop_end_s) + fmt("%.1f s)", kRecovery_s)});
  }
}

// Criteria on the motion (docs/sil.md#criteria), after the first 50 ms
// start-up: slip, the ratio criteria, the torque-capacity safety factor.
void motion_checks(const Scenario& sc, const std::vector<Sample>& trace, std::vector<Check>& c) {
  double max_slip = 0, min_sf = 1e9, min_sf_t = 0;
  for (const Sample& s : trace) {
    if (s.t_s < 0.05) continue;
    if (in_window(s.t_s, sc.clamp_drop_start_s, sc.clamp_drop_end_s + kRecovery_s)) continue;  // ratio_checks
    max_slip = std::fmax(max_slip, std::fabs(s.slip));
    if (s.safety < min_sf) {
      min_sf = s.safety;
      min_sf_t = s.t_s;
    }
  }
  c.push_back({"slip_bounded", max_slip <= sc.slip_bound,
               fmt("max |slip| %.4f (limit %.2f)", max_slip, sc.slip_bound)});
  if (sc.ratio_target) ratio_checks(sc, trace, c);
  c.push_back({"no_gross_slip", min_sf >= 1.05,
               fmt("min torque-capacity safety factor %.3f at t = %.2f s (limit 1.05)", min_sf, min_sf_t)});
}

bool any_watchdog(const std::vector<Sample>& trace) {
  for (const Sample& s : trace)
    if (s.watchdog) return true;
  return false;
}

// One trace sample from the plant's latest group as `speeds`..`shift` show
// it and the controller's last command.
Sample sample_of(const Scenario& sc, const cvtctl::ClampLawParams& law, double t_s, double t_cmd,
                 const cvt::can::PlantStatus& st, const cvt::can::PlantSpeeds& sp, const cvt::can::PlantRatio& ra,
                 const cvt::can::PlantForces& fo, const cvt::can::PlantShift& sh, const cvtctl::ControllerNode& ctl) {
  Sample s;
  s.t_s = t_s;
  s.demand_Nm = sc.demand_Nm(t_cmd);
  s.clamp_cmd_N = ctl.last_output().clamp_force_cmd_N;
  s.axial_N = fo.driver_axial_force_N;
  s.torque_Nm = sp.torque_transmitted_Nm;
  s.slip = ra.slip;
  s.omega1 = sp.omega_driver_rad_s;
  s.omega2 = sp.omega_driven_rad_s;
  const float tau = std::fabs(s.torque_Nm) < 1.0f ? 1.0f : std::fabs(s.torque_Nm);
  s.safety = cvtctl::torque_capacity_Nm(law, s.axial_N) / tau;
  s.cmd_timeout = st.fault_cmd_timeout;
  s.watchdog = st.fault_watchdog;
  s.ratio_target = sc.ratio_target ? sc.ratio_target(t_cmd) : 0.0f;
  s.geometric_ratio = ra.geometric_ratio;
  s.driven_cmd_N = ctl.last_ratio_output().driven_clamp_cmd_N;
  s.driven_axial_N = fo.driven_axial_force_N;
  s.radius1_m = sh.radius_driver_m;
  s.stop_under = sh.end_stop_underdrive;
  s.stop_over = sh.end_stop_overdrive;
  if (sc.ratio_target) {
    // The capacity at the driver's running radius (docs/sil.md#ratio-control).
    const float r1 = s.radius1_m > 0.01f ? s.radius1_m : law.r1_m;
    s.safety = cvtctl::torque_capacity_at_Nm(law, s.axial_N, r1) / tau;
  }
  return s;
}

bool write_trace(const std::string& csv, const std::vector<Sample>& trace) {
  std::FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "cvtplant-sil: %s: %s\n", csv.c_str(), std::strerror(errno));
    return false;
  }
  std::fprintf(f, "t_s,demand_Nm,clamp_cmd_N,axial_force_N,torque_transmitted_Nm,slip,omega1_rad_s,omega2_rad_s,"
                  "safety_factor,fault_cmd_timeout,fault_watchdog,ratio_target,geometric_ratio,driven_clamp_cmd_N,"
                  "driven_axial_force_N,radius_driver_m,end_stop_underdrive,end_stop_overdrive\n");
  for (const Sample& s : trace)
    std::fprintf(f, "%.3f,%.2f,%.0f,%.0f,%.2f,%.4f,%.2f,%.2f,%.3f,%d,%d,%.4f,%.4f,%.0f,%.0f,%.5f,%d,%d\n", s.t_s,
                 s.demand_Nm, s.clamp_cmd_N, s.axial_N, s.torque_Nm, s.slip, s.omega1, s.omega2, s.safety,
                 s.cmd_timeout, s.watchdog, s.ratio_target, s.geometric_ratio, s.driven_cmd_N, s.driven_axial_N,
                 s.radius1_m, s.stop_under, s.stop_over);
  std::fclose(f);
  return true;
}

ScenarioResult run_scenario(const Scenario& sc, Harness& h, FaultInjector& hf, cvtctl::ControllerNode& ctl,
                            FaultInjector& cf, const cvtctl::ClampLawParams& law, const std::string& out_dir) {
  cvt::port::PosixMonotonicClock clock;
  const std::int64_t t0 = clock.now_ns();
  ScenarioResult res;
  res.name = sc.name;
  res.what = sc.what;
  std::vector<Sample> trace;
  std::uint32_t no_reply = 0, bad_time = 0, bad_mode = 0;
  const Faults& fx = sc.faults;
  h.expect_shift(sc.scene == cvt::can::SceneId::RatioControl);
  if (!h.request(cvt::can::SimRequest::Reset, 0, sc.scene)) ++no_reply;
  // Baselines: the bridge's counters run over its lifetime.
  const cvt::can::PlantDiag diag0 = h.diag();
  const cvt::can::PlantCmdDiag cmd0 = h.cmd_diag();
  const std::uint32_t resends0 = h.resends(), lost_harness0 = hf.lost(), lost_ctl0 = cf.lost();
  const std::uint32_t ctl_rejected0 = ctl.counters().rejected;
  h.clear_recovery();
  ctl.poll(100000000);
  // Every run starts its E2E counters at 0, as the bridge's Reset expects
  // (docs/sil.md#lock-step): a scenario's counter sequence does not depend
  // on the scenarios before it.
  ctl.reboot();
  const int periods = static_cast<int>(sc.t_end_s / kPeriod_s + 0.5);
  std::uint32_t expect_us = 0;
  for (int k = 0; k < periods && no_reply == 0; ++k) {
    const double t = k * kPeriod_s;
    const bool silent = t >= sc.link_loss_start_s && t < sc.link_loss_end_s;
    cf.freeze(in_window(t, fx.freeze_start_s, fx.freeze_end_s));
    if (fx.reboot_s >= 0 && std::fabs(t - fx.reboot_s) < 1e-9) ctl.reboot();
    for (const int lost : fx.lost_cmd_periods)
      if (lost == k) cf.lose_next_sent(cvt::can::CtrlCmd::kId);
    cf.scale_clamp(in_window(t, sc.clamp_drop_start_s, sc.clamp_drop_end_s) ? sc.clamp_drop_factor : 1.0f);
    if (!silent && sc.ratio_target) {
      ctl.control_step_ratio(sc.demand_Nm(t), sc.ratio_target(t));
    } else if (!silent) {
      ctl.control_step(sc.demand_Nm(t));
      if (in_window(t, fx.flood_start_s, fx.flood_end_s))
        for (int i = 1; i < fx.flood_frames; ++i) ctl.send_command();
    }
    if (sc.load_override) h.send_load(true, sc.load_Nm(t));
    if (k == fx.lost_step_period) hf.lose_next_sent(cvt::can::SimCtrl::kId);
    if (k == fx.lost_status_period) hf.lose_next_received(cvt::can::PlantStatus::kId);
    if (k == fx.lost_speeds_period) hf.lose_next_received(cvt::can::PlantSpeeds::kId);
    if (!h.request(cvt::can::SimRequest::Step, kFramesPerPeriod, cvt::can::SceneId::Keep)) {
      ++no_reply;
      break;
    }
    // The controller's socket got the same group; wait until it has it
    // complete (a group the bridge sent again is not new to it).
    for (int i = 0; i < 1000 && !(ctl.poll(10000000), ctl.fresh_group()); ++i) {
    }
    expect_us += kFramesPerPeriod * 1000;
    const cvt::can::PlantStatus& st = h.status();
    if (st.sim_time_us != expect_us) ++bad_time;
    if (st.plant_mode != cvt::can::PlantMode::LockStep) ++bad_mode;
    const Sample s =
        sample_of(sc, law, st.sim_time_us * 1e-6, t, st, h.speeds(), h.ratio(), h.forces(), h.shift(), ctl);
    trace.push_back(s);
  }
  cf.freeze(false);
  cf.scale_clamp(1.0f);
  // The closing diagnostics (SimCtrl None answers with them).
  if (no_reply == 0 && !h.request(cvt::can::SimRequest::None, 0, cvt::can::SceneId::Keep)) ++no_reply;
  res.wall_s = static_cast<double>(clock.now_ns() - t0) * 1e-9;

  const std::string csv = out_dir + "/sil-" + sc.name + ".csv";
  const bool trace_written = write_trace(csv, trace);

  const double resends = h.resends() - resends0;
  const double ctl_rejected = ctl.counters().rejected - ctl_rejected0;
  const cvt::can::PlantCmdDiag& cmd1 = h.cmd_diag();
  auto& c = res.checks;
  c.push_back({"trace_written", trace_written, csv});
  c.push_back({"bridge_answered_every_step", no_reply == 0 && trace.size() == static_cast<size_t>(periods),
               fmt("%.0f of %.0f periods answered, %.0f requests sent again", static_cast<double>(trace.size()),
                   periods, resends)});
  c.push_back({"lockstep_time_exact", bad_time == 0 && bad_mode == 0,
               fmt("%.0f groups with sim_time_us != 10000 k, %.0f not in LockStep", bad_time, bad_mode)});
  c.push_back({"frames_valid", h.rejected() == 0 && ctl_rejected == 0,
               fmt("harness rejected %.0f, controller rejected %.0f", h.rejected(), ctl_rejected)});
  motion_checks(sc, trace, c);
  c.push_back({"no_watchdog_fault", !any_watchdog(trace), any_watchdog(trace) ? "plant watchdog fault" : "none"});
  const double timeouts = grew(h.diag().cmd_timeouts, diag0.cmd_timeouts);
  // A controller silent (or repeating itself) from `start`: its last fresh
  // command went out at start - 10 ms, the deadline is 50 ms later, seen by
  // the status closing that period (docs/sil.md#timeouts).
  const double outage_start = sc.link_loss_start_s >= 0 ? sc.link_loss_start_s : fx.freeze_start_s;
  const double outage_end = sc.link_loss_start_s >= 0 ? sc.link_loss_end_s : fx.freeze_end_s;
  if (outage_start >= 0) {
    double first_flag = -1, cleared = -1, axial_at_100ms = 0, axial_before = 0, max_rise = 0, max_drop = 0;
    float prev_axial = 0;
    for (const Sample& s : trace) {
      if (s.cmd_timeout && first_flag < 0) first_flag = s.t_s;
      if (first_flag < 0) axial_before = s.axial_N;
      if (first_flag >= 0 && cleared < 0 && !s.cmd_timeout && s.t_s > outage_end) cleared = s.t_s;
      if (first_flag >= 0 && s.t_s <= first_flag + 0.1 + 1e-9) axial_at_100ms = s.axial_N;
      if (first_flag >= 0 && s.t_s < outage_end) {
        max_rise = std::fmax(max_rise, s.axial_N - prev_axial);
        max_drop = std::fmax(max_drop, prev_axial - s.axial_N);
      }
      prev_axial = s.axial_N;
    }
    // The DBC's ramp rate of the clamp [N per 10 ms period], read from the
    // generated reaction itself (docs/sil.md#timeouts).
    cvt::can::CtrlCmd zero;
    zero.clamp_force_cmd_N = 0.0f;
    const double ramp_N = cvt::can::rx_timeout_ramp(zero, static_cast<float>(kPeriod_s)).clamp_force_cmd_N;
    const double expect = outage_start - kPeriod_s + 0.05;
    c.push_back({"timeout_flag_on_outage", first_flag >= expect - 1e-9 && first_flag <= expect + kPeriod_s + 1e-9,
                 fmt("fault_cmd_timeout first at %.3f s (expected within 10 ms after %.3f s)", first_flag, expect)});
    c.push_back({"no_force_step_on_timeout", max_rise <= 1.2 * ramp_N,
                 fmt("largest rise of the axial force per 10 ms while timed out %.0f N (ramp %.0f N per 10 ms)",
                     max_rise, ramp_N)});
    c.push_back({"timeout_reaction_raises_clamp", axial_at_100ms >= axial_before + 0.5 * ramp_N * 10.0,
                 fmt("axial force %.0f N 100 ms after the timeout, %.0f N before it", axial_at_100ms, axial_before)});
    c.push_back({"flag_clears_on_recovery", cleared > 0 && cleared <= outage_end + 0.02 + 1e-9,
                 fmt("cleared at %.3f s (controller back at %.3f s)", cleared, outage_end)});
    c.push_back({"timeout_counted_once", timeouts == 1, fmt("PlantDiag.cmd_timeouts grew by %.0f", timeouts)});
    if (fx.freeze_start_s >= 0) {
      // The hung controller's repeated frame is never used again: the
      // clamp only rises while the ramp runs (a re-applied stale command
      // would pull it back down every 50 ms).
      const double frozen_frames = std::round((fx.freeze_end_s - fx.freeze_start_s) / kPeriod_s);
      const double rejected = grew(h.diag().rejected_frames, diag0.rejected_frames);
      c.push_back({"stale_command_never_reapplied", max_drop <= 1.0,
                   fmt("largest drop of the axial force per 10 ms while timed out %.0f N", max_drop)});
      c.push_back({"repeated_frames_rejected", rejected == frozen_frames,
                   fmt("PlantDiag.rejected_frames grew by %.0f (%.0f repeated frames sent)", rejected,
                       frozen_frames)});
    }
  } else {
    bool any_timeout = false;
    for (const Sample& s : trace) any_timeout = any_timeout || s.cmd_timeout;
    c.push_back({"no_cmd_timeout", !any_timeout && timeouts == 0,
                 any_timeout ? "fault_cmd_timeout raised" : "none"});
  }
  const double cmd_lost = grew(cmd1.cmd_lost_frames, cmd0.cmd_lost_frames);
  const double resyncs = grew(cmd1.cmd_resyncs, cmd0.cmd_resyncs);
  const double superseded = grew(cmd1.cmd_superseded, cmd0.cmd_superseded);
  if (fx.lost_requests() > 0) {
    // One resend per loss at least (more if an answer was merely slow);
    // lockstep_time_exact above shows no request ran twice or not at all.
    const double lost = hf.lost() - lost_harness0;
    c.push_back({"lost_requests_recovered", resends >= fx.lost_requests() && lost == fx.lost_requests(),
                 fmt("%.0f frames lost on purpose, %.0f requests sent again; slowest recovery %.1f ms wall "
                     "(the reply timeout, then the answer to the resent request)",
                     lost, resends, static_cast<double>(h.max_recovery_ns()) * 1e-6)});
  }
  if (!fx.lost_cmd_periods.empty()) {
    const double n = static_cast<double>(fx.lost_cmd_periods.size());
    c.push_back({"lost_commands_resynchronised", cmd_lost == n && resyncs == 1 && cf.lost() - lost_ctl0 == n,
                 fmt("PlantCmdDiag: %.0f commands lost, %.0f re-synchronisations", cmd_lost, resyncs)});
  }
  if (fx.reboot_s >= 0) {
    // The restarted counter is a jump: adopted, one Sync frame, then used.
    c.push_back({"restart_resynchronised", resyncs == 1 && grew(h.diag().rejected_frames, diag0.rejected_frames) == 1,
                 fmt("PlantCmdDiag.cmd_resyncs grew by %.0f, PlantDiag.rejected_frames by %.0f", resyncs,
                     grew(h.diag().rejected_frames, diag0.rejected_frames))});
  }
  if (fx.flood_frames > 0) {
    const double expect = std::round((fx.flood_end_s - fx.flood_start_s) / kPeriod_s) * (fx.flood_frames - 1);
    c.push_back({"flood_superseded_counted", superseded == expect,
                 fmt("PlantCmdDiag.cmd_superseded grew by %.0f (expected %.0f: all but the last of each period)",
                     superseded, expect)});
  }
  return res;
}

// How a real-time run is paced (docs/sil.md#ratio-realtime). On SocketCAN
// the bridge process paces itself on CLOCK_MONOTONIC and `start`/`frame`
// are empty; with the bridge in-process on the loopback bus, `frame` sleeps
// the virtual clock to the next frame's deadline and runs it
// (deterministic), `start` sets the first deadline.
struct RealTimeBus {
  cvt::port::Clock& clock;
  std::function<void()> start, frame;
  std::int64_t poll_ns;  // how long the controller waits for a frame per turn
  const char* clock_name;
};

// A plant that overran more than this fraction of its frames did not keep
// time: only the functional criteria are judged (docs/sil.md#ratio-realtime).
// At 9.3 % overruns on a loaded VM a late clamping command let the slip reach
// 0.13: the motion criteria measure the controller only on a punctual bus.
constexpr double kMaxOverrunFraction = 0.01;

// A ratio scenario in real time: the bridge paces the plant at 1 kHz, the
// controller runs on every fresh group (ControlSchedule, as
// cvtplant-controller does), the harness only watches. Same criteria as in
// lock-step where the run is comparable.
ScenarioResult run_scenario_rt(const Scenario& sc, Harness& h, cvtctl::ControllerNode& ctl, FaultInjector& cf,
                               const cvtctl::ClampLawParams& law, const std::string& out_dir, const RealTimeBus& bus) {
  cvt::port::PosixMonotonicClock wall;
  const std::int64_t w0 = wall.now_ns();
  ScenarioResult res;
  res.name = std::string(sc.name) + ".realtime";
  res.what = std::string(sc.what) + " (real time)";
  std::vector<Sample> trace;
  h.expect_shift(true);
  bool answered = h.request(cvt::can::SimRequest::Reset, 0, sc.scene);
  const cvt::can::PlantDiag diag0 = h.diag();
  const std::uint32_t ctl_rejected0 = ctl.counters().rejected, h_rejected0 = h.rejected();
  const std::uint32_t rt_status0 = h.realtime_statuses();
  ctl.poll(100000000);
  ctl.reboot();
  cvtctl::ControlSchedule sched;
  long steps = 0, fresh_steps = 0;
  bool timeout_seen = false;
  answered = answered && h.start_realtime();
  if (bus.start) bus.start();
  const std::int64_t t0 = bus.clock.now_ns();
  const std::int64_t end = t0 + static_cast<std::int64_t>(sc.t_end_s * 1e9 + 0.5);
  while (answered) {
    if (bus.frame) bus.frame();
    const std::int64_t now = bus.clock.now_ns();
    if (now >= end) break;
    const double t = static_cast<double>(now - t0) * 1e-9;
    cf.scale_clamp(in_window(t, sc.clamp_drop_start_s, sc.clamp_drop_end_s) ? sc.clamp_drop_factor : 1.0f);
    ctl.poll(bus.poll_ns);
    h.drain();
    timeout_seen = timeout_seen || h.status().fault_cmd_timeout;
    if (!sched.due(now, ctl.fresh_group())) continue;
    ctl.poll(0);  // whatever else is queued: the newest group wins
    const bool fresh = ctl.fresh_group();
    ctl.control_step_ratio(sc.demand_Nm(t), sc.ratio_target(t));
    sched.ran(now);
    ++steps;
    if (!fresh) continue;
    ++fresh_steps;
    trace.push_back(sample_of(sc, law, t, t, h.status(), ctl.speeds(), ctl.ratio(), ctl.forces(), ctl.shift(), ctl));
  }
  cf.scale_clamp(1.0f);
  answered = answered && h.pause();
  res.wall_s = static_cast<double>(wall.now_ns() - w0) * 1e-9;

  const std::string csv = out_dir + "/sil-" + sc.name + "-realtime.csv";
  auto& c = res.checks;
  c.push_back({"trace_written", write_trace(csv, trace), csv});
  // Functional criteria: judged in every run.
  const double frames = h.status().sim_time_us / 1000.0;
  const double overruns = grew(h.diag().rt_overruns, diag0.rt_overruns);
  const double rt_statuses = h.realtime_statuses() - rt_status0;
  const bool kept_time = frames > 0 && overruns <= kMaxOverrunFraction * frames;
  c.push_back({"realtime_paced", answered && rt_statuses > 0 && frames > 0,
               fmt("%.0f plant frames in %.0f ms of the ", frames, sc.t_end_s * 1e3) + bus.clock_name +
                   fmt(", %.0f overran; %.0f PlantStatus in RealTime; ", overruns, rt_statuses) +
                   (kept_time ? "kept time: every criterion judged"
                              : "did not keep time (more than 1 % of the frames overran): only realtime_paced, "
                                "frames_valid and no_watchdog_fault are judged")});
  // The plant rejects nothing but the counter jump that may follow a
  // command timeout, one per command message (CtrlCmd, CtrlShiftCmd): the
  // frames queued during the outage are drained, the next fresh one skips
  // their counters (docs/sil.md#timeouts). With no timeout, nothing.
  const double plant_rejected = grew(h.diag().rejected_frames, diag0.rejected_frames);
  const double timeouts = grew(h.diag().cmd_timeouts, diag0.cmd_timeouts);
  const double h_rej = h.rejected() - h_rejected0, ctl_rej = ctl.counters().rejected - ctl_rejected0;
  c.push_back({"frames_valid", h_rej == 0 && ctl_rej == 0 && plant_rejected <= 2 * timeouts,
               fmt("harness rejected %.0f, controller rejected %.0f, ", h_rej, ctl_rej) +
                   fmt("PlantDiag.rejected_frames grew by %.0f (at most 2 counter jumps per command timeout: %.0f "
                       "timeouts)",
                       plant_rejected, timeouts)});
  const bool watchdog = any_watchdog(trace) || h.status().fault_watchdog;
  c.push_back({"no_watchdog_fault", !watchdog, watchdog ? "plant watchdog fault" : "none"});
  // Judged when the plant kept time.
  const std::size_t full_from = c.size();
  const double expect_steps = std::floor(sc.t_end_s / kPeriod_s) - 1;
  c.push_back({"control_on_fresh_groups", fresh_steps >= 0.95 * expect_steps,
               fmt("%.0f control steps on a fresh group of %.0f steps (at least 95 %% of %.0f periods)",
                   static_cast<double>(fresh_steps), static_cast<double>(steps), expect_steps)});
  motion_checks(sc, trace, c);
  c.push_back({"no_cmd_timeout", !timeout_seen && timeouts == 0,
               timeout_seen ? fmt("fault_cmd_timeout raised, PlantDiag.cmd_timeouts grew by %.0f", timeouts) : "none"});
  if (!kept_time)
    for (std::size_t i = full_from; i < c.size(); ++i) {
      c[i].judged = false;
      c[i].detail = "not judged, the plant did not keep time: " + c[i].detail;
    }
  return res;
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '<') o += "&lt;";
    else if (ch == '>') o += "&gt;";
    else if (ch == '&') o += "&amp;";
    else if (ch == '"') o += "&quot;";
    else o += ch;
  }
  return o;
}

bool write_junit(const std::string& path, const std::vector<ScenarioResult>& results) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  int tests = 0, failures = 0, skipped = 0;
  double wall = 0;
  for (const auto& r : results) {
    wall += r.wall_s;
    for (const auto& c : r.checks) {
      ++tests;
      failures += c.judged && !c.pass ? 1 : 0;
      skipped += c.judged ? 0 : 1;
    }
  }
  std::fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  std::fprintf(f, "<testsuites name=\"cvtplant-sil\" tests=\"%d\" failures=\"%d\" skipped=\"%d\" time=\"%.3f\">\n",
               tests, failures, skipped, wall);
  for (const auto& r : results) {
    int fails = 0, skips = 0;
    for (const auto& c : r.checks) {
      fails += c.judged && !c.pass ? 1 : 0;
      skips += c.judged ? 0 : 1;
    }
    std::fprintf(f, "  <testsuite name=\"sil.%s\" tests=\"%zu\" failures=\"%d\" skipped=\"%d\" time=\"%.3f\">\n",
                 r.name.c_str(), r.checks.size(), fails, skips, r.wall_s);
    std::fprintf(f, "    <properties><property name=\"description\" value=\"%s\"/></properties>\n",
                 xml_escape(r.what).c_str());
    for (const auto& c : r.checks) {
      std::fprintf(f, "    <testcase classname=\"sil.%s\" name=\"%s\" time=\"0\">\n", r.name.c_str(), c.name.c_str());
      if (!c.judged) std::fprintf(f, "      <skipped message=\"%s\"/>\n", xml_escape(c.detail).c_str());
      else if (!c.pass) std::fprintf(f, "      <failure message=\"%s\"/>\n", xml_escape(c.detail).c_str());
      std::fprintf(f, "      <system-out>%s</system-out>\n    </testcase>\n", xml_escape(c.detail).c_str());
    }
    std::fprintf(f, "  </testsuite>\n");
  }
  std::fprintf(f, "</testsuites>\n");
  std::fclose(f);
  return true;
}

// ---- bench -----------------------------------------------------------------

int bench(Harness& h, cvtctl::ControllerNode& ctl, long steps, bool with_controller) {
  if (!h.request(cvt::can::SimRequest::Reset, 0, cvt::can::SceneId::TipIn)) {
    std::fprintf(stderr, "cvtplant-sil: bridge did not answer the Reset\n");
    return 1;
  }
  ctl.restart();
  cvt::port::PosixMonotonicClock clock;
  std::vector<std::int64_t> rtt;
  rtt.reserve(static_cast<size_t>(steps));
  const std::int64_t t0 = clock.now_ns();
  for (long i = 0; i < steps; ++i) {
    const std::int64_t a = clock.now_ns();
    if (with_controller) {
      ctl.poll(0);
      ctl.control_step(50.0f);
    }
    if (!h.request(cvt::can::SimRequest::Step, 1, cvt::can::SceneId::Keep)) {
      std::fprintf(stderr, "cvtplant-sil: no answer to step %ld\n", i);
      return 1;
    }
    rtt.push_back(clock.now_ns() - a);
  }
  const double secs = static_cast<double>(clock.now_ns() - t0) * 1e-9;
  const cvt::sil::LatencySummary s = cvt::sil::summarize_latencies(rtt);
  std::printf(
      "{\"round_trips\": %ld, \"with_controller\": %s, \"seconds\": %.3f, \"round_trips_per_s\": %.0f, "
      "\"rtt_us\": {\"p50\": %.1f, \"p99\": %.1f, \"p99_9\": %.1f, \"max\": %.1f}, \"sim_time_us\": %u}\n",
      steps, with_controller ? "true" : "false", secs, static_cast<double>(steps) / secs, s.p50_ns * 1e-3,
      s.p99_ns * 1e-3, s.p999_ns * 1e-3, s.max_ns * 1e-3, h.status().sim_time_us);
  return h.status().sim_time_us == static_cast<std::uint32_t>(steps * 1000) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) bad_usage("missing subcommand run or bench");
  const std::string cmd = argv[1];
  if (cmd == "-h" || cmd == "--help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd != "run" && cmd != "bench") bad_usage("unknown subcommand '" + cmd + "'");
  std::string iface = "vcan0", scenario = "all", out_dir = ".", junit, mode = "lockstep";
  long steps = 5000;
  bool with_controller = false, loopback = false;
  double reply_timeout_ms = 0;  // 0: the default for the transport
  std::int64_t frame_cost_ns = 0;
  cvtctl::ClampLawParams law;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--with-controller" || a == "--loopback") {
      (a == "--loopback" ? loopback : with_controller) = true;
      continue;
    }
    if (a != "--iface" && a != "--scenario" && a != "--out" && a != "--junit" && a != "--safety" && a != "--steps" &&
        a != "--reply-timeout-ms" && a != "--mode" && a != "--loopback-frame-cost-us")
      bad_usage("unknown option '" + a + "'");
    if (i + 1 >= argc) bad_usage(a + ": missing value");
    const std::string v = argv[++i];
    char* end = nullptr;
    if (a == "--iface") iface = v;
    else if (a == "--scenario") scenario = v;
    else if (a == "--out") out_dir = v;
    else if (a == "--junit") junit = v;
    else if (a == "--loopback-frame-cost-us") {
      const double us = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(us >= 0 && us <= 100000))
        bad_usage("--loopback-frame-cost-us: expected 0..100000, got '" + v + "'");
      frame_cost_ns = static_cast<std::int64_t>(us * 1e3 + 0.5);
    } else if (a == "--mode") {
      mode = v;
      if (mode != "lockstep" && mode != "realtime" && mode != "both")
        bad_usage("--mode: expected lockstep, realtime or both, got '" + v + "'");
    }
    else if (a == "--safety") {
      law.safety = std::strtof(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(law.safety > 0.1f && law.safety < 10.0f))
        bad_usage("--safety: expected a number in (0.1, 10), got '" + v + "'");
    } else if (a == "--reply-timeout-ms") {
      reply_timeout_ms = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(reply_timeout_ms >= 1 && reply_timeout_ms <= 10000))
        bad_usage("--reply-timeout-ms: expected 1..10000, got '" + v + "'");
    } else if (a == "--steps") {
      steps = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || steps < 1 || steps > 10000000)
        bad_usage("--steps: expected 1..10000000, got '" + v + "'");
    }
  }
  std::vector<Scenario> chosen;
  for (const Scenario& s : scenarios())
    if (scenario == "all" || scenario == s.name) chosen.push_back(s);
  if (chosen.empty()) bad_usage("--scenario: expected " + scenario_names() + ", got '" + scenario + "'");
  // Real time runs the ratio scenarios (docs/sil.md#ratio-realtime); the
  // fault scenarios need the harness's control of every step.
  const bool run_lockstep = mode != "realtime", run_realtime = mode != "lockstep";
  if (mode == "realtime" && scenario != "all" && !chosen.front().ratio_target)
    bad_usage("--mode realtime: runs ratio-sweep, kick-down or slip-recovery, not '" + scenario + "'");
  if (frame_cost_ns > 0 && (!loopback || !run_realtime))
    bad_usage("--loopback-frame-cost-us: needs --loopback and --mode realtime or both");
  if (reply_timeout_ms == 0) reply_timeout_ms = loopback ? 20 : 1000;
  // Traces are part of the result: a directory that cannot be made is an
  // error now, not a silently missing CSV later.
  std::error_code mkdir_error;
  std::filesystem::create_directories(out_dir, mkdir_error);
  if (mkdir_error) {
    std::fprintf(stderr, "cvtplant-sil: --out %s: %s\n", out_dir.c_str(), mkdir_error.message().c_str());
    return 1;
  }

  // Three nodes on one bus: bridge (node 0, in-process only with
  // --loopback), harness and controller, each with its own transport.
  cvt::port::VirtualClock vclock;
  static cvt::port::LoopbackBus<3, 256> loop_bus(&vclock);
  static cvt::sil::Bridge loop_bridge(loop_bus.node(0), vclock);
  cvt::port::SocketCanTransport harness_sock, controller_sock;
  cvt::port::CanTransport* harness_bus = &loop_bus.node(1);
  cvt::port::CanTransport* controller_bus = &loop_bus.node(2);
  std::function<void()> pump;
  if (loopback) {
    loop_bridge.load_scene(*cvt::find_builtin_scene("tip-in"));
    pump = [] { loop_bridge.service(0); };
  } else {
    if (harness_sock.open(iface.c_str()) != 0 || controller_sock.open(iface.c_str()) != 0) {
      std::fprintf(stderr, "cvtplant-sil: %s: %s%s\n", iface.c_str(), harness_sock.error_text(),
                   controller_sock.error_text());
      return 1;
    }
    harness_bus = &harness_sock;
    controller_bus = &controller_sock;
  }
  // Each node's transport through a fault injector, which the fault
  // scenarios arm (docs/sil.md#fault-scenarios); otherwise it passes frames.
  FaultInjector harness_faults(*harness_bus), controller_faults(*controller_bus);
  Harness h(harness_faults, static_cast<std::int64_t>(reply_timeout_ms * 1e6), pump);
  // --safety sets the clamping margin of both laws (ClampLaw, RatioLaw).
  cvtctl::RatioLawParams ratio_law;
  ratio_law.clamp = law;
  cvtctl::ControllerNode ctl(controller_faults, law, ratio_law);
  if (!h.sync()) {
    std::fprintf(stderr, "cvtplant-sil: the bridge on %s does not answer SimCtrl\n", loopback ? "loopback" : iface.c_str());
    return 1;
  }
  if (cmd == "bench") return bench(h, ctl, steps, with_controller);

  // Real-time pacing: the bridge process on the wall clock, or the
  // in-process bridge one frame per virtual millisecond.
  // On the virtual clock the pacing is cvt::sil::pace_realtime's, one
  // frame per turn; --loopback-frame-cost-us makes each frame's work take
  // that long (a plant slower than its frame overruns).
  cvt::port::PosixMonotonicClock wall;
  std::int64_t deadline = 0;
  const RealTimeBus rt_bus =
      loopback ? RealTimeBus{vclock, [&] { deadline = vclock.now_ns() + loop_bridge.frame_ns(); },
                             [&] {
                               vclock.sleep_until(deadline);
                               loop_bridge.realtime_frame();
                               vclock.advance(frame_cost_ns);
                               deadline += loop_bridge.frame_ns();
                               if (vclock.now_ns() > deadline) loop_bridge.note_overrun();
                             },
                             0, "virtual clock"}
               : RealTimeBus{wall, {}, {}, 1000000, "wall clock"};
  std::vector<ScenarioResult> results;
  bool all_pass = true;
  auto report = [&](const Scenario& s) {
    const ScenarioResult& r = results.back();
    all_pass = all_pass && r.pass();
    std::printf("%s %s (%.1f s wall): %s\n", r.pass() ? "PASS" : "FAIL", r.name.c_str(), r.wall_s, s.what);
    for (const Check& c : r.checks)
      std::printf("  %s %s: %s\n", !c.judged ? "skip" : c.pass ? "ok  " : "FAIL", c.name.c_str(), c.detail.c_str());
    std::fflush(stdout);
  };
  for (const Scenario& s : chosen) {
    if (run_lockstep) {
      results.push_back(run_scenario(s, h, harness_faults, ctl, controller_faults, law, out_dir));
      report(s);
    }
    if (run_realtime && s.ratio_target) {
      results.push_back(run_scenario_rt(s, h, ctl, controller_faults, law, out_dir, rt_bus));
      report(s);
    }
  }
  if (!junit.empty() && !write_junit(junit, results)) {
    std::fprintf(stderr, "cvtplant-sil: --junit %s: %s\n", junit.c_str(), std::strerror(errno));
    return 1;
  }
  return all_pass ? 0 : 1;
}
