#include "cvtplant/sil/harness/harness_node.hpp"

namespace cvt::sil::harness {

using cvt::can::CanFrame;
using cvt::port::CanIoStatus;

bool HarnessNode::request(cvt::can::SimRequest r, std::uint16_t steps, cvt::can::SceneId scene) {
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

bool HarnessNode::sync(int attempts) {
  for (int i = 0; i < attempts; ++i) {
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

bool HarnessNode::start_realtime() {
  cvt::can::SimCtrl m;
  m.sim_request = cvt::can::SimRequest::RunRealTime;
  m.step_seq = seq_;
  seq_ = static_cast<std::uint8_t>((seq_ + 1) & 0x0F);
  CanFrame f;
  if (sim_.encode(m, f) != cvt::can::CodecStatus::Ok || bus_.send(f) != CanIoStatus::Ok) return false;
  if (on_idle_) on_idle_();
  return true;
}

bool HarnessNode::pause() {
  if (seq_ == 0) seq_ = 1;
  return request(cvt::can::SimRequest::Pause, 0, cvt::can::SceneId::Keep);
}

void HarnessNode::drain() {
  CanFrame f;
  for (CanIoStatus st = bus_.receive(f, 0); st != CanIoStatus::Timeout; st = bus_.receive(f, 0))
    if (st == CanIoStatus::Ok) take(f);
}

bool HarnessNode::send_load(bool active, float torque_Nm, float clamp_supply) {
  cvt::can::HarnessLoad m;
  m.load_override_active = active;
  m.load_torque_override_Nm = torque_Nm;
  m.clamp_supply_factor = clamp_supply;
  CanFrame f;
  return load_.encode(m, f) == cvt::can::CodecStatus::Ok && bus_.send(f) == CanIoStatus::Ok;
}

HarnessNode::Reply HarnessNode::wait_status(std::uint8_t seq, std::int64_t timeout_ns) {
  const std::int64_t end = clock_.now_ns() + timeout_ns;
  for (;;) {
    const std::int64_t left = end - clock_.now_ns();
    CanFrame f;
    // What is already queued is read before the time is up: a plant in this
    // process (on_idle) answers while it is serviced, however long its step
    // took; only an answer that never came is a lost one.
    const CanIoStatus st = bus_.receive(f, on_idle_ || left <= 0 ? 0 : left);
    if (st == CanIoStatus::Timeout) {
      if (left <= 0) return Reply::None;
      if (on_idle_) on_idle_();
      continue;
    }
    if (st != CanIoStatus::Ok || !take(f)) continue;
    if (status_.step_seq_ack != seq) continue;
    if (speeds_.sample_tag != status_.sample_tag || ratio_.sample_tag != status_.sample_tag ||
        forces_.sample_tag != status_.sample_tag || (expect_shift_ && shift_.sample_tag != status_.sample_tag))
      return Reply::Partial;
    return Reply::Complete;
  }
}

bool HarnessNode::take(const CanFrame& f) {
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
    case cvt::can::MessageId::PlantParams:
      params_ = a.plant_params;
      has_params_ = true;
      break;
    case cvt::can::MessageId::PlantStatus:
      status_ = a.plant_status;
      if (status_.plant_mode == cvt::can::PlantMode::RealTime) ++realtime_statuses_;
      break;
    default: break;
  }
  return a.which == cvt::can::MessageId::PlantStatus;
}

}  // namespace cvt::sil::harness
