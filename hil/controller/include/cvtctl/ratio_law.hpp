// Ratio control law of the example controller (docs/sil.md#ratio-control):
// tracks a geometric ratio set-point (driven / driver running radius) by the
// balance of the driver (primary) and driven (secondary) clamping forces,
// with the clamping level kept at a safety factor over the transmitted torque
// and raised on detected slip. Heap-free, float only, no libm call (ctest
// hil.sil_controller_cortex_m4 compiles it for Cortex-M4F).
//
// Physics (docs/sil.md#ratio-control derives it from docs/rom.md#wedging):
//   the chain is in radial equilibrium when F1 / F2 = kappa(ratio), the ratio
//   of the wrap angles theta1 / theta2; a larger F1 / F2 pushes the chain out
//   on the driver (upshift, the ratio falls), a smaller one pulls it in.
//   The belt carries tau_cap = 2 mu0 F1 r1 / cos(beta) on the driver, whose
//   running radius r1 now varies with the ratio.
// The set-point is followed through a reference that moves at most
// shift_rate_max: a faster shift swings the engine and wheel inertias
// against each other through the chain (the transmitted torque reverses and
// the strands ring), which the slip signal shows as a stretch rate beyond the
// slip protection's limit.
// Law per 10 ms period, ref = rate-limited set-point, e = ratio - ref:
//   F1 = safety * tau_ref cos(beta) / (2 mu0 r1) + slip extra    (clamping level)
//   k  = kappa_map(ref) - (d ref/dt) / g + kp e + ki sum(e dt)    (thrust ratio)
//   F2 = F1 / k                                                   (balance)
// g is the chain's shift speed per unit of thrust-ratio imbalance, so the
// feed-forward term asks for the reference's speed; the integral runs only
// while the reference rests, so a ramp's lag does not wind it up into an
// overshoot at the end of the shift, and not while the chain is on an end
// stop, where a set-point beyond the travel would wind it up against the
// stop and hold the chain short of the other stop afterwards.
#pragma once

#include "cvtctl/clamp_law.hpp"

namespace cvtctl {

// The thrust ratio kappa = theta1 / theta2 at five geometric ratios, from the
// transmission's geometry (pitch radii 76.2 / 114.3 mm at set-up, centre
// distance 0.5 m, chain length held): the ECU's calibration map, linear
// between the points, held beyond them.
struct ThrustMap {
  float ratio[5] = {0.8908f, 1.1567f, 1.5000f, 1.9671f, 2.6498f};
  float kappa[5] = {1.02855f, 0.96521f, 0.90738f, 0.85419f, 0.80494f};
  float at(float r) const {
    if (r <= ratio[0]) return kappa[0];
    for (int i = 1; i < 5; ++i) {
      if (r <= ratio[i]) {
        const float w = (r - ratio[i - 1]) / (ratio[i] - ratio[i - 1]);
        return kappa[i - 1] + w * (kappa[i] - kappa[i - 1]);
      }
    }
    return kappa[4];
  }
};

// The ECU's clamping calibration for the CVT the ratio scenes run, the
// production-like chain CVT (docs/sil.md#ratio-control): pin-sheave friction
// mu0 = 0.09 and a clamping floor of 12.5 kN on each pulley.
constexpr ClampLawParams production_clamp_law() {
  ClampLawParams c;
  c.mu0 = 0.09f;
  c.clamp_min_N = 12500.0f;
  return c;
}

struct RatioLawParams {
  ClampLawParams clamp = production_clamp_law();  // mu0, cos(beta), safety, limits, the slip loop
  ThrustMap map{};
  // The production CVT's chain shifts at about g = 1.3 ratio/s per unit of
  // thrust-ratio imbalance, linearly up to 0.3 at least (its radial motion
  // is damped, docs/sil.md#ratio-control): kp = 2 gives a time constant
  // 1 / (g kp) of about 0.4 s.
  float kp = 2.0f;               // thrust ratio per unit of ratio error
  float ki = 0.75f;              // thrust ratio per unit of ratio error and second
  float integral_max = 0.20f;    // bound of the integral part (anti-windup)
  // Bound of the whole correction around the map: the feed-forward of the
  // bounded shift speed (0.5 / 1.3 = 0.38) and a margin for the error.
  float correction_max = 0.45f;
  float thrust_min = 0.35f, thrust_max = 1.50f;  // the driven clamping at most 2.9 times the driver's
  float shift_rate_max = 0.5f;   // ratio per second the reference may move
  float shift_gain_per_s = 1.3f; // g: ratio per second per unit of thrust-ratio imbalance
  float period_s = 0.01f;
};

struct RatioLawInputs {
  float torque_demand_Nm = 0.0f;
  float ratio_target = 1.5f;             // geometric ratio set-point (driven / driver)
  float torque_transmitted_Nm = 0.0f;    // PlantSpeeds
  float slip = 0.0f;                     // PlantRatio
  float geometric_ratio = 1.5f;          // PlantRatio
  float radius_driver_m = 0.0762f;       // PlantShift
  bool on_end_stop = false;              // PlantShift: either end-stop flag
  bool plant_data_valid = false;
};

struct RatioLawOutputs {
  float driver_clamp_cmd_N = 0.0f;   // CtrlCmd.clamp_force_cmd_N
  float driven_clamp_cmd_N = 0.0f;   // CtrlShiftCmd.driven_clamp_force_cmd_N
  float driver_torque_req_Nm = 0.0f;
  float thrust_ratio = 1.0f;
  float ratio_reference = 1.5f;      // the rate-limited set-point the law tracks
};

class RatioLaw {
 public:
  explicit constexpr RatioLaw(const RatioLawParams& p = {}) : p_(p) {}

