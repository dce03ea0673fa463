// The SIL bridge on the loopback bus with a virtual clock (docs/sil.md#tests):
// lock-step stepping, determinism, the command timeout reaction, one
// rejection counter per malformed-frame kind, stale and repeated frames.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "cvtctl/ratio_law.hpp"
#include "cvtplant/port/loopback_transport.hpp"
#include "cvtplant/sil/bridge.hpp"

using namespace cvt;
using port::CanIoStatus;
using sil::Bridge;

namespace {

using Bus = port::LoopbackBus<2, 64>;

// The harness/controller side: node 1 of the loopback bus.
struct Peer {
  port::CanTransport& node;
  can::TxChannel<can::SimCtrl> sim;
  can::TxChannel<can::CtrlCmd> cmd;
  can::TxChannel<can::HarnessLoad> load;
  uint8_t seq = 0;

  void send_shift(float driven_N, float target) {
    can::CtrlShiftCmd m;
    m.driven_clamp_force_cmd_N = driven_N;
    m.ratio_target = target;
    can::CanFrame f;
    REQUIRE(shift.encode(m, f) == can::CodecStatus::Ok);
    REQUIRE(node.send(f) == CanIoStatus::Ok);
  }

  can::CanFrame cmd_frame(float clamp_N, float torque_Nm) {
    can::CtrlCmd m;
    m.clamp_force_cmd_N = clamp_N;
    m.driver_torque_req_Nm = torque_Nm;
    can::CanFrame f;
    REQUIRE(cmd.encode(m, f) == can::CodecStatus::Ok);
    return f;
  }
  void send_cmd(float clamp_N, float torque_Nm) { REQUIRE(node.send(cmd_frame(clamp_N, torque_Nm)) == CanIoStatus::Ok); }
  can::SimCtrl last_request;
  void request(can::SimRequest r, uint16_t steps = 0, can::SceneId scene = can::SceneId::Keep) {
    can::SimCtrl m;
    m.sim_request = r;
    m.step_count = steps;
    m.scene_id = scene;
    m.step_seq = seq;
    seq = static_cast<uint8_t>((seq + 1) & 0x0F);
    last_request = m;
    resend();
  }
  // The same request again (same step_seq, next E2E counter): what a
  // harness does when no complete answer came (docs/sil.md#lost-frames).
  void resend() {
    can::CanFrame f;
    REQUIRE(sim.encode(last_request, f) == can::CodecStatus::Ok);
    REQUIRE(node.send(f) == CanIoStatus::Ok);
  }
  can::TxChannel<can::CtrlShiftCmd> shift{};
};

struct Group {
  std::vector<can::CanFrame> frames;
  can::PlantSpeeds speeds;
  can::PlantRatio ratio;
  can::PlantForces forces;
  bool has_shift = false;
  can::PlantShift shift;
  can::PlantStatus status;
  bool has_diag = false;
  can::PlantDiag diag;
  can::PlantBusDiag bus_diag;
  can::PlantCmdDiag cmd_diag;
  bool has_params = false, has_maps = false;
  can::PlantParams params;
  can::PlantRatioMap ratio_map;
  can::PlantThrustMap thrust_map;
};

// Reads one output group and decodes it with a fresh, independent decoder.
Group read_group(port::CanTransport& node) {
  Group g;
  can::CanFrame f;
  while (node.receive(f, 0) == CanIoStatus::Ok) {
    g.frames.push_back(f);
    can::AnyMessage a;
    REQUIRE(can::decode_any(f, a) == can::CodecStatus::Ok);
    switch (a.which) {
      case can::MessageId::PlantSpeeds: g.speeds = a.plant_speeds; break;
      case can::MessageId::PlantRatio: g.ratio = a.plant_ratio; break;
      case can::MessageId::PlantForces: g.forces = a.plant_forces; break;
      case can::MessageId::PlantShift: g.has_shift = true; g.shift = a.plant_shift; break;
      case can::MessageId::PlantDiag: g.has_diag = true; g.diag = a.plant_diag; break;
      case can::MessageId::PlantBusDiag:
        REQUIRE(g.has_diag);  // PlantDiag, PlantBusDiag, PlantCmdDiag, in this order
        g.bus_diag = a.plant_bus_diag;
        break;
      case can::MessageId::PlantCmdDiag:
        REQUIRE(g.frames.size() >= 2);
        REQUIRE(g.frames[g.frames.size() - 2].id == can::PlantBusDiag::kId);
        g.cmd_diag = a.plant_cmd_diag;
        break;
      // The published parameters, after the diagnostics when both are due
      // (docs/sil.md#published-parameters); the maps only with a variable ratio.
      case can::MessageId::PlantParams:
        REQUIRE((!g.has_diag || g.frames[g.frames.size() - 2].id == can::PlantCmdDiag::kId));
        g.has_params = true;
        g.params = a.plant_params;
        break;
      case can::MessageId::PlantRatioMap:
        REQUIRE(g.frames[g.frames.size() - 2].id == can::PlantParams::kId);
        g.ratio_map = a.plant_ratio_map;
        break;
      case can::MessageId::PlantThrustMap:
        REQUIRE(g.frames[g.frames.size() - 2].id == can::PlantRatioMap::kId);
        g.has_maps = true;
        g.thrust_map = a.plant_thrust_map;
        break;
      case can::MessageId::PlantStatus: g.status = a.plant_status; return g;
      default: FAIL("unexpected message from the bridge");
    }
  }
  FAIL("no PlantStatus closing the group");
  return g;
}

struct Rig {
  port::VirtualClock clock;
  Bus bus{&clock};
  Bridge bridge{bus.node(0), clock};
  Peer peer{bus.node(1), {}, {}, {}, 0, {}, {}};

  explicit Rig(const char* scene = "tip-in") { REQUIRE(bridge.load_scene(*find_builtin_scene(scene))); }
  Group step(uint16_t n) {
    peer.request(can::SimRequest::Step, n);
    bridge.service(0);
    return read_group(bus.node(1));
  }
  // SimCtrl None: answered with the diagnostics, nothing executed.
  Group query() {
    peer.request(can::SimRequest::None);
    bridge.service(0);
    return read_group(bus.node(1));
  }
};

}  // namespace

