// End-to-end protection in the style of AUTOSAR E2E Profile 1, DataIDMode
// BOTH (docs/can.md#e2e): CRC-8 SAE J1850 in byte 0, a 4-bit alive counter
// 0..14 in the low nibble of byte 1, and a 16-bit data ID folded into the CRC
// but never sent. Payloads are always 8 bytes (every cvtplant message has
// DLC 8; the DLC is checked before E2E runs).
#pragma once

#include <cstddef>
#include <cstdint>

namespace cvt::can {

// CRC-8 SAE J1850: poly 0x1D, init 0xFF, xorout 0xFF, not reflected.
// Chaining follows AUTOSAR Crc_CalculateCRC8: with first_call = false,
// `start` is the value returned by the previous call (final XOR undone
// before continuing), so crc(a ++ b) == crc(b, crc(a), false).
constexpr uint8_t crc8_j1850(const uint8_t* data, size_t len, uint8_t start = 0xFF,
                             bool first_call = true) noexcept {
  uint8_t reg = first_call ? uint8_t{0xFF} : static_cast<uint8_t>(start ^ 0xFFu);
  for (size_t i = 0; i < len; ++i) {
    reg = static_cast<uint8_t>(reg ^ data[i]);
    for (int b = 0; b < 8; ++b) {
      reg = (reg & 0x80u) ? static_cast<uint8_t>((reg << 1) ^ 0x1Du)
                          : static_cast<uint8_t>(reg << 1);
    }
  }
  return static_cast<uint8_t>(reg ^ 0xFFu);
}

inline constexpr uint8_t kE2eCounterModulo = 15;  // counter 0..14; 15 is never sent

// Profile 1, DataIDMode BOTH: CRC over data-ID low byte, data-ID high byte,
// then payload bytes 1..7 (byte 0 holds the CRC). Profile 1 opens the chain
// with Crc_CalculateCRC8(&id_lo, 1, 0xFF, FALSE) and XORs the final result
// with 0xFF; both together make it a plain 0x1D CRC register started at 0x00
// with no final XOR. docs/can.md#e2e derives this; the Python agreement test
// checks it with that closed form.
constexpr uint8_t e2e_crc(uint16_t data_id, const uint8_t (&payload)[8]) noexcept {
  const uint8_t id_lo[1] = {static_cast<uint8_t>(data_id & 0xFFu)};
  const uint8_t id_hi[1] = {static_cast<uint8_t>(data_id >> 8)};
  uint8_t crc = crc8_j1850(id_lo, 1, 0xFF, false);
  crc = crc8_j1850(id_hi, 1, crc, false);
  crc = crc8_j1850(payload + 1, 7, crc, false);
  return static_cast<uint8_t>(crc ^ 0xFFu);
}

constexpr uint8_t e2e_counter(const uint8_t (&payload)[8]) noexcept {
  return static_cast<uint8_t>(payload[1] & 0x0Fu);
}

// Sender side: writes counter then CRC, then advances the counter 0..14.
class E2eProtector {
 public:
  explicit constexpr E2eProtector(uint16_t data_id) noexcept : data_id_(data_id) {}

  constexpr void protect(uint8_t (&payload)[8]) noexcept {
    payload[1] = static_cast<uint8_t>((payload[1] & 0xF0u) | counter_);
    payload[0] = e2e_crc(data_id_, payload);
    counter_ = static_cast<uint8_t>((counter_ + 1u) % kE2eCounterModulo);
  }

  constexpr uint8_t next_counter() const noexcept { return counter_; }
  constexpr uint16_t data_id() const noexcept { return data_id_; }
  constexpr void reset() noexcept { counter_ = 0; }

 private:
  uint16_t data_id_;
  uint8_t counter_ = 0;
};

enum class E2eStatus : uint8_t {
  Ok,             // CRC good, counter advanced by 1..max_delta (or first frame)
  Repeated,       // CRC good, same counter as the last accepted frame
  WrongSequence,  // CRC good, counter jumped by more than max_delta, or is 15
  WrongCrc,       // CRC (including the data ID) does not match
  NoNewData,      // no frame arrived in this check cycle
  Sync,           // CRC good, counter in sequence, but re-synchronising: not used yet
};

struct E2eCheckerConfig {
  // Largest accepted counter jump: 1 accepts only consecutive frames; 2
  // tolerates one lost frame; 14 rejects only exact repeats (event messages).
  uint8_t max_delta_counter = 2;
  // Profile 1's SyncCounterInit: after a counter jump (or a receive timeout)
  // this many in-sequence frames are checked but reported as Sync, not Ok;
  // the frame after them is Ok again. 0: a jump is never adopted (the
  // checker keeps its reference) and a timeout needs no re-synchronisation.
  uint8_t sync_counter_init = 1;
};

// Receiver side, AUTOSAR E2E Profile 1's check state machine
// (docs/can.md#e2e-checker). The stored counter changes only through
// commit(), which the caller invokes for frames that also passed its own
// checks (range, enum); evaluate() is const. Frames that fail the CRC, repeat
// the last counter or fail the caller's checks therefore never move the
// reference. A frame with a valid CRC whose counter jumped by more than
// max_delta is not used, but (sync_counter_init > 0) becomes the new
// reference; the next sync_counter_init in-sequence frames are reported as
// Sync and not used either, then frames are Ok again. After a receive
// timeout the receiver calls require_resync(): the reference is kept (a
// frozen sender's repeated frame stays Repeated) and the same number of
// in-sequence frames must pass before one is used.
class E2eChecker {
 public:
  struct Verdict {
    E2eStatus status;
    uint8_t counter;  // received counter
    uint8_t delta;    // counter jump versus the reference (0 when first or 15)
  };

