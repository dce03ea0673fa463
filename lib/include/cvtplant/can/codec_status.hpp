// Result of packing or unpacking one message (docs/can.md#rejection). Every
// rejection reason is distinct so a receiver can count them separately.
#pragma once

#include <cstdint>

namespace cvt::can {

enum class CodecStatus : uint8_t {
  Ok,
  NotDataFrame,  // error frame, remote frame, extended ID or DLC > 8
  UnknownId,     // no message with this ID in the DBC
  WrongDlc,      // DLC differs from the DBC length
  NotFinite,     // NaN or +-inf physical value (encode side)
  OutOfRange,    // physical value outside the DBC [min|max]
  InvalidEnum,   // value not in the DBC's VAL_ table
};

constexpr const char* to_string(CodecStatus s) noexcept {
  switch (s) {
    case CodecStatus::Ok: return "OK";
    case CodecStatus::NotDataFrame: return "NOT_DATA_FRAME";
    case CodecStatus::UnknownId: return "UNKNOWN_ID";
    case CodecStatus::WrongDlc: return "WRONG_DLC";
    case CodecStatus::NotFinite: return "NOT_FINITE";
    case CodecStatus::OutOfRange: return "OUT_OF_RANGE";
    case CodecStatus::InvalidEnum: return "INVALID_ENUM";
  }
  return "?";
}

}  // namespace cvt::can