TEST_CASE("lock-step: a Step advances exactly step_count frames and answers one group") {
  Rig rig;
  const uint8_t seq0 = rig.peer.seq;
  Group g = rig.step(37);
  CHECK(rig.bridge.plant().frames() == 37);
  CHECK(g.status.sim_time_us == 37000u);
  CHECK(g.status.step_seq_ack == seq0);
  CHECK(g.status.plant_mode == can::PlantMode::LockStep);
  REQUIRE(g.frames.size() == 4);  // no 100 ms boundary crossed: no PlantDiag
  CHECK(g.frames[0].id == can::PlantSpeeds::kId);
  CHECK(g.frames[1].id == can::PlantRatio::kId);
  CHECK(g.frames[2].id == can::PlantForces::kId);
  CHECK(g.frames[3].id == can::PlantStatus::kId);
  CHECK(g.speeds.sample_tag == g.status.sample_tag);

  g = rig.step(0);  // a query: no frame advanced
  CHECK(rig.bridge.plant().frames() == 37);
  CHECK(g.status.sim_time_us == 37000u);
  CHECK(g.status.sample_tag == 1);

  g = rig.step(63);  // crosses 100 ms: the three diagnostics before PlantStatus
  CHECK(rig.bridge.plant().frames() == 100);
  CHECK(g.status.sim_time_us == 100000u);
  CHECK(g.has_diag);
  REQUIRE(g.frames.size() == 7);
  CHECK(g.frames[3].id == can::PlantDiag::kId);
  CHECK(g.frames[4].id == can::PlantBusDiag::kId);
  CHECK(g.frames[5].id == can::PlantCmdDiag::kId);
  CHECK(g.frames.back().id == can::PlantStatus::kId);
  CHECK(rig.bridge.steps_requested() == 100);
}

TEST_CASE("lock-step: the latest valid command drives the plant and two runs are bit-identical") {
  auto run = [](std::vector<can::CanFrame>& trace) {
    Rig rig;
    for (int k = 0; k < 30; ++k) {
      rig.peer.send_cmd(3000.0f + 100.0f * static_cast<float>(k), 20.0f + static_cast<float>(k));
      const Group g = rig.step(10);
      trace.insert(trace.end(), g.frames.begin(), g.frames.end());
    }
    return rig.bridge.plant().outputs();
  };
  std::vector<can::CanFrame> a, b;
  const RomOutputs<double> oa = run(a);
  run(b);
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() > 100);
  for (size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].id == b[i].id);
    CHECK(std::memcmp(a[i].data, b[i].data, 8) == 0);
  }

  // The same inputs applied offline to the scene's simulator give the same
  // state: the bridge applied each command for exactly its 10 frames.
  const Scene& s = *find_builtin_scene("tip-in");
  RomSimulator<double, rom_feature::axial | rom_feature::road_load> sim(s.params, sim_config_of(s));
  sim.reset(s.initial, scene_inputs_at<double>(s, 0.0));
  for (int k = 0; k < 30; ++k) {
    for (int i = 0; i < 10; ++i) {
      RomInputs<double> u;
      u.clamp_N = 3000.0 + 100.0 * k;
      u.tau_in_Nm = static_cast<double>(static_cast<float>(20.0f + static_cast<float>(k)));
      u.tau_load_Nm = s.tau_load.at(static_cast<double>(k * 10 + i) * 1e-3);
      REQUIRE(sim.step_frame(u) == RomFault::none);
    }
  }
  CHECK(sim.outputs().omega1_rad_s == oa.omega1_rad_s);
  CHECK(sim.outputs().clamp_force_N == oa.clamp_force_N);
}

TEST_CASE("lock-step command timeout: ramps from the last command, fault flag, counted once, recovery") {
  Rig rig;
  rig.peer.send_cmd(5000.0f, 50.0f);
  Group g = rig.step(50);  // frames start at 0..49 ms: 49 ms since the command
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::Valid);
  CHECK_FALSE(g.status.fault_cmd_timeout);
  CHECK(rig.bridge.current_inputs().clamp_N == 5000.0);

  // The frame starting at 50 ms sees the deadline. DBC: clamp ramps toward
  // 20 kN at 50 kN/s, torque toward 0 at 250 N m/s, one 1 ms step per frame.
  g = rig.step(1);
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::TimedOut);
  CHECK(g.status.fault_cmd_timeout);
  CHECK(rig.bridge.cmd_timeouts() == 1);
  double prev_clamp = 5000.0;
  for (int j = 1; j <= 400; ++j) {
    // Frame j after the deadline used the command ramped by j steps.
    CAPTURE(j);
    const RomInputs<double> u = rig.bridge.current_inputs();
    CHECK(u.clamp_N == doctest::Approx(std::min(20000.0, 5000.0 + 50.0 * j)).epsilon(1e-6));
    CHECK(u.tau_in_Nm == doctest::Approx(std::max(0.0, 50.0 - 0.25 * j)).epsilon(1e-6));
    CHECK(u.clamp_N - prev_clamp <= 50.001);  // never a step
    prev_clamp = u.clamp_N;
    g = rig.step(1);
    CHECK(g.status.fault_cmd_timeout);
  }
  CHECK(rig.bridge.current_inputs().clamp_N == 20000.0);  // reached, never passed
  CHECK(rig.bridge.current_inputs().tau_in_Nm == 0.0);
  g = rig.step(49);  // to 500 ms: PlantDiag carries the count; one event per outage
  REQUIRE(g.has_diag);
  CHECK(g.diag.cmd_timeouts == 1);
  CHECK(g.forces.driver_axial_force_N > 19900.0f);

  // Recovery: the checker kept its reference, so the controller's next
  // frame (counter advanced) is a Sync frame, not used; the one after it is.
  rig.peer.send_cmd(6000.0f, 40.0f);
  g = rig.step(1);
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::TimedOut);
  CHECK(rig.bridge.rx().resync_withheld == 1);
  CHECK(g.status.fault_cmd_timeout);
  rig.peer.send_cmd(6000.0f, 40.0f);
  g = rig.step(1);
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::Valid);
  CHECK_FALSE(g.status.fault_cmd_timeout);
  CHECK(rig.bridge.current_inputs().clamp_N == 6000.0);
  CHECK(rig.bridge.cmd_timeouts() == 1);
}

TEST_CASE("command timeout, hold-last: the last applied command stays, bit for bit") {
  Rig rig;
  rig.bridge.set_cmd_timeout_reaction(sil::CmdTimeoutReaction::HoldLast);
  rig.peer.send_cmd(5000.0f, 50.0f);
  rig.step(50);
  Group g = rig.step(1);
  CHECK(g.status.fault_cmd_timeout);
  for (int j = 0; j < 300; ++j) {
    CHECK(rig.bridge.current_inputs().clamp_N == 5000.0);
    CHECK(rig.bridge.current_inputs().tau_in_Nm == 50.0);
    rig.step(1);
  }
  CHECK(rig.bridge.cmd_timeouts() == 1);
}

TEST_CASE("monitoring starts on entering lock-step; without any command the ramp starts from the scene's profile") {
  Rig rig;
  Group g = rig.step(50);
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::NoneYet);
  CHECK(rig.bridge.current_inputs().clamp_N == 4000.0);  // tip-in scene profile until then
  g = rig.step(1);
  CHECK(g.status.fault_cmd_timeout);
  CHECK(rig.bridge.current_inputs().clamp_N == doctest::Approx(4050.0).epsilon(1e-6));
}