  RatioLawOutputs step(const RatioLawInputs& in) {
    RatioLawOutputs out;
    out.driver_torque_req_Nm = in.torque_demand_Nm;
    const ClampLawParams& c = p_.clamp;
    const float a = abs_f(in.torque_demand_Nm);
    float tau_ref = a, r1 = last_r1_m_, err = 0.0f;
    // The reference starts at the first set-point and then moves toward
    // the set-point at the bounded shift speed, with or without fresh data.
    const float dmax = p_.shift_rate_max * p_.period_s;
    const float step = have_ref_ ? clamp_f(in.ratio_target - ref_, -dmax, dmax) : 0.0f;
    ref_ = have_ref_ ? ref_ + step : in.ratio_target;
    have_ref_ = true;
    const bool ref_at_rest = ref_ == in.ratio_target;
    out.ratio_reference = ref_;
    if (in.plant_data_valid) {
      extra_N_ = slip_extra_next_N(c, extra_N_, in.slip);
      const float b = abs_f(in.torque_transmitted_Nm);
      tau_ref = a > b ? a : b;
      r1 = clamp_f(in.radius_driver_m, 0.02f, 0.2f);
      last_r1_m_ = r1;
      err = in.geometric_ratio - ref_;
      if (ref_at_rest && !in.on_end_stop)
        integral_ = clamp_f(integral_ + p_.ki * err * p_.period_s, -p_.integral_max, p_.integral_max);
    }
    // Without fresh data: the clamping for the demand at the last known
    // radius, the thrust ratio from the map and the held integral.
    const float level = c.safety * clamp_for_torque_at_N(c, tau_ref, r1);
    const float feed = -step / (p_.period_s * p_.shift_gain_per_s);
    const float corr = clamp_f(feed + p_.kp * err + integral_, -p_.correction_max, p_.correction_max);
    const float k = clamp_f(p_.map.at(ref_) + corr, p_.thrust_min, p_.thrust_max);
    // The smaller clamping sits at the floor, the other is raised to shift
    // (in overdrive, k > 1, the driven one is the smaller).
    const float f1 = clamp_f(level + extra_N_, c.clamp_min_N * (k > 1.0f ? k : 1.0f), c.clamp_max_N);
    out.thrust_ratio = k;
    out.driver_clamp_cmd_N = f1;
    out.driven_clamp_cmd_N = clamp_f(f1 / k, c.clamp_min_N, c.clamp_max_N);
    return out;
  }

  void reset() {
    extra_N_ = 0.0f;
    integral_ = 0.0f;
    last_r1_m_ = 0.0762f;
    ref_ = 1.5f;
    have_ref_ = false;
  }
  float extra_N() const { return extra_N_; }
  const RatioLawParams& params() const { return p_; }

 private:
  RatioLawParams p_;
  float extra_N_ = 0.0f, integral_ = 0.0f, last_r1_m_ = 0.0762f, ref_ = 1.5f;
  bool have_ref_ = false;
};

}  // namespace cvtctl
