// Classic CAN frame as the core sees it: no heap, no OS types, so the codec,
// the E2E layer and the port layer share one representation on every target.
#pragma once

#include <cstdint>

namespace cvt::can {

inline constexpr uint8_t kMaxClassicDlc = 8;
inline constexpr uint32_t kStdIdMask = 0x7FFu;
inline constexpr uint32_t kExtIdMask = 0x1FFFFFFFu;

// Frame kind bits. Anything but a plain standard data frame is refused by the
// message decoder (docs/can.md#rejection), so an error frame or a remote
// request can never be decoded as data even if a transport hands one up.
enum CanFrameFlag : uint8_t {
  kFrameExtendedId = 1u << 0,
  kFrameRemote = 1u << 1,
  kFrameError = 1u << 2,
};

struct CanFrame {
  uint32_t id = 0;     // 11-bit (or 29-bit with kFrameExtendedId); error class for kFrameError
  uint8_t dlc = 0;     // 0..8 (classic CAN only)
  uint8_t flags = 0;   // CanFrameFlag bits
  uint8_t data[kMaxClassicDlc] = {};
};

constexpr bool is_standard_data_frame(const CanFrame& f) noexcept {
  return f.flags == 0 && f.id <= kStdIdMask && f.dlc <= kMaxClassicDlc;
}

}  // namespace cvt::can