namespace {

// Lowest torque-capacity safety factor 2 mu0 F_ax r1 / (cos(beta) |tau|) of
// the tip-in plant (docs/sil.md#criteria) over `periods` 10 ms periods, with
// the controller silent from period 10 on and the harness raising the load
// to `load_Nm` at period 20.
double min_safety_during_outage(sil::CmdTimeoutReaction reaction, float load_Nm, int periods) {
  Rig rig;
  rig.bridge.set_cmd_timeout_reaction(reaction);
  can::HarnessLoad hl;
  double min_sf = 1e9;
  for (int k = 0; k < periods; ++k) {
    // The example controller's feed-forward for 60 N m at safety 1.3.
    if (k < 10) rig.peer.send_cmd(1.3f * 60.0f * 0.96592583f / (2.0f * 0.25f * 0.0762f), 60.0f);
    hl.load_override_active = true;
    hl.load_torque_override_Nm = k < 20 ? 20.0f : load_Nm;
    can::CanFrame f;
    REQUIRE(rig.peer.load.encode(hl, f) == can::CodecStatus::Ok);
    REQUIRE(rig.bus.node(1).send(f) == CanIoStatus::Ok);
    const Group g = rig.step(10);
    const double tau = std::max(1.0, std::fabs(static_cast<double>(g.speeds.torque_transmitted_Nm)));
    const double sf = 2.0 * 0.25 * g.forces.driver_axial_force_N * 0.0762 / (0.96592583 * tau);
    if (k >= 5) min_sf = std::min(min_sf, sf);
  }
  return min_sf;
}

}  // namespace

TEST_CASE("command timeout, the consequence: hold-last lets the belt slip when the load rises, the ramp does not") {
  // The controller goes silent while the harness raises the load from 20 to
  // 200 N m. Hold-last keeps the clamping the controller sized for 60 N m:
  // the lumps slide (factor 1.00, docs/sil.md#criteria). The DBC ramp
  // raises the clamp toward 20 kN: the belt holds.
  const double hold = min_safety_during_outage(sil::CmdTimeoutReaction::HoldLast, 200.0f, 150);
  const double ramp = min_safety_during_outage(sil::CmdTimeoutReaction::Dbc, 200.0f, 150);
  MESSAGE("min torque-capacity safety factor during the outage: hold-last " << hold << ", ramp " << ramp);
  CHECK(hold < 1.02);
  CHECK(ramp > 1.05);
}

namespace {
void fix_crc(can::CanFrame& f, uint16_t data_id) { f.data[0] = can::e2e_crc(data_id, f.data); }
can::CanFrame data_frame_for_test(uint32_t id) {
  can::CanFrame f;
  f.id = id;
  f.dlc = 8;
  for (uint8_t i = 0; i < 8; ++i) f.data[i] = static_cast<uint8_t>(0x11 * i);
  return f;
}
}  // namespace

TEST_CASE("malformed frames: each kind rejected and counted, plant keeps running, command unchanged") {
  Rig rig;
  rig.peer.send_cmd(5000.0f, 30.0f);
  rig.step(10);
  REQUIRE(rig.bridge.rx().accepted == 2);  // CtrlCmd + SimCtrl
  port::CanTransport& n = rig.bus.node(1);

  auto expect_rejected = [&](const can::CanFrame& f, uint64_t sil::RxCounts::*counter, const char* what) {
    INFO(what);
    const uint64_t before = rig.bridge.rx().*counter;
    const uint64_t rejected_before = rig.bridge.rx().rejected();
    const long frames_before = rig.bridge.plant().frames();
    REQUIRE(n.send(f) == CanIoStatus::Ok);
    const Group g = rig.step(5);
    CHECK(rig.bridge.rx().*counter == before + 1);
    CHECK(rig.bridge.rx().rejected() == rejected_before + 1);
    CHECK(g.status.fault_rx_rejected);
    CHECK(rig.bridge.plant().frames() == frames_before + 5);  // still stepping
    CHECK(rig.bridge.command().clamp_force_cmd_N == 5000.0f);
  };

  // Every malformed frame below carries clamp 59000 N: applying any of them
  // would show up in command().
  // would show up in command(). Counter 1 is the next valid one.
  const can::CanFrame good = rig.peer.cmd_frame(59000.0f, 30.0f);

  can::CanFrame f = good;
  f.dlc = 7;
  expect_rejected(f, &sil::RxCounts::wrong_dlc, "wrong DLC");

  f = good;
  f.data[0] ^= 0x5A;
  expect_rejected(f, &sil::RxCounts::wrong_crc, "bad CRC");

  // Counter 15 is never sent; a valid jump would be adopted for
  // re-synchronisation (tested below), 15 never is.
  f = good;
  f.data[1] = static_cast<uint8_t>((f.data[1] & 0xF0u) | 15u);
  fix_crc(f, can::CtrlCmd::kE2eDataId);
  expect_rejected(f, &sil::RxCounts::wrong_sequence, "counter 15");

  f = good;
  f.data[2] = 0x61;  // clamp raw 0xEA61 = 60001 > 60000: out of range, CRC valid
  f.data[3] = 0xEA;
  fix_crc(f, can::CtrlCmd::kE2eDataId);
  expect_rejected(f, &sil::RxCounts::out_of_range, "out-of-range value");

  {
    can::SimCtrl m;
    m.sim_request = can::SimRequest::None;
    can::TxChannel<can::SimCtrl> other;
    REQUIRE(other.encode(m, f) == can::CodecStatus::Ok);
    f.data[1] = static_cast<uint8_t>((f.data[1] & 0x0Fu) | 0x90u);  // sim_request 9: not in the VAL_ table
    // Counter of the harness's next SimCtrl so only the enum is wrong.
    f.data[1] = static_cast<uint8_t>((f.data[1] & 0xF0u) | rig.peer.sim.protector().next_counter());
    fix_crc(f, can::SimCtrl::kE2eDataId);
    expect_rejected(f, &sil::RxCounts::invalid_enum, "invalid enum");
  }

  f = good;
  f.id = 0x555;
  expect_rejected(f, &sil::RxCounts::unknown_id, "unknown ID");

  f = good;
  f.flags = can::kFrameRemote;
  expect_rejected(f, &sil::RxCounts::not_data_frame, "remote frame");

  f = good;
  f.flags = can::kFrameExtendedId;
  expect_rejected(f, &sil::RxCounts::not_data_frame, "extended ID");


  // None of the above moved the E2E reference: the frame they were built
  // from is still the next valid one.
  REQUIRE(n.send(good) == CanIoStatus::Ok);
  rig.step(1);
  CHECK(rig.bridge.command().clamp_force_cmd_N == 59000.0f);
}

