#pragma once
// The built-in scenes (docs/rom.md#built-in-scenes): constexpr data, usable
// from firmware without the heap. Parameter choices are justified in
// docs/rom.md; the tests in lib/tests/test_rom_scenes.cpp run every one.
#include <cstring>

#include "cvtplant/scene/calibrated_params.hpp"
#include "cvtplant/scene/calibrated_production.hpp"
#include "cvtplant/scene/calibrated_tension.hpp"
#include "cvtplant/scene/calibrated_wrap_tension.hpp"
#include "cvtplant/scene/production_params.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt {

namespace builtin_detail {

// The wrap of the scenes the multibody reference validates (seed cases,
// gross-slip; docs/rom.md#lump-load-split): the entry lump carries the share
// of the driver wrap's normal load that the reference's strand tensions
// give, and the parameters fitted to the reference by `cvtplant calibrate`
// (calibrated_params.hpp, written with tools/params/calibrated.toml;
// docs/validation.md#calibrated-set), and the wrap-tension share the
// variable-ratio plant fitted to the reference's ratio under load
// (calibrated_wrap_tension.hpp, with tools/params/wrap-tension.toml; it acts
// only with the wedging feature, docs/rom.md#wrap-tension). clamp-step and
// tip-in, not calibrated (docs/validation.md#calibrated-set), keep the
// seed's even wrap.
constexpr void calibrated_wrap(RomParams& p) {
  p.entry_load_share = 0.705;
  calibrated::apply(p);
  calibrated::apply_wrap_tension(p);
}

// Seed section 3 oscillator (Eq. 9) as a plant with both pulleys held:
// r1 = 1 m so the belt speed v = r1 w1 is exact, beta0 = 0 and F_ax = m g so
// N_i = m g exactly (docs/rom.md#holds).
constexpr Scene oscillator(const char* name, const char* summary, const FrictionParams<double>& f, double t_end) {
  Scene s;
  s.name = name;
  s.summary = summary;
  s.features = 0;
  s.params.r1_m = 1.0;
  s.params.r2_m = 1.0;
  s.params.beta0_rad = 0.0;
  s.params.J1_kgm2 = 1.0;
  s.params.J2_kgm2 = 1.0;
  s.params.lump_mass_kg = seed::kOscMass_kg;
  s.params.k1_N_m = seed::kOscStiffness_N_m;
  s.params.k2_N_m = seed::kOscStiffness_N_m;
  s.params.c1_Ns_m = seed::kOscDamping_Ns_m;
  s.params.c2_Ns_m = seed::kOscDamping_Ns_m;
  s.params.friction = f;
  s.params.hold_driver_speed = true;
  s.params.hold_driven_speed = true;
  s.initial.omega1_rad_s = seed::kOscBeltSpeed_m_s;  // r1 = 1 m
  s.initial.xd1_m_s = 3.0;  // seed start [x1 v1 x2 v2] = [0 3 0 6]
  s.initial.xd2_m_s = 6.0;
  s.clamp = constant_profile(seed::kOscMass_kg * kGravity_m_s2);  // m g
  s.t_end_s = t_end;
  s.log = rom_log::friction | rom_log::energy | rom_log::states;
  return s;
}

// Seed section 4: tau_in = 100 N m, tau_l = 50 N m, Table 1/2, from rest,
// under a clamping actuator: command 3.3 kN = 1.3 x the 2.54 kN that carries
// 100 N m at mu0.
constexpr Scene seed_case(const char* name, const char* summary, const FrictionParams<double>& f) {
  Scene s;
  s.name = name;
  s.summary = summary;
  s.features = rom_feature::axial;
  s.params.friction = f;
  calibrated_wrap(s.params);
  s.tau_in = constant_profile(seed::kInputTorque_Nm);
  s.tau_load = constant_profile(seed::kLoadTorque_Nm);
  s.clamp = constant_profile(3300.0);
  s.t_end_s = 10.0;
  return s;
}

// Seed section 4 as the seed runs it: its pulleys are fixed (the seed gives
// no clamping force), so the chain's own tension sets the axial force: the
// tension feature on fixed sheaves (docs/rom.md#tension) with the parameters
// calibrated on the multibody reference's fixed sheaves
// (calibrated_tension.hpp, written with tools/params/tension.toml;
// docs/validation.md#calibrated-set). The clamping profile stays the
// actuator case's 3.3 kN: fixed sheaves do not use it, the scene files that
// add the axial feature (seed-case1-clamped, seed-case1-wedging) do.
constexpr Scene seed_case_fixed(const char* name, const char* summary, const FrictionParams<double>& f) {
  Scene s = seed_case(name, summary, f);
  s.features = rom_feature::tension;
  s.params.fixed_sheaves = true;
  calibrated::apply_tension(s.params);
  return s;
}

// A drive-away load at the driven shaft (docs/rom.md#road-load): 35 N m at
// w2 = 100 rad/s.
constexpr void road(Scene& s) {
  s.params.road_T0_Nm = 10.0;
  s.params.road_cv_Nms_rad = 0.05;
  s.params.road_ca_Nms2_rad2 = 0.002;
}

constexpr Scene clamp_step() {
  Scene s;
  s.name = "clamp-step";
  s.summary = "clamping command 1.2 -> 3.0 kN at 2 s under 60 N m: flare (gross slip), then re-grip";
  s.features = rom_feature::axial | rom_feature::road_load;
  s.params.friction = friction_presets::table2_case1<double>();
  road(s);
  s.initial.omega1_rad_s = 150.0;
  s.initial.omega2_rad_s = 100.0;  // = 150 r1/r2: no slip at the start
  s.tau_in = constant_profile(60.0);
  s.clamp = step_profile(1200.0, 3000.0, 2.0);
  s.t_end_s = 6.0;
  return s;
}

constexpr Scene tip_in() {
  Scene s;
  s.name = "tip-in";
  s.summary = "driver torque 20 -> 120 N m in 0.2 s at 1 s, 4 kN clamping, road load";
  s.features = rom_feature::axial | rom_feature::road_load;
  s.params.friction = friction_presets::table2_case1<double>();
  road(s);
  s.initial.omega1_rad_s = 150.0;
  s.initial.omega2_rad_s = 100.0;
  s.tau_in = ramp_profile(20.0, 120.0, 1.0, 1.2);
  s.clamp = constant_profile(4000.0);
  s.t_end_s = 5.0;
  return s;
}

constexpr Scene gross_slip() {
  Scene s;
  s.name = "gross-slip";
  s.summary = "seed torques with 1 kN clamping (capacity 39 N m): the chain slips on the driver";
  s.features = 0;
  s.params.friction = friction_presets::table2_case1<double>();
  calibrated_wrap(s.params);
  s.tau_in = constant_profile(100.0);
  s.tau_load = constant_profile(50.0);
  s.clamp = constant_profile(1000.0);
  s.t_end_s = 10.0;
  return s;
}

// The controller scenes' CVT: the production-like chain CVT
// (docs/rom.md#production-lumps), its lumps derived from the multibody
// reference's production set, with the values fitted to it
// (calibrated_production.hpp, written with tools/params/production.toml;
// docs/validation.md#calibrated-production).
constexpr void production_cvt(RomParams& p) {
  production::apply(p);
  calibrated::apply_production(p);
}

constexpr Scene ratio_control() {
  Scene s;
  s.name = "ratio-control";
  s.summary =
      "production-like chain CVT, every physics (wedging, tension, road load): 60 N m, 11.3 kN primary against the "
      "12.5 kN driven clamping (ratio 1.5 held), 150/100 rad/s; the plant for ratio control over CAN";
  s.features = rom_feature::axial | rom_feature::road_load | rom_feature::wedging | rom_feature::tension;
  production_cvt(s.params);
  s.reference_set = "production";
  road(s);
  s.initial.omega1_rad_s = 150.0;
  s.initial.omega2_rad_s = 100.0;
  s.tau_in = constant_profile(60.0);
  // kappa(0) = theta1/theta2 = 0.907382 of the driven clamping holds the
  // set-up ratio without load (docs/rom.md#wedging).
  s.clamp = constant_profile(production::kClampMin_N * 0.90738229);
  s.t_end_s = 10.0;
  return s;
}

}  // namespace builtin_detail

