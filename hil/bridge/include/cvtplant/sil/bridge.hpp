// The SIL bridge: a scene's plant on a CAN bus (docs/sil.md). Heap-free and
// transport-agnostic: it talks through cvt::port::CanTransport and reads time
// from cvt::port::Clock, so the same code runs on SocketCAN and, in unit
// tests, on the loopback bus with a virtual clock.
//
// The plant is a template parameter (docs/sil.md#plant-interface): `Bridge`
// is the bridge of the scene's real-time plant (ScenePlant, heap-free); a
// host program may put another plant with the same members behind the same
// bus code (the multibody reference, docs/sil.md#reference-plant).
//
// Lock-step (docs/sil.md#lock-step): a SimCtrl Step advances exactly
// step_count frames, then one output group is sent. Real time
// (docs/sil.md#real-time): the caller paces realtime_frame() on absolute
// deadlines; cyclic frames follow the DBC cycle times.
#pragma once

#include <csignal>
#include <cstdint>
#include <type_traits>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/port/can_transport.hpp"
#include "cvtplant/port/clock.hpp"
#include "cvtplant/sil/scene_plant.hpp"

namespace cvt::sil {

// PlantBusDiag.bus_state carries port::CanBusState's value.
static_assert(static_cast<int>(can::BusState::ErrorActive) == static_cast<int>(port::CanBusState::ErrorActive) &&
                  static_cast<int>(can::BusState::ErrorWarning) == static_cast<int>(port::CanBusState::ErrorWarning) &&
                  static_cast<int>(can::BusState::ErrorPassive) == static_cast<int>(port::CanBusState::ErrorPassive) &&
                  static_cast<int>(can::BusState::BusOff) == static_cast<int>(port::CanBusState::BusOff),
              "DBC bus_state values must match port::CanBusState");

// Receives every frame the bridge put on the bus (the candump log).
class FrameSink {
 public:
  virtual void on_tx(const can::CanFrame& f, std::int64_t host_ns, std::int64_t sim_ns) noexcept = 0;

 protected:
  FrameSink() = default;
  ~FrameSink() = default;
};

// One counter per rejection reason (docs/can.md#rejection), plus what the
// bridge itself refuses.
struct RxCounts {
  std::uint64_t accepted = 0;
  std::uint64_t not_data_frame = 0;  // remote, extended-ID, DLC > 8
  std::uint64_t unknown_id = 0;
  std::uint64_t wrong_dlc = 0;
  std::uint64_t wrong_crc = 0;
  std::uint64_t repeated = 0;        // E2E counter equal to the last accepted one
  std::uint64_t wrong_sequence = 0;  // counter jump > max delta, or 15
  std::uint64_t resync_withheld = 0; // valid, in sequence, but E2E re-synchronising: not used (not a rejection)
  std::uint64_t out_of_range = 0;
  std::uint64_t invalid_enum = 0;
  std::uint64_t error_frames = 0;    // reported, never decoded (docs/sil.md#robustness)
  std::uint64_t stale_discarded = 0; // drained after a command timeout (docs/can.md#timeouts)
  std::uint64_t plant_ids_ignored = 0;  // the plant's own output IDs sent by another node
  std::uint64_t requests_ignored = 0;   // e.g. Step while running in real time
  std::uint64_t cmd_superseded = 0;     // valid CtrlCmd replaced before any frame used it
  std::uint64_t requests_resent = 0;    // SimCtrl repeating the last step_seq: answered again, not executed
  // PlantDiag.rejected_frames: every refused data frame. Not error frames
  // (fault_bus_error), not re-synchronisation, not stale drains, not ignored
  // requests (docs/sil.md#robustness).
  std::uint64_t rejected() const noexcept {
    return not_data_frame + unknown_id + wrong_dlc + wrong_crc + repeated + wrong_sequence + out_of_range +
           invalid_enum + plant_ids_ignored;
  }
};

struct TxCounts {
  std::uint64_t sent = 0;
  std::uint64_t failed = 0;      // Dropped (after the transport's ENOBUFS bound), BusOff, IoError
  std::uint64_t bus_off_refused = 0;
  std::uint64_t saturated = 0;   // output values clamped to the DBC range before packing
  std::uint64_t encode_errors = 0;
};

inline const Scene* builtin_scene_for(can::SceneId id) {
  switch (id) {
    case can::SceneId::OscillatorCoulomb: return find_builtin_scene("oscillator-coulomb");
    case can::SceneId::OscillatorStribeck: return find_builtin_scene("oscillator-stribeck");
    case can::SceneId::SeedCase1: return find_builtin_scene("seed-case1");
    case can::SceneId::SeedCase2: return find_builtin_scene("seed-case2");
    case can::SceneId::ClampStep: return find_builtin_scene("clamp-step");
    case can::SceneId::TipIn: return find_builtin_scene("tip-in");
    case can::SceneId::GrossSlip: return find_builtin_scene("gross-slip");
    case can::SceneId::RatioControl: return find_builtin_scene("ratio-control");
    case can::SceneId::Keep: break;
  }
  return nullptr;
}

// Clamp every float signal into its DBC [min|max] so an extreme plant state
// still produces a frame (the receiver sees the rail, the bridge counts it)
// instead of a silently missing one. NaN cannot occur: the plant's watchdog
// keeps outputs finite (docs/rom.md#watchdog); it is mapped to 0 regardless.
template <class Msg>
std::uint32_t saturate_to_dbc(Msg& m) noexcept {
  std::uint32_t n = 0;
  m.visit([&n](const can::SignalInfo& s, auto& v) {
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, float>) {
      const float lo = static_cast<float>(s.min), hi = static_cast<float>(s.max);
      if (!(v == v)) {
        v = 0.0f;
        ++n;
      } else if (v < lo) {
        v = lo;
        ++n;
      } else if (v > hi) {
        v = hi;
        ++n;
      }
    }
  });
  return n;
}