TEST_CASE("the plant's own output IDs from another node are rejections; PlantDiag.rejected_frames sums every reason") {
  Rig rig;
  // An ID conflict: another node sends with the plant's output IDs.
  for (const uint32_t id : {can::PlantSpeeds::kId, can::PlantStatus::kId, can::PlantCmdDiag::kId}) {
    REQUIRE(rig.bus.node(1).send(data_frame_for_test(id)) == CanIoStatus::Ok);
    const Group g = rig.step(1);
    CHECK(g.status.fault_rx_rejected);
  }
  CHECK(rig.bridge.rx().plant_ids_ignored == 3);
  // One of each other kind, plus an error frame, which is not a rejection.
  can::CanFrame f = data_frame_for_test(0x555);
  REQUIRE(rig.bus.node(1).send(f) == CanIoStatus::Ok);
  f = rig.peer.cmd_frame(5000.0f, 10.0f);
  f.dlc = 6;
  REQUIRE(rig.bus.node(1).send(f) == CanIoStatus::Ok);
  rig.bus.inject_error(0, port::can_err::kProtocol);
  const Group g = rig.step(100);
  REQUIRE(g.has_diag);
  CHECK(rig.bridge.rx().rejected() == 5);
  CHECK(rig.bridge.rx().error_frames == 1);
  CHECK(g.diag.rejected_frames == 5);
  CHECK(g.status.fault_rx_rejected);
  CHECK(g.status.fault_bus_error);
  CHECK_FALSE(rig.step(1).status.fault_rx_rejected);
}

TEST_CASE("error frames and bus-off are reported, never decoded; sends refused while bus-off") {
  Rig rig;
  rig.step(1);
  rig.bus.inject_error(0, port::can_err::kProtocol);
  Group g = rig.step(1);
  CHECK(rig.bridge.rx().error_frames == 1);
  CHECK(rig.bridge.rx().rejected() == 0);
  CHECK(rig.bridge.rx().accepted == 2);  // only the two SimCtrl requests
  CHECK(g.status.fault_bus_error);
  g = rig.step(1);
  CHECK_FALSE(g.status.fault_bus_error);

  rig.bus.inject_error(0, port::can_err::kBusOff);
  rig.peer.request(can::SimRequest::Step, 3);
  rig.bridge.service(0);
  CHECK(rig.bridge.plant().frames() == 6);  // the plant kept stepping
  CHECK(rig.bridge.tx().bus_off_refused == 4);
  can::CanFrame r;
  CHECK(rig.bus.node(1).receive(r, 0) == CanIoStatus::Timeout);

  rig.bus.inject_error(0, port::can_err::kRestarted);
  g = rig.step(1);
  CHECK(g.status.fault_bus_error);  // the bus-off, whose own status never went out
  CHECK(rig.bridge.rx().error_frames == 3);
}

TEST_CASE("ENOBUFS: bounded retries still deliver, beyond the bound the frame is dropped and counted") {
  Rig rig;
  rig.bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound);
  Group g = rig.step(1);
  CHECK(g.frames.size() == 4);
  CHECK(rig.bus.node(0).counters().tx_enobufs_retries == Bus::kTxRetryBound);

  rig.bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound + 1);
  rig.peer.request(can::SimRequest::Step, 1);
  rig.bridge.service(0);
  CHECK(rig.bridge.tx().failed == 1);
  CHECK(rig.bus.node(0).counters().tx_dropped == 1);
  g = read_group(rig.bus.node(1));
  CHECK(g.frames.size() == 3);  // PlantSpeeds was the dropped one
  CHECK(g.frames[0].id == can::PlantRatio::kId);
}

TEST_CASE("receive-queue overflow and ENOBUFS are reported on the bus: PlantBusDiag and fault_frames_dropped") {
  Rig rig;  // the bridge's receive ring holds 64 frames
  rig.step(1);
  for (int i = 0; i < 100; ++i) REQUIRE(rig.bus.node(1).send(data_frame_for_test(0x555)) == CanIoStatus::Ok);
  rig.bridge.service(0);  // the 64 that fit: read and rejected
  CHECK(rig.bridge.rx().unknown_id == 64);
  Group g = rig.step(99);  // to 100 ms: the diagnostics are due
  REQUIRE(g.has_diag);
  CHECK(g.bus_diag.rx_kernel_drops == 36);
  CHECK(g.bus_diag.bus_state == can::BusState::ErrorActive);
  CHECK(g.status.fault_frames_dropped);
  g = rig.step(1);
  CHECK_FALSE(g.status.fault_frames_dropped);  // cleared once a status carried it

  rig.bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound);  // retried, delivered
  rig.step(1);
  rig.bus.node(0).fail_next_tx_attempts(Bus::kTxRetryBound + 1);  // PlantSpeeds given up
  rig.peer.request(can::SimRequest::Step, 1);
  rig.bridge.service(0);
  g = read_group(rig.bus.node(1));
  CHECK(g.status.fault_frames_dropped);
  g = rig.step(97);  // to 200 ms
  REQUIRE(g.has_diag);
  CHECK(g.bus_diag.tx_enobufs_retries == 2 * Bus::kTxRetryBound);
  CHECK(g.bus_diag.tx_dropped == 1);
  CHECK(g.bus_diag.rx_kernel_drops == 36);
  CHECK_FALSE(g.status.fault_frames_dropped);

  // The bus state of the plant's controller, e.g. error warning.
  rig.bus.inject_error(0, port::can_err::kController, port::can_err::kCtrlTxWarning);
  g = rig.step(100);
  REQUIRE(g.has_diag);
  CHECK(g.bus_diag.bus_state == can::BusState::ErrorWarning);
  CHECK(g.status.fault_bus_error);
}

TEST_CASE("two lost commands: the E2E receiver re-synchronises before the deadline, reported in PlantCmdDiag") {
  // A controller at 10 ms, commands 1 kN apart; two frames lost on the wire.
  Rig rig;
  for (int k = 0; k < 20; ++k) {
    const can::CanFrame f = rig.peer.cmd_frame(1000.0f * static_cast<float>(k % 10 + 1), 30.0f);
    const bool lost = k == 8 || k == 9;
    if (!lost) REQUIRE(rig.bus.node(1).send(f) == CanIoStatus::Ok);
    const Group g = rig.step(10);
    CAPTURE(k);
    CHECK_FALSE(g.status.fault_cmd_timeout);
    if (k == 10) CHECK(rig.bridge.rx().wrong_sequence == 1);  // the jump: new reference, not used
    if (k == 11) CHECK(rig.bridge.rx().resync_withheld == 1);  // one Sync frame, not used
    // What the plant applies: the last command used; 8..11 keep command 7.
    const float expect = k >= 8 && k <= 11 ? 8000.0f : 1000.0f * static_cast<float>(k % 10 + 1);
    CHECK(rig.bridge.command().clamp_force_cmd_N == expect);
  }
  CHECK(rig.bridge.cmd_timeouts() == 0);
  const Group g = rig.query();
  REQUIRE(g.has_diag);
  CHECK(g.cmd_diag.cmd_lost_frames == 2);
  CHECK(g.cmd_diag.cmd_resyncs == 1);
  CHECK(g.cmd_diag.cmd_superseded == 0);

  // Three lost: the deadline comes first (docs/can.md#e2e-checker).
  Rig three;
  for (int k = 0; k < 20; ++k) {
    const can::CanFrame f = three.peer.cmd_frame(5000.0f, 30.0f);
    if (k < 8 || k > 10) REQUIRE(three.bus.node(1).send(f) == CanIoStatus::Ok);
    three.step(10);
  }
  CHECK(three.bridge.cmd_timeouts() == 1);
  CHECK(three.bridge.cmd_state() == Bridge::CmdState::Valid);
}

