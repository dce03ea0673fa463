// The reduced-order CVT plant in the analysis toolkit (docs/analysis.md#rom-scenes).
#include "cvtplant/analysis/rom_scenes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt::analysis {
namespace {

using Outputs = cvt::RomOutputs<double>;

struct SignalDef {
  const char* name;
  double Outputs::*member;
};
constexpr SignalDef kSignals[] = {
    {"F_ax", &Outputs::clamp_force_N},        {"torque_transmitted", &Outputs::torque_transmitted_Nm},
    {"slip", &Outputs::slip},                 {"v_rel1", &Outputs::v_rel1_m_s},
    {"v_rel2", &Outputs::v_rel2_m_s},         {"F1", &Outputs::friction1_N},
    {"F2", &Outputs::friction2_N},            {"omega1", &Outputs::omega1_rad_s},
    {"omega2", &Outputs::omega2_rad_s},       {"speed_ratio", &Outputs::speed_ratio},
};

const cvt::Scene& builtin(const std::string& name) {
  if (const cvt::Scene* s = cvt::find_builtin_scene(name.c_str())) return *s;
  std::string known;
  for (const cvt::Scene& s : cvt::kBuiltinScenes) known += (known.empty() ? "" : ", ") + std::string(s.name);
  throw InputError("unknown ROM scene '" + name + "' (built-in: " + known + ")");
}

// The feature sets the toolkit instantiates (each is a separate plant type).
template <class Fn>
void with_features(std::uint32_t mask, const std::string& scene, Fn&& fn) {
  using cvt::rom_feature::axial;
  using cvt::rom_feature::road_load;
  switch (mask) {
    case 0: fn(std::integral_constant<std::uint32_t, 0>{}); return;
    case axial: fn(std::integral_constant<std::uint32_t, axial>{}); return;
    case axial | road_load: fn(std::integral_constant<std::uint32_t, axial | road_load>{}); return;
    default: break;
  }
  throw InputError("scene '" + scene + "': its feature set is not instantiated by the analysis toolkit (none, axial, "
                   "axial+road_load are)");
}

// The plant as a Benettin flow, watching the places where its vector field is
// not smooth (docs/analysis.md#rom-lyapunov): the sign function at v_rel = 0
// (width 1/lambda) and the bolt contact kink at delta = 0.
template <std::uint32_t F>
struct RomFlow {
  using Plant = cvt::CvtRom<double, F>;
  using Scalar = double;
  static constexpr int kStates = Plant::kStates;
  const Plant* plant;
  mutable double min_abs_vrel = std::numeric_limits<double>::infinity();
  mutable double min_delta = std::numeric_limits<double>::infinity();
  mutable double last1 = 0, last2 = 0;
  mutable long sign_changes = 0;

