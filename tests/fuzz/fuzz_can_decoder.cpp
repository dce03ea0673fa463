// libFuzzer target for the CAN frame decoder (docs/can.md#fuzzing).
// Input: a sequence of 12-byte records {id_lo, id_hi, dlc|flags, pad, data[8]}
// fed through one RxBank (so E2E state carries across frames) and through
// decode_any. Properties checked on every frame, beyond "no crash, no
// sanitizer report":
//  - a frame that is accepted re-packs to the same signal bits (unpack and
//    pack are inverse on valid payloads; unused bits aside);
//  - a rejected frame changes the receiver's stored E2E counter only when it
//    passed the CRC and value checks and is Sync or an adopted
//    WrongSequence (re-synchronisation, docs/can.md#e2e-checker);
//  - non-data frames (error/remote/extended/DLC > 8) are never accepted.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "cvtplant/can/messages.hpp"

using namespace cvt::can;

namespace {

[[noreturn]] void violated() { __builtin_trap(); }

template <class Msg>
void check_repack(const Msg& m, const uint8_t (&payload)[8]) {
  uint8_t again[8];
  if (pack(m, again) != CodecStatus::Ok) violated();
  if ((bits::load_le64(payload) & Msg::kSignalMask) != bits::load_le64(again)) violated();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* in, size_t n) {
  RxBank bank;
  AnyMessage any;
  for (size_t off = 0; off + 12 <= n; off += 12) {
    const uint8_t* r = in + off;
    CanFrame f;
    f.id = static_cast<uint32_t>(r[0] | (r[1] << 8));
    f.dlc = static_cast<uint8_t>(r[2] & 0x0F);
    f.flags = static_cast<uint8_t>((r[2] >> 4) & 0x07);
    if (r[2] & 0x80) f.id |= static_cast<uint32_t>(r[3]) << 16;
    std::memcpy(f.data, r + 4, 8);

    const int idx = find_message(f.id);
    const E2eChecker* chk = idx >= 0 ? &bank.checker(static_cast<MessageId>(idx)) : nullptr;
    const bool was_synced = chk && chk->synced();
    const uint8_t before = chk ? chk->last_counter() : 0;

    const RxResult res = bank.receive(f, any);
    if (res.accepted()) {
      if (!is_standard_data_frame(f) || f.dlc != 8) violated();
      visit_any(any, [&](const auto& m) { check_repack(m, f.data); });
    } else if (chk && (chk->synced() != was_synced || chk->last_counter() != before)) {
      const bool resync = res.codec == CodecStatus::Ok &&
                          (res.e2e == E2eStatus::Sync || res.e2e == E2eStatus::WrongSequence) && was_synced;
      if (!resync) violated();
    }
    AnyMessage scratch;
    const CodecStatus st = decode_any(f, scratch);
    if (st == CodecStatus::Ok && !is_standard_data_frame(f)) violated();
  }
  return 0;
}
