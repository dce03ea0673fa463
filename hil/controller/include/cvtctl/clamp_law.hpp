// Clamping-force control law of the example controller (docs/sil.md#controller).
// Heap-free, float only, no libm call: it is the part of the firmware that
// would be cross-compiled for the ECU (ctest hil.sil_controller_cortex_m4 compiles
// it for Cortex-M4F and refuses heap, exception and RTTI references).
//
// The belt can carry tau_cap = 2 mu0 F_ax r1 / cos(beta) (docs/rom.md#contact).
// The law keeps tau_cap = safety * tau_ref, where tau_ref is the larger of the
// driver's torque demand and the torque the belt carries right now (a load
// transient can raise the latter before the demand changes). Because the
// plant's slip signal is mostly the strand's elastic stretch rate
// (docs/sil.md#controller), slip acts only beyond a limit: each control
// period with |slip| > slip_limit adds clamping in proportion to the excess;
// the extra clamping then decays back to the feed-forward value.
#pragma once

#include "cvtplant/physics/seed.hpp"

namespace cvtctl {

struct ClampLawParams {
  // Calibration the ECU holds for its CVT (tip-in scene values, docs/rom.md).
  float mu0 = static_cast<float>(cvt::seed::kMu0);
  float r1_m = static_cast<float>(cvt::seed::kDriverPitchRadius_m);
  float cos_beta = 0.96592583f;  // cos(15 deg): precomputed, no libm on the target
  float safety = 1.3f;           // torque-capacity safety factor kept by feed-forward
  float clamp_min_N = 1000.0f;   // keeps the chain seated at zero torque
  float clamp_max_N = 40000.0f;  // actuator limit (docs/rom.md#lumped-parameters)
  float slip_limit = 0.08f;      // above the elastic stretch rate of tip-in transients (<= 0.07)
  float slip_gain_N = 5.0e4f;    // extra clamping per unit of slip excess and period
  float extra_decay_per_period = 0.98f;
  float extra_max_N = 20000.0f;
};

struct ClampLawInputs {
  float torque_demand_Nm = 0.0f;       // driver demand (pedal map), sent on as the torque request
  float torque_transmitted_Nm = 0.0f;  // PlantSpeeds
  float slip = 0.0f;                   // PlantRatio
  bool plant_data_valid = false;       // a complete, E2E-valid output group this period
};

struct ClampLawOutputs {
  float clamp_force_cmd_N = 0.0f;
  float driver_torque_req_Nm = 0.0f;
};

// tau_cap = 2 mu0 F_ax r1 / cos(beta) [N m] at the driver's running radius
// r1 (docs/rom.md#contact; r1 varies with the ratio, docs/sil.md#ratio-control).
constexpr float torque_capacity_at_Nm(const ClampLawParams& p, float axial_force_N, float r1_m) {
  return 2.0f * p.mu0 * axial_force_N * r1_m / p.cos_beta;
}
constexpr float torque_capacity_Nm(const ClampLawParams& p, float axial_force_N) {
  return torque_capacity_at_Nm(p, axial_force_N, p.r1_m);
}

// F_ax giving tau_cap = tau [N], the inverse of torque_capacity_at_Nm.
constexpr float clamp_for_torque_at_N(const ClampLawParams& p, float torque_Nm, float r1_m) {
  return torque_Nm * p.cos_beta / (2.0f * p.mu0 * r1_m);
}
constexpr float clamp_for_torque_N(const ClampLawParams& p, float torque_Nm) {
  return clamp_for_torque_at_N(p, torque_Nm, p.r1_m);
}

constexpr float abs_f(float v) { return v < 0.0f ? -v : v; }
constexpr float clamp_f(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

// Slip protection, one control period with fresh data: the extra clamping
// decays and grows in proportion to the slip beyond the limit (bounded).
constexpr float slip_extra_next_N(const ClampLawParams& p, float extra_N, float slip) {
  const float excess = abs_f(slip) - p.slip_limit;
  return clamp_f(extra_N * p.extra_decay_per_period + (excess > 0.0f ? p.slip_gain_N * excess : 0.0f), 0.0f,
                 p.extra_max_N);
}

class ClampLaw {
 public:
  explicit constexpr ClampLaw(const ClampLawParams& p = {}) : p_(p) {}

  // One control period (10 ms, the CtrlCmd cycle).
  ClampLawOutputs step(const ClampLawInputs& in) {
    ClampLawOutputs out;
    out.driver_torque_req_Nm = in.torque_demand_Nm;
    if (!in.plant_data_valid) {
      // No trustworthy feedback: clamp for the demand at the safety factor
      // plus everything the slip loop had added, and let nothing decay.
      out.clamp_force_cmd_N = clamp_f(feed_forward_N(abs_f(in.torque_demand_Nm)) + extra_N_, p_.clamp_min_N,
                                      p_.clamp_max_N);
      return out;
    }
    extra_N_ = slip_extra_next_N(p_, extra_N_, in.slip);
    const float a = abs_f(in.torque_demand_Nm), b = abs_f(in.torque_transmitted_Nm);
    const float tau_ref = a > b ? a : b;
    out.clamp_force_cmd_N = clamp_f(feed_forward_N(tau_ref) + extra_N_, p_.clamp_min_N, p_.clamp_max_N);
    return out;
  }

  void reset() { extra_N_ = 0.0f; }
  float extra_N() const { return extra_N_; }
  const ClampLawParams& params() const { return p_; }

 private:
  float feed_forward_N(float tau_ref_Nm) const { return p_.safety * clamp_for_torque_N(p_, tau_ref_Nm); }

  ClampLawParams p_;
  float extra_N_ = 0.0f;
};

}  // namespace cvtctl
