#include "cvtplant/sil/harness/external_controller.hpp"

#include <cstdio>
#include <type_traits>

#include "cvtplant/sil/latency_stats.hpp"

namespace cvt::sil::harness {

using cvt::can::CanFrame;
using cvt::port::CanIoStatus;

namespace {

constexpr std::int64_t kDemandCycle_ns = std::int64_t{cvt::can::HarnessDemand::kCycleTime_ms} * 1000000;
// A command later than 1.5 cycles after the previous one was late; the plant
// times out after its 50 ms deadline (docs/sil.md#external-realtime).
constexpr std::int64_t kLateInterval_ns = 15000000;
constexpr std::int64_t kDeadline_ns = std::int64_t{cvt::can::CtrlCmd::kRxTimeout_ms} * 1000000;

std::string at_period(const char* what, int k, double t) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s at period %d (t = %.2f s)", what, k, t);
  return buf;
}

}  // namespace

bool ExternalController::accepts(const Scenario& sc, std::string& why) {
  if (!sc.faults.in_controller() && sc.link_loss_start_s < 0) return true;
  why = std::string(sc.name) +
        " injects its faults into the controller's own link or software, which only the example controller run "
        "by the harness can show";
  return false;
}

void ExternalController::reset_run() {
  cmd_check_.reset();
  shift_check_.reset();
  plant_rx_.reset_all();
  // HarnessDemand's counter continues from run to run, as the plant's own
  // transmit counters do: a controller's checker sees no jump.
  answers_.clear();
  silent_ = late_ = e2e_ = range_ = Misbehaviour{};
  frames_checked_[0] = frames_checked_[1] = 0;
  lost_by_counter_ = 0;
  full_timeouts_ = short_timeouts_ = 0;
  commands_ = Commands{};
  quiet_ = false;
  period_ = 0;
  tag_ = 0;
  for (bool& h : have_) h = false;
  last_used_tag_ = -1;
  t0_ = -1;
  last_cmd_ns_ = last_group_ns_ = -1;
  group_waiting_ = false;
  intervals_.clear();
  responses_.clear();
  // Frames of the previous run still queued are not this run's.
  CanFrame f;
  for (CanIoStatus st = bus_.receive(f, 0); st != CanIoStatus::Timeout; st = bus_.receive(f, 0)) {
  }
}

void ExternalController::begin_run(const Scenario& sc) {
  ratio_control_ = static_cast<bool>(sc.ratio_target);
  realtime_ = false;
  reset_run();
}

bool ExternalController::send_demand(std::uint8_t tag, float demand_Nm, float ratio_target, bool ratio_control) {
  cvt::can::HarnessDemand m;
  m.demand_tag = tag;
  m.driver_demand_Nm = demand_Nm;
  m.ratio_target = ratio_target;
  m.ratio_control = ratio_control;
  CanFrame f;
  return tx_demand_.encode(m, f) == cvt::can::CodecStatus::Ok && bus_.send(f) == CanIoStatus::Ok;
}

void ExternalController::control_period(const Scenario& sc, int k, double t) {
  period_ = k;
  tag_ = static_cast<std::uint8_t>(k & 0x0F);
  answers_.emplace_back();
  send_demand(tag_, sc.demand_Nm(t), ratio_control_ ? sc.ratio_target(t) : 0.0f, ratio_control_);
  // Wait for this period's commands; the one wall-clock wait of lock-step.
  const std::int64_t end = wall_.now_ns() + (quiet_ ? opt_.silent_wait_ns : opt_.answer_timeout_ns);
  while (!answered(k)) {
    const std::int64_t left = end - wall_.now_ns();
    if (left <= 0) break;
    CanFrame f;
    const CanIoStatus st = bus_.receive(f, idle_ ? 0 : left);
    if (st == CanIoStatus::Timeout && idle_) idle_();
    if (st == CanIoStatus::Ok) take(f, k, true);
  }
  if (!answered(k)) ++(quiet_ ? short_timeouts_ : full_timeouts_);
  quiet_ = !answered(k);
}

void ExternalController::after_step() {
  // Whatever came after the deadline: late answers.
  CanFrame f;
  for (CanIoStatus st = bus_.receive(f, 0); st != CanIoStatus::Timeout; st = bus_.receive(f, 0))
    if (st == CanIoStatus::Ok) take(f, period_, false);
}

