/* The C99 codec runtime (docs/can.md#c-codec); the same rules as
 * lib/include/cvtplant/can/{frame,bits,e2e,channel}.hpp. */
#include "cvtplant_c/can.h"

bool cvt_can_is_standard_data_frame(const cvt_can_frame* f) {
  return f->flags == 0 && f->id <= 0x7FFu && f->dlc <= 8u;
}

const char* cvt_codec_status_name(cvt_codec_status s) {
  switch (s) {
    case CVT_CODEC_OK: return "OK";
    case CVT_CODEC_NOT_DATA_FRAME: return "NOT_DATA_FRAME";
    case CVT_CODEC_UNKNOWN_ID: return "UNKNOWN_ID";
    case CVT_CODEC_WRONG_DLC: return "WRONG_DLC";
    case CVT_CODEC_NOT_FINITE: return "NOT_FINITE";
    case CVT_CODEC_OUT_OF_RANGE: return "OUT_OF_RANGE";
    case CVT_CODEC_INVALID_ENUM: return "INVALID_ENUM";
  }
  return "?";
}

uint64_t cvt_can_load_le64(const uint8_t d[8]) {
  uint64_t w = 0;
  for (int i = 7; i >= 0; --i) w = (w << 8) | d[i];
  return w;
}

void cvt_can_store_le64(uint64_t w, uint8_t d[8]) {
  for (int i = 0; i < 8; ++i) {
    d[i] = (uint8_t)(w & 0xFFu);
    w >>= 8;
  }
}

static uint64_t mask(unsigned len) { return len >= 64 ? ~(uint64_t)0 : (((uint64_t)1 << len) - 1u); }

uint64_t cvt_can_get_unsigned(uint64_t word, unsigned start, unsigned len) { return (word >> start) & mask(len); }

int64_t cvt_can_get_signed(uint64_t word, unsigned start, unsigned len) {
  const uint64_t u = cvt_can_get_unsigned(word, start, len);
  const uint64_t sign = (uint64_t)1 << (len - 1u);
  /* Two's complement without implementation-defined shifts of negatives. */
  return (u & sign) ? (int64_t)(u | ~mask(len)) : (int64_t)u;
}

uint64_t cvt_can_put(uint64_t word, unsigned start, unsigned len, uint64_t raw) {
  const uint64_t m = mask(len) << start;
  return (word & ~m) | ((raw << start) & m);
}

/* Comparisons only: no libm, and NaN fails both. */
bool cvt_can_is_finite(float x) { return x >= -3.40282347e38f && x <= 3.40282347e38f; }

int32_t cvt_can_round_to_i32(float x) {
  const int32_t t = (int32_t)x; /* toward zero, exact in range */
  const float frac = x - (float)t;
  if (frac >= 0.5f) return t + 1;
  if (frac <= -0.5f) return t - 1;
  return t;
}

float cvt_can_ramp_toward(float v, float target, float max_step) {
  if (v < target) return target - v > max_step ? v + max_step : target;
  if (v > target) return v - target > max_step ? v - max_step : target;
  return v;
}

uint8_t cvt_crc8_j1850(const uint8_t* data, size_t len, uint8_t start, bool first_call) {
  uint8_t reg = first_call ? (uint8_t)0xFF : (uint8_t)(start ^ 0xFFu);
  for (size_t i = 0; i < len; ++i) {
    reg = (uint8_t)(reg ^ data[i]);
    for (int b = 0; b < 8; ++b) reg = (reg & 0x80u) ? (uint8_t)((reg << 1) ^ 0x1Du) : (uint8_t)(reg << 1);
  }
  return (uint8_t)(reg ^ 0xFFu);
}

uint8_t cvt_e2e_crc(uint16_t data_id, const uint8_t payload[8]) {
  const uint8_t id_lo = (uint8_t)(data_id & 0xFFu);
  const uint8_t id_hi = (uint8_t)(data_id >> 8);
  uint8_t crc = cvt_crc8_j1850(&id_lo, 1, 0xFF, false);
  crc = cvt_crc8_j1850(&id_hi, 1, crc, false);
  crc = cvt_crc8_j1850(payload + 1, 7, crc, false);
  return (uint8_t)(crc ^ 0xFFu);
}

