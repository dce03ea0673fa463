// A plant scene as the multibody reference's inputs (docs/validation.md#method).
#include "cvtplant/validation/reference.hpp"

#include <cmath>

#include "cvtplant/friction/friction_fields.hpp"
#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/validation/errors.hpp"

namespace cvt::validation {

namespace {

// A scene's input profile as the reference's piecewise-linear one (a step
// becomes a 1 ms ramp: the reference integrates it, the plant samples it per
// frame). what: "clamping" or "torque", for the reason a sine is refused.
std::optional<cvt::mbd::TimeProfile> time_profile(const cvt::Profile& p, const char* what, std::string& why_not) {
  cvt::mbd::TimeProfile f;
  switch (p.kind) {
    case cvt::ProfileKind::constant: f.points = {{0.0, p.value}}; break;
    case cvt::ProfileKind::step: f.points = {{p.t0_s, p.value}, {p.t0_s + 1e-3, p.value2}}; break;
    case cvt::ProfileKind::ramp: f.points = {{p.t0_s, p.value}, {p.t1_s, p.value2}}; break;
    case cvt::ProfileKind::table:
      for (int i = 0; i < p.n; ++i) f.points.emplace_back(p.t_s[i], p.v[i]);
      break;
    case cvt::ProfileKind::sine:
      why_not = std::string("a sine ") + what + " profile (the reference takes piecewise-linear profiles)";
      return std::nullopt;
  }
  return f;
}

}  // namespace

SheaveChoice sheave_choice(const std::string& name) {
  if (name == "fixed") return SheaveChoice::fixed;
  if (name == "clamped") return SheaveChoice::clamped;
  if (name == "scene") return SheaveChoice::scene;
  throw InputError("unknown sheaves '" + name + "' (scene, clamped, fixed)");
}

const char* sheave_mode_name(cvt::mbd::SheaveMode m) { return cvt::value_name(cvt::mbd::kSheaveModeNames, m); }

cvt::mbd::SheaveMode reference_sheaves(const cvt::Scene& s, SheaveChoice c) {
  switch (c) {
    case SheaveChoice::fixed: return cvt::mbd::SheaveMode::fixed;
    case SheaveChoice::clamped: return cvt::mbd::SheaveMode::clamped;
    case SheaveChoice::scene: break;
  }
  // fixed_sheaves acts only with the tension feature (docs/rom.md#tension);
  // without it the plant's axial force is its clamping input.
  const bool fixed = (s.features & cvt::rom_feature::tension) != 0 && s.params.fixed_sheaves;
  return fixed ? cvt::mbd::SheaveMode::fixed : cvt::mbd::SheaveMode::clamped;
}

double settle_rtol(cvt::mbd::ParameterSet set) {
  return set == cvt::mbd::ParameterSet::production ? 1e-6 : cvt::mbd::RunOptions{}.settle_rtol;
}

cvt::mbd::ParameterSet parameter_set(const std::string& name) {
  const auto set = cvt::mbd::parameter_set_by_name(name);
  if (!set) throw InputError("unknown parameter set '" + name + "' (seed, production)");
  return *set;
}

std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice c, std::string& why_not) {
  return reference_params(s, c, cvt::mbd::ParameterSet::seed, why_not);
}

