// CRC-8 SAE J1850 and the E2E Profile-1-style protector/checker
// (docs/can.md#e2e, docs/can.md#e2e-checker).
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "cvtplant/can/e2e.hpp"

using cvt::can::crc8_j1850;
using cvt::can::e2e_crc;
using cvt::can::E2eChecker;
using cvt::can::E2eCheckerConfig;
using cvt::can::E2eProtector;
using cvt::can::E2eStatus;

namespace {

// Written independently of the library: the closed form docs/can.md#e2e
// derives for Profile 1 DataIDMode BOTH (register from 0x00, no final XOR).
uint8_t closed_form_p01(uint16_t data_id, const uint8_t (&p)[8]) {
  uint8_t bytes[9] = {static_cast<uint8_t>(data_id & 0xFF), static_cast<uint8_t>(data_id >> 8)};
  std::memcpy(bytes + 2, p + 1, 7);
  uint8_t r = 0x00;
  for (uint8_t b : bytes) {
    r ^= b;
    for (int i = 0; i < 8; ++i) r = (r & 0x80) ? static_cast<uint8_t>((r << 1) ^ 0x1D) : static_cast<uint8_t>(r << 1);
  }
  return r;
}

struct Frame {
  uint8_t d[8];
};

Frame make(E2eProtector& p, uint8_t fill) {
  Frame f{};
  for (int i = 2; i < 8; ++i) f.d[i] = static_cast<uint8_t>(fill + i);
  f.d[1] = 0xA0;  // high nibble belongs to the message, must survive protect()
  p.protect(f.d);
  return f;
}

constexpr uint16_t kId = 0x1100;

}  // namespace

TEST_CASE("CRC-8 SAE J1850 check value and AUTOSAR reference table") {
  const char* check = "123456789";
  CHECK(crc8_j1850(reinterpret_cast<const uint8_t*>(check), 9) == 0x4B);
  // Test table of the AUTOSAR CRC library specification for the 8-bit
  // SAE J1850 CRC.
  struct V {
    uint8_t data[9];
    size_t n;
    uint8_t crc;
  };
  const V vs[] = {
      {{0x00, 0x00, 0x00, 0x00}, 4, 0x59},
      {{0xF2, 0x01, 0x83}, 3, 0x37},
      {{0x0F, 0xAA, 0x00, 0x55}, 4, 0x79},
      {{0x00, 0xFF, 0x55, 0x11}, 4, 0xB8},
      {{0x33, 0x22, 0x55, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF}, 9, 0xCB},
      {{0x92, 0x6B, 0x55}, 3, 0x8C},
      {{0xFF, 0xFF, 0xFF, 0xFF}, 4, 0x74},
  };
  for (const V& v : vs) CHECK(crc8_j1850(v.data, v.n) == v.crc);
}

TEST_CASE("CRC chaining follows Crc_CalculateCRC8 (start = previous result)") {
  const uint8_t a[] = {0x33, 0x22, 0x55, 0xAA};
  const uint8_t b[] = {0xBB, 0xCC, 0xDD, 0xEE, 0xFF};
  CHECK(crc8_j1850(b, 5, crc8_j1850(a, 4), false) == 0xCB);
}

TEST_CASE("E2E CRC equals the Profile 1 closed form and covers data ID and bytes 1..7") {
  uint8_t p[8] = {0, 0x03, 0x10, 0x20, 0x30, 0x40, 0x50, 0x60};
  for (uint16_t id : {uint16_t{0x0000}, uint16_t{0x1100}, uint16_t{0xFFFF}, uint16_t{0x1234}}) {
    CHECK(e2e_crc(id, p) == closed_form_p01(id, p));
  }
  const uint8_t base = e2e_crc(kId, p);
  // Byte 0 is the CRC itself and is not covered.
  p[0] = 0x5A;
  CHECK(e2e_crc(kId, p) == base);
  // Every single-bit error in bytes 1..7 changes the CRC.
  for (int byte = 1; byte < 8; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      p[byte] ^= static_cast<uint8_t>(1u << bit);
      CHECK(e2e_crc(kId, p) != base);
      p[byte] ^= static_cast<uint8_t>(1u << bit);
    }
  }
  // Both data-ID bytes matter (DataIDMode BOTH): masquerade detection.
  CHECK(e2e_crc(0x1101, p) != base);
  CHECK(e2e_crc(0x1000, p) != base);
}

TEST_CASE("protector: counter 0..14 then wraps to 0, high nibble of byte 1 kept") {
  E2eProtector p(kId);
  for (int i = 0; i < 32; ++i) {
    const Frame f = make(p, 1);
    CHECK((f.d[1] & 0x0F) == i % 15);
    CHECK((f.d[1] & 0xF0) == 0xA0);
    CHECK(f.d[0] == closed_form_p01(kId, f.d));
  }
}

TEST_CASE("checker: OK sequence including the 14 -> 0 wrap") {
  E2eProtector p(kId);
  E2eChecker c(kId, E2eCheckerConfig{1});
  for (int i = 0; i < 40; ++i) {
    const Frame f = make(p, static_cast<uint8_t>(i));
    REQUIRE(c.check(f.d) == E2eStatus::Ok);
  }
  CHECK(c.last_counter() == 39 % 15);
  CHECK(c.lost_frames() == 0);
}