// What the plant applies while CtrlCmd is timed out (docs/sil.md#timeouts).
enum class CmdTimeoutReaction : std::uint8_t {
  Dbc,       // the DBC's CvtTimeoutAction: ramps from the last applied values
  HoldLast,  // every CtrlCmd signal keeps the last applied value
};

inline const char* to_string(CmdTimeoutReaction r) noexcept {
  return r == CmdTimeoutReaction::HoldLast ? "hold-last" : "dbc";
}

template <class Plant>
class BasicBridge {
 public:
  enum class CmdState : std::uint8_t { NoneYet, Valid, TimedOut };

  // `plant_args` construct the plant (none for ScenePlant).
  template <class... PlantArgs>
  BasicBridge(port::CanTransport& bus, port::Clock& clock, FrameSink* sink = nullptr, PlantArgs&&... plant_args)
      : bus_(bus), clock_(clock), sink_(sink), plant_(static_cast<PlantArgs&&>(plant_args)...) {}

  // Loads a scene and resets to its initial state in mode Ready.
  bool load_scene(const Scene& s) {
    if (!plant_.load(s)) {
      fault_scene_ = true;
      return false;
    }
    fault_scene_ = false;
    restart();
    return true;
  }

  // Lock-step / idle service: waits up to wait_ns for a frame, then handles
  // every frame already queued.
  void service(std::int64_t wait_ns) {
    can::CanFrame f;
    port::CanIoStatus st = bus_.receive(f, wait_ns);
    while (st != port::CanIoStatus::Timeout) {
      handle_io(st, f, false);
      if (mode_ == can::PlantMode::RealTime) return;  // the caller starts pacing now
      st = bus_.receive(f, 0);
    }
  }

  // Switch to real time now (also what SimCtrl RunRealTime does). A plant
  // that cannot keep time refuses (docs/sil.md#reference-realtime): false,
  // the mode unchanged.
  bool start_realtime() {
    if (!plant_.keeps_time()) {
      ++realtime_refused_;
      return false;
    }
    enter_mode(can::PlantMode::RealTime);
    return true;
  }
  // RunRealTime requests and --mode realtime refused because the plant cannot keep time.
  std::uint64_t realtime_refused() const noexcept { return realtime_refused_; }

  void set_cmd_timeout_reaction(CmdTimeoutReaction r) noexcept { cmd_reaction_ = r; }
  CmdTimeoutReaction cmd_timeout_reaction() const noexcept { return cmd_reaction_; }

  // One paced frame (docs/sil.md#real-time): deadlines on the host clock,
  // then the receive queue (drained of stale commands after a timeout),
  // then one plant frame and the cyclic frames that fall due.
  void realtime_frame() {
    if (mode_ != can::PlantMode::RealTime) return;
    check_deadlines(clock_.now_ns());
    can::CanFrame f;
    for (port::CanIoStatus st = bus_.receive(f, 0); st != port::CanIoStatus::Timeout; st = bus_.receive(f, 0)) {
      handle_io(st, f, drain_cmd_ || drain_load_);
      if (mode_ != can::PlantMode::RealTime) break;
    }
    drain_cmd_ = drain_load_ = false;
    if (mode_ != can::PlantMode::RealTime) return;
    step_one_frame();
    const long n = plant_.frames();
    if (n % fast_cycle_frames_ == 0) {
      const bool slow_due = n % slow_cycle_frames_ == 0;
      send_group(0, slow_due, n % params_cycle_frames_ == 0, slow_due);
    }
  }