  template <class S>
  void derivative(const Eigen::Matrix<S, kStates, 1>& x, Eigen::Matrix<S, kStates, 1>& d) const {
    plant->derivative(x, d);
  }
  void jacobian(const Eigen::Matrix<double, kStates, 1>& x, Eigen::Matrix<double, kStates, kStates>& J) const {
    plant->jacobian(x, J);
    const Outputs o = plant->outputs(x);
    if (last1 * o.v_rel1_m_s < 0) ++sign_changes;
    if (last2 * o.v_rel2_m_s < 0) ++sign_changes;
    last1 = o.v_rel1_m_s;
    last2 = o.v_rel2_m_s;
    min_abs_vrel = std::min({min_abs_vrel, std::abs(o.v_rel1_m_s), std::abs(o.v_rel2_m_s)});
    if constexpr (cvt::RomLayout<F>::kAxial) min_delta = std::min(min_delta, x(cvt::RomLayout<F>::kDelta));
  }
};

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[320];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

// Scene parameters that `--param` may change: the three constant inputs and mu0.
Params rom_params_of(const cvt::Scene& s) {
  return {{"tau_in_Nm", s.tau_in.value},
          {"tau_load_Nm", s.tau_load.value},
          {"clamp_N", s.clamp.value},
          {"mu0", s.params.friction.mu0}};
}
cvt::Scene apply(const cvt::Scene& base, const Params& p) {
  cvt::Scene s = base;
  s.tau_in = cvt::constant_profile(p.at("tau_in_Nm"));
  s.tau_load = cvt::constant_profile(p.at("tau_load_Nm"));
  s.clamp = cvt::constant_profile(p.at("clamp_N"));
  s.params.friction.mu0 = p.at("mu0");
  const cvt::SceneIssue issue = cvt::validate_scene(s);
  if (!issue.ok) throw InputError(std::string("scene '") + base.name + "': " + issue.field + ": " + issue.message);
  return s;
}

template <std::uint32_t F>
Eigen::Matrix<double, cvt::CvtRom<double, F>::kStates, 1> state_from(const std::vector<double>& x0) {
  constexpr int N = cvt::CvtRom<double, F>::kStates;
  if (static_cast<int>(x0.size()) != N) throw InputError("x0 needs " + std::to_string(N) + " values");
  for (double v : x0)
    if (!std::isfinite(v)) throw InputError("x0 must be finite");
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(x0.data());
}

// Integrates with the scene's own method (ros2) at step h: the plant's
// validated real-time integration (docs/rom.md#real-time-integrator), W with
// the friction slope floor as in RomSimulator (docs/rom.md#slope-floor).
template <std::uint32_t F, class State>
void advance(const cvt::CvtRom<double, F>& plant, cvt::Method method, State& x, double h, long steps) {
  for (long i = 0; i < steps; ++i) {
    cvt::rom_step(method, plant, x, h, true);
    plant.wrap(x);
    if (!x.allFinite()) throw std::runtime_error("ROM state became non-finite at step " + std::to_string(i));
  }
}

constexpr double kStiffStep = 0.33;  // largest h * |eigenvalue| for RK4 (docs/analysis.md#rom-lyapunov)
constexpr double kQrEfolds = 10.0;   // largest spread of e-folds between two QR steps

template <std::uint32_t F>
SpectrumResult rom_spectrum(const cvt::Scene& base, const Params& p, const std::vector<double>& x0,
                            const BenettinOptions& o) {
  using L = cvt::RomLayout<F>;
  const cvt::Scene s = apply(base, p);
  cvt::CvtRom<double, F> plant(s.params);
  plant.inputs = cvt::scene_inputs_at<double>(s, 0.0);
  auto x = state_from<F>(x0);
  if (!(o.dt > 0) || o.t_transient < 0) throw std::invalid_argument("lyapunov: need dt > 0 and t_transient >= 0");
  // Transient with the real-time integrator: it passes the stiff stick phase
  // of the start from rest (eigenvalue ~ -1e7 1/s), which RK4 cannot.
  const double h_tr = s.frame_s / s.substeps;
  const long n_tr = std::lround(o.t_transient / h_tr);
  advance<F>(plant, s.method, x, h_tr, n_tr);
  // The contact stiffness depends on the slip speed the orbit settles at
  // (case 1: ~1.3e4 1/s, case 2: ~5.9e4 1/s), so the RK4 step and the QR
  // interval are bounded by the stiffest eigenvalue rho of J after the
  // transient: h rho <= 0.33 (RK4's error there ~1e-4 relative) and at most
  // 10 e-folds of spread between QR steps (docs/analysis.md#rom-lyapunov).
  double rho = 0;
  {
    typename cvt::CvtRom<double, F>::Jacobian J0;
    plant.jacobian(x, J0);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(J0), false);
    for (int i = 0; i < J0.rows(); ++i) rho = std::max(rho, std::abs(es.eigenvalues()(i)));
  }
  BenettinOptions ob = o;
  ob.t_transient = 0;
  if (rho > 0) {
    ob.dt = std::min(o.dt, kStiffStep / rho);
    const double renorm = o.t_renorm > 0 ? o.t_renorm : std::max(o.dt, 0.05);
    ob.t_renorm = std::max(ob.dt, std::min(renorm, kQrEfolds / rho));
  }
  RomFlow<F> flow{&plant};
  SpectrumResult r = lyapunov_flow(flow, x, ob);
  r.t_transient = n_tr * h_tr;
  r.steps += n_tr;
  {
    // At a relative equilibrium the exponents are the real parts of J's
    // eigenvalues there: an independent check of the QR machinery.
    typename cvt::CvtRom<double, F>::Jacobian J;
    plant.jacobian(Eigen::Map<const typename cvt::CvtRom<double, F>::State>(r.x_final.data()), J);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(J), false);
    for (int i = 0; i < J.rows(); ++i) r.jacobian_eigen_real_final.push_back(es.eigenvalues()(i).real());
    std::sort(r.jacobian_eigen_real_final.rbegin(), r.jacobian_eigen_real_final.rend());
  }
  const double lambda = s.params.friction.lambda_s_m;
  r.diagnostics["stiffest_eigenvalue_modulus_1_s"] = rho;
  r.notes.push_back(fmt("RK4 step %.3g s and QR every %.3g s, from the stiffest eigenvalue |%.4g| 1/s after the "
                        "transient (h rho <= 0.33; the --dt given is an upper bound)",
                        r.dt, r.t_renorm, rho));
  r.diagnostics["min_abs_v_rel_m_s"] = flow.min_abs_vrel;
  r.diagnostics["v_rel_sign_changes"] = static_cast<double>(flow.sign_changes);
  r.diagnostics["sign_function_width_m_s"] = 1.0 / lambda;
  r.notes.push_back("transient integrated with the scene's " + std::string(cvt::method_name(s.method)) + " at h = " +
                    fmt("%g s; Benettin (RK4 on the variational equations) from there", h_tr));
  // The vector field is smooth except at v_rel = 0 (sign function, width
  // 1/lambda) and delta = 0 (bolt contact). 10 widths keeps the atan slope
  // below 1% of its peak.
  r.smooth_along_orbit = flow.sign_changes == 0 && flow.min_abs_vrel > 10.0 / lambda;
  if constexpr (L::kAxial) {
    r.diagnostics["min_delta_m"] = flow.min_delta;
    if (!(flow.min_delta > 0)) r.smooth_along_orbit = false;
    // The axial subsystem is linear and one-way coupled: its exponents are
    // known in closed form (docs/analysis.md#rom-lyapunov).
    const double a = -1.0 / s.params.actuator_tau_s;
    const double zc = s.params.sheave_damping_Ns_m / (2.0 * s.params.sheave_mass_kg);
    const double w2 = s.params.K_ax_N_m / s.params.sheave_mass_kg;
    r.diagnostics["axial_actuator_exponent"] = a;
    if (zc * zc < w2) {
      r.diagnostics["axial_sheave_exponent"] = -zc;
      r.notes.push_back(fmt("axial subsystem (one-way coupled, linear): exact exponents %.6g (actuator lag) and "
                            "%.6g twice (sheave mode)",
                            a, -zc));
    }
  }
  if (r.smooth_along_orbit) {
    r.notes.push_back(fmt("the orbit stays in the smooth region: min |v_rel| = %.4g m/s = %.3g sign-function widths, "
                          "no sign change of v_rel",
                          flow.min_abs_vrel, flow.min_abs_vrel * lambda));
  } else {
    r.notes.push_back(fmt("UNRELIABLE: the orbit crosses or nears a kink of the vector field (min |v_rel| = %.3g m/s, "
                          "%g sign changes; the sign function's width is %.3g m/s): RK4 Jacobians there are not "
                          "resolved and the exponents are not trustworthy",
                          flow.min_abs_vrel, static_cast<double>(flow.sign_changes), 1.0 / lambda));
  }
  // Without speed-dependent load and with both pulleys free, the equations
  // depend on the speeds only through v_rel = r2 w2 + xd_i - r1 w1: shifting
  // (w1, w2) by (c, c r1/r2) is a symmetry, so one exponent is exactly 0.
  if (!L::kRoad && !s.params.hold_driver_speed && !s.params.hold_driven_speed) {
    r.symmetry_zero_exponents = 1;
    r.notes.push_back("one exponent is exactly 0 by symmetry: the equations see the pulley speeds only through the "
                      "slip, so (w1, w2) -> (w1 + c, w2 + c r1/r2) maps solutions to solutions; the drive train "
                      "accelerates without bound (no road load), and a constant slip state is a relative "
                      "equilibrium (steady acceleration), which the verdict calls fixed_point");
  }
  return r;
}