namespace {
// Drops the next frame with `id` sent by node `from` (a frame lost on the wire).
struct DropNext {
  size_t from;
  uint32_t id;
  int left = 1;
  static bool filter(void* ctx, size_t from, const can::CanFrame& f) {
    auto* d = static_cast<DropNext*>(ctx);
    if (d->left == 0 || from != d->from || f.id != d->id) return false;
    --d->left;
    return true;
  }
};

// Reads whatever the bridge answered, possibly nothing.
std::vector<can::CanFrame> drain(port::CanTransport& node) {
  std::vector<can::CanFrame> v;
  can::CanFrame f;
  while (node.receive(f, 0) == CanIoStatus::Ok) v.push_back(f);
  return v;
}
}  // namespace

TEST_CASE("lock-step, lost Step request: the resend executes it exactly once") {
  Rig rig;
  rig.step(10);
  DropNext drop{1, can::SimCtrl::kId};
  rig.bus.set_drop_filter(&DropNext::filter, &drop);
  const uint8_t seq = rig.peer.seq;
  rig.peer.request(can::SimRequest::Step, 10);
  rig.bridge.service(0);
  CHECK(drain(rig.bus.node(1)).empty());  // no answer: the harness times out
  CHECK(rig.bridge.plant().frames() == 10);
  rig.peer.resend();
  rig.bridge.service(0);
  const Group g = read_group(rig.bus.node(1));
  CHECK(rig.bridge.plant().frames() == 20);
  CHECK(g.status.sim_time_us == 20000u);
  CHECK(g.status.step_seq_ack == seq);
  CHECK(rig.bridge.rx().requests_resent == 0);  // the bridge never saw the first
}

TEST_CASE("lock-step, lost reply: the resend is answered with the same group, not stepped again") {
  for (const uint32_t lost : {can::PlantStatus::kId, can::PlantSpeeds::kId}) {
    CAPTURE(lost);
    Rig rig;
    rig.step(10);
    DropNext drop{0, lost};
    rig.bus.set_drop_filter(&DropNext::filter, &drop);
    const uint8_t seq = rig.peer.seq;
    rig.peer.request(can::SimRequest::Step, 10);
    rig.bridge.service(0);
    const std::vector<can::CanFrame> partial = drain(rig.bus.node(1));
    CHECK(partial.size() == 3);  // the group without the lost frame
    CHECK(rig.bridge.plant().frames() == 20);
    rig.peer.resend();
    rig.bridge.service(0);
    const Group g = read_group(rig.bus.node(1));
    CHECK(rig.bridge.plant().frames() == 20);  // not executed twice
    CHECK(g.status.sim_time_us == 20000u);
    CHECK(g.status.step_seq_ack == seq);
    CHECK(g.frames.size() == 4);
    // Same sample: the sample_tag of the group the harness partly missed.
    CHECK(g.status.sample_tag == (partial[0].data[1] >> 4));  // sample_tag: bits 12..15
    CHECK(g.speeds.sample_tag == g.status.sample_tag);
    CHECK(rig.bridge.rx().requests_resent == 1);
    CHECK(rig.bridge.groups_resent() == 1);
    // The next request is a new one again.
    const Group next = rig.step(10);
    CHECK(next.status.sim_time_us == 30000u);
    CHECK(next.status.sample_tag == static_cast<uint8_t>((g.status.sample_tag + 1) & 0x0F));
  }
}

TEST_CASE("a controller flooding the bus beyond the bridge's receive queue: drops reported, Step resent, commands re-synchronise") {
  Rig rig;  // the bridge's receive ring holds 64 frames
  rig.peer.send_cmd(3000.0f, 30.0f);
  rig.step(10);
  // 100 valid commands with advancing counters in one period, then the Step.
  for (int i = 0; i < 100; ++i) rig.peer.send_cmd(3000.0f + static_cast<float>(i), 30.0f);
  rig.peer.request(can::SimRequest::Step, 10);  // lost: the queue is full
  rig.bridge.service(0);
  CHECK(drain(rig.bus.node(1)).empty());
  CHECK(rig.bridge.plant().frames() == 10);
  // Of the 64 that fit, the last one is applied; 63 were superseded.
  CHECK(rig.bridge.command().clamp_force_cmd_N == 3063.0f);
  CHECK(rig.bridge.rx().cmd_superseded == 63);
  rig.peer.resend();  // the harness's reply timeout
  rig.bridge.service(0);
  Group g = read_group(rig.bus.node(1));
  CHECK(g.status.sim_time_us == 20000u);
  CHECK(g.status.fault_frames_dropped);
  CHECK(rig.bridge.rx().cmd_superseded == 63);  // the frame that stepped used the last one
  // Back to one command per period: the first jumps over the 36 dropped
  // counters (new reference), one Sync, then used, inside the deadline.
  for (int k = 0; k < 4; ++k) {
    rig.peer.send_cmd(4000.0f, 30.0f);
    g = rig.step(10);
    CHECK_FALSE(g.status.fault_cmd_timeout);
  }
  CHECK(rig.bridge.command().clamp_force_cmd_N == 4000.0f);
  g = rig.query();
  CHECK(g.bus_diag.rx_kernel_drops == 37);  // 36 commands and the Step
  CHECK(g.cmd_diag.cmd_superseded == 63);
  CHECK(g.cmd_diag.cmd_resyncs == 1);
  CHECK(rig.bridge.cmd_timeouts() == 0);
}