bool ExternalController::wait_ready() {
  const std::int64_t end = wall_.now_ns() + opt_.start_timeout_ns;
  constexpr std::int64_t kProbe_ns = 200000000;
  // A tag no run's first period uses, so that a late answer is not taken for one.
  constexpr std::uint8_t kProbeTag = 15;
  while (wall_.now_ns() < end) {
    send_demand(kProbeTag, 0.0f, 0.0f, false);
    const std::int64_t next = wall_.now_ns() + kProbe_ns;
    for (std::int64_t left = next - wall_.now_ns(); left > 0; left = next - wall_.now_ns()) {
      CanFrame f;
      const CanIoStatus st = bus_.receive(f, idle_ ? 0 : left);
      if (st == CanIoStatus::Timeout && idle_) idle_();
      cvt::can::CtrlCmd m;
      if (st == CanIoStatus::Ok && f.id == cvt::can::CtrlCmd::kId && f.dlc == cvt::can::CtrlCmd::kDlc &&
          cvt::can::unpack(f.data, m) == cvt::can::CodecStatus::Ok && m.demand_tag == kProbeTag)
        return true;
    }
  }
  return false;
}

bool ExternalController::answered(int k) const {
  const PeriodAnswers& a = answers_[static_cast<std::size_t>(k)];
  return a.on_time[kCmd] && (!ratio_control_ || a.on_time[kShift]);
}

void ExternalController::take(const CanFrame& f, int period, bool waiting) {
  if (f.id == cvt::can::CtrlCmd::kId) take_command<cvt::can::CtrlCmd>(f, kCmd, cmd_check_, period, waiting);
  else if (f.id == cvt::can::CtrlShiftCmd::kId)
    take_command<cvt::can::CtrlShiftCmd>(f, kShift, shift_check_, period, waiting);
  else if (realtime_ && f.id >= cvt::can::PlantSpeeds::kId) take_plant(f);
}

// The controller's command through the receive pipeline of docs/can.md#rejection,
// with the harness's own checker: each failure is a misbehaviour of the
// period. A frame with a valid CRC and valid values answers the demand whose
// tag it echoes (also a counter jump: the controller did answer).
template <class Msg>
void ExternalController::take_command(const CanFrame& f, Kind kind, cvt::can::E2eChecker& ck, int period,
                                      bool waiting) {
  const char* name = Msg::kName;
  char what[160];
  ++frames_checked_[kind];
  const double t = period_s(period);
  if (!cvt::can::is_standard_data_frame(f) || f.dlc != Msg::kDlc) {
    std::snprintf(what, sizeof what, "%s with DLC %d (not %d)", name, f.dlc, Msg::kDlc);
    e2e_.note(period, at_period(what, period, t));
    return;
  }
  const cvt::can::E2eChecker::Verdict v = ck.evaluate(f.data);
  switch (v.status) {
    case cvt::can::E2eStatus::WrongCrc:
      std::snprintf(what, sizeof what, "%s CRC wrong (counter %d)", name, v.counter);
      e2e_.note(period, at_period(what, period, t));
      return;
    case cvt::can::E2eStatus::Repeated:
      std::snprintf(what, sizeof what, "%s counter %d repeated", name, v.counter);
      e2e_.note(period, at_period(what, period, t));
      return;
    case cvt::can::E2eStatus::WrongSequence:
      if (v.counter >= cvt::can::kE2eCounterModulo) std::snprintf(what, sizeof what, "%s counter 15", name);
      else std::snprintf(what, sizeof what, "%s counter %d jumped by %d (at most %d)", name, v.counter, v.delta,
                         Msg::kE2eMaxDeltaCounter);
      e2e_.note(period, at_period(what, period, t));
      break;
    default: break;
  }
  Msg m;
  const cvt::can::CodecStatus cs = cvt::can::unpack(f.data, m);
  if (cs != cvt::can::CodecStatus::Ok) {
    std::snprintf(what, sizeof what, "%s %s", name, cvt::can::to_string(cs));
    range_.note(period, at_period(what, period, t));
    return;
  }
  if (v.status == cvt::can::E2eStatus::Ok && v.delta > 1) lost_by_counter_ += v.delta - 1u;
  ck.commit(v);
  if (v.status == cvt::can::E2eStatus::WrongSequence && v.counter >= cvt::can::kE2eCounterModulo) return;
  if constexpr (std::is_same_v<Msg, cvt::can::CtrlCmd>) commands_.clamp_cmd_N = m.clamp_force_cmd_N;
  else commands_.driven_cmd_N = m.driven_clamp_force_cmd_N;
  if (realtime_) return;
  // The period this answer belongs to: the latest with its tag.
  const int j = period - static_cast<int>((static_cast<unsigned>(tag_) - m.demand_tag) & 0x0Fu);
  if (j < 0 || j >= static_cast<int>(answers_.size())) return;
  PeriodAnswers& a = answers_[static_cast<std::size_t>(j)];
  if (j == period && waiting) a.on_time[kind] = true;
  else if (!a.on_time[kind] && !a.late[kind]) {
    a.late[kind] = true;
    std::snprintf(what, sizeof what, "%s for period %d arrived after its deadline", name, j);
    late_.note(j, at_period(what, j, period_s(j)));
  }
}

