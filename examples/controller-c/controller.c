/* The template controller's law and CAN application (controller.h). */
#include "controller.h"

static float absf(float v) { return v < 0.0f ? -v : v; }
static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

void controller_init(controller* c) {
  *c = (controller){0};
  cvt_can_rx_bank_init(&c->rx);
  cvt_ctrl_cmd_protector_init(&c->tx_cmd);
  cvt_ctrl_shift_cmd_protector_init(&c->tx_shift);
  c->last_used_tag = -1;
}

/* The harness reset the plant (its answer: Ready at sim time 0): a new run,
 * the law starts from rest and the harness's counter may start anywhere. */
static void new_run(controller* c) {
  c->extra_N = 0.0f;
  c->integral = 0.0f;
  c->have_ref = false;
  c->demand_pending = false;
  cvt_can_rx_bank_reset(&c->rx, CVT_MSG_HARNESS_DEMAND);
  ++c->runs;
}

void controller_receive(controller* c, const cvt_can_frame* f) {
  /* Only the plant's and the harness's messages are inputs; own commands
   * and frames of other nodes are not checked here. */
  const int i = cvt_can_find_message(f->id);
  if (i < 0 || f->id == CVT_CTRL_CMD_ID || f->id == CVT_CTRL_SHIFT_CMD_ID || f->id == CVT_SIM_CTRL_ID ||
      f->id == CVT_HARNESS_LOAD_ID)
    return;
  cvt_can_any a;
  const cvt_rx_result r = cvt_can_rx_bank_receive(&c->rx, f, &a);
  if (!cvt_rx_accepted(r)) {
    if (!(r.e2e == CVT_E2E_SYNC && r.codec == CVT_CODEC_OK)) ++c->rejected;
    return;
  }
  ++c->accepted;
  switch (a.which) {
    case CVT_MSG_PLANT_SPEEDS:
      c->speeds = a.u.plant_speeds;
      c->have_speeds = true;
      if (c->speeds.sample_tag != c->last_used_tag) c->last_used_tag = -1; /* a newer sample is in */
      break;
    case CVT_MSG_PLANT_RATIO: c->ratio = a.u.plant_ratio; c->have_ratio = true; break;
    case CVT_MSG_PLANT_FORCES: c->forces = a.u.plant_forces; c->have_forces = true; break;
    case CVT_MSG_PLANT_SHIFT: c->shift = a.u.plant_shift; c->have_shift = true; break;
    case CVT_MSG_PLANT_PARAMS: c->params = a.u.plant_params; c->have_params = true; break;
    case CVT_MSG_PLANT_RATIO_MAP: c->ratio_map = a.u.plant_ratio_map; break;
    case CVT_MSG_PLANT_THRUST_MAP: c->thrust_map = a.u.plant_thrust_map; c->have_maps = true; break;
    case CVT_MSG_HARNESS_DEMAND:
      c->demand = a.u.harness_demand;
      c->demand_pending = true;
      break;
    case CVT_MSG_PLANT_STATUS:
      if (a.u.plant_status.plant_mode == CVT_PLANT_MODE_READY && a.u.plant_status.sim_time_us == 0) new_run(c);
      break;
    default: break;
  }
}

bool controller_fresh_group(const controller* c) {
  return c->have_speeds && c->have_ratio && c->have_forces && c->speeds.sample_tag == c->ratio.sample_tag &&
         c->speeds.sample_tag == c->forces.sample_tag && c->speeds.sample_tag != c->last_used_tag;
}

/* The thrust ratio F1/F2 at which the chain rests at ratio r: the plant's
 * three points, linear between them, held beyond them. */
static float thrust_at(const controller* c, float r) {
  const float x[3] = {c->ratio_map.ratio_overdrive_stop, c->ratio_map.ratio_setup, c->ratio_map.ratio_underdrive_stop};
  const float k[3] = {c->thrust_map.thrust_ratio_overdrive_stop, c->thrust_map.thrust_ratio_setup,
                      c->thrust_map.thrust_ratio_underdrive_stop};
  if (r <= x[0]) return k[0];
  if (r >= x[2]) return k[2];
  const int i = r <= x[1] ? 0 : 1;
  return k[i] + (k[i + 1] - k[i]) * (r - x[i]) / (x[i + 1] - x[i]);
}