  // The pacing loop reports an overrun here (docs/sil.md#real-time).
  void note_overrun() noexcept {
    ++rt_overruns_;
    overrun_since_status_ = true;
  }

  can::PlantMode mode() const noexcept { return mode_; }
  CmdState cmd_state() const noexcept { return cmd_state_; }
  const can::CtrlCmd& command() const noexcept { return cmd_; }
  CmdState shift_state() const noexcept { return shift_state_; }
  const can::CtrlShiftCmd& shift_command() const noexcept { return shift_; }
  std::uint64_t shift_timeouts() const noexcept { return shift_timeouts_; }
  // The driven (secondary) clamping command the next frame uses: the last
  // CtrlShiftCmd (or its timeout ramp), else the scene's set-up value.
  double driven_command() const {
    if (shift_state_ == CmdState::NoneYet) return plant_.scene()->params.driven_clamp_N;
    return shift_.driven_clamp_force_cmd_N;
  }
  // The inputs the next frame will use.
  RomInputs<double> current_inputs() const {
    RomInputs<double> u;
    const Scene& s = *plant_.scene();
    const double t = static_cast<double>(sim_ns()) * 1e-9;
    if (cmd_state_ == CmdState::NoneYet) {
      u.tau_in_Nm = s.tau_in.at(t);
      u.clamp_N = s.clamp.at(t);
    } else {
      u.tau_in_Nm = cmd_.driver_torque_req_Nm;
      u.clamp_N = cmd_.clamp_force_cmd_N;
    }
    u.tau_load_Nm = load_.load_override_active ? static_cast<double>(load_.load_torque_override_Nm)
                                               : s.tau_load.at(t);
    return u;
  }
  std::int64_t sim_ns() const noexcept { return static_cast<std::int64_t>(plant_.frames()) * plant_.frame_ns(); }
  const Plant& plant() const noexcept { return plant_; }
  // The plant itself, for what the bus does not carry (a host plant's
  // settings and checks); stepping it behind the bridge's back breaks lock-step.
  Plant& plant() noexcept { return plant_; }
  const RxCounts& rx() const noexcept { return rx_; }
  const TxCounts& tx() const noexcept { return tx_; }
  std::uint64_t cmd_timeouts() const noexcept { return cmd_timeouts_; }
  const can::E2eChecker& cmd_checker() const noexcept { return rxbank_.checker(can::MessageId::CtrlCmd); }
  std::uint64_t load_timeouts() const noexcept { return load_timeouts_; }
  std::uint64_t rt_overruns() const noexcept { return rt_overruns_; }
  std::uint64_t steps_requested() const noexcept { return steps_requested_; }
  std::uint64_t groups_sent() const noexcept { return groups_sent_; }
  std::uint64_t groups_resent() const noexcept { return groups_resent_; }
  bool fault_scene() const noexcept { return fault_scene_; }
  std::int64_t frame_ns() const noexcept { return plant_.frame_ns(); }

 private:
  static constexpr std::int64_t kCmdTimeout_ns = std::int64_t{can::CtrlCmd::kRxTimeout_ms} * 1000000;
  static constexpr std::int64_t kLoadTimeout_ns = std::int64_t{can::HarnessLoad::kRxTimeout_ms} * 1000000;
  static constexpr std::int64_t kShiftTimeout_ns = std::int64_t{can::CtrlShiftCmd::kRxTimeout_ms} * 1000000;

  void restart() {
    plant_.reset();
    mode_ = can::PlantMode::Ready;
    cmd_state_ = CmdState::NoneYet;
    cmd_ = can::CtrlCmd{};
    load_ = can::HarnessLoad{};
    shift_state_ = CmdState::NoneYet;
    shift_ = can::CtrlShiftCmd{};
    shift_monitor_ = false;
    cmd_monitor_ = load_monitor_ = false;
    load_timed_out_ = false;
    drain_cmd_ = drain_load_ = false;
    cmd_unused_ = false;
    // A new run may restart its counters at 0 (docs/sil.md#lock-step).
    rxbank_.reset(can::MessageId::CtrlCmd);
    rxbank_.reset(can::MessageId::HarnessLoad);
    rxbank_.reset(can::MessageId::CtrlShiftCmd);
    const std::int64_t cycle_ns = std::int64_t{can::PlantSpeeds::kCycleTime_ms} * 1000000;
    const std::int64_t slow_ns = std::int64_t{can::PlantStatus::kCycleTime_ms} * 1000000;
    const std::int64_t params_ns = std::int64_t{can::PlantParams::kCycleTime_ms} * 1000000;
    fast_cycle_frames_ = cycle_ns / plant_.frame_ns() < 1 ? 1 : cycle_ns / plant_.frame_ns();
    slow_cycle_frames_ = slow_ns / plant_.frame_ns() < 1 ? 1 : slow_ns / plant_.frame_ns();
    params_cycle_frames_ = params_ns / plant_.frame_ns() < 1 ? 1 : params_ns / plant_.frame_ns();
    params_ = plant_.published();
  }

