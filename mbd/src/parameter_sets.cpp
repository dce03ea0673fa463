// The named parameter sets of the multibody reference: the seed's Table 1 and
// the production-like chain CVT (docs/mbd-production.md, every value with its
// source or derivation there).
#include <cmath>
#include <stdexcept>

#include "cvtplant/mbd/params.hpp"

namespace cvt::mbd {

MbdParams seed_case(int friction_case) {
  if (friction_case != 1 && friction_case != 2) throw std::invalid_argument("seed case: 1 or 2");
  MbdParams p;
  p.friction = friction_case == 1 ? friction_presets::table2_case1<double>() : friction_presets::table2_case2<double>();
  return p;
}

const char* parameter_set_name(ParameterSet s) { return s == ParameterSet::seed ? "seed" : "production"; }

std::optional<ParameterSet> parameter_set_by_name(std::string_view name) {
  if (name == "seed") return ParameterSet::seed;
  if (name == "production") return ParameterSet::production;
  return std::nullopt;
}

MbdParams production_set() {
  MbdParams p;  // the seed's geometry: C, r1, r2, beta0, Eq. 3-4 (docs/mbd-production.md#kept)
  // docs/mbd-production.md#chain: 53 links fill the 1.6014 m pitch line.
  p.links = 53;
  p.link_length_m = 0.0302;
  p.link_mass_kg = 0.04;
  p.joint_stiffness_N_m = 5.0e7;
  p.joint_damping_Ns_m = 2.7e3;
  p.joint_rot_damping_Nms_rad = 0.005;
  // docs/mbd-production.md#bolts
  p.bolt_stiffness_N_m = 2.0e7;
  // docs/mbd-production.md#friction: Coulomb pin-sheave friction in oil.
  p.friction = FrictionParams<double>{};
  p.friction.law = FrictionLaw::case1;
  p.friction.mu0 = 0.09;
  p.friction.a = 0.0;
  p.friction.b_m_s = 0.03;
  p.friction.sign = SignFunction::atan;
  p.friction.lambda_s_m = 1e4;
  // docs/mbd-production.md#sheaves
  p.sheaves = SheaveMode::clamped;
  p.sheave_mass_kg = 2.0;
  p.sheave_damping_Ns_m = 1.0e4;
  p.sheave_stop_N_m = 3.5e8;
  p.tolerance_link_rate_rad_s = 1000.0;
  p.start_ratio_lock = true;
  p.start.spinup_s = 0.2;
  p.start.hold_s = 0.2;
  p.tau_in_Nm = TimeProfile::constant(0.0);
  p.tau_load_Nm = TimeProfile::constant(0.0);
  return p;
}

ProductionEnvelope production_envelope() {
  ProductionEnvelope e;
  e.rated_torque_Nm = 150.0;
  e.omega1_min_rad_s = 100.0;
  e.omega1_max_rad_s = 200.0;
  e.clamp_min_N = 12.5e3;
  e.clamp_max_N = 30.0e3;
  e.clamp_safety = 1.3;
  e.ratio_underdrive = 2.65;
  e.ratio_overdrive = 0.89;
  return e;
}

}  // namespace cvt::mbd