  constexpr E2eChecker(uint16_t data_id, E2eCheckerConfig cfg = {}) noexcept
      : data_id_(data_id), cfg_(cfg) {}

  constexpr Verdict evaluate(const uint8_t (&payload)[8]) const noexcept {
    const uint8_t c = e2e_counter(payload);
    if (payload[0] != e2e_crc(data_id_, payload)) return {E2eStatus::WrongCrc, c, 0};
    if (c >= kE2eCounterModulo) return {E2eStatus::WrongSequence, c, 0};
    if (!synced_) return {E2eStatus::Ok, c, 0};
    const uint8_t delta = static_cast<uint8_t>((c + kE2eCounterModulo - last_) % kE2eCounterModulo);
    if (delta == 0) return {E2eStatus::Repeated, c, 0};
    if (delta > cfg_.max_delta_counter) return {E2eStatus::WrongSequence, c, delta};
    if (sync_left_ > 0) return {E2eStatus::Sync, c, delta};
    return {E2eStatus::Ok, c, delta};
  }

  // Records a frame the caller checked in full. Ok and Sync move the
  // reference; WrongSequence (valid CRC, counter 0..14) re-synchronises on
  // it when sync_counter_init > 0. Repeated, WrongCrc and NoNewData change
  // nothing, so calling commit() for them is harmless.
  constexpr void commit(const Verdict& v) noexcept {
    switch (v.status) {
      case E2eStatus::Ok:
      case E2eStatus::Sync:
        if (synced_ && v.delta > 1) lost_frames_ += static_cast<uint32_t>(v.delta - 1u);
        if (v.status == E2eStatus::Sync) --sync_left_;
        last_ = v.counter;
        synced_ = true;
        break;
      case E2eStatus::WrongSequence:
        if (!synced_ || v.counter >= kE2eCounterModulo || cfg_.sync_counter_init == 0) break;
        lost_frames_ += static_cast<uint32_t>(v.delta - 1u);
        last_ = v.counter;
        sync_left_ = cfg_.sync_counter_init;
        ++resyncs_;
        break;
      default: break;
    }
  }

  // evaluate + commit for receivers that have no further checks of their own.
  constexpr E2eStatus check(const uint8_t (&payload)[8]) noexcept {
    const Verdict v = evaluate(payload);
    commit(v);
    return v.status;
  }

  static constexpr E2eStatus no_new_data() noexcept { return E2eStatus::NoNewData; }

  // The receiver's deadline expired (docs/can.md#timeouts): keep the
  // reference and require sync_counter_init in-sequence frames again.
  constexpr void require_resync() noexcept {
    if (!synced_ || cfg_.sync_counter_init == 0) return;
    sync_left_ = cfg_.sync_counter_init;
    ++resyncs_;
  }

  // Forget the sender entirely (a new run): the next valid frame is Ok.
  constexpr void reset() noexcept {
    synced_ = false;
    last_ = 0;
    sync_left_ = 0;
  }

  constexpr bool synced() const noexcept { return synced_; }
  constexpr bool resynchronising() const noexcept { return sync_left_ > 0; }
  constexpr uint8_t last_counter() const noexcept { return last_; }
  // Frames the counter says were lost (gaps of accepted, synced and adopted frames).
  constexpr uint32_t lost_frames() const noexcept { return lost_frames_; }
  // Re-synchronisations started (counter jumps adopted, timeouts).
  constexpr uint32_t resyncs() const noexcept { return resyncs_; }
  constexpr uint16_t data_id() const noexcept { return data_id_; }
  constexpr const E2eCheckerConfig& config() const noexcept { return cfg_; }

 private:
  uint16_t data_id_;
  E2eCheckerConfig cfg_;
  uint8_t last_ = 0;
  uint8_t sync_left_ = 0;
  bool synced_ = false;
  uint32_t lost_frames_ = 0;
  uint32_t resyncs_ = 0;
};

inline const char* to_string(E2eStatus s) noexcept {
  switch (s) {
    case E2eStatus::Ok: return "OK";
    case E2eStatus::Repeated: return "REPEATED";
    case E2eStatus::WrongSequence: return "WRONG_SEQUENCE";
    case E2eStatus::WrongCrc: return "WRONG_CRC";
    case E2eStatus::NoNewData: return "NONEW_DATA";
    case E2eStatus::Sync: return "SYNC";
  }
  return "?";
}

}  // namespace cvt::can