TEST_CASE("a repeated frame (same counter, valid CRC, new value) is never applied") {
  Rig rig;
  const can::CanFrame first = rig.peer.cmd_frame(5000.0f, 30.0f);
  REQUIRE(rig.bus.node(1).send(first) == CanIoStatus::Ok);
  rig.step(1);
  CHECK(rig.bridge.command().clamp_force_cmd_N == 5000.0f);

  can::CanFrame replay = first;
  replay.data[2] = 0x10;  // 10000 N ...
  replay.data[3] = 0x27;
  fix_crc(replay, can::CtrlCmd::kE2eDataId);  // ... with the old counter and a valid CRC
  REQUIRE(rig.bus.node(1).send(replay) == CanIoStatus::Ok);
  rig.step(1);
  CHECK(rig.bridge.rx().repeated == 1);
  CHECK(rig.bridge.command().clamp_force_cmd_N == 5000.0f);

  // A replayed SimCtrl Step is not executed either.
  rig.peer.seq = 3;
  rig.peer.sim.reset();
  can::CanFrame step;
  can::SimCtrl m;
  m.sim_request = can::SimRequest::Step;
  m.step_count = 100;
  // SimCtrl accepts any counter jump but 0 (docs/can.md#e2e-checker): the
  // replay carries counter 1, that of the last Step.
  REQUIRE(rig.peer.sim.encode(m, step) == can::CodecStatus::Ok);
  REQUIRE(rig.peer.sim.encode(m, step) == can::CodecStatus::Ok);
  REQUIRE(can::e2e_counter(step.data) == 1);
  const long before = rig.bridge.plant().frames();
  REQUIRE(rig.bus.node(1).send(step) == CanIoStatus::Ok);
  rig.bridge.service(0);
  CHECK(rig.bridge.plant().frames() == before);
  CHECK(rig.bridge.rx().repeated == 2);
}

TEST_CASE("real time: frames queued during a command outage are drained, not applied") {
  Rig rig;
  rig.bridge.start_realtime();
  rig.peer.send_cmd(5000.0f, 30.0f);
  rig.bridge.realtime_frame();
  CHECK(rig.bridge.command().clamp_force_cmd_N == 5000.0f);

  // The bridge stalls for 60 ms; meanwhile five commands pile up in its queue.
  for (int i = 0; i < 5; ++i) rig.peer.send_cmd(59000.0f, 30.0f);
  rig.clock.advance(60000000);
  rig.bridge.realtime_frame();
  CHECK(rig.bridge.cmd_state() == Bridge::CmdState::TimedOut);
  CHECK(rig.bridge.rx().stale_discarded == 5);
  CHECK(rig.bridge.command().clamp_force_cmd_N == 5050.0f);  // the ramp's first 1 ms step

  // Fresh frames: the first jumps over the five drained counters and becomes
  // the new reference, the second is the Sync frame, the third is used.
  for (int i = 0; i < 3; ++i) {
    rig.peer.send_cmd(7000.0f, 30.0f);
    rig.bridge.realtime_frame();
    CHECK(rig.bridge.cmd_state() == (i < 2 ? Bridge::CmdState::TimedOut : Bridge::CmdState::Valid));
  }
  CHECK(rig.bridge.rx().wrong_sequence == 1);
  CHECK(rig.bridge.rx().resync_withheld == 1);
  CHECK(rig.bridge.command().clamp_force_cmd_N == 7000.0f);
  CHECK(rig.bridge.cmd_timeouts() == 1);
}

namespace {
// A controller that hangs but whose CAN driver keeps sending its last
// mailbox: the identical frame (same counter, same CRC) every 10 ms.
struct FrozenController {
  can::CanFrame last;
  int sent = 0;
};
}  // namespace

TEST_CASE("frozen controller, lock-step: its repeated frame is never applied again, one timeout per outage") {
  for (const auto reaction : {sil::CmdTimeoutReaction::Dbc, sil::CmdTimeoutReaction::HoldLast}) {
    CAPTURE(sil::to_string(reaction));
    Rig rig;
    rig.bridge.set_cmd_timeout_reaction(reaction);
    for (int k = 0; k < 10; ++k) {
      rig.peer.send_cmd(3000.0f + 100.0f * static_cast<float>(k), 40.0f);
      rig.step(10);
    }
    FrozenController frozen{rig.peer.cmd_frame(4000.0f, 40.0f)};
    // Frozen for 500 ms: ten deadlines' worth.
    for (int k = 0; k < 50; ++k) {
      REQUIRE(rig.bus.node(1).send(frozen.last) == CanIoStatus::Ok);
      ++frozen.sent;
      const Group g = rig.step(10);
      if (k == 0) {
        CHECK(rig.bridge.command().clamp_force_cmd_N == 4000.0f);  // its last fresh frame, once
        CHECK_FALSE(g.status.fault_cmd_timeout);
      }
      if (k >= 5) {
        CHECK(g.status.fault_cmd_timeout);
        CHECK(rig.bridge.cmd_state() == Bridge::CmdState::TimedOut);
      }
    }
    CHECK(rig.bridge.rx().repeated == static_cast<uint64_t>(frozen.sent - 1));
    CHECK(rig.bridge.cmd_timeouts() == 1);
    if (reaction == sil::CmdTimeoutReaction::Dbc) {
      // 500 ms - 50 ms of ramp from 4 kN: at 20 kN, never back at 4 kN.
      CHECK(rig.bridge.current_inputs().clamp_N == 20000.0);
    }
    // It comes back: the counter advances, one Sync frame, then used.
    rig.peer.send_cmd(4500.0f, 40.0f);
    rig.step(10);
    CHECK(rig.bridge.cmd_state() == Bridge::CmdState::TimedOut);
    rig.peer.send_cmd(4600.0f, 40.0f);
    const Group g = rig.step(10);
    CHECK_FALSE(g.status.fault_cmd_timeout);
    CHECK(rig.bridge.command().clamp_force_cmd_N == 4600.0f);
    CHECK(rig.bridge.cmd_timeouts() == 1);
  }
}

TEST_CASE("frozen controller, real time: its repeated frame is never applied again, one timeout per outage") {
  Rig rig;
  rig.bridge.start_realtime();
  FrozenController frozen{rig.peer.cmd_frame(4000.0f, 40.0f)};
  bool applied_after_timeout = false;
  for (int ms = 0; ms < 500; ++ms) {
    if (ms % 10 == 0) REQUIRE(rig.bus.node(1).send(frozen.last) == CanIoStatus::Ok);
    rig.bridge.realtime_frame();
    if (rig.bridge.cmd_timeouts() > 0 && rig.bridge.cmd_state() == Bridge::CmdState::Valid)
      applied_after_timeout = true;
    rig.clock.advance(1000000);
  }
  CHECK(rig.bridge.cmd_timeouts() == 1);
  CHECK_FALSE(applied_after_timeout);
  // The first copy is used once; the one queued when the deadline expired
  // is drained; every later copy is REPEATED.
  CHECK(rig.bridge.rx().stale_discarded == 1);
  CHECK(rig.bridge.rx().repeated == 48);
  CHECK(rig.bridge.current_inputs().clamp_N == 20000.0);
}