  // Deadlines run on simulated time in lock-step and on the host clock in
  // real time (docs/can.md#timeouts).
  std::int64_t deadline_now() const {
    return mode_ == can::PlantMode::RealTime ? clock_.now_ns() : sim_ns();
  }

  void enter_mode(can::PlantMode m) {
    if (!plant_.loaded()) return;
    if (m != mode_ && (m == can::PlantMode::LockStep || m == can::PlantMode::RealTime)) {
      // Monitoring starts on entering a running mode, on that mode's clock.
      mode_ = m;
      const std::int64_t now = deadline_now();
      cmd_monitor_ = true;
      cmd_last_ns_ = now;
      load_last_ns_ = now;
      return;
    }
    mode_ = m;
  }

  // docs/sil.md#timeouts: the reaction starts from what the plant applies
  // now (a command, or the scene's profile before the first one); the E2E
  // checker keeps its reference and has to re-synchronise, so a frozen
  // controller's repeated frame is never used again; flag; count once.
  void check_deadlines(std::int64_t now) {
    if (cmd_monitor_ && cmd_state_ != CmdState::TimedOut && now - cmd_last_ns_ >= kCmdTimeout_ns) {
      const RomInputs<double> u = current_inputs();
      cmd_.clamp_force_cmd_N = static_cast<float>(u.clamp_N);
      cmd_.driver_torque_req_Nm = static_cast<float>(u.tau_in_Nm);
      if (cmd_reaction_ == CmdTimeoutReaction::Dbc) cmd_ = can::on_rx_timeout(cmd_);
      cmd_state_ = CmdState::TimedOut;
      rxbank_.require_resync(can::MessageId::CtrlCmd);
      ++cmd_timeouts_;
      cmd_timeout_since_status_ = true;
      drain_cmd_ = mode_ == can::PlantMode::RealTime;
    }
    // CtrlShiftCmd: monitored from its first accepted frame (a controller of
    // a fixed-ratio plant need not send it); the same reactions as CtrlCmd,
    // from the driven command the plant applies now (docs/sil.md#ratio-control).
    if (shift_monitor_ && shift_state_ != CmdState::TimedOut && now - shift_last_ns_ >= kShiftTimeout_ns) {
      shift_.driven_clamp_force_cmd_N = static_cast<float>(driven_command());
      if (cmd_reaction_ == CmdTimeoutReaction::Dbc) shift_ = can::on_rx_timeout(shift_);
      shift_state_ = CmdState::TimedOut;
      rxbank_.require_resync(can::MessageId::CtrlShiftCmd);
      ++shift_timeouts_;
      cmd_timeout_since_status_ = true;
      drain_cmd_ = mode_ == can::PlantMode::RealTime;
    }
    if (load_monitor_ && !load_timed_out_ && now - load_last_ns_ >= kLoadTimeout_ns) {
      load_ = can::on_rx_timeout(load_);
      load_timed_out_ = true;
      rxbank_.require_resync(can::MessageId::HarnessLoad);
      ++load_timeouts_;
      load_timeout_since_status_ = true;
      drain_load_ = mode_ == can::PlantMode::RealTime;
    }
  }

