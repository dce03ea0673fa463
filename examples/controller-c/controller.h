/* A template CVT controller in C (examples/controller-c, docs/tutorial.md):
 * the clamping for a safety factor over the driver's demand, and a ratio
 * loop on the balance of the two pulleys' clamping forces. Every constant
 * of the plant (its torque capacity per newton, radii, actuator limit, the
 * thrust ratio at which the chain rests) is read from the plant's published
 * parameters on the bus (PlantParams, PlantRatioMap, PlantThrustMap), so a
 * new parameter set needs no change here; the constants below are the
 * controller's own tuning. Transport-agnostic: main.c feeds it the frames
 * of a SocketCAN socket. No heap, no libm. */
#ifndef CONTROLLER_H
#define CONTROLLER_H

#include <stdbool.h>
#include <stdint.h>

#include "cvtplant_c/can_messages.h"

/* ---- the controller's tuning ---- */
#define SAFETY_FACTOR 1.3f        /* torque capacity kept over max(|demand|, |transmitted|) */
#define CLAMP_MIN_N 12500.0f      /* each pulley's floor: the production CVT's (seats the chain, sets the shift speed) */
#define SLIP_LIMIT 0.08f          /* |slip| above this adds clamping */
#define SLIP_GAIN_N 5.0e4f        /* per unit of slip beyond the limit, per period */
#define EXTRA_DECAY 0.98f         /* of that extra clamping, per period */
#define EXTRA_MAX_N 20000.0f
#define RATIO_KP 3.0f             /* thrust ratio per unit of ratio error */
#define RATIO_KI 1.0f             /* ... and per unit of error and second */
#define RATIO_INTEGRAL_MAX 0.2f
#define SHIFT_RATE_PER_S 0.5f     /* the set-point is followed at most this fast */
#define THRUST_MIN 0.35f
#define THRUST_MAX 1.5f
#define PERIOD_S 0.01f            /* one control period: the CtrlCmd cycle */
#define CLAMP_NO_PARAMS_N 20000.0f /* before the plant's parameters are known */

typedef struct {
  /* what the plant published */
  bool have_params, have_maps;
  cvt_plant_params params;
  cvt_plant_ratio_map ratio_map;
  cvt_plant_thrust_map thrust_map;
  /* the latest plant group and the harness's demand */
  cvt_plant_speeds speeds;
  cvt_plant_ratio ratio;
  cvt_plant_forces forces;
  cvt_plant_shift shift;
  bool have_speeds, have_ratio, have_forces, have_shift;
  int last_used_tag;
  cvt_harness_demand demand;
  bool demand_pending;
  /* E2E */
  cvt_can_rx_bank rx;
  cvt_e2e_protector tx_cmd, tx_shift;
  /* the law's state */
  float extra_N, integral, ref;
  bool have_ref;
  /* counters, for the summary */
  uint32_t periods, fresh_periods, accepted, rejected, runs;
} controller;

void controller_init(controller* c);
/* One frame from the bus (data or error frame). */
void controller_receive(controller* c, const cvt_can_frame* f);
/* A complete plant group the last step did not use. */
bool controller_fresh_group(const controller* c);
/* One control period on the latest demand: writes the commands to send
 * (CtrlCmd, and CtrlShiftCmd when the harness asks for ratio control) into
 * out[] and returns how many. */
int controller_step(controller* c, cvt_can_frame out[2]);

#endif
