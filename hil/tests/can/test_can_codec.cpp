// Generated codec (hil/codegen/include/cvtplant/can/messages.hpp) against the DBC's
// intent: bit layout, rounding, range/NaN/enum rejection, DLC/ID/kind
// rejection and the receive pipeline (docs/can.md).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>

#include "cvtplant/can/messages.hpp"

using namespace cvt::can;

namespace {

int16_t le_i16(const uint8_t* p) { return static_cast<int16_t>(p[0] | (p[1] << 8)); }
uint16_t le_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

bool all_zero(const uint8_t (&d)[8]) {
  for (uint8_t b : d)
    if (b) return false;
  return true;
}

// Small deterministic generator so the sweep is reproducible.
struct Lcg {
  uint32_t s;
  float uniform(float lo, float hi) {
    s = s * 1664525u + 1013904223u;
    return lo + (hi - lo) * static_cast<float>(s >> 8) * (1.0f / 16777216.0f);
  }
};

}  // namespace

TEST_CASE("bit layout matches the DBC: Intel order, start bit = LSB") {
  CtrlCmd c;
  c.clamp_force_cmd_N = 1234.0f;
  c.driver_torque_req_Nm = 12.34f;  // 617 LSB of 0.02 Nm
  uint8_t d[8];
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(d[0] == 0);  // CRC and counter left for E2E
  CHECK(d[1] == 0);
  CHECK(le_u16(d + 2) == 1234);
  CHECK(le_i16(d + 4) == 617);
  CHECK(d[6] == 0);
  CHECK(d[7] == 0);

  PlantStatus s;
  s.plant_mode = PlantMode::RealTime;
  s.sim_time_us = 0x12345678u;
  s.fault_cmd_timeout = true;
  s.fault_rx_rejected = true;
  s.step_seq_ack = 0x9;
  s.sample_tag = 0xC;
  REQUIRE(pack(s, d) == CodecStatus::Ok);
  CHECK(d[1] == 0x30);  // mode in the high nibble, counter nibble free
  CHECK(d[2] == 0x78);
  CHECK(d[3] == 0x56);
  CHECK(d[4] == 0x34);
  CHECK(d[5] == 0x12);
  CHECK(d[6] == ((1u << 1) | (1u << 6)));
  CHECK(d[7] == 0xC9);
}

TEST_CASE("round trip of every message on grid values is exact") {
  uint8_t d[8];
  SimCtrl a;
  a.sim_request = SimRequest::Step;
  a.scene_id = SceneId::GrossSlip;
  a.step_count = 65535;
  a.step_seq = 15;
  REQUIRE(pack(a, d) == CodecStatus::Ok);
  SimCtrl a2;
  REQUIRE(unpack(d, a2) == CodecStatus::Ok);
  CHECK(a2.sim_request == SimRequest::Step);
  CHECK(a2.scene_id == SceneId::GrossSlip);
  CHECK(a2.step_count == 65535);
  CHECK(a2.step_seq == 15);

  PlantRatio r;
  r.sample_tag = 7;
  r.speed_ratio = 2.5f;
  r.geometric_ratio = 0.4375f;
  r.slip = -0.0625f;
  REQUIRE(pack(r, d) == CodecStatus::Ok);
  PlantRatio r2;
  REQUIRE(unpack(d, r2) == CodecStatus::Ok);
  CHECK(r2.sample_tag == 7);
  // 1e-4 is not a float; the decoded value is raw * 0.0001f, within one
  // float ulp of the exact grid value.
  CHECK(r2.speed_ratio == doctest::Approx(2.5f).epsilon(1e-6));
  CHECK(r2.geometric_ratio == doctest::Approx(0.4375f).epsilon(1e-6));
  CHECK(r2.slip == doctest::Approx(-0.0625f).epsilon(1e-6));

  PlantForces f;
  f.driver_axial_force_N = 65535.0f;
  f.driven_axial_force_N = 0.0f;
  REQUIRE(pack(f, d) == CodecStatus::Ok);
  PlantForces f2;
  REQUIRE(unpack(d, f2) == CodecStatus::Ok);
  CHECK(f2.driver_axial_force_N == 65535.0f);
  CHECK(f2.driven_axial_force_N == 0.0f);

  PlantDiag g;
  g.rejected_frames = 65535;
  g.cmd_timeouts = 1;
  g.rt_overruns = 258;
  REQUIRE(pack(g, d) == CodecStatus::Ok);
  PlantDiag g2;
  REQUIRE(unpack(d, g2) == CodecStatus::Ok);
  CHECK(g2.rejected_frames == 65535);
  CHECK(g2.cmd_timeouts == 1);
  CHECK(g2.rt_overruns == 258);

  HarnessLoad h;
  h.load_override_active = true;
  h.load_torque_override_Nm = -600.0f;
  REQUIRE(pack(h, d) == CodecStatus::Ok);
  HarnessLoad h2;
  REQUIRE(unpack(d, h2) == CodecStatus::Ok);
  CHECK(h2.load_override_active);
  CHECK(h2.load_torque_override_Nm == doctest::Approx(-600.0f).epsilon(1e-6));
}

