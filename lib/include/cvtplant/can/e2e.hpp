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
};

struct E2eCheckerConfig {
  // Largest accepted counter jump: 1 accepts only consecutive frames; 2
  // tolerates one lost frame; 14 rejects only exact repeats (event messages).
  uint8_t max_delta_counter = 2;
};

// Receiver side. The stored counter changes only through commit(), which the
// caller invokes for frames it actually applies; evaluate() is const. A
// rejected frame therefore can never move the reference a later stale frame
// is compared against (docs/can.md#e2e-checker). After WrongSequence the
// checker stays on the last good counter until reset(), which the receiver
// calls on its deadline-monitoring timeout (docs/can.md#timeouts).
class E2eChecker {
 public:
  struct Verdict {
    E2eStatus status;
    uint8_t counter;  // received counter
    uint8_t delta;    // counter jump versus the last accepted frame (0 when first)
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
    return {E2eStatus::Ok, c, delta};
  }

  // Accept a frame evaluated as Ok. Any other verdict is ignored, so calling
  // commit() unconditionally is still safe.
  constexpr void commit(const Verdict& v) noexcept {
    if (v.status != E2eStatus::Ok) return;
    if (synced_ && v.delta > 1) lost_frames_ += static_cast<uint32_t>(v.delta - 1u);
    last_ = v.counter;
    synced_ = true;
  }

  // evaluate + commit for receivers that have no further checks of their own.
  constexpr E2eStatus check(const uint8_t (&payload)[8]) noexcept {
    const Verdict v = evaluate(payload);
    commit(v);
    return v.status;
  }

  static constexpr E2eStatus no_new_data() noexcept { return E2eStatus::NoNewData; }

  constexpr void reset() noexcept {
    synced_ = false;
    last_ = 0;
  }

  constexpr bool synced() const noexcept { return synced_; }
  constexpr uint8_t last_counter() const noexcept { return last_; }
  constexpr uint32_t lost_frames() const noexcept { return lost_frames_; }
  constexpr uint16_t data_id() const noexcept { return data_id_; }

 private:
  uint16_t data_id_;
  E2eCheckerConfig cfg_;
  uint8_t last_ = 0;
  bool synced_ = false;
  uint32_t lost_frames_ = 0;
};

inline const char* to_string(E2eStatus s) noexcept {
  switch (s) {
    case E2eStatus::Ok: return "OK";
    case E2eStatus::Repeated: return "REPEATED";
    case E2eStatus::WrongSequence: return "WRONG_SEQUENCE";
    case E2eStatus::WrongCrc: return "WRONG_CRC";
    case E2eStatus::NoNewData: return "NONEW_DATA";
  }
  return "?";
}

}  // namespace cvt::can