void ExternalController::add_checks(const Scenario&, std::vector<Check>& c) {
  auto first = [](const Misbehaviour& m, const char* none) {
    return m.first_period < 0 ? std::string(none) : m.first_what;
  };
  if (!realtime_) {
    // Silent: a period whose commands never came, not even late.
    for (std::size_t k = 0; k < answers_.size(); ++k) {
      const PeriodAnswers& a = answers_[k];
      const bool cmd = a.on_time[kCmd] || a.late[kCmd];
      const bool shift = !ratio_control_ || a.on_time[kShift] || a.late[kShift];
      if (!cmd || !shift)
        silent_.note(static_cast<int>(k),
                     at_period(!cmd ? "no CtrlCmd" : "no CtrlShiftCmd", static_cast<int>(k),
                               period_s(static_cast<int>(k))));
    }
    const double timeout_ms = static_cast<double>(opt_.answer_timeout_ns) * 1e-6;
    c.push_back({"controller_answered", silent_.count == 0,
                 silent_.count == 0
                     ? fmt("all %.0f periods answered within the answer timeout: CtrlCmd",
                           static_cast<double>(answers_.size())) +
                           (ratio_control_ ? " and CtrlShiftCmd" : "") + " echoing the period's demand_tag"
                     : fmt("silent in %.0f of %.0f periods, first: ", static_cast<double>(silent_.count),
                           static_cast<double>(answers_.size())) +
                           silent_.first_what});
    c.push_back({"commands_on_time", late_.count == 0,
                 late_.count == 0
                     ? fmt("every answer within the %.0f ms answer timeout", timeout_ms)
                     : fmt("%.0f answers after the %.0f ms answer timeout, first: ", static_cast<double>(late_.count),
                           timeout_ms) +
                           late_.first_what});
  }
  const std::string checked = fmt("%.0f CtrlCmd and %.0f CtrlShiftCmd frames checked", frames_checked_[kCmd],
                                  frames_checked_[kShift]);
  c.push_back({"commands_e2e_valid", e2e_.count == 0,
               e2e_.count == 0
                   ? checked + fmt(", CRC and counters valid; %.0f frames missing by the counter", lost_by_counter_)
                   : fmt("%.0f frames with a wrong CRC, DLC or counter, first: ", static_cast<double>(e2e_.count)) +
                         first(e2e_, "")});
  c.push_back({"commands_in_range", range_.count == 0,
               range_.count == 0 ? checked + ", every value inside its DBC range"
                                 : fmt("%.0f frames with a value outside its DBC range, first: ",
                                       static_cast<double>(range_.count)) +
                                       first(range_, "")});
}

// ---- real time -------------------------------------------------------------

void ExternalController::rt_begin(const Scenario& sc) {
  ratio_control_ = static_cast<bool>(sc.ratio_target);
  realtime_ = true;
  reset_run();
}

void ExternalController::take_plant(const CanFrame& f) {
  cvt::can::AnyMessage a;
  if (!plant_rx_.receive(f, a).accepted()) return;
  switch (a.which) {
    case cvt::can::MessageId::PlantSpeeds: speeds_ = a.plant_speeds; have_[0] = true; break;
    case cvt::can::MessageId::PlantRatio: ratio_ = a.plant_ratio; have_[1] = true; break;
    case cvt::can::MessageId::PlantForces: forces_ = a.plant_forces; have_[2] = true; break;
    case cvt::can::MessageId::PlantShift: shift_ = a.plant_shift; have_[3] = true; break;
    default: break;
  }
}

