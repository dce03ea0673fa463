/* The C99 runtime of the generated CAN codec (docs/can.md#c-codec): the
 * frame, Intel bit fields, rounding, AUTOSAR E2E Profile 1 (CRC-8 SAE J1850,
 * alive counter, data ID), the E2E checker's state machine and the timeout
 * ramp. The same rules as the C++ runtime (lib/include/cvtplant/can/), so C
 * and C++ firmware encode and decode every frame identically; ctest
 * hil.c_codec_agreement checks it. No heap, no libm, no stdio; only memcpy-free
 * integer and float arithmetic (build with -ffp-contract=off). */
#ifndef CVTPLANT_C_CAN_H
#define CVTPLANT_C_CAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Classic CAN frame. Anything but a standard data frame (flags 0, 11-bit ID,
 * DLC <= 8) is refused by every decoder. */
enum { CVT_CAN_FRAME_EXTENDED_ID = 1u << 0, CVT_CAN_FRAME_REMOTE = 1u << 1, CVT_CAN_FRAME_ERROR = 1u << 2 };
typedef struct {
  uint32_t id;
  uint8_t dlc;
  uint8_t flags;
  uint8_t data[8];
} cvt_can_frame;

bool cvt_can_is_standard_data_frame(const cvt_can_frame* f);

/* docs/can.md#rejection: every reason distinct. */
typedef enum {
  CVT_CODEC_OK = 0,
  CVT_CODEC_NOT_DATA_FRAME, /* error, remote, extended-ID frame or DLC > 8 */
  CVT_CODEC_UNKNOWN_ID,
  CVT_CODEC_WRONG_DLC,
  CVT_CODEC_NOT_FINITE, /* NaN or +-inf (encode) */
  CVT_CODEC_OUT_OF_RANGE,
  CVT_CODEC_INVALID_ENUM
} cvt_codec_status;
const char* cvt_codec_status_name(cvt_codec_status s);

/* ---- bit fields and rounding (docs/can.md#rounding) ---- */
uint64_t cvt_can_load_le64(const uint8_t d[8]);
void cvt_can_store_le64(uint64_t w, uint8_t d[8]);
uint64_t cvt_can_get_unsigned(uint64_t word, unsigned start, unsigned len);
int64_t cvt_can_get_signed(uint64_t word, unsigned start, unsigned len);
uint64_t cvt_can_put(uint64_t word, unsigned start, unsigned len, uint64_t raw);
bool cvt_can_is_finite(float x);
/* Round half away from zero, |x| < 2^31 (range-checked by the caller). */
int32_t cvt_can_round_to_i32(float x);
/* v moved toward target by at most max_step (>= 0), never past it. */
float cvt_can_ramp_toward(float v, float target, float max_step);

/* ---- E2E Profile 1, DataIDMode BOTH (docs/can.md#e2e) ---- */
#define CVT_E2E_COUNTER_MODULO 15u
/* Crc_CalculateCRC8 semantics: first_call false continues from `start`. */
uint8_t cvt_crc8_j1850(const uint8_t* data, size_t len, uint8_t start, bool first_call);
/* CRC over the data ID's low byte, its high byte, payload bytes 1..7. */
uint8_t cvt_e2e_crc(uint16_t data_id, const uint8_t payload[8]);

typedef struct {
  uint16_t data_id;
  uint8_t counter; /* the next counter, 0..14 */
} cvt_e2e_protector;
void cvt_e2e_protector_init(cvt_e2e_protector* p, uint16_t data_id);
/* Writes counter and CRC, then advances the counter. */
void cvt_e2e_protect(cvt_e2e_protector* p, uint8_t payload[8]);

typedef enum {
  CVT_E2E_OK = 0,
  CVT_E2E_REPEATED,
  CVT_E2E_WRONG_SEQUENCE,
  CVT_E2E_WRONG_CRC,
  CVT_E2E_NO_NEW_DATA,
  CVT_E2E_SYNC
} cvt_e2e_status;
const char* cvt_e2e_status_name(cvt_e2e_status s);

/* The receiver's state machine (docs/can.md#e2e-checker): the reference
 * counter moves only in commit(), for a frame that also passed the value
 * checks; a valid jump becomes the reference and the next sync_init frames
 * are Sync (checked, not used). */
typedef struct {
  uint16_t data_id;
  uint8_t max_delta;
  uint8_t sync_init;
  uint8_t last;
  uint8_t sync_left;
  bool synced;
  uint32_t lost_frames;
  uint32_t resyncs;
} cvt_e2e_checker;
typedef struct {
  cvt_e2e_status status;
  uint8_t counter;
  uint8_t delta;
} cvt_e2e_verdict;
void cvt_e2e_checker_init(cvt_e2e_checker* c, uint16_t data_id, uint8_t max_delta, uint8_t sync_init);
cvt_e2e_verdict cvt_e2e_evaluate(const cvt_e2e_checker* c, const uint8_t payload[8]);
void cvt_e2e_commit(cvt_e2e_checker* c, cvt_e2e_verdict v);
/* The receive deadline expired: keep the reference, re-synchronise. */
void cvt_e2e_require_resync(cvt_e2e_checker* c);
/* A new run: forget the sender. */
void cvt_e2e_reset(cvt_e2e_checker* c);

/* Outcome of a receive: accepted when codec OK and E2E OK. e2e is
 * NO_NEW_DATA when the frame was refused before E2E ran (kind, ID, DLC). */
typedef struct {
  cvt_codec_status codec;
  cvt_e2e_status e2e;
} cvt_rx_result;
bool cvt_rx_accepted(cvt_rx_result r);

#ifdef __cplusplus
}
#endif

#endif /* CVTPLANT_C_CAN_H */