void cvt_e2e_protector_init(cvt_e2e_protector* p, uint16_t data_id) {
  p->data_id = data_id;
  p->counter = 0;
}

void cvt_e2e_protect(cvt_e2e_protector* p, uint8_t payload[8]) {
  payload[1] = (uint8_t)((payload[1] & 0xF0u) | p->counter);
  payload[0] = cvt_e2e_crc(p->data_id, payload);
  p->counter = (uint8_t)((p->counter + 1u) % CVT_E2E_COUNTER_MODULO);
}

const char* cvt_e2e_status_name(cvt_e2e_status s) {
  switch (s) {
    case CVT_E2E_OK: return "OK";
    case CVT_E2E_REPEATED: return "REPEATED";
    case CVT_E2E_WRONG_SEQUENCE: return "WRONG_SEQUENCE";
    case CVT_E2E_WRONG_CRC: return "WRONG_CRC";
    case CVT_E2E_NO_NEW_DATA: return "NONEW_DATA";
    case CVT_E2E_SYNC: return "SYNC";
  }
  return "?";
}

void cvt_e2e_checker_init(cvt_e2e_checker* c, uint16_t data_id, uint8_t max_delta, uint8_t sync_init) {
  c->data_id = data_id;
  c->max_delta = max_delta;
  c->sync_init = sync_init;
  c->last = 0;
  c->sync_left = 0;
  c->synced = false;
  c->lost_frames = 0;
  c->resyncs = 0;
}

cvt_e2e_verdict cvt_e2e_evaluate(const cvt_e2e_checker* c, const uint8_t payload[8]) {
  cvt_e2e_verdict v;
  v.counter = (uint8_t)(payload[1] & 0x0Fu);
  v.delta = 0;
  if (payload[0] != cvt_e2e_crc(c->data_id, payload)) {
    v.status = CVT_E2E_WRONG_CRC;
    return v;
  }
  if (v.counter >= CVT_E2E_COUNTER_MODULO) {
    v.status = CVT_E2E_WRONG_SEQUENCE;
    return v;
  }
  if (!c->synced) {
    v.status = CVT_E2E_OK;
    return v;
  }
  const uint8_t delta = (uint8_t)((v.counter + CVT_E2E_COUNTER_MODULO - c->last) % CVT_E2E_COUNTER_MODULO);
  if (delta == 0) {
    v.status = CVT_E2E_REPEATED;
    return v;
  }
  v.delta = delta;
  if (delta > c->max_delta) v.status = CVT_E2E_WRONG_SEQUENCE;
  else v.status = c->sync_left > 0 ? CVT_E2E_SYNC : CVT_E2E_OK;
  return v;
}

void cvt_e2e_commit(cvt_e2e_checker* c, cvt_e2e_verdict v) {
  switch (v.status) {
    case CVT_E2E_OK:
    case CVT_E2E_SYNC:
      if (c->synced && v.delta > 1) c->lost_frames += (uint32_t)(v.delta - 1u);
      if (v.status == CVT_E2E_SYNC) --c->sync_left;
      c->last = v.counter;
      c->synced = true;
      break;
    case CVT_E2E_WRONG_SEQUENCE:
      if (!c->synced || v.counter >= CVT_E2E_COUNTER_MODULO || c->sync_init == 0) break;
      c->lost_frames += (uint32_t)(v.delta - 1u);
      c->last = v.counter;
      c->sync_left = c->sync_init;
      ++c->resyncs;
      break;
    default: break;
  }
}

void cvt_e2e_require_resync(cvt_e2e_checker* c) {
  if (!c->synced || c->sync_init == 0) return;
  c->sync_left = c->sync_init;
  ++c->resyncs;
}

void cvt_e2e_reset(cvt_e2e_checker* c) {
  c->synced = false;
  c->last = 0;
  c->sync_left = 0;
}

bool cvt_rx_accepted(cvt_rx_result r) { return r.codec == CVT_CODEC_OK && r.e2e == CVT_E2E_OK; }
