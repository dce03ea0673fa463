#pragma once
// The plant's parameters by name (docs/rom.md#parameters): one line per
// RomParams field, in declaration order, with the key that scene and
// parameter files use (`[params]`, `[friction]`), its unit and how
// `cvtplant calibrate` may fit it. The scene-file reader, the parameter-file
// and C++ header writers and calibrate's names all walk this list.
#include <type_traits>

#include "cvtplant/friction/friction_fields.hpp"
#include "cvtplant/physics/param_field.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// v(const ParamField&, field&) for every field of RomParams; P is RomParams
// or const RomParams. beta0 is written in degrees (to_si); the friction
// fields have group "friction" (a scene file's [friction] table).
template <class P, class V>
constexpr void visit_rom_params(P& p, V&& v) {
  constexpr ParamFit no = ParamFit::none, pos = ParamFit::positive, share = ParamFit::share;
  v(ParamField{"r1_m", "m", pos}, p.r1_m);
  v(ParamField{"r2_m", "m", pos}, p.r2_m);
  v(ParamField{"beta0_deg", "deg", no, kDegToRad}, p.beta0_rad);
  v(ParamField{"center_distance_m", "m", no}, p.center_distance_m);
  v(ParamField{"J1_kgm2", "kg.m^2", no}, p.J1_kgm2);
  v(ParamField{"J2_kgm2", "kg.m^2", no}, p.J2_kgm2);
  v(ParamField{"lump_mass_kg", "kg", pos}, p.lump_mass_kg);
  v(ParamField{"k1_N_m", "N/m", pos}, p.k1_N_m);
  v(ParamField{"c1_Ns_m", "N.s/m", pos}, p.c1_Ns_m);
  v(ParamField{"k2_N_m", "N/m", pos}, p.k2_N_m);
  v(ParamField{"c2_Ns_m", "N.s/m", pos}, p.c2_Ns_m);
  v(ParamField{"entry_load_share", "1", share}, p.entry_load_share);
  v(ParamField{"normal_load_factor", "1", pos}, p.normal_load_factor);
  visit_friction_fields(p.friction, [&v](ParamField f, auto& x) {
    f.group = "friction";
    v(f, x);
  });
  v(ParamField{"hold_driver_speed", ""}, p.hold_driver_speed);
  v(ParamField{"hold_driven_speed", ""}, p.hold_driven_speed);
  v(ParamField{"stick_speed_m_s", "m/s", no}, p.stick_speed_m_s);
  v(ParamField{"speed_limit_rad_s", "rad/s", no}, p.speed_limit_rad_s);
  v(ParamField{"actuator_tau_s", "s", no}, p.actuator_tau_s);
  v(ParamField{"clamp_max_N", "N", no}, p.clamp_max_N);
  v(ParamField{"sheave_mass_kg", "kg", no}, p.sheave_mass_kg);
  v(ParamField{"sheave_damping_Ns_m", "N.s/m", no}, p.sheave_damping_Ns_m);
  v(ParamField{"K_ax_N_m", "N/m", no}, p.K_ax_N_m);
  v(ParamField{"road_T0_Nm", "N.m", no}, p.road_T0_Nm);
  v(ParamField{"road_cv_Nms_rad", "N.m.s/rad", no}, p.road_cv_Nms_rad);
  v(ParamField{"road_ca_Nms2_rad2", "N.m.s^2/rad^2", no}, p.road_ca_Nms2_rad2);
  v(ParamField{"road_w_eps_rad_s", "rad/s", no}, p.road_w_eps_rad_s);
  v(ParamField{"zeta1_rad", "rad", no}, p.zeta1_rad);
  v(ParamField{"zeta2_rad", "rad", no}, p.zeta2_rad);
  v(ParamField{"pitch_m", "m", no}, p.pitch_m);
  v(ParamField{"ripple_gain", "1", no}, p.ripple_gain);
  v(ParamField{"driven_clamp_N", "N", no}, p.driven_clamp_N);
  v(ParamField{"radial_mass_kg", "kg", no}, p.radial_mass_kg);
  v(ParamField{"radial_damping_Ns_m", "N.s/m", no}, p.radial_damping_Ns_m);
  v(ParamField{"radial_travel_m", "m", no}, p.radial_travel_m);
  v(ParamField{"radial_stop_N_m", "N/m", no}, p.radial_stop_N_m);
  v(ParamField{"wrap_tension_share", "1", share}, p.wrap_tension_share);
  v(ParamField{"chain_mass_kg_m", "kg/m", pos}, p.chain_mass_kg_m);
  v(ParamField{"centrifugal_gain", "1", pos}, p.centrifugal_gain);
  v(ParamField{"chain_stiffness_N", "N", pos}, p.chain_stiffness_N);
  v(ParamField{"creep_gain", "1", pos}, p.creep_gain);
  v(ParamField{"stop_tension_N", "N", pos}, p.stop_tension_N);
  v(ParamField{"stop_tension_share", "1", share}, p.stop_tension_share);
  // eta_w is a share by its name but fitted as a positive value.
  v(ParamField{"wrap_excess_share", "1", pos}, p.wrap_excess_share);
  v(ParamField{"fixed_sheaves", ""}, p.fixed_sheaves);
}

// The field of a plain [params] number (group "", a double) by its key,
// or nullptr; with it the description.
inline double* rom_param_number(RomParams& p, const char* name, ParamField* field = nullptr) {
  double* out = nullptr;
  visit_rom_params(p, [&](const ParamField& f, auto& x) {
    if constexpr (std::is_same_v<std::remove_reference_t<decltype(x)>, double>) {
      if (out == nullptr && f.group[0] == '\0' && param_names_equal(f.name, name)) {
        out = &x;
        if (field != nullptr) *field = f;
      }
    }
  });
  return out;
}

}  // namespace cvt