TEST_CASE("real time: cyclic frames follow the DBC cycle times") {
  Rig rig;
  rig.bridge.start_realtime();
  for (int i = 0; i < 100; ++i) {
    rig.peer.send_cmd(5000.0f, 30.0f);
    rig.bridge.realtime_frame();
    rig.clock.advance(1000000);
  }
  int speeds = 0, status = 0, diag = 0, bus_diag = 0, cmd_diag = 0;
  can::CanFrame f;
  while (rig.bus.node(1).receive(f, 0) == CanIoStatus::Ok) {
    speeds += f.id == can::PlantSpeeds::kId;
    status += f.id == can::PlantStatus::kId;
    diag += f.id == can::PlantDiag::kId;
    bus_diag += f.id == can::PlantBusDiag::kId;
    cmd_diag += f.id == can::PlantCmdDiag::kId;
  }
  CHECK(speeds == 100 / can::PlantSpeeds::kCycleTime_ms);
  CHECK(status == 100 / can::PlantStatus::kCycleTime_ms);
  CHECK(diag == 100 / can::PlantDiag::kCycleTime_ms);
  CHECK(bus_diag == 100 / can::PlantBusDiag::kCycleTime_ms);
  CHECK(cmd_diag == 100 / can::PlantCmdDiag::kCycleTime_ms);
  CHECK(rig.bridge.cmd_timeouts() == 0);
}

TEST_CASE("Reset selects a scene; a scene the plants cannot run is a scene fault, not a crash") {
  Rig rig;
  rig.peer.request(can::SimRequest::Reset, 0, can::SceneId::GrossSlip);
  rig.bridge.service(0);
  Group g = read_group(rig.bus.node(1));
  REQUIRE(rig.bridge.plant().scene() != nullptr);
  CHECK(std::strcmp(rig.bridge.plant().scene()->name, "gross-slip") == 0);
  CHECK(g.status.plant_mode == can::PlantMode::Ready);
  CHECK_FALSE(g.status.fault_scene);
  CHECK(g.status.sim_time_us == 0u);

  Scene odd = *find_builtin_scene("tip-in");
  odd.features = rom_feature::wedging;  // wedging without the axial feature has no plant
  CHECK_FALSE(rig.bridge.load_scene(odd));
  CHECK(rig.bridge.fault_scene());
  // The previous scene stays loaded.
  CHECK(std::strcmp(rig.bridge.plant().scene()->name, "gross-slip") == 0);
}

TEST_CASE("the bridge runs every feature set: chordal action and wedging step like the built-in plants") {
  for (const std::uint32_t features : {rom_feature::polygon | rom_feature::deformation,
                                       rom_feature::axial | rom_feature::wedging | rom_feature::road_load}) {
    CAPTURE(features);
    Scene s = *find_builtin_scene("seed-case1");
    s.features = features;
    s.substeps = 4;  // chordal action needs >= 4 substeps (docs/rom.md#polygon)
    Rig rig;
    REQUIRE(rig.bridge.load_scene(s));
    rig.peer.request(can::SimRequest::Step, 10);
    rig.bridge.service(0);
    CHECK(rig.bridge.plant().frames() == 10);
    CHECK(rig.bridge.plant().fault() == RomFault::none);
    // The drive train starts from rest under 100 N m: the driver has spun up.
    CHECK(rig.bridge.plant().outputs().omega1_rad_s > 0.0);
  }
}

namespace {
// A clock on which every reading costs `cost_ns`: the bridge's work per
// frame then takes a known, deterministic amount of time.
class SlowClock final : public port::Clock {
 public:
  explicit SlowClock(int64_t cost_ns) : cost_(cost_ns) {}
  int64_t now_ns() const noexcept override { return t_ += cost_; }
  void sleep_until(int64_t t_ns) noexcept override {
    if (t_ns > t_) t_ = t_ns;
  }

 private:
  int64_t cost_;
  mutable int64_t t_ = 0;
};
}  // namespace

TEST_CASE("real-time pacing: on time without overruns; slow frames are overruns and are caught up") {
  for (const int64_t cost : {int64_t{0}, int64_t{600000}}) {
    CAPTURE(cost);
    SlowClock clock(cost);
    Bus bus(nullptr);
    Bridge bridge(bus.node(0), clock);
    REQUIRE(bridge.load_scene(*find_builtin_scene("tip-in")));
    bridge.start_realtime();
    std::vector<int64_t> late;
    sil::pace_realtime(bridge, clock, 200000000, nullptr, [&](int64_t ns) { late.push_back(ns); });
    CHECK(bridge.plant().frames() == 200);  // 200 ms simulated, one frame per period
    CHECK(late.size() == 200);
    if (cost == 0) {
      CHECK(bridge.rt_overruns() == 0);
      CHECK(late.back() == 0);
    } else {
      // Every frame reads the clock at least twice (1.2 ms > 1 ms period).
      CHECK(bridge.rt_overruns() == 200);
      CHECK(late.back() > late.front());  // behind, and catching up without sleeping
    }
  }
}

TEST_CASE("variable ratio: PlantShift in the group, CtrlShiftCmd sets the driven clamping, its timeout ramps") {
  // docs/sil.md#ratio-control
  Rig rig("ratio-control");
  const Scene& sc = *find_builtin_scene("ratio-control");
  Group g = rig.step(10);
  REQUIRE(g.frames.size() == 5);
  CHECK(g.frames[3].id == can::PlantShift::kId);
  CHECK(g.shift.sample_tag == g.status.sample_tag);
  // Before any CtrlShiftCmd: the scene's driven clamping, and the set-up radii.
  CHECK(std::fabs(g.forces.driven_axial_force_N - sc.params.driven_clamp_N) <= 0.5);
  CHECK(std::fabs(g.shift.radius_driver_m - sc.params.r1_m) < 2e-4);
  CHECK(!g.shift.end_stop_underdrive);
  CHECK(!g.shift.end_stop_overdrive);
  // 16 kN driven against 12.5 kN primary (thrust ratio 0.78, below the
  // 0.805 that holds the underdrive stop): the chain moves in on the driver
  // (downshift) and reaches the underdrive stop, which PlantShift reports.
  bool stop_seen = false;
  for (int k = 0; k < 600 && !stop_seen; ++k) {
    rig.peer.send_cmd(12500.0f, 60.0f);
    rig.peer.send_shift(16000.0f, 2.6f);
    g = rig.step(10);
    stop_seen = g.shift.end_stop_underdrive;
  }
  CHECK(stop_seen);
  CHECK(g.ratio.geometric_ratio > 2.5f);
  CHECK(std::fabs(g.forces.driven_axial_force_N - 16000.0f) < 100.0f);
  CHECK(rig.bridge.plant().stop_refined_frames() > 0);
  CHECK(g.status.plant_mode == can::PlantMode::LockStep);
  // The controller stops sending CtrlShiftCmd: after 50 ms the timeout
  // flag, and the driven command ramps from 16 kN toward 20 kN at 50 N per
  // frame (the DBC's Ramp), never a step.
  const double before = rig.bridge.driven_command();
  for (int k = 0; k < 10; ++k) {
    rig.peer.send_cmd(12500.0f, 60.0f);
    g = rig.step(10);
  }
  CHECK(g.status.fault_cmd_timeout);
  CHECK(rig.bridge.shift_timeouts() == 1);
  CHECK(rig.bridge.shift_state() == Bridge::CmdState::TimedOut);
  const double after = rig.bridge.driven_command();
  CHECK(after > before);
  CHECK(after <= before + 100 * 50.0 + 1.0);
}