template <std::uint32_t F>
std::vector<double> rom_trajectory(const cvt::Scene& base, const Params& p, const std::vector<double>& x0, double dt,
                                   double t_tr, double t_end, double sample_dt) {
  constexpr int N = cvt::CvtRom<double, F>::kStates;
  const cvt::Scene s = apply(base, p);
  cvt::CvtRom<double, F> plant(s.params);
  plant.inputs = cvt::scene_inputs_at<double>(s, 0.0);
  auto x = state_from<F>(x0);
  if (!(dt > 0) || !(sample_dt > 0) || !(t_end > 0) || t_tr < 0)
    throw InputError("trajectory: need dt, sample_dt, t_end > 0 and t_transient >= 0");
  advance<F>(plant, s.method, x, dt, std::lround(t_tr / dt));
  const long every = std::max(1L, std::lround(sample_dt / dt)), n = std::lround(t_end / dt);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n / every + 1) * N);
  for (long i = 1; i <= n; ++i) {
    advance<F>(plant, s.method, x, dt, 1);
    if (i % every == 0)
      for (int k = 0; k < N; ++k) out.push_back(x(k));
  }
  return out;
}

}  // namespace

const std::vector<std::string>& rom_signal_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& d : kSignals) v.push_back(d.name);
    return v;
  }();
  return names;
}