  void step_one_frame() {
    if (plant_.faulted()) {
      mode_ = can::PlantMode::Fault;
      return;
    }
    check_deadlines(deadline_now());
    // A Ramp reaction advances one frame before the frame uses it, so the
    // first timed-out frame already moves by one rate step, never by more.
    if (cmd_state_ == CmdState::TimedOut && cmd_reaction_ == CmdTimeoutReaction::Dbc)
      cmd_ = can::rx_timeout_ramp(cmd_, static_cast<float>(static_cast<double>(plant_.frame_ns()) * 1e-9));
    if (shift_state_ == CmdState::TimedOut && cmd_reaction_ == CmdTimeoutReaction::Dbc)
      shift_ = can::rx_timeout_ramp(shift_, static_cast<float>(static_cast<double>(plant_.frame_ns()) * 1e-9));
    cmd_unused_ = false;
    // The actuators deliver the supply's fraction of each clamping command
    // (HarnessLoad.clamp_supply_factor, 1 unless the harness lowers it).
    const double supply = load_.clamp_supply_factor;
    plant_.set_driven_clamp_command(driven_command() * supply);
    RomInputs<double> u = current_inputs();
    u.clamp_N *= supply;
    plant_.step(u);
    if (plant_.faulted()) mode_ = can::PlantMode::Fault;
  }

  void count_rejection(const can::RxResult& r) {
    using can::CodecStatus;
    using can::E2eStatus;
    if (r.e2e == E2eStatus::Sync && r.codec == CodecStatus::Ok) {
      ++rx_.resync_withheld;
      return;
    }
    if (r.e2e == E2eStatus::WrongCrc) ++rx_.wrong_crc;
    else if (r.e2e == E2eStatus::Repeated) ++rx_.repeated;
    else if (r.e2e == E2eStatus::WrongSequence) ++rx_.wrong_sequence;
    else if (r.codec == CodecStatus::NotDataFrame) ++rx_.not_data_frame;
    else if (r.codec == CodecStatus::UnknownId) ++rx_.unknown_id;
    else if (r.codec == CodecStatus::WrongDlc) ++rx_.wrong_dlc;
    else if (r.codec == CodecStatus::InvalidEnum) ++rx_.invalid_enum;
    else ++rx_.out_of_range;
    rejected_since_status_ = true;
  }

  static bool is_plant_output(std::uint32_t id) {
    return id == can::PlantSpeeds::kId || id == can::PlantRatio::kId || id == can::PlantForces::kId ||
           id == can::PlantStatus::kId || id == can::PlantDiag::kId || id == can::PlantBusDiag::kId ||
           id == can::PlantCmdDiag::kId || id == can::PlantShift::kId || id == can::PlantParams::kId ||
           id == can::PlantRatioMap::kId || id == can::PlantThrustMap::kId;
  }

  void handle_io(port::CanIoStatus st, const can::CanFrame& f, bool draining) {
    if (st == port::CanIoStatus::ErrorFrame) {
      // Reported through fault_bus_error and the counters; never decoded.
      ++rx_.error_frames;
      bus_error_since_status_ = true;
      return;
    }
    if (st != port::CanIoStatus::Ok) return;
    if (can::is_standard_data_frame(f) && is_plant_output(f.id)) {
      // Another node sends with the plant's IDs: an ID conflict on the bus.
      ++rx_.plant_ids_ignored;
      rejected_since_status_ = true;
      return;
    }
    // Frames queued while a command timed out are stale by definition: the
    // E2E counter cannot tell a replayed burst from fresh data, so they are
    // dropped before anything can apply them (docs/can.md#timeouts).
    if (draining && ((drain_cmd_ && (f.id == can::CtrlCmd::kId || f.id == can::CtrlShiftCmd::kId)) || (drain_load_ && f.id == can::HarnessLoad::kId))) {
      ++rx_.stale_discarded;
      return;
    }
    const can::RxResult r = rxbank_.receive(f, any_);
    if (!r.accepted()) {
      count_rejection(r);
      return;
    }
    ++rx_.accepted;
    switch (any_.which) {
      case can::MessageId::SimCtrl: handle_sim_ctrl(any_.sim_ctrl); break;
      case can::MessageId::CtrlCmd:
        if (cmd_unused_) ++rx_.cmd_superseded;
        cmd_unused_ = true;
        cmd_ = any_.ctrl_cmd;
        cmd_state_ = CmdState::Valid;
        cmd_monitor_ = true;
        cmd_last_ns_ = deadline_now();
        break;
      case can::MessageId::CtrlShiftCmd:
        shift_ = any_.ctrl_shift_cmd;
        shift_state_ = CmdState::Valid;
        shift_monitor_ = true;
        shift_last_ns_ = deadline_now();
        break;
      case can::MessageId::HarnessLoad:
        load_ = any_.harness_load;
        load_timed_out_ = false;
        load_monitor_ = true;
        load_last_ns_ = deadline_now();
        break;
      default: break;
    }
  }