TEST_CASE("encoding rounds to nearest, not toward zero") {
  uint8_t d[8];
  CtrlCmd c;
  // 0.02 Nm LSB: 0.029 -> 1.45 LSB -> 1; 0.031 -> 1.55 -> 2 (truncation: 1).
  c.driver_torque_req_Nm = 0.029f;
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == 1);
  c.driver_torque_req_Nm = 0.031f;
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == 2);
  c.driver_torque_req_Nm = -0.031f;
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == -2);
  c.driver_torque_req_Nm = 99.9999f;  // 4999.995 LSB -> 5000
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == 5000);
  c.clamp_force_cmd_N = 1500.5f;  // exact tie rounds away from zero
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_u16(d + 2) == 1501);
  c.clamp_force_cmd_N = 1500.49f;
  REQUIRE(pack(c, d) == CodecStatus::Ok);
  CHECK(le_u16(d + 2) == 1500);
}

TEST_CASE("encode/decode error is at most half an LSB over the whole range") {
  // Tolerance: 0.5 LSB from rounding plus float rounding of the scale
  // operations, bounded by 4 ulp at |x| <= 650 (4 * 6.1e-5 = 2.4e-4).
  Lcg g{12345};
  uint8_t d[8];
  for (int i = 0; i < 20000; ++i) {
    PlantSpeeds s;
    s.omega_driver_rad_s = g.uniform(-650.0f, 650.0f);
    s.omega_driven_rad_s = g.uniform(-650.0f, 650.0f);
    s.torque_transmitted_Nm = g.uniform(-600.0f, 600.0f);
    REQUIRE(pack(s, d) == CodecStatus::Ok);
    PlantSpeeds o;
    REQUIRE(unpack(d, o) == CodecStatus::Ok);
    REQUIRE(std::fabs(o.omega_driver_rad_s - s.omega_driver_rad_s) <= 0.01f + 2.4e-4f);
    REQUIRE(std::fabs(o.omega_driven_rad_s - s.omega_driven_rad_s) <= 0.01f + 2.4e-4f);
    REQUIRE(std::fabs(o.torque_transmitted_Nm - s.torque_transmitted_Nm) <= 0.01f + 2.4e-4f);
  }
}