TEST_CASE("checker: repeated frame is REPEATED and not applied") {
  E2eProtector p(kId);
  E2eChecker c(kId);
  const Frame f0 = make(p, 0);
  CHECK(c.check(f0.d) == E2eStatus::Ok);
  CHECK(c.check(f0.d) == E2eStatus::Repeated);
  const Frame f1 = make(p, 0);
  CHECK(c.check(f1.d) == E2eStatus::Ok);
}

TEST_CASE("checker: wrong CRC and wrong data ID are WRONG_CRC") {
  E2eProtector p(kId);
  E2eChecker c(kId);
  Frame f = make(p, 3);
  Frame bad = f;
  bad.d[5] ^= 0x01;
  CHECK(c.check(bad.d) == E2eStatus::WrongCrc);
  bad = f;
  bad.d[0] ^= 0x80;
  CHECK(c.check(bad.d) == E2eStatus::WrongCrc);
  E2eChecker other(0x1101);
  CHECK(other.check(f.d) == E2eStatus::WrongCrc);
  CHECK_FALSE(c.synced());  // nothing accepted yet
  CHECK(c.check(f.d) == E2eStatus::Ok);
}

TEST_CASE("checker: lost frames within max_delta are OK and counted, beyond are WRONG_SEQUENCE") {
  E2eProtector p(kId);
  E2eChecker c(kId, E2eCheckerConfig{2});
  CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);  // counter 0
  (void)make(p, 0);                               // counter 1 lost
  CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);  // counter 2, delta 2
  CHECK(c.lost_frames() == 1);
  (void)make(p, 0);  // 3 lost
  (void)make(p, 0);  // 4 lost
  CHECK(c.check(make(p, 0).d) == E2eStatus::WrongSequence);  // 5, delta 3
  CHECK(c.lost_frames() == 3);  // 1, and the 2 the jump skipped

  E2eChecker strict(kId, E2eCheckerConfig{1});
  E2eProtector q(kId);
  CHECK(strict.check(make(q, 0).d) == E2eStatus::Ok);
  (void)make(q, 0);
  CHECK(strict.check(make(q, 0).d) == E2eStatus::WrongSequence);
}

TEST_CASE("checker: counter value 15 with a valid CRC is WRONG_SEQUENCE") {
  uint8_t d[8] = {0, 0x0F, 1, 2, 3, 4, 5, 6};
  d[0] = e2e_crc(kId, d);
  E2eChecker c(kId);
  CHECK(c.check(d) == E2eStatus::WrongSequence);
  CHECK_FALSE(c.synced());
}

TEST_CASE("checker: rejected frames never move the reference; a jump is never used") {
  // Frames with every counter value, all with valid CRCs, as a replaying
  // tunnel could deliver them.
  E2eProtector p(kId);
  Frame by_counter[15];
  for (int i = 0; i < 15; ++i) by_counter[i] = make(p, 7);

  SUBCASE("sync_counter_init 0: the reference stays on the last good counter") {
    E2eChecker c(kId, E2eCheckerConfig{2, 0});
    REQUIRE(c.check(by_counter[5].d) == E2eStatus::Ok);
    // Stale frames far ahead: rejected, and 13 after 12 too.
    CHECK(c.check(by_counter[12].d) == E2eStatus::WrongSequence);
    CHECK(c.last_counter() == 5);
    CHECK(c.check(by_counter[13].d) == E2eStatus::WrongSequence);
    CHECK(c.last_counter() == 5);
    // Bad CRC carrying the next counter: rejected, counter unchanged.
    Frame corrupt = by_counter[6];
    corrupt.d[7] ^= 0x10;
    CHECK(c.check(corrupt.d) == E2eStatus::WrongCrc);
    CHECK(c.check(by_counter[5].d) == E2eStatus::Repeated);
    CHECK(c.last_counter() == 5);
    // The genuine next frame is still accepted.
    CHECK(c.check(by_counter[6].d) == E2eStatus::Ok);
    CHECK(c.last_counter() == 6);
    CHECK(c.resyncs() == 0);
  }
  SUBCASE("sync_counter_init 2: the jump and the next two in-sequence frames are not used") {
    E2eChecker c(kId, E2eCheckerConfig{2, 2});
    REQUIRE(c.check(by_counter[5].d) == E2eStatus::Ok);
    Frame corrupt = by_counter[12];
    corrupt.d[7] ^= 0x10;
    CHECK(c.check(corrupt.d) == E2eStatus::WrongCrc);  // a bad CRC never re-synchronises
    CHECK(c.last_counter() == 5);
    CHECK(c.check(by_counter[12].d) == E2eStatus::WrongSequence);  // new reference, not used
    CHECK(c.last_counter() == 12);
    CHECK(c.resynchronising());
    CHECK(c.check(by_counter[12].d) == E2eStatus::Repeated);  // repeats neither count nor reset
    CHECK(c.check(by_counter[13].d) == E2eStatus::Sync);
    CHECK(c.check(by_counter[14].d) == E2eStatus::Sync);
    CHECK_FALSE(c.resynchronising());
    CHECK(c.check(by_counter[0].d) == E2eStatus::Ok);
    CHECK(c.resyncs() == 1);
  }
}

