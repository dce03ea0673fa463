#pragma once
// The ROM plant's spectrum and trajectory for a plant of N states
// (docs/analysis.md#rom-lyapunov), the definitions of the templates that
// rom_scenes_detail.hpp declares, for the rom_spectrum_<k>.cpp files that
// instantiate them, one state count each.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/lyapunov.hpp"
#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "rom_scenes_detail.hpp"

namespace cvt::analysis::rom_detail {

// The plant as a Benettin flow of N states, watching the places where its
// vector field is not smooth (docs/analysis.md#rom-lyapunov): the sign
// function at v_rel = 0 (width 1/lambda) and the bolt contact kink at
// delta = 0.
template <int N>
struct RomFlow {
  using Scalar = double;
  static constexpr int kStates = N;
  using V = Eigen::Matrix<double, N, 1>;
  using M = Eigen::Matrix<double, N, N>;
  const Sim* plant;
  int delta = -1;  // index of the bolt compression (axial), else -1
  mutable double min_abs_vrel = std::numeric_limits<double>::infinity();
  mutable double min_delta = std::numeric_limits<double>::infinity();
  mutable double last1 = 0, last2 = 0;
  mutable long sign_changes = 0;

  void derivative(const V& x, V& d) const { plant->derivative(x.data(), d.data()); }
  void jacobian(const V& x, M& J) const {
    plant->jacobian(x.data(), J.data());
    const Outputs o = plant->outputs_at(x.data());
    if (last1 * o.v_rel1_m_s < 0) ++sign_changes;
    if (last2 * o.v_rel2_m_s < 0) ++sign_changes;
    last1 = o.v_rel1_m_s;
    last2 = o.v_rel2_m_s;
    min_abs_vrel = std::min({min_abs_vrel, std::abs(o.v_rel1_m_s), std::abs(o.v_rel2_m_s)});
    if (delta >= 0) min_delta = std::min(min_delta, x(delta));
  }
};

template <int N>
Eigen::Matrix<double, N, 1> state_from(const std::vector<double>& x0) {
  if (static_cast<int>(x0.size()) != N) throw InputError("x0 needs " + std::to_string(N) + " values");
  for (double v : x0)
    if (!std::isfinite(v)) throw InputError("x0 must be finite");
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(x0.data());
}

// Integrates with the scene's own method (ros2) at step h: the plant's
// validated real-time integration (docs/rom.md#real-time-integrator), W with
// the friction slope floor as in the simulator (docs/rom.md#slope-floor).
template <class State>
void advance(const Sim& plant, cvt::Method method, State& x, double h, long steps) {
  for (long i = 0; i < steps; ++i) {
    plant.advance(x.data(), h, method);
    if (!x.allFinite()) throw std::runtime_error("ROM state became non-finite at step " + std::to_string(i));
  }
}

constexpr double kStiffStep = 0.33;  // largest h * |eigenvalue| for RK4 (docs/analysis.md#rom-lyapunov)
constexpr double kQrEfolds = 10.0;   // largest spread of e-folds between two QR steps

template <int N>
SpectrumResult rom_spectrum(const cvt::Scene& base, const std::string& name, const Params& p,
                            const std::vector<double>& x0, const BenettinOptions& o) {
  const cvt::Scene s = apply(base, name, p);
  Holder holder;
  load(holder, s, name);
  const Sim& plant = holder.sim();
  const cvt::RomStateIndex index = cvt::rom_state_index(s.features);
  auto x = state_from<N>(x0);
  if (!(o.dt > 0) || o.t_transient < 0) throw std::invalid_argument("lyapunov: need dt > 0 and t_transient >= 0");
  // Transient with the real-time integrator: it passes the stiff stick phase
  // of the start from rest (eigenvalue ~ -1e7 1/s), which RK4 cannot.
  const double h_tr = s.frame_s / s.substeps;
  const long n_tr = std::lround(o.t_transient / h_tr);
  advance(plant, s.method, x, h_tr, n_tr);
  // The contact stiffness depends on the slip speed the orbit settles at
  // (case 1: ~1.3e4 1/s, case 2: ~5.9e4 1/s), so the RK4 step and the QR
  // interval are bounded by the stiffest eigenvalue rho of J after the
  // transient: h rho <= 0.33 (RK4's error there ~1e-4 relative) and at most
  // 10 e-folds of spread between QR steps (docs/analysis.md#rom-lyapunov).
  double rho = 0;
  {
    Eigen::Matrix<double, N, N> J0;
    plant.jacobian(x.data(), J0.data());
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
  RomFlow<N> flow{&plant, index.delta};
  SpectrumResult r = lyapunov_flow(flow, x, ob);
  r.t_transient = n_tr * h_tr;
  r.steps += n_tr;
  {
    // At a relative equilibrium the exponents are the real parts of J's
    // eigenvalues there: an independent check of the QR machinery.
    Eigen::Matrix<double, N, N> J;
    plant.jacobian(r.x_final.data(), J.data());
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
  if (index.delta >= 0) {
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
  if ((s.features & cvt::rom_feature::road_load) == 0u && !s.params.hold_driver_speed && !s.params.hold_driven_speed) {
    r.symmetry_zero_exponents = 1;
    r.notes.push_back("one exponent is exactly 0 by symmetry: the equations see the pulley speeds only through the "
                      "slip, so (w1, w2) -> (w1 + c, w2 + c r1/r2) maps solutions to solutions; the drive train "
                      "accelerates without bound (no road load), and a constant slip state is a relative "
                      "equilibrium (steady acceleration), which the verdict calls fixed_point");
  }
  return r;
}

template <int N>
std::vector<double> rom_trajectory(const cvt::Scene& base, const std::string& name, const Params& p,
                                   const std::vector<double>& x0, double dt, double t_tr, double t_end,
                                   double sample_dt, const ProgressFn& progress) {
  const cvt::Scene s = apply(base, name, p);
  Holder holder;
  load(holder, s, name);
  const Sim& plant = holder.sim();
  auto x = state_from<N>(x0);
  if (!(dt > 0) || !(sample_dt > 0) || !(t_end > 0) || t_tr < 0)
    throw InputError("trajectory: need dt, sample_dt, t_end > 0 and t_transient >= 0");
  const long n_tr = std::lround(t_tr / dt);
  const long every = std::max(1L, std::lround(sample_dt / dt)), n = std::lround(t_end / dt);
  if (progress) progress(0.0, static_cast<double>(n_tr + n));
  advance(plant, s.method, x, dt, n_tr);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n / every + 1) * N);
  for (long i = 1; i <= n; ++i) {
    if ((i & 4095) == 0 && progress) progress(static_cast<double>(n_tr + i), static_cast<double>(n_tr + n));
    advance(plant, s.method, x, dt, 1);
    if (i % every == 0)
      for (int k = 0; k < N; ++k) out.push_back(x(k));
  }
  return out;
}

// Explicit instantiation for the k-th state count (rom_spectrum_<k>.cpp).
#define CVT_ROM_SCENES_INSTANTIATE(k)                                                                           \
  static_assert((k) < kRomStateCounts.size(), "no state count k");                                             \
  template SpectrumResult rom_spectrum<kRomStateCounts[k]>(const cvt::Scene&, const std::string&, const Params&, \
                                                           const std::vector<double>&, const BenettinOptions&); \
  template std::vector<double> rom_trajectory<kRomStateCounts[k]>(                                              \
      const cvt::Scene&, const std::string&, const Params&, const std::vector<double>&, double, double, double,  \
      double, const ProgressFn&);

// One rom_spectrum_<k>.cpp per state count: a new count (a feature with
// states of its own) needs a file of its own, else its spectrum would not
// link.
static_assert(kRomStateCounts.size() == 6, "add rom_spectrum_<k>.cpp for the new state count");

}  // namespace cvt::analysis::rom_detail
