#pragma once
// The reference's inputs by name (docs/mbd.md#parameters): one line per
// field of MbdParams and RunOptions, in declaration order, nested structs
// flattened with their group (physics/param_field.hpp). The reference-run
// cache key (docs/validation.md#cache) and any reader or writer of these
// parameters walk this list, so a field added to MbdParams is added here in
// one line; validation/tests/test_param_lists.cpp fails until it is.
#include <type_traits>

#include "cvtplant/friction/friction_fields.hpp"
#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/physics/param_field.hpp"
#include "cvtplant/scene/scene_params.hpp"

namespace cvt::mbd {

inline constexpr NamedValue<SheaveMode> kSheaveModeNames[] = {{"fixed", SheaveMode::fixed},
                                                              {"clamped", SheaveMode::clamped}};
inline constexpr NamedValue<Method> kMethodNames[] = {{"bdf", Method::bdf}, {"rk4", Method::rk4}};
constexpr const auto& value_names(SheaveMode) { return kSheaveModeNames; }
inline constexpr NamedValue<LinearSolver> kLinearSolverNames[] = {{"chain", LinearSolver::chain},
                                                                   {"klu", LinearSolver::klu}};
constexpr const auto& value_names(Method) { return kMethodNames; }
constexpr const auto& value_names(LinearSolver) { return kLinearSolverNames; }

// The friction parameters (FrictionParams<double>, F possibly const): the law
// and the sign function by name, the coefficients by the friction.* rows of
// scene/scene_params.hpp, the one list of their names, each visited as a
// copy that is written back after the visit.
template <class F, class V>
void visit_friction(F& f, V&& v) {
  v(ParamField{"law", "", "friction"}, f.law);
  for (const SceneParamInfo& row : kSceneParams) {
    const char* name = row.name;
    const char* prefix = "friction.";
    while (*prefix != '\0' && *name == *prefix) ++name, ++prefix;
    if (*prefix != '\0') continue;
    Scene s;
    s.params.friction = f;
    double x = row.get(s);
    v(ParamField{name, row.unit, "friction"}, x);
    if constexpr (!std::is_const_v<F>) {
      row.set(s, x);
      f = s.params.friction;
    }
  }
  v(ParamField{"sign", "", "friction"}, f.sign);
}

// v(const ParamField&, field&) for every field of MbdParams (P: MbdParams or
// const MbdParams); the field is a double, an int, a bool, an enum or a
// TimeProfile.
template <class P, class V>
void visit_mbd_params(P& p, V&& v) {
  v(ParamField{"beta0_rad", "rad"}, p.beta0_rad);
  v(ParamField{"center_distance_m", "m"}, p.center_distance_m);
  v(ParamField{"link_mass_kg", "kg"}, p.link_mass_kg);
  v(ParamField{"J1_kgm2", "kg.m^2"}, p.J1_kgm2);
  v(ParamField{"J2_kgm2", "kg.m^2"}, p.J2_kgm2);
  v(ParamField{"link_length_m", "m"}, p.link_length_m);
  v(ParamField{"bolt_stiffness_N_m", "N/m"}, p.bolt_stiffness_N_m);
  v(ParamField{"bolt_length_m", "m"}, p.bolt_length_m);
  v(ParamField{"joint_stiffness_N_m", "N/m"}, p.joint_stiffness_N_m);
  v(ParamField{"joint_damping_Ns_m", "N.s/m"}, p.joint_damping_Ns_m);
  v(ParamField{"joint_rot_damping_Nms_rad", "N.m.s/rad"}, p.joint_rot_damping_Nms_rad);
  v(ParamField{"r1_m", "m"}, p.r1_m);
  v(ParamField{"r2_m", "m"}, p.r2_m);
  v(ParamField{"links", "1"}, p.links);
  v(ParamField{"link_inertia_kgm2", "kg.m^2"}, p.link_inertia_kgm2);
  v(ParamField{"sheave_deformation", ""}, p.sheave_deformation);
  visit_friction(p.friction, v);
  v(ParamField{"tau_in_Nm", "N.m"}, p.tau_in_Nm);
  v(ParamField{"tau_load_Nm", "N.m"}, p.tau_load_Nm);
  v(ParamField{"T0_Nm", "N.m", "road"}, p.road.T0_Nm);
  v(ParamField{"cv_Nms_rad", "N.m.s/rad", "road"}, p.road.cv_Nms_rad);
  v(ParamField{"ca_Nms2_rad2", "N.m.s^2/rad^2", "road"}, p.road.ca_Nms2_rad2);
  v(ParamField{"w_eps_rad_s", "rad/s", "road"}, p.road.w_eps_rad_s);
  v(ParamField{"active", "", "hold1"}, p.hold1.active);
  v(ParamField{"omega_rad_s", "rad/s", "hold1"}, p.hold1.omega_rad_s);
  v(ParamField{"active", "", "hold2"}, p.hold2.active);
  v(ParamField{"omega_rad_s", "rad/s", "hold2"}, p.hold2.omega_rad_s);
  v(ParamField{"sheaves", ""}, p.sheaves);
  v(ParamField{"clamp1_N", "N"}, p.clamp1_N);
  v(ParamField{"clamp2_N", "N"}, p.clamp2_N);
  v(ParamField{"sheave_mass_kg", "kg"}, p.sheave_mass_kg);
  v(ParamField{"sheave_damping_Ns_m", "N.s/m"}, p.sheave_damping_Ns_m);
  v(ParamField{"sheave_stop_m", "m"}, p.sheave_stop_m);
  v(ParamField{"sheave_stop_N_m", "N/m"}, p.sheave_stop_N_m);
  v(ParamField{"settle_s", "s"}, p.settle_s);
  v(ParamField{"settle_drag_Ns_m", "N.s/m"}, p.settle_drag_Ns_m);
  v(ParamField{"active", "", "start"}, p.start.active);
  v(ParamField{"omega1_rad_s", "rad/s", "start"}, p.start.omega1_rad_s);
  v(ParamField{"omega2_rad_s", "rad/s", "start"}, p.start.omega2_rad_s);
  v(ParamField{"spinup_s", "s", "start"}, p.start.spinup_s);
  v(ParamField{"hold_s", "s", "start"}, p.start.hold_s);
  v(ParamField{"start_r1_m", "m"}, p.start_r1_m);
  v(ParamField{"start_ratio_lock", ""}, p.start_ratio_lock);
  v(ParamField{"tolerance_link_rate_rad_s", "rad/s"}, p.tolerance_link_rate_rad_s);
}

// The same for RunOptions; max_steps is a cap (it ends a run, it does not
// change the samples made up to there).
template <class P, class V>
void visit_run_options(P& r, V&& v) {
  v(ParamField{"method", ""}, r.method);
  v(ParamField{"t_end_s", "s"}, r.t_end_s);
  v(ParamField{"rtol", "1"}, r.rtol);
  v(ParamField{"dt_s", "s"}, r.dt_s);
  v(ParamField{"sample_s", "s"}, r.sample_s);
  v(ParamField{"max_steps", "1", "", true}, r.max_steps);
  v(ParamField{"ledger_tol", "1"}, r.ledger_tol);
  v(ParamField{"settle_rtol", "1"}, r.settle_rtol);
  v(ParamField{"linear_solver", ""}, r.linear_solver);
}

}  // namespace cvt::mbd
