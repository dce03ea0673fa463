#pragma once
// A scene: features + parameters + input profiles + run settings
// (docs/rom.md#scenes). Plain constexpr-friendly data, heap-free, so firmware
// can hold scene tables in flash; the offline tool also reads them from TOML
// files (tools/cvtplant/scene_file.cpp).
#include <cstdint>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/plant/rom_signals.hpp"

namespace cvt {

enum class ProfileKind : std::uint8_t { constant, step, ramp, sine, table };
inline constexpr int kMaxProfilePoints = 16;

// An input as a function of time (docs/rom.md#profiles). Evaluated once per
// frame in double (set-up class arithmetic; firmware normally takes its inputs
// from the controller instead).
struct Profile {
  ProfileKind kind = ProfileKind::constant;
  double value = 0;        // constant; step: before; ramp: start; sine: offset
  double value2 = 0;       // step: after; ramp: end
  double t0_s = 0;         // step time; ramp start; sine start
  double t1_s = 0;         // ramp end
  double amplitude = 0;    // sine
  double freq_hz = 0;      // sine
  int n = 0;               // table: points, linear interpolation, held outside
  double t_s[kMaxProfilePoints] = {};
  double v[kMaxProfilePoints] = {};

  double at(double t) const {
    switch (kind) {
      case ProfileKind::constant: return value;
      case ProfileKind::step: return t < t0_s ? value : value2;
      case ProfileKind::ramp:
        if (t <= t0_s) return value;
        if (t >= t1_s) return value2;
        return value + (value2 - value) * ((t - t0_s) / (t1_s - t0_s));
      case ProfileKind::sine:
        if (t < t0_s) return value;
        return value + amplitude * dm::sin(kTwoPi * freq_hz * (t - t0_s));
      case ProfileKind::table: {
        if (n <= 0) return 0.0;
        if (t <= t_s[0]) return v[0];
        for (int i = 1; i < n; ++i)
          if (t < t_s[i]) return v[i - 1] + (v[i] - v[i - 1]) * ((t - t_s[i - 1]) / (t_s[i] - t_s[i - 1]));
        return v[n - 1];
      }
    }
    return 0.0;
  }
};

constexpr Profile constant_profile(double v) {
  Profile p;
  p.value = v;
  return p;
}
constexpr Profile step_profile(double before, double after, double t_s) {
  Profile p;
  p.kind = ProfileKind::step;
  p.value = before;
  p.value2 = after;
  p.t0_s = t_s;
  return p;
}
constexpr Profile ramp_profile(double from, double to, double t0_s, double t1_s) {
  Profile p;
  p.kind = ProfileKind::ramp;
  p.value = from;
  p.value2 = to;
  p.t0_s = t0_s;
  p.t1_s = t1_s;
  return p;
}
constexpr Profile sine_profile(double offset, double amplitude, double freq_hz, double t0_s) {
  Profile p;
  p.kind = ProfileKind::sine;
  p.value = offset;
  p.amplitude = amplitude;
  p.freq_hz = freq_hz;
  p.t0_s = t0_s;
  return p;
}

// The largest |value| a profile takes at any time: its declared range, which
// a fixed-point plant must be able to represent (scene/plant_set.hpp).
inline double profile_bound(const Profile& p) {
  auto mag = [](double v) { return v < 0 ? -v : v; };
  auto larger = [](double a, double b) { return a > b ? a : b; };
  switch (p.kind) {
    case ProfileKind::constant: return mag(p.value);
    case ProfileKind::step:
    case ProfileKind::ramp: return larger(mag(p.value), mag(p.value2));
    case ProfileKind::sine: return mag(p.value) + mag(p.amplitude);
    case ProfileKind::table: {
      double m = 0;
      for (int i = 0; i < p.n && i < kMaxProfilePoints; ++i) m = larger(m, mag(p.v[i]));
      return m;
    }
  }
  return 0.0;
}

// The inputs' ranges, one per quantity for every front door that sets it:
// scene files (validate_scene), `cvtplant mbd`'s flags and the reference's
// mapping of a scene (docs/rom.md#scene-validation). Beyond them the plant
// and the multibody reference leave the regime they are built for (the
// seed's 100 N m and 3.3 kN), and a run would end in a fault or crawl.
namespace input_limits {
inline constexpr double kTorque_Nm = 1000.0;      // |tau_in|, |tau_load|
inline constexpr double kClamp_N = 1e5;           // clamping force, [0, 1e5] N
inline constexpr double kRoadT0_Nm = 1000.0;      // road load: T0 in [0, 1000] N m
inline constexpr double kRoadCv_Nms_rad = 100.0;  // c_v in [0, 100] N m s/rad
inline constexpr double kRoadCa_Nms2_rad2 = 10.0; // c_a in [0, 10] N m s^2/rad^2
// w_eps in [1e-3, 1000] rad/s: below 1e-3 rad/s the tanh is a sign
// function at the integrators' resolution of the driven speed, and the
// multibody reference's steps collapse (docs/mbd.md#loads).
inline constexpr double kRoadWepsMin_rad_s = 1e-3;
inline constexpr double kRoadWepsMax_rad_s = 1000.0;
}  // namespace input_limits

// The smallest and largest value a profile takes at any time.
inline void profile_range(const Profile& p, double& lo, double& hi) {
  auto take = [&](double v) {
    lo = v < lo ? v : lo;
    hi = v > hi ? v : hi;
  };
  lo = hi = p.value;
  switch (p.kind) {
    case ProfileKind::constant: break;
    case ProfileKind::step:
    case ProfileKind::ramp: take(p.value2); break;
    case ProfileKind::sine: {
      const double a = p.amplitude < 0 ? -p.amplitude : p.amplitude;
      lo = p.value - a;
      hi = p.value + a;
      break;
    }
    case ProfileKind::table:
      if (p.n >= 1) lo = hi = p.v[0];
      for (int i = 1; i < p.n && i < kMaxProfilePoints; ++i) take(p.v[i]);
      break;
  }
}

enum class ScalarKind : std::uint8_t { f64, f32, q16_16 };
inline constexpr const char* scalar_kind_name(ScalarKind s) {
  return s == ScalarKind::f64 ? "double" : s == ScalarKind::f32 ? "float" : "fixed";
}

struct Scene {
  const char* name = "";
  const char* summary = "";
  std::uint32_t features = 0;
  RomParams params{};
  RomInitial initial{};
  Profile tau_in{}, tau_load{}, clamp{};
  double t_end_s = 10.0;
  // The real-time default, chosen by measurement (docs/rom.md#real-time-integrator):
  // one ROS2 step per 1 ms frame, W with the friction slope floor
  // (docs/rom.md#slope-floor), is stable in every built-in scene.
  double frame_s = 1e-3;
  int substeps = 1;
  Method method = Method::ros2;
  ScalarKind scalar = ScalarKind::f64;
  // The energy ledger and its watchdog check (RomSimConfig::energy_ledger):
  // about a tenth of a frame, so a scene that does not need the balance can
  // leave it off (docs/rom.md#cost); the log's energy group needs it.
  bool energy_ledger = true;
  std::uint32_t log = rom_log::torques | rom_log::friction | rom_log::energy;
  // The multibody reference's parameter set the scene is validated against
  // (docs/validation.md#parameter-sets): "seed" (Table 1) or "production"
  // (the production-like chain CVT of the controller scenes). Offline tools
  // only; the plant does not read it.
  const char* reference_set = "seed";
};

// First problem found in a scene, or ok (docs/rom.md#scene-validation). Field
// names are the scene-file keys, so the file reader can point at the line.
struct SceneIssue {
  bool ok = true;
  const char* field = "";
  const char* message = "";
};

namespace scene_detail {
constexpr bool fin(double v) { return v == v && v - v == 0.0; }
constexpr double abs_of(double v) { return v < 0 ? -v : v; }
constexpr SceneIssue bad(const char* field, const char* message) { return SceneIssue{false, field, message}; }

// `frame_s`: the profile is sampled once per frame, so a sine above half the
// frame rate would alias to another frequency (docs/rom.md#scene-validation).
inline SceneIssue check_profile(const Profile& p, const char* field, bool non_negative, double frame_s) {
  if (!fin(p.value) || !fin(p.value2) || !fin(p.t0_s) || !fin(p.t1_s) || !fin(p.amplitude) || !fin(p.freq_hz))
    return bad(field, "profile values must be finite");
  if (p.t0_s < 0) return bad(field, "profile times must be >= 0");
  switch (p.kind) {
    case ProfileKind::constant:
      if (non_negative && p.value < 0) return bad(field, "must be >= 0");
      break;
    case ProfileKind::step:
      if (non_negative && (p.value < 0 || p.value2 < 0)) return bad(field, "must be >= 0");
      break;
    case ProfileKind::ramp:
      if (!(p.t1_s > p.t0_s)) return bad(field, "ramp needs t1_s > t0_s");
      if (non_negative && (p.value < 0 || p.value2 < 0)) return bad(field, "must be >= 0");
      break;
    case ProfileKind::sine:
      if (p.freq_hz < 0) return bad(field, "sine frequency must be >= 0");
      if (!(p.freq_hz * frame_s <= 0.5))
        return bad(field, "sine frequency must be at most half the frame rate, 1/(2 frame_s): inputs are sampled once per frame");
      if (non_negative && p.value - (p.amplitude < 0 ? -p.amplitude : p.amplitude) < 0)
        return bad(field, "sine must stay >= 0 (offset >= |amplitude|)");
      break;
    case ProfileKind::table:
      if (p.n < 1 || p.n > kMaxProfilePoints) return bad(field, "table needs 1..16 points");
      for (int i = 0; i < p.n; ++i) {
        if (!fin(p.t_s[i]) || !fin(p.v[i])) return bad(field, "table values must be finite");
        if (p.t_s[i] < 0) return bad(field, "profile times must be >= 0");
        if (i > 0 && !(p.t_s[i] > p.t_s[i - 1])) return bad(field, "table times must increase strictly");
        if (non_negative && p.v[i] < 0) return bad(field, "must be >= 0");
      }
      break;
  }
  double lo = 0, hi = 0;
  profile_range(p, lo, hi);
  if (non_negative) {
    if (!(hi <= input_limits::kClamp_N)) return bad(field, "must stay within [0, 1e5] N");
  } else if (!(lo >= -input_limits::kTorque_Nm && hi <= input_limits::kTorque_Nm)) {
    return bad(field, "must stay within [-1000, 1000] N m");
  }
  return SceneIssue{};
}
}  // namespace scene_detail

// Rejects non-physical or out-of-range parameters before a run.
inline SceneIssue validate_scene(const Scene& s) {
  using scene_detail::abs_of;
  using scene_detail::bad;
  using scene_detail::fin;
  const RomParams& p = s.params;
  if ((s.features & ~rom_feature::known) != 0u) return bad("features", "unknown feature bit");
  if (!(fin(p.r1_m) && p.r1_m > 0 && p.r1_m <= 2)) return bad("r1_m", "must be in (0, 2] m");
  if (!(fin(p.r2_m) && p.r2_m > 0 && p.r2_m <= 2)) return bad("r2_m", "must be in (0, 2] m");
  if (!(fin(p.beta0_rad) && p.beta0_rad >= 0 && p.beta0_rad < 1.4)) return bad("beta0_deg", "must be in [0, 80) deg");
  if (!(fin(p.center_distance_m) && p.center_distance_m > (p.r2_m > p.r1_m ? p.r2_m - p.r1_m : p.r1_m - p.r2_m)))
    return bad("center_distance_m", "must exceed |r2 - r1|");
  if (!(fin(p.J1_kgm2) && p.J1_kgm2 > 0)) return bad("J1_kgm2", "must be > 0");
  if (!(fin(p.J2_kgm2) && p.J2_kgm2 > 0)) return bad("J2_kgm2", "must be > 0");
  if (!(fin(p.lump_mass_kg) && p.lump_mass_kg > 0)) return bad("lump_mass_kg", "must be > 0");
  if (!(fin(p.k1_N_m) && p.k1_N_m > 0)) return bad("k1_N_m", "must be > 0");
  if (!(fin(p.k2_N_m) && p.k2_N_m >= 0)) return bad("k2_N_m", "must be >= 0");
  if (!(fin(p.c1_Ns_m) && p.c1_Ns_m >= 0)) return bad("c1_Ns_m", "must be >= 0");
  if (!(fin(p.c2_Ns_m) && p.c2_Ns_m >= 0)) return bad("c2_Ns_m", "must be >= 0");
  if (!(fin(p.entry_load_share) && p.entry_load_share > 0 && p.entry_load_share < 1))
    return bad("entry_load_share", "must be in (0, 1)");
  if (!(fin(p.normal_load_factor) && p.normal_load_factor > 0 && p.normal_load_factor <= 4))
    return bad("normal_load_factor", "must be in (0, 4]");
  if (!(fin(p.stick_speed_m_s) && p.stick_speed_m_s > 0)) return bad("stick_speed_m_s", "must be > 0");
  if (!(fin(p.speed_limit_rad_s) && p.speed_limit_rad_s > 0 && p.speed_limit_rad_s <= 30000))
    return bad("speed_limit_rad_s", "must be in (0, 30000] rad/s");
  const FrictionParams<double>& f = p.friction;
  if (!(fin(f.mu0) && f.mu0 > 0 && f.mu0 <= 2)) return bad("mu0", "must be in (0, 2]");
  if (!(fin(f.lambda_s_m) && f.lambda_s_m > 0)) return bad("lambda_s_m", "must be > 0");
  if (f.law == FrictionLaw::case1) {
    if (!(fin(f.a) && f.a >= 0 && f.a <= f.mu0)) return bad("a", "must be in [0, mu0]");
    if (!(fin(f.b_m_s) && f.b_m_s > 0)) return bad("b_m_s", "must be > 0");
  }
  if (f.law == FrictionLaw::case2) {
    if (!(fin(f.sigma) && f.sigma >= 1)) return bad("sigma", "must be >= 1");
    if (!(fin(f.kappa_s_m) && f.kappa_s_m > 0)) return bad("kappa_s_m", "must be > 0");
    if (!(fin(f.chi_s_m) && f.chi_s_m > 0)) return bad("chi_s_m", "must be > 0");
  }
  if (s.features & rom_feature::axial) {
    if (!(fin(p.actuator_tau_s) && p.actuator_tau_s > 0)) return bad("actuator_tau_s", "must be > 0");
    if (!(fin(p.clamp_max_N) && p.clamp_max_N > 0)) return bad("clamp_max_N", "must be > 0");
    if (!(fin(p.sheave_mass_kg) && p.sheave_mass_kg > 0)) return bad("sheave_mass_kg", "must be > 0");
    if (!(fin(p.sheave_damping_Ns_m) && p.sheave_damping_Ns_m >= 0))
      return bad("sheave_damping_Ns_m", "must be >= 0");
    if (!(fin(p.K_ax_N_m) && p.K_ax_N_m > 0)) return bad("K_ax_N_m", "must be > 0");
  }
  if (s.features & rom_feature::road_load) {
    namespace lim = input_limits;
    if (!(fin(p.road_T0_Nm) && p.road_T0_Nm >= 0 && p.road_T0_Nm <= lim::kRoadT0_Nm))
      return bad("road_T0_Nm", "must be in [0, 1000] N m");
    if (!(fin(p.road_cv_Nms_rad) && p.road_cv_Nms_rad >= 0 && p.road_cv_Nms_rad <= lim::kRoadCv_Nms_rad))
      return bad("road_cv_Nms_rad", "must be in [0, 100] N m s/rad");
    if (!(fin(p.road_ca_Nms2_rad2) && p.road_ca_Nms2_rad2 >= 0 && p.road_ca_Nms2_rad2 <= lim::kRoadCa_Nms2_rad2))
      return bad("road_ca_Nms2_rad2", "must be in [0, 10] N m s^2/rad^2");
    if (!(fin(p.road_w_eps_rad_s) && p.road_w_eps_rad_s >= lim::kRoadWepsMin_rad_s &&
          p.road_w_eps_rad_s <= lim::kRoadWepsMax_rad_s))
      return bad("road_w_eps_rad_s", "must be in [0.001, 1000] rad/s");
  }
  if (s.features & rom_feature::wedging) {
    if (!(s.features & rom_feature::axial)) return bad("features", "wedging needs the axial feature");
    if (s.scalar == ScalarKind::q16_16) return bad("scalar", "wedging runs in double or float only");
    if (!(fin(p.driven_clamp_N) && p.driven_clamp_N > 0)) return bad("driven_clamp_N", "must be > 0");
    if (!(fin(p.radial_mass_kg) && p.radial_mass_kg > 0)) return bad("radial_mass_kg", "must be > 0");
    if (!(fin(p.radial_damping_Ns_m) && p.radial_damping_Ns_m >= 0)) return bad("radial_damping_Ns_m", "must be >= 0");
    if (!(fin(p.radial_travel_m) && p.radial_travel_m > 0 && 2 * p.radial_travel_m < p.r1_m &&
          2 * p.radial_travel_m < p.r2_m))
      return bad("radial_travel_m", "must be in (0, min(r1, r2)/2)");
    if (!(fin(p.radial_stop_N_m) && p.radial_stop_N_m > 0)) return bad("radial_stop_N_m", "must be > 0");
    if (!(fin(p.wrap_tension_share) && p.wrap_tension_share >= 0 && p.wrap_tension_share < 1))
      return bad("wrap_tension_share", "must be in [0, 1)");
    // Eq. 7 divides by 1 + tan(beta) mu g_r/|v| >= 1 - mu_max tan(beta): at
    // mu_max tan(beta) >= 1 the chain self-locks in the groove.
    const double mu_max = f.law == FrictionLaw::case2 ? f.mu0 * f.sigma : f.mu0;
    const double beta_max = p.beta0_rad + 0.01;  // deformation adds < 3e-4 rad
    if (!(mu_max * dm::sin(beta_max) / dm::cos(beta_max) < 0.9))
      return bad("beta0_deg", "wedging needs mu_max tan(beta0) < 0.9 (self-locking groove)");
    if (!(fin(s.initial.radius_offset_m) && s.initial.radius_offset_m > -p.radial_travel_m &&
          s.initial.radius_offset_m < p.radial_travel_m))
      return bad("initial", "radius_offset_m must be within the radial travel");
  }
  if (s.features & rom_feature::tension) {
    // docs/rom.md#tension
    if (!(p.beta0_rad >= 0.01))
      return bad("beta0_deg", "tension needs beta0 >= 0.573 deg: a wrap's axial force is theta1 (T - T_c) / (2 tan beta0)");
    if (!(fin(p.chain_mass_kg_m) && p.chain_mass_kg_m >= 0 && p.chain_mass_kg_m <= 100))
      return bad("chain_mass_kg_m", "must be in [0, 100] kg/m");
    if (!(fin(p.chain_stiffness_N) && p.chain_stiffness_N > 0 && p.chain_stiffness_N <= 1e9))
      return bad("chain_stiffness_N", "must be in (0, 1e9] N");
    if (!(fin(p.creep_gain) && p.creep_gain >= 0 && p.creep_gain <= 10)) return bad("creep_gain", "must be in [0, 10]");
    if (!(fin(p.stop_tension_N) && p.stop_tension_N >= 0 && p.stop_tension_N <= 1e6))
      return bad("stop_tension_N", "must be in [0, 1e6] N");
    if (!(fin(p.stop_tension_share) && p.stop_tension_share >= 0 && p.stop_tension_share <= 1))
      return bad("stop_tension_share", "must be in [0, 1]");
    if (!(fin(p.centrifugal_gain) && p.centrifugal_gain >= 0 && p.centrifugal_gain <= 10))
      return bad("centrifugal_gain", "must be in [0, 10]");
    if (!(fin(p.wrap_excess_share) && p.wrap_excess_share >= -0.5 && p.wrap_excess_share <= 0.5))
      return bad("wrap_excess_share", "must be in [-0.5, 0.5] (the driver wrap's mean between the strands)");
    if (p.fixed_sheaves && (s.features & rom_feature::axial))
      return bad("fixed_sheaves", "fixed sheaves have no clamping actuator: drop the axial feature");
  }
  if (s.features & rom_feature::polygon) {
    if (!(fin(p.pitch_m) && p.pitch_m > 0 && p.pitch_m < 1.5 * p.r1_m)) return bad("pitch_m", "must be in (0, 1.5 r1)");
    // docs/rom.md#link-ripple: F_ax (1 + A cos(theta)) must not press the
    // lumps with a negative load.
    if (!(fin(p.ripple_gain) && p.ripple_gain >= 0 && p.ripple_gain <= 10))
      return bad("ripple_gain", "must be in [0, 10]");
    if (!(rom_ripple_amplitude(p) < 1.0))
      return bad("ripple_gain", "the ripple's amplitude A = gain (2/pi) sin(pi d) / n_w must be below 1");
  }
  const RomInitial& x = s.initial;
  if (!(fin(x.omega1_rad_s) && fin(x.omega2_rad_s) && fin(x.x1_m) && fin(x.xd1_m_s) && fin(x.x2_m) &&
        fin(x.xd2_m_s) && fin(x.phase_rad)))
    return bad("initial", "initial values must be finite");
  if (!(abs_of(x.omega1_rad_s) <= p.speed_limit_rad_s && abs_of(x.omega2_rad_s) <= p.speed_limit_rad_s))
    return bad("initial", "pulley speeds must be within speed_limit_rad_s");
  if (!(fin(s.t_end_s) && s.t_end_s > 0 && s.t_end_s <= 1e5)) return bad("t_end_s", "must be in (0, 1e5] s");
  if (!(fin(s.frame_s) && s.frame_s >= 1e-7 && s.frame_s <= s.t_end_s)) return bad("frame_s", "must be in [1e-7 s, t_end_s]");
  if (SceneIssue i = scene_detail::check_profile(s.tau_in, "tau_in", false, s.frame_s); !i.ok) return i;
  if (SceneIssue i = scene_detail::check_profile(s.tau_load, "tau_load", false, s.frame_s); !i.ok) return i;
  if (SceneIssue i = scene_detail::check_profile(s.clamp, "clamp", true, s.frame_s); !i.ok) return i;
  if (s.substeps < 1 || s.substeps > 10000) return bad("substeps", "must be in 1..10000");
  // docs/rom.md#polygon: 8 steps per link passage at the starting link phase
  // rate, w1 or with tension bounded by the chain speed (docs/rom.md#link-ripple;
  // the watchdog faults step-unresolved when it gets faster).
  if ((s.features & rom_feature::polygon) &&
      rom_polygon_phase_rate_bound_rad_s(p, x.omega1_rad_s, x.omega2_rad_s, (s.features & rom_feature::tension) != 0u,
                                         (s.features & rom_feature::wedging) != 0u ? x.radius_offset_m : 0.0) >
          rom_polygon_resolved_speed_rad_s(p, s.frame_s / s.substeps))
    return bad("substeps", "polygon: the step does not resolve the link passing at the starting speed "
                           "(8 steps per link needed): raise substeps");
  if ((s.log & ~rom_log::all) != 0u) return bad("log", "unknown log group");
  if ((s.log & rom_log::tension) != 0u && (s.features & rom_feature::tension) == 0u)
    return bad("log", "the tension group needs the tension feature");
  if (!s.energy_ledger && (s.log & rom_log::energy) != 0u)
    return bad("log", "the energy group needs energy_ledger = true");
  return SceneIssue{};
}

}  // namespace cvt