std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice choice,
                                                    cvt::mbd::ParameterSet set, std::string& why_not) {
  const bool production = set == cvt::mbd::ParameterSet::production;
  const cvt::mbd::SheaveMode sheaves = reference_sheaves(s, choice);
  if (production && sheaves == cvt::mbd::SheaveMode::fixed) {
    why_not = "fixed sheaves on the production set (its pulleys are clamped, docs/mbd-production.md)";
    return std::nullopt;
  }
  const cvt::RomParams& rp = s.params;
  const cvt::RomInitial& in = s.initial;
  if (rp.hold_driver_speed || rp.hold_driven_speed) {
    why_not = "held pulleys (the oscillator scenes; the reference is a drive train)";
    return std::nullopt;
  }
  if (in.x1_m != 0.0 || in.xd1_m_s != 0.0 || in.x2_m != 0.0 || in.xd2_m_s != 0.0 ||
      (!production && in.radius_offset_m != 0.0)) {
    why_not = production ? "initial lump states (the reference's chain starts settled)"
                         : "initial lump or radial states (the seed set's chain starts settled on its pitch line)";
    return std::nullopt;
  }
  const bool at_rest = in.omega1_rad_s == 0.0 && in.omega2_rad_s == 0.0;
  if (!at_rest && !(in.omega1_rad_s > 0.0 && in.omega2_rad_s > 0.0)) {
    why_not = "a start with a pulley at rest or turning backwards (the reference starts from rest or with both "
              "pulleys running forward)";
    return std::nullopt;
  }
  // The chain and its pulley radii stay the set's: the plant's r1, r2 and
  // lump parameters are effective values fitted to this chain (`cvtplant
  // calibrate`), not inputs of the reference.
  cvt::mbd::MbdParams p = production ? cvt::mbd::production_set() : cvt::mbd::seed_case(1);
  p.J1_kgm2 = rp.J1_kgm2;
  p.J2_kgm2 = rp.J2_kgm2;
  if (!production) {
    // The seed set's friction and sheave angle are the scene's; the
    // production set's are its own (docs/mbd-production.md#friction).
    p.friction = rp.friction;
    p.beta0_rad = rp.beta0_rad;
  } else if (in.radius_offset_m != 0.0) {
    // The chain starts at the plant's radial offset on the driver, its
    // sheave locked there until the release (docs/mbd-production.md#start).
    p.start_r1_m = p.r1_m + in.radius_offset_m;
    if (!(std::fabs(in.radius_offset_m) * 2.0 * std::tan(p.beta0_rad) < p.sheave_stop_m)) {
      why_not = "an initial radial offset beyond the production set's ratio stops";
      return std::nullopt;
    }
  }
  auto tau_in = time_profile(s.tau_in, "torque", why_not);
  if (!tau_in) return std::nullopt;
  auto tau_load = time_profile(s.tau_load, "torque", why_not);
  if (!tau_load) return std::nullopt;
  p.tau_in_Nm = *tau_in;
  p.tau_load_Nm = *tau_load;
  if (s.features & cvt::rom_feature::road_load) {
    // docs/rom.md#road-load, the same law (cvt::road_load_torque).
    p.road.T0_Nm = rp.road_T0_Nm;
    p.road.cv_Nms_rad = rp.road_cv_Nms_rad;
    p.road.ca_Nms2_rad2 = rp.road_ca_Nms2_rad2;
    p.road.w_eps_rad_s = rp.road_w_eps_rad_s;
  }
  if (!at_rest) {
    // docs/mbd.md#start-at-speed
    p.start.active = true;
    p.start.omega1_rad_s = in.omega1_rad_s;
    p.start.omega2_rad_s = in.omega2_rad_s;
  }
  p.sheaves = sheaves;
  // Fixed sheaves: the seed's pulleys, the axial force is the reference's
  // output and the scene's clamping is not an input.
  if (sheaves == cvt::mbd::SheaveMode::fixed) return p;
  auto clamp = time_profile(s.clamp, "clamping", why_not);
  if (!clamp) return std::nullopt;
  for (const auto& pt : clamp->points)
    if (!(pt.second >= 100.0)) {
      why_not = "a clamping force below 100 N (the reference's clamped sheaves need a seated chain)";
      return std::nullopt;
    }
  p.clamp1_N = *clamp;
  // The wedging plant holds the driven clamping constant; without wedging the
  // plant has no driven clamping and the reference's default (the static
  // thrust ratio) keeps its ratio.
  if (s.features & cvt::rom_feature::wedging) p.clamp2_N.points = {{0.0, rp.driven_clamp_N}};
  return p;
}

}  // namespace cvt::validation