TEST_CASE("physical range check: limits accepted, beyond rejected, nothing written") {
  uint8_t d[8] = {};
  CtrlCmd c;
  c.driver_torque_req_Nm = 600.0f;
  CHECK(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == 30000);
  c.driver_torque_req_Nm = -600.0f;
  CHECK(pack(c, d) == CodecStatus::Ok);
  CHECK(le_i16(d + 4) == -30000);
  // 600.01 Nm would still fit the 16-bit raw field (30000.5): the check is on
  // the physical value, not on the raw one.
  uint8_t e[8] = {};
  c.driver_torque_req_Nm = 600.01f;
  CHECK(pack(c, e) == CodecStatus::OutOfRange);
  c.driver_torque_req_Nm = std::nextafter(-600.0f, -1000.0f);
  CHECK(pack(c, e) == CodecStatus::OutOfRange);
  c.driver_torque_req_Nm = 0.0f;
  c.clamp_force_cmd_N = -1.0f;
  CHECK(pack(c, e) == CodecStatus::OutOfRange);
  c.clamp_force_cmd_N = 60000.5f;
  CHECK(pack(c, e) == CodecStatus::OutOfRange);
  CHECK(all_zero(e));

  SimCtrl s;
  s.step_seq = 16;
  CHECK(pack(s, e) == CodecStatus::OutOfRange);
  s.step_seq = 0;
  s.sim_request = static_cast<SimRequest>(9);
  CHECK(pack(s, e) == CodecStatus::InvalidEnum);
  s.sim_request = SimRequest::Reset;
  s.scene_id = static_cast<SceneId>(9);
  CHECK(pack(s, e) == CodecStatus::InvalidEnum);
  PlantStatus st;
  st.step_seq_ack = 200;
  CHECK(pack(st, e) == CodecStatus::OutOfRange);
  CHECK(all_zero(e));
}

TEST_CASE("NaN and infinities are rejected before range checks") {
  uint8_t d[8] = {};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (float bad : {nan, -nan, inf, -inf}) {
    CtrlCmd c;
    c.clamp_force_cmd_N = bad;
    CHECK(pack(c, d) == CodecStatus::NotFinite);
    PlantRatio r;
    r.slip = bad;
    CHECK(pack(r, d) == CodecStatus::NotFinite);
  }
  CHECK(all_zero(d));
}

TEST_CASE("decoder rejects raw codes outside [min|max] and unknown enum values") {
  uint8_t d[8] = {};
  CtrlCmd keep;
  keep.clamp_force_cmd_N = 777.0f;
  CtrlCmd out = keep;
  d[4] = 0x31;  // raw 30001 = 600.02 Nm > 600
  d[5] = 0x75;
  CHECK(unpack(d, out) == CodecStatus::OutOfRange);
  CHECK(out.clamp_force_cmd_N == 777.0f);  // untouched
  std::memset(d, 0, 8);
  d[2] = 0x61;  // 60001 N > 60000
  d[3] = 0xEA;
  CHECK(unpack(d, out) == CodecStatus::OutOfRange);

  std::memset(d, 0, 8);
  d[1] = 0x50;  // sim_request 5: not in the VAL_ table
  SimCtrl s;
  CHECK(unpack(d, s) == CodecStatus::InvalidEnum);
  std::memset(d, 0, 8);
  d[2] = 0x09;  // scene_id 9
  CHECK(unpack(d, s) == CodecStatus::InvalidEnum);
  std::memset(d, 0, 8);
  d[1] = 0x70;  // plant_mode 7
  PlantStatus st;
  CHECK(unpack(d, st) == CodecStatus::InvalidEnum);
  std::memset(d, 0, 8);
  d[2] = 0xFF;  // speed_ratio raw 65535 = 6.5535 > 6.5
  d[3] = 0xFF;
  PlantRatio r;
  CHECK(unpack(d, r) == CodecStatus::OutOfRange);
}

TEST_CASE("frame-level rejection: wrong DLC, unknown ID, not a data frame") {
  TxChannel<CtrlCmd> tx;
  CtrlCmd c;
  c.clamp_force_cmd_N = 5000.0f;
  CanFrame f;
  REQUIRE(tx.encode(c, f) == CodecStatus::Ok);
  CHECK(f.id == 0x100);
  CHECK(f.dlc == 8);

  AnyMessage any;
  CHECK(decode_any(f, any) == CodecStatus::Ok);
  CHECK(any.which == MessageId::CtrlCmd);
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == 5000.0f);

  CanFrame g = f;
  g.dlc = 7;
  CHECK(decode_any(g, any) == CodecStatus::WrongDlc);
  g.dlc = 0;
  CHECK(decode_any(g, any) == CodecStatus::WrongDlc);
  g.dlc = 9;
  CHECK(decode_any(g, any) == CodecStatus::NotDataFrame);
  g = f;
  g.id = 0x123;
  CHECK(decode_any(g, any) == CodecStatus::UnknownId);
  CHECK(find_message(0x123) == -1);
  CHECK(find_message(0x100) == 1);
  g = f;
  g.flags = kFrameError;
  CHECK(decode_any(g, any) == CodecStatus::NotDataFrame);
  g.flags = kFrameRemote;
  CHECK(decode_any(g, any) == CodecStatus::NotDataFrame);
  g.flags = kFrameExtendedId;  // same numeric ID, 29-bit: a different message
  CHECK(decode_any(g, any) == CodecStatus::NotDataFrame);
  g = f;
  g.id = 0x800;
  CHECK(decode_any(g, any) == CodecStatus::NotDataFrame);
}