TEST_CASE("published parameters: in every Reset and None answer and once per second, values from the scene") {
  // docs/sil.md#published-parameters. Fixed ratio (tip-in): PlantParams alone.
  {
    Rig rig;
    rig.peer.request(can::SimRequest::Reset, 0, can::SceneId::TipIn);
    rig.bridge.service(0);
    Group g = read_group(rig.bus.node(1));
    REQUIRE(g.has_params);
    CHECK(!g.has_maps);
    CHECK(!g.params.variable_ratio);
    const RomParams& p = find_builtin_scene("tip-in")->params;
    // 2 f mu0 / cos(beta0) with the seed's mu0 = 0.25 and 15 degrees, f = 1:
    // 0.517638; the signal's LSB is 2e-5.
    CHECK(p.normal_load_factor == 1.0);
    CHECK(std::fabs(g.params.capacity_coeff - 2.0 * p.friction.mu0 / std::cos(p.beta0_rad)) <= 1e-5);
    CHECK(std::fabs(g.params.capacity_coeff - 0.517638) <= 1e-5);
    CHECK(std::fabs(g.params.radius_driver_m - p.r1_m) <= 5e-6);
    CHECK(g.params.clamp_max_N == static_cast<float>(p.clamp_max_N));
    // Steps inside a second: none; the step crossing 1 s: again.
    int with_params = 0;
    for (int k = 0; k < 100; ++k) with_params += rig.step(10).has_params ? 1 : 0;
    CHECK(with_params == 1);
    CHECK(rig.query().has_params);
  }
  // Variable ratio: the ratio and thrust-ratio maps at the stops and set-up.
  Rig rig("ratio-control");
  rig.peer.request(can::SimRequest::None);
  rig.bridge.service(0);
  const Group g = read_group(rig.bus.node(1));
  REQUIRE(g.has_params);
  REQUIRE(g.has_maps);
  CHECK(g.params.variable_ratio);
  const RomParams& p = find_builtin_scene("ratio-control")->params;
  const double C = p.center_distance_m, t = p.radial_travel_m;
  // The plant's cubic for r2(rho) is fitted to the exact geometry (the
  // chain length held) at rho = 0, +-travel/2, +-travel (docs/rom.md#wedging):
  // at the stops the ratios agree with the geometry's to 2e-4.
  CHECK(std::fabs(g.ratio_map.ratio_setup - p.r2_m / p.r1_m) <= 5e-5);
  CHECK(std::fabs(g.ratio_map.ratio_overdrive_stop - seed::driven_pitch_radius_m(p.r1_m, p.r2_m, C, t) / (p.r1_m + t)) <=
        2e-4);
  CHECK(std::fabs(g.ratio_map.ratio_underdrive_stop -
                  seed::driven_pitch_radius_m(p.r1_m, p.r2_m, C, -t) / (p.r1_m - t)) <= 2e-4);
  // The thrust ratio at rest is theta1 / theta2 (the wrap angles) to 1e-2
  // (docs/rom.md#wedging); at set-up exactly the cubic's -a1.
  const double th1 = seed::wrap_angle_driver_rad(p.r1_m, p.r2_m, C);
  CHECK(std::fabs(g.thrust_map.thrust_ratio_setup - th1 / (2.0 * 3.14159265358979 - th1)) <= 1e-2);
  CHECK(g.thrust_map.thrust_ratio_overdrive_stop > g.thrust_map.thrust_ratio_setup);
  CHECK(g.thrust_map.thrust_ratio_setup > g.thrust_map.thrust_ratio_underdrive_stop);
  // The example controller's calibration map holds the exact geometry's
  // wrap-angle ratio (hil/controller/include/cvtctl/ratio_law.hpp); the
  // plant's cubic agrees with it to 1.1e-3 at the stops.
  MESSAGE("ratio-control publishes: capacity_coeff ", g.params.capacity_coeff, ", r1 ", g.params.radius_driver_m,
          " m, clamp max ", g.params.clamp_max_N, " N; ratios ", g.ratio_map.ratio_overdrive_stop, ", ",
          g.ratio_map.ratio_setup, ", ", g.ratio_map.ratio_underdrive_stop, "; thrust ratios ",
          g.thrust_map.thrust_ratio_overdrive_stop, ", ", g.thrust_map.thrust_ratio_setup, ", ",
          g.thrust_map.thrust_ratio_underdrive_stop);
  const cvtctl::ThrustMap map;
  CHECK(std::fabs(g.ratio_map.ratio_overdrive_stop - map.ratio[0]) <= 3e-4);
  CHECK(std::fabs(g.ratio_map.ratio_underdrive_stop - map.ratio[4]) <= 3e-4);
  CHECK(std::fabs(g.thrust_map.thrust_ratio_overdrive_stop - map.kappa[0]) <= 1.5e-3);
  CHECK(std::fabs(g.thrust_map.thrust_ratio_setup - map.kappa[2]) <= 2e-4);
  CHECK(std::fabs(g.thrust_map.thrust_ratio_underdrive_stop - map.kappa[4]) <= 1.5e-3);
}

TEST_CASE("clamping supply: the actuators deliver HarnessLoad.clamp_supply_factor of each command; 1 again on its timeout") {
  Rig rig;
  auto supply = [&](float factor) {
    can::HarnessLoad m;
    m.clamp_supply_factor = factor;
    can::CanFrame f;
    REQUIRE(rig.peer.load.encode(m, f) == can::CodecStatus::Ok);
    REQUIRE(rig.peer.node.send(f) == CanIoStatus::Ok);
  };
  Group g;
  for (int k = 0; k < 30; ++k) {
    rig.peer.send_cmd(8000.0f, 50.0f);
    g = rig.step(10);
  }
  CHECK(std::fabs(g.forces.driver_axial_force_N - 8000.0f) < 150.0f);
  // A quarter of the supply: the actuator (20 ms lag) settles at 2 kN.
  for (int k = 0; k < 30; ++k) {
    rig.peer.send_cmd(8000.0f, 50.0f);
    supply(0.25f);
    g = rig.step(10);
  }
  CHECK(std::fabs(g.forces.driver_axial_force_N - 2000.0f) < 100.0f);
  CHECK(!g.status.fault_load_timeout);
  // The harness stops sending: after 50 ms the Replace reaction, full supply.
  for (int k = 0; k < 30; ++k) {
    rig.peer.send_cmd(8000.0f, 50.0f);
    g = rig.step(10);
  }
  CHECK(rig.bridge.load_timeouts() == 1);
  CHECK(std::fabs(g.forces.driver_axial_force_N - 8000.0f) < 150.0f);
}