void ExternalController::rt_receive(std::int64_t now, std::int64_t wait_ns) {
  if (t0_ < 0) {
    t0_ = now;
    next_demand_ = now;
  }
  last_now_ = now;
  if (rt_idle_) rt_idle_();
  const int period = static_cast<int>((now - t0_) / kDemandCycle_ns);
  CanFrame f;
  for (CanIoStatus st = bus_.receive(f, wait_ns); st != CanIoStatus::Timeout; st = bus_.receive(f, 0)) {
    if (st != CanIoStatus::Ok) continue;
    if (f.id == cvt::can::CtrlCmd::kId) {
      // The controller's cycle on the pacing clock, and how long after a
      // fresh plant group its next command came.
      if (last_cmd_ns_ >= 0) intervals_.push_back(now - last_cmd_ns_);
      last_cmd_ns_ = now;
      if (group_waiting_) {
        responses_.push_back(now - last_group_ns_);
        group_waiting_ = false;
      }
    }
    take(f, period, false);
  }
}

RealtimeStep ExternalController::rt_step(const Scenario& sc, std::int64_t now, double t) {
  if (now >= next_demand_) {
    send_demand(tag_, sc.demand_Nm(t), ratio_control_ ? sc.ratio_target(t) : 0.0f, ratio_control_);
    tag_ = static_cast<std::uint8_t>((tag_ + 1) & 0x0F);
    next_demand_ += kDemandCycle_ns;
  }
  // A fresh group as this node received it: Speeds, Ratio, Forces (and
  // Shift) with one sample_tag it has not recorded yet.
  RealtimeStep r;
  const bool complete = have_[0] && have_[1] && have_[2] && speeds_.sample_tag == ratio_.sample_tag &&
                        speeds_.sample_tag == forces_.sample_tag &&
                        (!ratio_control_ || (have_[3] && shift_.sample_tag == speeds_.sample_tag));
  if (complete && speeds_.sample_tag != last_used_tag_) {
    last_used_tag_ = speeds_.sample_tag;
    r.ran = r.fresh = true;
    last_group_ns_ = now;
    group_waiting_ = true;
  }
  return r;
}

void ExternalController::add_realtime_checks(double periods, std::vector<Check>& c) {
  long late = 0, missed = 0;
  // A controller that fell silent: the gap from its last command to the end.
  const std::int64_t n_cmds = last_cmd_ns_ >= 0 ? static_cast<std::int64_t>(intervals_.size()) + 1 : 0;
  if (last_cmd_ns_ >= 0 && last_now_ - last_cmd_ns_ > kLateInterval_ns) intervals_.push_back(last_now_ - last_cmd_ns_);
  for (const std::int64_t d : intervals_) {
    late += d > kLateInterval_ns ? 1 : 0;
    missed += d >= kDeadline_ns ? 1 : 0;
  }
  const LatencySummary iv = summarize_latencies(intervals_);
  const LatencySummary rs = summarize_latencies(responses_);
  const double n = static_cast<double>(intervals_.size());
  const bool ok = static_cast<double>(n_cmds) >= 0.95 * periods && late <= 0.05 * n && missed == 0;
  c.push_back({"controller_on_time", ok,
               fmt("%.0f CtrlCmd (%.0f 10 ms periods); intervals p50 %.1f ms, ", static_cast<double>(n_cmds), periods,
                   static_cast<double>(iv.p50_ns) * 1e-6) +
                   fmt("p99 %.1f ms, max %.1f ms; ", static_cast<double>(iv.p99_ns) * 1e-6,
                       static_cast<double>(iv.max_ns) * 1e-6) +
                   fmt("%.0f later than 15 ms (at most 5 %%), %.0f at or beyond the plant's 50 ms deadline; ",
                       static_cast<double>(late), static_cast<double>(missed)) +
                   fmt("command after a fresh group p50 %.1f ms, p99 %.1f ms", static_cast<double>(rs.p50_ns) * 1e-6,
                       static_cast<double>(rs.p99_ns) * 1e-6)});
}

}  // namespace cvt::sil::harness