TEST_CASE("checker: re-synchronisation after lost frames, Profile 1 state machine") {
  for (const uint8_t n : {uint8_t{1}, uint8_t{2}, uint8_t{3}}) {
    CAPTURE(n);
    E2eProtector p(kId);
    E2eChecker c(kId, E2eCheckerConfig{2, n});
    for (int i = 0; i < 4; ++i) REQUIRE(c.check(make(p, 0).d) == E2eStatus::Ok);
    for (int i = 0; i < 3; ++i) (void)make(p, 0);  // three frames lost: delta 4
    CHECK(c.check(make(p, 0).d) == E2eStatus::WrongSequence);
    for (uint8_t k = 0; k < n; ++k) CHECK(c.check(make(p, 0).d) == E2eStatus::Sync);
    CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);
    CHECK(c.lost_frames() == 3);
    // Within max_delta while re-synchronising: still Sync, and counted.
    for (int i = 0; i < 5; ++i) (void)make(p, 0);
    CHECK(c.check(make(p, 0).d) == E2eStatus::WrongSequence);
    (void)make(p, 0);
    CHECK(c.check(make(p, 0).d) == E2eStatus::Sync);  // delta 2
    CHECK(c.lost_frames() == 3 + 5 + 1);
    CHECK(c.resyncs() == 2);
  }
}

TEST_CASE("checker: after a receive timeout a repeated frame stays REPEATED, fresh frames re-synchronise") {
  E2eProtector p(kId);
  E2eChecker c(kId, E2eCheckerConfig{2, 1});
  Frame last{};
  for (int i = 0; i < 5; ++i) {
    last = make(p, 0);
    REQUIRE(c.check(last.d) == E2eStatus::Ok);
  }
  // A frozen sender keeps sending its last frame; the deadline expires.
  c.require_resync();
  for (int i = 0; i < 10; ++i) CHECK(c.check(last.d) == E2eStatus::Repeated);
  CHECK(c.last_counter() == 4);
  // The sender runs again: the counter has to advance, then one Sync frame.
  CHECK(c.check(make(p, 0).d) == E2eStatus::Sync);
  CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);
  // sync_counter_init 0: the first advanced frame is used at once.
  E2eChecker now(kId, E2eCheckerConfig{2, 0});
  REQUIRE(now.check(last.d) == E2eStatus::Ok);
  now.require_resync();
  CHECK(now.check(last.d) == E2eStatus::Repeated);
  E2eProtector q(kId);
  for (int i = 0; i < 5; ++i) (void)make(q, 0);
  CHECK(now.check(make(q, 0).d) == E2eStatus::Ok);  // counter 5 after 4
}

TEST_CASE("checker: evaluate() is const and commit() ignores rejected verdicts") {
  E2eProtector p(kId);
  E2eChecker c(kId);
  const Frame f0 = make(p, 0);
  const E2eChecker::Verdict v0 = c.evaluate(f0.d);
  CHECK(v0.status == E2eStatus::Ok);
  CHECK_FALSE(c.synced());  // evaluate alone changes nothing
  c.commit(v0);
  CHECK(c.synced());
  const E2eChecker::Verdict rep = c.evaluate(f0.d);
  CHECK(rep.status == E2eStatus::Repeated);
  c.commit(rep);
  CHECK(c.last_counter() == 0);
}

TEST_CASE("checker: NONEW_DATA, reset and event messages (max_delta 14)") {
  CHECK(E2eChecker::no_new_data() == E2eStatus::NoNewData);
  E2eProtector p(kId);
  E2eChecker c(kId, E2eCheckerConfig{14});
  CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);
  for (int i = 0; i < 9; ++i) (void)make(p, 0);
  CHECK(c.check(make(p, 0).d) == E2eStatus::Ok);  // jump of 10 accepted
  // Sender restarts from 0 (counter 0 after 8 here): re-synchronised by
  // the state machine, or at once after reset() (a new run).
  E2eProtector restarted(kId), again(kId);
  E2eChecker s(kId, E2eCheckerConfig{2, 1});
  E2eChecker r(kId, E2eCheckerConfig{2, 1});
  E2eProtector q(kId);
  for (int i = 0; i < 9; ++i) {
    const Frame f = make(q, 1);
    REQUIRE(s.check(f.d) == E2eStatus::Ok);
    REQUIRE(r.check(f.d) == E2eStatus::Ok);
  }
  CHECK(s.check(make(restarted, 1).d) == E2eStatus::WrongSequence);
  CHECK(s.check(make(restarted, 1).d) == E2eStatus::Sync);
  CHECK(s.check(make(restarted, 1).d) == E2eStatus::Ok);
  r.reset();
  CHECK(r.check(make(again, 1).d) == E2eStatus::Ok);
}