inline constexpr Scene kBuiltinScenes[] = {
    builtin_detail::oscillator("oscillator-coulomb", "seed Eq. 9, constant mu0 = 0.25 from [0 3 0 6]: settles",
                               friction_presets::oscillator_coulomb<double>(), 40.0),
    builtin_detail::oscillator("oscillator-stribeck", "seed Eq. 9, Stribeck (sec. 3) from [0 3 0 6]: stick-slip cycle",
                               friction_presets::oscillator_stribeck<double>(), 60.0),
    builtin_detail::seed_case_fixed("seed-case1",
                                    "seed sec. 4: 100/50 N m, Table 1, Table 2 case 1, fixed sheaves (clamp input "
                                    "unused): chain creep and centrifugal unloading to gross slip",
                                    friction_presets::table2_case1<double>()),
    builtin_detail::seed_case("seed-case2", "seed sec. 4: 100/50 N m, Table 1, Table 2 case 2, 3.3 kN clamping",
                              friction_presets::table2_case2<double>()),
    builtin_detail::clamp_step(),
    builtin_detail::tip_in(),
    builtin_detail::gross_slip(),
    builtin_detail::ratio_control(),
};
inline constexpr int kBuiltinSceneCount = static_cast<int>(sizeof(kBuiltinScenes) / sizeof(kBuiltinScenes[0]));

// nullptr if there is no built-in scene of that name.
inline const Scene* find_builtin_scene(const char* name) {
  for (const Scene& s : kBuiltinScenes)
    if (std::strcmp(s.name, name) == 0) return &s;
  return nullptr;
}

}  // namespace cvt