  // docs/sil.md#lost-frames: a request that repeats the step_seq of the
  // last executed one is the harness's resend after a lost reply (or a
  // request it could not tell was lost): answer it again, execute nothing.
  void handle_sim_ctrl(const can::SimCtrl& m) {
    if (have_last_seq_ && m.step_seq == last_seq_) {
      ++rx_.requests_resent;
      if (m.sim_request != can::SimRequest::RunRealTime && mode_ != can::PlantMode::RealTime)
        send_group(m.step_seq, last_group_diag_, last_group_params_, true, true);
      return;
    }
    if (m.sim_request == can::SimRequest::Step && (mode_ == can::PlantMode::RealTime || !plant_.loaded())) {
      ++rx_.requests_ignored;
      return;
    }
    have_last_seq_ = true;
    last_seq_ = m.step_seq;
    switch (m.sim_request) {
      case can::SimRequest::Reset: {
        const Scene* s = m.scene_id == can::SceneId::Keep ? plant_.scene() : builtin_scene_for(m.scene_id);
        if (s == nullptr || !plant_.load(*s)) {
          fault_scene_ = true;
        } else {
          fault_scene_ = false;
          restart();
        }
        send_group(m.step_seq, true, true);
        break;
      }
      case can::SimRequest::Step:
        if (mode_ != can::PlantMode::Fault) enter_mode(can::PlantMode::LockStep);
        steps_requested_ += m.step_count;
        {
          const long before = plant_.frames();
          const bool faulted_before = plant_.faulted();
          bool slow_due = false, params_due = false;
          for (std::uint32_t i = 0; i < m.step_count; ++i) {
            step_one_frame();
            if (plant_.frames() % slow_cycle_frames_ == 0 && plant_.frames() != before) slow_due = true;
            if (plant_.frames() % params_cycle_frames_ == 0 && plant_.frames() != before) params_due = true;
          }
          // A plant that stopped in this step: its reason (PlantDiag.plant_fault)
          // goes out with the status that first shows the fault.
          if (plant_.faulted() && !faulted_before) slow_due = true;
          send_group(m.step_seq, slow_due, params_due);
        }
        break;
      case can::SimRequest::RunRealTime: start_realtime(); break;
      case can::SimRequest::Pause:
        if (mode_ != can::PlantMode::Fault) enter_mode(can::PlantMode::Ready);
        send_group(m.step_seq, true, true);
        break;
      case can::SimRequest::None: send_group(m.step_seq, true, true); break;
    }
  }

  template <class Msg>
  bool send(Msg& m, can::TxChannel<Msg>& ch) {
    tx_.saturated += saturate_to_dbc(m);
    can::CanFrame f;
    if (ch.encode(m, f) != can::CodecStatus::Ok) {
      ++tx_.encode_errors;
      return false;
    }
    const port::CanIoStatus st = bus_.send(f);
    if (st == port::CanIoStatus::Ok) {
      ++tx_.sent;
      if (sink_ != nullptr) sink_->on_tx(f, clock_.now_ns(), sim_ns());
      return true;
    }
    if (st == port::CanIoStatus::BusOff) {
      ++tx_.bus_off_refused;
      bus_error_since_status_ = true;
    } else {
      ++tx_.failed;
    }
    return false;
  }