int controller_step(controller* c, cvt_can_frame out[2]) {
  const cvt_harness_demand* d = &c->demand;
  const bool ratio_control = d->ratio_control && c->have_maps;
  const bool valid = controller_fresh_group(c) && (!ratio_control || (c->have_shift && c->shift.sample_tag == c->speeds.sample_tag));
  c->demand_pending = false;
  ++c->periods;
  if (valid) {
    ++c->fresh_periods;
    c->last_used_tag = c->speeds.sample_tag;
  }
  float f1 = CLAMP_NO_PARAMS_N, f2 = CLAMP_NO_PARAMS_N;
  if (c->have_params) {
    /* Clamping for the torque: capacity = coeff F1 r1 (PlantParams). */
    const float clamp_max = c->params.clamp_max_N;
    float tau = absf(d->driver_demand_Nm);
    float r1 = c->params.radius_driver_m;
    if (valid) {
      const float excess = absf(c->ratio.slip) - SLIP_LIMIT;
      c->extra_N = clampf(c->extra_N * EXTRA_DECAY + (excess > 0.0f ? SLIP_GAIN_N * excess : 0.0f), 0.0f, EXTRA_MAX_N);
      if (absf(c->speeds.torque_transmitted_Nm) > tau) tau = absf(c->speeds.torque_transmitted_Nm);
      if (ratio_control) r1 = clampf(c->shift.radius_driver_m, 0.02f, 0.2f);
    }
    f1 = clampf(SAFETY_FACTOR * tau / (c->params.capacity_coeff * r1) + c->extra_N, CLAMP_MIN_N, clamp_max);
    f2 = f1;
    if (ratio_control) {
      /* The ratio: a reference moving toward the set-point at a bounded
       * speed, the thrust ratio at rest there, and a PI correction. */
      const float step = SHIFT_RATE_PER_S * PERIOD_S;
      c->ref = c->have_ref ? c->ref + clampf(d->ratio_target - c->ref, -step, step) : d->ratio_target;
      c->have_ref = true;
      float e = 0.0f;
      if (valid) {
        e = c->ratio.geometric_ratio - c->ref;
        const bool on_stop = c->shift.end_stop_underdrive || c->shift.end_stop_overdrive;
        if (c->ref == d->ratio_target && !on_stop)
          c->integral = clampf(c->integral + RATIO_KI * e * PERIOD_S, -RATIO_INTEGRAL_MAX, RATIO_INTEGRAL_MAX);
      }
      const float k = clampf(thrust_at(c, c->ref) + RATIO_KP * e + c->integral, THRUST_MIN, THRUST_MAX);
      /* The smaller clamping at the floor, the other raised to shift: in
       * overdrive (k > 1) the driven one is the smaller. */
      if (f1 < CLAMP_MIN_N * k) f1 = clampf(CLAMP_MIN_N * k, CLAMP_MIN_N, clamp_max);
      f2 = clampf(f1 / k, CLAMP_MIN_N, clamp_max);
    }
  }
  int n = 0;
  cvt_ctrl_cmd cmd;
  cvt_ctrl_cmd_init(&cmd);
  cmd.demand_tag = d->demand_tag;
  cmd.clamp_force_cmd_N = f1;
  cmd.driver_torque_req_Nm = clampf(d->driver_demand_Nm, -600.0f, 600.0f);
  if (cvt_ctrl_cmd_encode(&cmd, &c->tx_cmd, &out[n]) == CVT_CODEC_OK) ++n;
  if (d->ratio_control) {
    cvt_ctrl_shift_cmd sh;
    cvt_ctrl_shift_cmd_init(&sh);
    sh.demand_tag = d->demand_tag;
    sh.driven_clamp_force_cmd_N = f2;
    sh.ratio_target = clampf(d->ratio_target, 0.0f, 6.5f);
    if (cvt_ctrl_shift_cmd_encode(&sh, &c->tx_shift, &out[n]) == CVT_CODEC_OK) ++n;
  }
  return n;
}