TEST_CASE("receive pipeline: E2E first, then values; nothing applied on reject") {
  TxChannel<CtrlCmd> tx;
  RxBank rx;
  AnyMessage any;
  CtrlCmd c;
  CanFrame f;

  c.clamp_force_cmd_N = 1000.0f;
  REQUIRE(tx.encode(c, f) == CodecStatus::Ok);
  RxResult r = rx.receive(f, any);
  CHECK(r.accepted());
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == 1000.0f);

  // Replay: REPEATED, not applied.
  any.ctrl_cmd.clamp_force_cmd_N = -1.0f;
  r = rx.receive(f, any);
  CHECK(r.e2e == E2eStatus::Repeated);
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == -1.0f);

  // A sender-side pack error sends nothing and does not burn a counter.
  c.clamp_force_cmd_N = std::numeric_limits<float>::quiet_NaN();
  CanFrame untouched = f;
  CHECK(tx.encode(c, untouched) == CodecStatus::NotFinite);
  CHECK(std::memcmp(&untouched, &f, sizeof f) == 0);
  CHECK(tx.protector().next_counter() == 1);

  // Valid E2E around an out-of-range value (a sender bug): rejected by the
  // range check, and the E2E counter does not move.
  uint8_t d[8] = {0, 0x01, 0x61, 0xEA, 0, 0, 0, 0};  // 60001 N, counter 1
  d[0] = e2e_crc(CtrlCmd::kE2eDataId, d);
  CanFrame bad = f;
  std::memcpy(bad.data, d, 8);
  r = rx.receive(bad, any);
  CHECK(r.e2e == E2eStatus::Ok);
  CHECK(r.codec == CodecStatus::OutOfRange);
  CHECK_FALSE(r.accepted());
  CHECK(rx.checker(MessageId::CtrlCmd).last_counter() == 0);

  // The next good frame (counter 1) is accepted.
  c.clamp_force_cmd_N = 2000.0f;
  REQUIRE(tx.encode(c, f) == CodecStatus::Ok);
  r = rx.receive(f, any);
  CHECK(r.accepted());
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == 2000.0f);

  // Corrupted payload: WRONG_CRC.
  REQUIRE(tx.encode(c, f) == CodecStatus::Ok);
  f.data[3] ^= 0x04;
  r = rx.receive(f, any);
  CHECK(r.e2e == E2eStatus::WrongCrc);

  // Wrong DLC is refused before E2E runs.
  f.dlc = 6;
  r = rx.receive(f, any);
  CHECK(r.codec == CodecStatus::WrongDlc);
  CHECK(r.e2e == E2eStatus::NoNewData);

  // Unknown ID.
  f.dlc = 8;
  f.id = 0x7FF;
  r = rx.receive(f, any);
  CHECK(r.codec == CodecStatus::UnknownId);

  // A counter jump (counter 9 after 1) with an out-of-range value: rejected
  // by the range check and not adopted for re-synchronisation.
  uint8_t jump[8] = {0, 0x09, 0x61, 0xEA, 0, 0, 0, 0};
  jump[0] = e2e_crc(CtrlCmd::kE2eDataId, jump);
  CanFrame j = f;
  j.id = CtrlCmd::kId;
  std::memcpy(j.data, jump, 8);
  r = rx.receive(j, any);
  CHECK(r.e2e == E2eStatus::WrongSequence);
  CHECK(r.codec == CodecStatus::OutOfRange);
  CHECK(rx.checker(MessageId::CtrlCmd).last_counter() == 1);
  CHECK_FALSE(rx.checker(MessageId::CtrlCmd).resynchronising());
  // The same jump with a valid value: still not applied, but adopted; the
  // next in-sequence frame is Sync (not applied), the one after it is OK.
  jump[2] = 0x88;  // 5000 N
  jump[3] = 0x13;
  jump[0] = e2e_crc(CtrlCmd::kE2eDataId, jump);
  std::memcpy(j.data, jump, 8);
  any.ctrl_cmd.clamp_force_cmd_N = -1.0f;
  r = rx.receive(j, any);
  CHECK(r.e2e == E2eStatus::WrongSequence);
  CHECK(r.codec == CodecStatus::Ok);
  CHECK_FALSE(r.accepted());
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == -1.0f);
  CHECK(rx.checker(MessageId::CtrlCmd).last_counter() == 9);
  for (const E2eStatus expect : {E2eStatus::Sync, E2eStatus::Ok}) {
    jump[1] = static_cast<uint8_t>(jump[1] + 1);
    jump[0] = e2e_crc(CtrlCmd::kE2eDataId, jump);
    std::memcpy(j.data, jump, 8);
    r = rx.receive(j, any);
    CHECK(r.e2e == expect);
  }
  CHECK(r.accepted());
  CHECK(any.ctrl_cmd.clamp_force_cmd_N == 5000.0f);
}