  // docs/can.md#layout "Output groups": Speeds, Ratio, Forces, [Shift,]
  // [Diag, BusDiag, CmdDiag,] [Params, RatioMap, ThrustMap,] Status.
  // In real time the 100 ms frames (the diagnostics, Status) go out only on
  // every tenth 10 ms group, as the DBC cycle times say; there step_seq_ack
  // is 0 because no request is being acknowledged.
  // A resent group repeats the last group's sample_tag: same sample, the
  // receivers can tell it from a new one.
  void send_group(std::uint8_t step_seq, bool with_diag, bool with_params, bool with_status = true,
                  bool resend = false) {
    const RomOutputs<double> o = plant_.loaded() ? plant_.outputs() : RomOutputs<double>{};
    const auto tag = resend ? last_group_tag_ : static_cast<std::uint8_t>(groups_sent_ & 0x0Fu);
    if (resend) {
      ++groups_resent_;
    } else {
      last_group_tag_ = tag;
      last_group_diag_ = with_diag;
      last_group_params_ = with_params;
    }
    auto f = [](double v) { return static_cast<float>(v); };
    can::PlantSpeeds sp{tag, f(o.omega1_rad_s), f(o.omega2_rad_s), f(o.torque_transmitted_Nm)};
    send(sp, tx_speeds_);
    can::PlantRatio ra{tag, f(o.speed_ratio), f(o.geometric_ratio), f(o.slip)};
    send(ra, tx_ratio_);
    can::PlantForces fo{tag, f(o.clamp_force_N), f(plant_.driven_axial_N())};
    send(fo, tx_forces_);
    // PlantShift only from a plant with a variable ratio (docs/can.md#layout):
    // a fixed-ratio plant's radii are constants.
    if (plant_.variable_ratio()) {
      const EndStops stops = plant_.end_stops();
      can::PlantShift sh{};
      sh.sample_tag = tag;
      sh.radius_driver_m = f(o.radius1_m);
      sh.radius_driven_m = f(o.radius2_m);
      sh.end_stop_underdrive = stops.underdrive;
      sh.end_stop_overdrive = stops.overdrive;
      send(sh, tx_shift_);
    }
    if (with_diag) {
      // Counters wrap modulo 2^16 by design (docs/can.md#layout).
      can::PlantDiag d;
      d.plant_fault = plant_.loaded() ? plant_.fault_code() : can::PlantFault::None;
      d.rejected_frames = static_cast<std::uint16_t>(rx_.rejected());
      d.cmd_timeouts = static_cast<std::uint16_t>(cmd_timeouts_);
      d.rt_overruns = static_cast<std::uint16_t>(rt_overruns_);
      send(d, tx_diag_);
      const port::CanTransportCounters c = bus_.counters();
      can::PlantBusDiag b;
      b.bus_state = static_cast<can::BusState>(bus_.bus_state());
      b.rx_kernel_drops = static_cast<std::uint16_t>(c.rx_kernel_drops);
      b.tx_enobufs_retries = static_cast<std::uint16_t>(c.tx_enobufs_retries);
      b.tx_dropped = static_cast<std::uint16_t>(c.tx_dropped);
      send(b, tx_bus_diag_);
      const can::E2eChecker& ck = rxbank_.checker(can::MessageId::CtrlCmd);
      can::PlantCmdDiag cd;
      cd.cmd_lost_frames = static_cast<std::uint16_t>(ck.lost_frames());
      cd.cmd_resyncs = static_cast<std::uint16_t>(ck.resyncs());
      cd.cmd_superseded = static_cast<std::uint16_t>(rx_.cmd_superseded);
      send(cd, tx_cmd_diag_);
    }
    if (with_params && plant_.loaded()) send_params();
    if (!with_status) {
      if (!resend) ++groups_sent_;
      return;
    }
    can::PlantStatus s;
    s.plant_mode = plant_.faulted() ? can::PlantMode::Fault : mode_;
    s.sim_time_us = static_cast<std::uint32_t>(static_cast<std::uint64_t>(sim_ns() / 1000));
    s.fault_watchdog = plant_.faulted();
    s.fault_cmd_timeout =
        cmd_state_ == CmdState::TimedOut || shift_state_ == CmdState::TimedOut || cmd_timeout_since_status_;
    s.fault_load_timeout = load_timed_out_ || load_timeout_since_status_;
    s.fault_rt_overrun = overrun_since_status_;
    s.fault_bus_error = bus_error_since_status_ || bus_.bus_state() != port::CanBusState::ErrorActive;
    s.fault_scene = fault_scene_;
    s.fault_rx_rejected = rejected_since_status_;
    const port::CanTransportCounters tc = bus_.counters();
    const std::uint64_t dropped = tc.rx_kernel_drops + tc.tx_dropped;
    s.fault_frames_dropped = dropped != dropped_at_status_;
    s.step_seq_ack = static_cast<std::uint8_t>(step_seq & 0x0Fu);
    s.sample_tag = tag;
    // Event flags are cleared only once a status carrying them is on the bus.
    if (send(s, tx_status_)) {
      cmd_timeout_since_status_ = load_timeout_since_status_ = overrun_since_status_ = false;
      bus_error_since_status_ = rejected_since_status_ = false;
      dropped_at_status_ = dropped;
    }
    if (!resend) ++groups_sent_;
  }

  // docs/sil.md#published-parameters.
  void send_params() {
    auto f = [](double v) { return static_cast<float>(v); };
    can::PlantParams pp;
    pp.variable_ratio = params_.variable_ratio;
    pp.capacity_coeff = f(params_.capacity_coeff);
    pp.radius_driver_m = f(params_.radius_driver_m);
    pp.clamp_max_N = f(params_.clamp_max_N);
    send(pp, tx_params_);
    if (!params_.variable_ratio) return;
    can::PlantRatioMap rm;
    rm.ratio_overdrive_stop = f(params_.ratio[0]);
    rm.ratio_setup = f(params_.ratio[1]);
    rm.ratio_underdrive_stop = f(params_.ratio[2]);
    send(rm, tx_ratio_map_);
    can::PlantThrustMap tm;
    tm.thrust_ratio_overdrive_stop = f(params_.thrust_ratio[0]);
    tm.thrust_ratio_setup = f(params_.thrust_ratio[1]);
    tm.thrust_ratio_underdrive_stop = f(params_.thrust_ratio[2]);
    send(tm, tx_thrust_map_);
  }

