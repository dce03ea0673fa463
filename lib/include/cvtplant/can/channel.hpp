// Per-message transmit and receive pipelines on top of the generated
// pack()/unpack() (messages.hpp) and the E2E layer (e2e.hpp).
//
// Receive order (docs/can.md#rejection): frame kind -> ID -> DLC -> E2E
// (CRC, then counter) -> physical range / enum checks -> commit. The E2E
// counter is committed and the output written only when every stage passed,
// so a frame rejected at any stage leaves the receiver exactly as it was.
#pragma once

#include "cvtplant/can/codec_status.hpp"
#include "cvtplant/can/e2e.hpp"
#include "cvtplant/can/frame.hpp"

namespace cvt::can {

struct RxResult {
  CodecStatus codec = CodecStatus::Ok;
  // NoNewData when the frame was refused before E2E ran (kind, ID or DLC).
  E2eStatus e2e = E2eStatus::NoNewData;
  constexpr bool accepted() const noexcept {
    return codec == CodecStatus::Ok && e2e == E2eStatus::Ok;
  }
};

template <class Msg>
constexpr CodecStatus check_frame_shape(const CanFrame& f) noexcept {
  if (!is_standard_data_frame(f)) return CodecStatus::NotDataFrame;
  if (f.id != Msg::kId) return CodecStatus::UnknownId;
  if (f.dlc != Msg::kDlc) return CodecStatus::WrongDlc;
  return CodecStatus::Ok;
}

// Pack and protect. On a pack error nothing is written and the sender's
// counter does not advance, so the receiver sees no gap for a frame that was
// never sent.
template <class Msg>
CodecStatus encode(const Msg& m, E2eProtector& protector, CanFrame& out) noexcept {
  CanFrame f;
  f.id = Msg::kId;
  f.dlc = Msg::kDlc;
  const CodecStatus st = pack(m, f.data);
  if (st != CodecStatus::Ok) return st;
  protector.protect(f.data);
  out = f;
  return CodecStatus::Ok;
}

template <class Msg>
RxResult receive(const CanFrame& f, E2eChecker& checker, Msg& out) noexcept {
  RxResult r;
  r.codec = check_frame_shape<Msg>(f);
  if (r.codec != CodecStatus::Ok) return r;
  const E2eChecker::Verdict v = checker.evaluate(f.data);
  r.e2e = v.status;
  if (v.status != E2eStatus::Ok) return r;
  Msg tmp;
  r.codec = unpack(f.data, tmp);
  if (r.codec != CodecStatus::Ok) return r;
  checker.commit(v);
  out = tmp;
  return r;
}

template <class Msg>
class TxChannel {
 public:
  CodecStatus encode(const Msg& m, CanFrame& out) noexcept {
    return cvt::can::encode(m, protector_, out);
  }
  void reset() noexcept { protector_.reset(); }
  const E2eProtector& protector() const noexcept { return protector_; }

 private:
  E2eProtector protector_{Msg::kE2eDataId};
};

template <class Msg>
class RxChannel {
 public:
  RxResult receive(const CanFrame& f, Msg& out) noexcept {
    return cvt::can::receive(f, checker_, out);
  }
  // Call on the deadline-monitoring timeout (docs/can.md#timeouts).
  void reset() noexcept { checker_.reset(); }
  const E2eChecker& checker() const noexcept { return checker_; }

 private:
  E2eChecker checker_{Msg::kE2eDataId, E2eCheckerConfig{Msg::kE2eMaxDeltaCounter}};
};

}  // namespace cvt::can
