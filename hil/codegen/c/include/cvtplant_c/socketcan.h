/* SocketCAN for C programs (docs/can.md#c-codec): the POSIX port's
 * transport (port/posix, docs/can.md#port) behind a C API on the C codec's
 * frame. Classic CAN only; error frames come back as CVT_CAN_IO_ERROR_FRAME
 * and update the bus state, never as data; ENOBUFS is retried with a bound
 * and counted; kernel receive-queue drops are counted. Linux hosts only. */
#ifndef CVTPLANT_C_SOCKETCAN_H
#define CVTPLANT_C_SOCKETCAN_H

#include <stdint.h>

#include "cvtplant_c/can.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  CVT_CAN_IO_OK = 0,        /* a data frame sent or received */
  CVT_CAN_IO_ERROR_FRAME,   /* an error frame received (flags CVT_CAN_FRAME_ERROR, id = error class) */
  CVT_CAN_IO_TIMEOUT,       /* nothing before the deadline (0 = poll) */
  CVT_CAN_IO_DROPPED,       /* send gave up after the bounded ENOBUFS retries */
  CVT_CAN_IO_INVALID_FRAME, /* refused locally (DLC > 8, FD, bad ID, flags) */
  CVT_CAN_IO_BUS_OFF,       /* the controller is bus-off */
  CVT_CAN_IO_ERROR          /* any other OS error: cvt_socketcan_error() */
} cvt_can_io_status;

typedef enum {
  CVT_CAN_BUS_ERROR_ACTIVE = 0,
  CVT_CAN_BUS_ERROR_WARNING,
  CVT_CAN_BUS_ERROR_PASSIVE,
  CVT_CAN_BUS_OFF
} cvt_can_bus_state;

typedef struct {
  uint64_t tx_frames, rx_frames, tx_enobufs_retries, tx_dropped, tx_invalid;
  uint64_t rx_error_frames, rx_invalid, rx_kernel_drops, bus_off_events;
} cvt_can_io_counters;

/* An open raw CAN socket. Opaque storage: no heap. */
typedef struct cvt_socketcan {
  union {
    unsigned char bytes[320];
    int64_t align_;
    void* align_p_;
  } opaque;
} cvt_socketcan;

/* Opens and binds `ifname` (vcan0, can0). 0, or the errno of the failing
 * step; cvt_socketcan_error() names the step, e.g. "socket(AF_CAN): Address
 * family not supported by protocol" on a kernel without SocketCAN. */
int cvt_socketcan_open(cvt_socketcan* s, const char* ifname);
/* After cvt_socketcan_open (whatever it returned). */
void cvt_socketcan_close(cvt_socketcan* s);
const char* cvt_socketcan_error(const cvt_socketcan* s);
cvt_can_io_status cvt_socketcan_send(cvt_socketcan* s, const cvt_can_frame* f);
/* Waits up to timeout_ns (0: poll) for the next frame. */
cvt_can_io_status cvt_socketcan_receive(cvt_socketcan* s, cvt_can_frame* out, int64_t timeout_ns);
cvt_can_io_counters cvt_socketcan_counters(const cvt_socketcan* s);
cvt_can_bus_state cvt_socketcan_bus_state(const cvt_socketcan* s);
const char* cvt_can_io_status_name(cvt_can_io_status st);

#ifdef __cplusplus
}
#endif

#endif /* CVTPLANT_C_SOCKETCAN_H */
