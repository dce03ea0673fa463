#pragma once
// A scene's physical parameters and initial values, one row each: the
// scene-file key, the SI unit, what it is, the features that use it and the
// fixed range validate_scene holds it to (docs/rom.md#scene-validation).
// The FMU's parameters are these rows (docs/fmu.md#variables). Heap-free.
#include <cstdint>
#include <limits>

#include "cvtplant/scene/scene.hpp"

namespace cvt {

enum class SceneParamKind : std::uint8_t { real, flag };

// Which friction law a row belongs to (the law's own coefficients).
enum class SceneParamLaw : std::uint8_t { any, case1, case2 };

struct SceneParamInfo {
  // "params.r1_m", "friction.mu0", "initial.omega1_rad_s": the table and key of
  // the scene file. The one exception: the file takes beta0_deg in degrees,
  // this row is params.beta0_rad in rad (SI).
  const char* name;
  const char* unit;  // SI; "1" for a dimensionless value or a flag
  SceneParamKind kind;
  std::uint32_t features;  // every one of these feature bits must be on (0: every plant)
  SceneParamLaw law;
  // validate_scene's bounds that do not depend on other values; where a
  // bound does (a <= mu0, center distance > |r2 - r1|), the widest fixed
  // one. Open ends are marked: an FMU's min/max are inclusive, the check
  // at initialisation refuses the bound itself.
  double min, max;
  bool min_open, max_open;
  const char* description;
  double (*get)(const Scene&);
  void (*set)(Scene&, double);  // flags: non-zero is true
};

namespace scene_param_detail {
inline constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace scene_param_detail

#define CVT_SCENE_PARAM(NAME, UNIT, FEATURES, LAW, MIN, MAX, MIN_OPEN, MAX_OPEN, DESC, EXPR)                      \
  SceneParamInfo {                                                                                               \
    NAME, UNIT, SceneParamKind::real, FEATURES, SceneParamLaw::LAW, MIN, MAX, MIN_OPEN, MAX_OPEN, DESC,           \
        [](const Scene& s) { return double(s.EXPR); }, [](Scene& s, double v) { s.EXPR = v; }                     \
  }
#define CVT_SCENE_FLAG(NAME, FEATURES, DESC, EXPR)                                                             \
  SceneParamInfo {                                                                                             \
    NAME, "1", SceneParamKind::flag, FEATURES, SceneParamLaw::any, 0.0, 1.0, false, false, DESC,               \
        [](const Scene& s) { return s.EXPR ? 1.0 : 0.0; }, [](Scene& s, double v) { s.EXPR = v != 0.0; }        \
  }

// In the order of the scene file's keys; a row's index is stable (the FMU's
// value references count from it), so rows are only ever appended.
inline constexpr SceneParamInfo kSceneParams[] = {
    CVT_SCENE_PARAM("params.r1_m", "m", 0, any, 0, 2, true, false, "driver pitch radius", params.r1_m),
    CVT_SCENE_PARAM("params.r2_m", "m", 0, any, 0, 2, true, false, "driven pitch radius", params.r2_m),
    CVT_SCENE_PARAM("params.beta0_rad", "rad", 0, any, 0, 1.4, false, true,
                    "half sheave angle (the scene file's beta0_deg in degrees)", params.beta0_rad),
    CVT_SCENE_PARAM("params.center_distance_m", "m", 0, any, 0, scene_param_detail::kInf, true, false,
                    "centre distance of the pulleys (must exceed |r2 - r1|)", params.center_distance_m),
    CVT_SCENE_PARAM("params.J1_kgm2", "kg.m2", 0, any, 0, scene_param_detail::kInf, true, false,
                    "driver pulley inertia", params.J1_kgm2),
    CVT_SCENE_PARAM("params.J2_kgm2", "kg.m2", 0, any, 0, scene_param_detail::kInf, true, false,
                    "driven pulley inertia", params.J2_kgm2),
    CVT_SCENE_PARAM("params.lump_mass_kg", "kg", 0, any, 0, scene_param_detail::kInf, true, false,
                    "mass of each link lump of the driver wrap", params.lump_mass_kg),
    CVT_SCENE_PARAM("params.k1_N_m", "N/m", 0, any, 0, scene_param_detail::kInf, true, false,
                    "stiffness tying each lump to its strand", params.k1_N_m),
    CVT_SCENE_PARAM("params.c1_Ns_m", "N.s/m", 0, any, 0, scene_param_detail::kInf, false, false,
                    "damping tying each lump to its strand", params.c1_Ns_m),
    CVT_SCENE_PARAM("params.k2_N_m", "N/m", 0, any, 0, scene_param_detail::kInf, false, false,
                    "stiffness coupling the two lumps", params.k2_N_m),
    CVT_SCENE_PARAM("params.c2_Ns_m", "N.s/m", 0, any, 0, scene_param_detail::kInf, false, false,
                    "damping coupling the two lumps", params.c2_Ns_m),
    CVT_SCENE_PARAM("params.entry_load_share", "1", 0, any, 0, 1, true, true,
                    "share of the wrap's normal load on the entry lump", params.entry_load_share),
    CVT_SCENE_PARAM("params.normal_load_factor", "1", 0, any, 0, 4, true, false,
                    "effective normal load over F_ax / cos(beta)", params.normal_load_factor),
    CVT_SCENE_FLAG("params.hold_driver_speed", 0, "driver pulley held at its initial speed", params.hold_driver_speed),
    CVT_SCENE_FLAG("params.hold_driven_speed", 0, "driven pulley held at its initial speed", params.hold_driven_speed),
    CVT_SCENE_PARAM("params.stick_speed_m_s", "m/s", 0, any, 0, scene_param_detail::kInf, true, false,
                    "sliding speed below which a lump is reported as sticking", params.stick_speed_m_s),
    CVT_SCENE_PARAM("params.speed_limit_rad_s", "rad/s", 0, any, 0, 30000, true, false,
                    "pulley speed beyond which the watchdog faults speed-out-of-range", params.speed_limit_rad_s),
    CVT_SCENE_PARAM("params.actuator_tau_s", "s", rom_feature::axial, any, 0, scene_param_detail::kInf, true, false,
                    "time constant of the clamping actuators", params.actuator_tau_s),
    CVT_SCENE_PARAM("params.clamp_max_N", "N", rom_feature::axial, any, 0, scene_param_detail::kInf, true, false,
                    "saturation of the clamping actuators", params.clamp_max_N),
    CVT_SCENE_PARAM("params.sheave_mass_kg", "kg", rom_feature::axial, any, 0, scene_param_detail::kInf, true, false,
                    "mass of the driver's movable sheave", params.sheave_mass_kg),
    CVT_SCENE_PARAM("params.sheave_damping_Ns_m", "N.s/m", rom_feature::axial, any, 0, scene_param_detail::kInf, false,
                    false, "axial damping of the movable sheave", params.sheave_damping_Ns_m),
    CVT_SCENE_PARAM("params.K_ax_N_m", "N/m", rom_feature::axial, any, 0, scene_param_detail::kInf, true, false,
                    "axial stiffness of the loaded bolts", params.K_ax_N_m),
    CVT_SCENE_PARAM("params.road_T0_Nm", "N.m", rom_feature::road_load, any, 0, scene_param_detail::kInf, false, false,
                    "road load: rolling-resistance torque at the driven shaft", params.road_T0_Nm),
    CVT_SCENE_PARAM("params.road_cv_Nms_rad", "N.m.s/rad", rom_feature::road_load, any, 0, scene_param_detail::kInf,
                    false, false, "road load: torque per driven speed", params.road_cv_Nms_rad),
    CVT_SCENE_PARAM("params.road_ca_Nms2_rad2", "N.m.s2/rad2", rom_feature::road_load, any, 0,
                    scene_param_detail::kInf, false, false, "road load: torque per driven speed squared",
                    params.road_ca_Nms2_rad2),
    CVT_SCENE_PARAM("params.road_w_eps_rad_s", "rad/s", rom_feature::road_load, any, 0, scene_param_detail::kInf, true,
                    false, "road load: speed scale of the rolling resistance's tanh sign", params.road_w_eps_rad_s),
    CVT_SCENE_PARAM("params.zeta1_rad", "rad", rom_feature::deformation, any, -scene_param_detail::kInf,
                    scene_param_detail::kInf, false, false, "wrap angle of the entry lump's flank deformation",
                    params.zeta1_rad),
    CVT_SCENE_PARAM("params.zeta2_rad", "rad", rom_feature::deformation, any, -scene_param_detail::kInf,
                    scene_param_detail::kInf, false, false, "wrap angle of the exit lump's flank deformation",
                    params.zeta2_rad),
    CVT_SCENE_PARAM("params.pitch_m", "m", rom_feature::polygon, any, 0, 3, true, true,
                    "link length (must be below 1.5 r1)", params.pitch_m),
    CVT_SCENE_PARAM("params.ripple_gain", "1", rom_feature::polygon, any, 0, 10, false, false,
                    "gain of the link-passing ripple of the axial force (0: smooth)", params.ripple_gain),
    CVT_SCENE_PARAM("params.driven_clamp_N", "N", rom_feature::wedging, any, 0, scene_param_detail::kInf, true, false,
                    "set-up driven clamping force (the driven clamping input's start)", params.driven_clamp_N),
    CVT_SCENE_PARAM("params.radial_mass_kg", "kg", rom_feature::wedging, any, 0, scene_param_detail::kInf, true, false,
                    "mass of the chain's radial motion", params.radial_mass_kg),
    CVT_SCENE_PARAM("params.radial_damping_Ns_m", "N.s/m", rom_feature::wedging, any, 0, scene_param_detail::kInf,
                    false, false, "damping of the chain's radial motion", params.radial_damping_Ns_m),
    CVT_SCENE_PARAM("params.radial_travel_m", "m", rom_feature::wedging, any, 0, 1, true, true,
                    "radial travel to the ratio end stops (must be below min(r1, r2) / 2)", params.radial_travel_m),
    CVT_SCENE_PARAM("params.radial_stop_N_m", "N/m", rom_feature::wedging, any, 0, scene_param_detail::kInf, true,
                    false, "contact stiffness of the ratio end stops", params.radial_stop_N_m),
    CVT_SCENE_PARAM("params.wrap_tension_share", "1", rom_feature::wedging, any, 0, 1, false, true,
                    "excess of the driver wrap's tension per N of the strands' difference", params.wrap_tension_share),
    CVT_SCENE_PARAM("params.chain_mass_kg_m", "kg/m", rom_feature::tension, any, 0, 100, false, false,
                    "chain mass per length (0: no centrifugal tension)", params.chain_mass_kg_m),
    CVT_SCENE_PARAM("params.chain_stiffness_N", "N", rom_feature::tension, any, 0, 1e9, true, false,
                    "chain stiffness k L (a link stretches by T / (k L))", params.chain_stiffness_N),
    CVT_SCENE_PARAM("params.creep_gain", "1", rom_feature::tension, any, 0, 10, false, false,
                    "creep gain (1: belt-creep theory, 0: no creep)", params.creep_gain),
    CVT_SCENE_PARAM("params.stop_tension_N", "N", rom_feature::tension, any, 0, 1e6, false, false,
                    "driver wrap's mean tension at rest with the sheaves on their stops", params.stop_tension_N),
    CVT_SCENE_PARAM("params.stop_tension_share", "1", rom_feature::tension, any, 0, 1, false, false,
                    "rise of the stop tension per N of the strands' difference", params.stop_tension_share),
    CVT_SCENE_PARAM("params.centrifugal_gain", "1", rom_feature::tension, any, 0, 10, false, false,
                    "centrifugal tension gain kappa (T_c = kappa m' v^2)", params.centrifugal_gain),
    CVT_SCENE_PARAM("params.wrap_excess_share", "1", rom_feature::tension, any, -0.5, 0.5, false, false,
                    "driver wrap's mean tension over the strands' mean per N of their difference",
                    params.wrap_excess_share),
    CVT_SCENE_FLAG("params.fixed_sheaves", rom_feature::tension,
                   "driver sheave never leaves its stop (the clamping input is unused)", params.fixed_sheaves),
    CVT_SCENE_PARAM("friction.mu0", "1", 0, any, 0, 2, true, false, "kinetic friction coefficient", params.friction.mu0),
    CVT_SCENE_PARAM("friction.a", "1", 0, case1, 0, 2, false, false,
                    "case-1 law: starting coefficient (at most mu0)", params.friction.a),
    CVT_SCENE_PARAM("friction.b_m_s", "m/s", 0, case1, 0, scene_param_detail::kInf, true, false,
                    "case-1 law: velocity scale", params.friction.b_m_s),
    CVT_SCENE_PARAM("friction.sigma", "1", 0, case2, 1, scene_param_detail::kInf, false, false,
                    "case-2 law: static over kinetic ratio", params.friction.sigma),
    CVT_SCENE_PARAM("friction.kappa_s_m", "s/m", 0, case2, 0, scene_param_detail::kInf, true, false,
                    "case-2 law: rate of growth", params.friction.kappa_s_m),
    CVT_SCENE_PARAM("friction.chi_s_m", "s/m", 0, case2, 0, scene_param_detail::kInf, true, false,
                    "case-2 law: Stribeck decay", params.friction.chi_s_m),
    CVT_SCENE_PARAM("friction.lambda_s_m", "s/m", 0, any, 0, scene_param_detail::kInf, true, false,
                    "slope of the smoothed sign of the sliding speed", params.friction.lambda_s_m),
    CVT_SCENE_PARAM("initial.omega1_rad_s", "rad/s", 0, any, -30000, 30000, false, false,
                    "initial driver speed (within speed_limit_rad_s)", initial.omega1_rad_s),
    CVT_SCENE_PARAM("initial.omega2_rad_s", "rad/s", 0, any, -30000, 30000, false, false,
                    "initial driven speed (within speed_limit_rad_s)", initial.omega2_rad_s),
    CVT_SCENE_PARAM("initial.x1_m", "m", 0, any, -scene_param_detail::kInf, scene_param_detail::kInf, false, false,
                    "initial displacement of the entry lump", initial.x1_m),
    CVT_SCENE_PARAM("initial.xd1_m_s", "m/s", 0, any, -scene_param_detail::kInf, scene_param_detail::kInf, false, false,
                    "initial velocity of the entry lump", initial.xd1_m_s),
    CVT_SCENE_PARAM("initial.x2_m", "m", 0, any, -scene_param_detail::kInf, scene_param_detail::kInf, false, false,
                    "initial displacement of the exit lump", initial.x2_m),
    CVT_SCENE_PARAM("initial.xd2_m_s", "m/s", 0, any, -scene_param_detail::kInf, scene_param_detail::kInf, false, false,
                    "initial velocity of the exit lump", initial.xd2_m_s),
    CVT_SCENE_PARAM("initial.phase_rad", "rad", rom_feature::polygon, any, -scene_param_detail::kInf,
                    scene_param_detail::kInf, false, false, "initial link-passing phase", initial.phase_rad),
    CVT_SCENE_PARAM("initial.radius_offset_m", "m", rom_feature::wedging, any, -1, 1, true, true,
                    "initial driver radius offset r1 - r1_m (within the radial travel)", initial.radius_offset_m),
};
#undef CVT_SCENE_PARAM
#undef CVT_SCENE_FLAG

inline constexpr int kSceneParamCount = static_cast<int>(sizeof(kSceneParams) / sizeof(kSceneParams[0]));

// Whether the row matters for scene s: its features are on and, for a law's
// own coefficient, the scene uses that law.
inline bool scene_param_applies(const SceneParamInfo& p, const Scene& s) {
  if ((s.features & p.features) != p.features) return false;
  switch (p.law) {
    case SceneParamLaw::any: return true;
    case SceneParamLaw::case1: return s.params.friction.law == FrictionLaw::case1;
    case SceneParamLaw::case2: return s.params.friction.law == FrictionLaw::case2;
  }
  return false;
}

}  // namespace cvt
