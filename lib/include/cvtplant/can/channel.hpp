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

// `out` is written only for an accepted frame (codec Ok, E2E Ok). A frame
// with a valid CRC that is Sync or WrongSequence is value-checked too and, if
// its values are valid, recorded by the checker (it re-synchronises on it),
// but never written to `out` (docs/can.md#e2e-checker).
template <class Msg>
RxResult receive(const CanFrame& f, E2eChecker& checker, Msg& out) noexcept {
  RxResult r;
  r.codec = check_frame_shape<Msg>(f);
  if (r.codec != CodecStatus::Ok) return r;
  const E2eChecker::Verdict v = checker.evaluate(f.data);
  r.e2e = v.status;
  if (v.status != E2eStatus::Ok && v.status != E2eStatus::Sync && v.status != E2eStatus::WrongSequence) return r;
  Msg tmp;
  r.codec = unpack(f.data, tmp);
  if (r.codec != CodecStatus::Ok) return r;
  checker.commit(v);
  if (v.status == E2eStatus::Ok) out = tmp;
  return r;
}

// The substitute of a Ramp timeout action (docs/can.md#timeouts): `v` moved
// toward `target` by at most `max_step` (>= 0), never past it.
constexpr float ramp_toward(float v, float target, float max_step) noexcept {
  if (v < target) return target - v > max_step ? v + max_step : target;
  if (v > target) return v - target > max_step ? v - max_step : target;
  return v;
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
  void require_resync() noexcept { checker_.require_resync(); }
  // A new run: forget the sender.
  void reset() noexcept { checker_.reset(); }
  const E2eChecker& checker() const noexcept { return checker_; }

 private:
  E2eChecker checker_{Msg::kE2eDataId, E2eCheckerConfig{Msg::kE2eMaxDeltaCounter, Msg::kE2eSyncCounterInit}};
};

}  // namespace cvt::can