RomSeries rom_scene_series(const std::string& scene, const std::vector<std::string>& signals, double t_end) {
  cvt::Scene s = builtin(scene);
  if (t_end > 0) s.t_end_s = t_end;
  std::vector<const SignalDef*> defs;
  for (const auto& name : signals) {
    const SignalDef* d = nullptr;
    for (const auto& k : kSignals)
      if (name == k.name) d = &k;
    if (d == nullptr) {
      std::string known;
      for (const auto& k : kSignals) known += (known.empty() ? "" : ", ") + std::string(k.name);
      throw InputError("unknown signal '" + name + "' (known: " + known + ")");
    }
    defs.push_back(d);
  }
  RomSeries r;
  r.scene = s.name;
  r.frame_s = s.frame_s;
  with_features(s.features, scene, [&](auto fc) {
    constexpr std::uint32_t F = decltype(fc)::value;
    const cvt::RomFault fault =
        cvt::run_scene<double, F>(s, cvt::sim_config_of(s), [&](long, double t, const cvt::RomSimulator<double, F>& sim) {
          const Outputs o = sim.outputs();
          r.t.push_back(t);
          for (const SignalDef* d : defs) r.signal[d->name].push_back(o.*(d->member));
          return true;
        });
    r.fault = cvt::rom_fault_name(fault);
  });
  return r;
}

void add_rom_scenes(std::vector<Scene>& table) {
  // Not gross-slip: there the friction saturates (|v_rel| ~ 86 m/s), so each
  // pulley speed is separately neutral and the one-symmetry count below would
  // call the motion periodic (docs/analysis.md#rom-lyapunov).
  for (const char* name : {"seed-case1", "seed-case2"}) {
    const cvt::Scene& b = builtin(name);
    Scene s;
    s.name = name;
    s.description = std::string("ROM plant (docs/rom.md): ") + b.summary;
    with_features(b.features, name, [&](auto fc) {
      constexpr std::uint32_t F = decltype(fc)::value;
      using L = cvt::RomLayout<F>;
      s.dim = L::kStates;
      s.state_names = {"omega1", "omega2", "x1", "xd1", "x2", "xd2"};
      if (L::kAxial) s.state_names.insert(s.state_names.end(), {"F_h", "delta", "delta_dot"});
      cvt::CvtRom<double, F> plant(b.params);
      plant.inputs = cvt::scene_inputs_at<double>(b, 0.0);
      const auto x0 = plant.initial_state(b.initial);
      s.default_x0.assign(x0.data(), x0.data() + L::kStates);
      s.spectrum = [&b](const Params& p, const std::vector<double>& x, const BenettinOptions& o) {
        return rom_spectrum<F>(b, p, x, o);
      };
      s.trajectory = [&b](const Params& p, const std::vector<double>& x, double dt, double a, double t, double c) {
        return rom_trajectory<F>(b, p, x, dt, a, t, c);
      };
    });
    s.default_params = rom_params_of(b);
    // docs/analysis.md#rom-lyapunov: upper bounds; rom_spectrum shortens both
    // from the stiffest eigenvalue after the transient (the lump contact modes,
    // -1.3e4 1/s in case 1: at 1e-4 s RK4's own damping ln|R(h lambda)|/h would
    // replace them and the trace check would miss by 5 %). The start from rest
    // (stick, ~ -1e7 1/s) is left to the ros2 transient.
    s.defaults.dt = 1e-4;
    s.defaults.t_renorm = 1e-3;
    s.defaults.t_transient = 30;
    s.defaults.t_warmup = 5;  // > 4 / (torsional decay ~0.95 1/s): separates it from the symmetry direction
    s.defaults.t_end = 20;
    table.push_back(std::move(s));
  }
}

}  // namespace cvt::analysis