TEST_CASE("timeout reaction values come from the DBC") {
  CtrlCmd last;
  last.clamp_force_cmd_N = 3000.0f;
  last.driver_torque_req_Nm = 150.0f;
  const CtrlCmd t = on_rx_timeout(last);
  CHECK(t.clamp_force_cmd_N == 3000.0f);  // Ramp: starts from the last value
  CHECK(t.driver_torque_req_Nm == 150.0f);
  // Ramp: 50000 N/s toward 20000 N, 250 N m/s toward 0, never past.
  const CtrlCmd r = rx_timeout_ramp(t, 0.125f);
  CHECK(r.clamp_force_cmd_N == 3000.0f + 6250.0f);
  CHECK(r.driver_torque_req_Nm == 150.0f - 31.25f);
  const CtrlCmd end = rx_timeout_ramp(t, 10.0f);
  CHECK(end.clamp_force_cmd_N == 20000.0f);
  CHECK(end.driver_torque_req_Nm == 0.0f);
  CtrlCmd high;
  high.clamp_force_cmd_N = 30000.0f;
  high.driver_torque_req_Nm = -100.0f;
  const CtrlCmd down = rx_timeout_ramp(high, 0.125f);
  CHECK(down.clamp_force_cmd_N == 30000.0f - 6250.0f);  // toward 20 kN from above too
  CHECK(down.driver_torque_req_Nm == -100.0f + 31.25f);
  CHECK(ramp_toward(5.0f, 5.0f, 1.0f) == 5.0f);
  HarnessLoad h;
  h.load_override_active = true;
  h.load_torque_override_Nm = 80.0f;
  const HarnessLoad ht = on_rx_timeout(h);
  CHECK_FALSE(ht.load_override_active);
  CHECK(ht.load_torque_override_Nm == 0.0f);
  PlantSpeeds s;
  s.omega_driver_rad_s = 100.0f;
  CHECK(on_rx_timeout(s).omega_driver_rad_s == 100.0f);  // None: keep last
}

TEST_CASE("message table: 11-bit IDs, DLC 8, unique E2E data IDs") {
  for (uint8_t i = 0; i < kMessageCount; ++i) {
    CHECK(kMessages[i].can_id <= 0x7FFu);
    CHECK(kMessages[i].dlc == 8);
    CHECK(find_message(kMessages[i].can_id) == i);
    for (uint8_t j = 0; j < i; ++j) CHECK(kMessages[i].e2e_data_id != kMessages[j].e2e_data_id);
  }
}