  port::CanTransport& bus_;
  port::Clock& clock_;
  FrameSink* sink_;
  Plant plant_;
  can::RxBank rxbank_;
  can::AnyMessage any_;
  can::TxChannel<can::PlantSpeeds> tx_speeds_;
  can::TxChannel<can::PlantRatio> tx_ratio_;
  can::TxChannel<can::PlantForces> tx_forces_;
  can::TxChannel<can::PlantShift> tx_shift_;
  can::TxChannel<can::PlantStatus> tx_status_;
  can::TxChannel<can::PlantDiag> tx_diag_;
  can::TxChannel<can::PlantBusDiag> tx_bus_diag_;
  can::TxChannel<can::PlantCmdDiag> tx_cmd_diag_;
  can::TxChannel<can::PlantParams> tx_params_;
  can::TxChannel<can::PlantRatioMap> tx_ratio_map_;
  can::TxChannel<can::PlantThrustMap> tx_thrust_map_;
  PublishedParams params_{};

  can::PlantMode mode_ = can::PlantMode::Init;
  CmdTimeoutReaction cmd_reaction_ = CmdTimeoutReaction::Dbc;
  CmdState cmd_state_ = CmdState::NoneYet;
  can::CtrlCmd cmd_{};
  can::HarnessLoad load_{};
  CmdState shift_state_ = CmdState::NoneYet;
  can::CtrlShiftCmd shift_{};
  bool shift_monitor_ = false;
  std::int64_t shift_last_ns_ = 0;
  std::uint64_t shift_timeouts_ = 0;
  bool cmd_monitor_ = false, load_monitor_ = false, load_timed_out_ = false;
  bool drain_cmd_ = false, drain_load_ = false;
  bool cmd_unused_ = false;  // a used CtrlCmd no plant frame has applied yet
  std::uint64_t dropped_at_status_ = 0;
  std::int64_t cmd_last_ns_ = 0, load_last_ns_ = 0;
  long fast_cycle_frames_ = 10, slow_cycle_frames_ = 100, params_cycle_frames_ = 1000;

  bool fault_scene_ = false;
  bool cmd_timeout_since_status_ = false, load_timeout_since_status_ = false;
  bool overrun_since_status_ = false, bus_error_since_status_ = false, rejected_since_status_ = false;

  RxCounts rx_{};
  TxCounts tx_{};
  std::uint64_t cmd_timeouts_ = 0, load_timeouts_ = 0, rt_overruns_ = 0;
  std::uint64_t steps_requested_ = 0, groups_sent_ = 0, groups_resent_ = 0, realtime_refused_ = 0;
  bool have_last_seq_ = false, last_group_diag_ = false, last_group_params_ = false;
  std::uint8_t last_seq_ = 0, last_group_tag_ = 0;
};

// The real-time pacing loop (docs/sil.md#real-time): absolute deadlines;
// lateness = wake-up minus deadline, reported to on_lateness(ns); an overrun
// is a frame whose work ends after the next deadline, so the next frame
// starts while this one is still running. Late frames are caught up (no
// sleep), so simulated time keeps pace with the clock. Runs while the bridge
// is in RealTime, until end_sim_ns of simulated time (0 = no end) or *stop.
template <class BridgeT, class OnLateness>
void pace_realtime(BridgeT& b, port::Clock& clock, std::int64_t end_sim_ns, const volatile std::sig_atomic_t* stop,
                   OnLateness&& on_lateness) {
  const std::int64_t period = b.frame_ns();
  std::int64_t deadline = clock.now_ns() + period;
  while ((stop == nullptr || *stop == 0) && b.mode() == can::PlantMode::RealTime &&
         (end_sim_ns == 0 || b.sim_ns() < end_sim_ns)) {
    clock.sleep_until(deadline);
    on_lateness(clock.now_ns() - deadline);
    b.realtime_frame();
    deadline += period;
    if (clock.now_ns() > deadline) b.note_overrun();
  }
}

// The bridge of a scene's real-time plant: heap-free, what firmware and
// cvtplant-bridge run.
using Bridge = BasicBridge<ScenePlant>;

}  // namespace cvt::sil
