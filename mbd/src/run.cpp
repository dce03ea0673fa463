// Settle, release, integrate, sample (docs/mbd.md#numerics).
#include "cvtplant/mbd/run.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <vector>

#include "integrators.hpp"

namespace cvt::mbd {

namespace {

constexpr long long kSettleStepCap = 1000000;

std::string format_time(double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", t);
  return buf;
}

}  // namespace

RunFailure::RunFailure(double t, const std::string& q)
    : std::runtime_error("at t = " + format_time(t) + " s: " + q), t_s(t), quantity(q) {}

// docs/mbd.md#energy-ledger
double ledger_residual_J(const Sample& s, double energy0_J) {
  const double stored = s.E_kin_J + s.E_el_J - energy0_J;
  const double flows = s.W_in_J - s.W_load_J - s.D_friction_J - s.D_damping_J + s.W_clamp_J;
  return stored - flows;
}

double ledger_scale_J(const Sample& s, double energy0_J, double floor_J) {
  return std::max({floor_J, std::fabs(energy0_J), std::fabs(s.E_kin_J + s.E_el_J), std::fabs(s.W_in_J), std::fabs(s.W_load_J),
                   std::fabs(s.D_friction_J), std::fabs(s.D_damping_J), std::fabs(s.W_clamp_J)});
}

namespace {

// docs/mbd.md#start-at-speed: the spin-up, both speeds imposed, then the hold,
// the driver held and the driven pulley free under the load at t = 0, sampled
// every millisecond for the report (RunStats::hold_samples). Fixed work like
// the settle, at the settle's tolerance.
void start_at_speed(ChainModel& model, std::vector<double>& y, const RunOptions& opt, RunStats& stats) {
  const StartAtSpeed& st = model.params().start;
  auto check = [&](double t, const char* phase) {
    const std::string bad = model.state_problem(y.data());
    if (!bad.empty()) throw RunFailure(t, std::string(phase) + ": " + bad);
  };
  model.set_phase(ChainModel::Phase::spinup);
  {
    auto spin = detail::make_bdf(model, model.spinup_start_s(), y.data(), opt.settle_rtol, kSettleStepCap, false,
                                 opt.linear_solver);
    spin->advance_to(model.hold_start_s(), y.data());
    stats.start_steps += spin->counters().steps;
  }
  // The ramp's end, exactly (the integrated speeds are within the tolerance of it).
  y[static_cast<std::size_t>(model.pulley_speed(0))] = st.omega1_rad_s;
  y[static_cast<std::size_t>(model.pulley_speed(1))] = st.omega2_rad_s;
  check(model.hold_start_s(), "spin-up to speed");
  model.set_phase(ChainModel::Phase::hold);
  auto hold = detail::make_bdf(model, model.hold_start_s(), y.data(), opt.settle_rtol, kSettleStepCap, false,
                               opt.linear_solver);
  const long long n = std::max<long long>(1, std::llround(st.hold_s / 1e-3));
  stats.hold_samples.clear();
  stats.hold_samples.push_back(model.sample(model.hold_start_s(), y.data()));
  for (long long k = 1; k <= n; ++k) {
    // CVODE steps past each time and interpolates: sampling does not move the steps.
    const double t = k == n ? 0.0 : model.hold_start_s() + static_cast<double>(k) * 1e-3;
    hold->advance_to(t, y.data());
    check(t, "holding at speed");
    stats.hold_samples.push_back(model.sample(t, y.data()));
  }
  stats.start_steps += hold->counters().steps;
}

}  // namespace

void detail::settle_and_start(ChainModel& model, std::vector<double>& y, const RunOptions& opt, RunStats& stats) {
  const MbdParams& params = model.params();
  // docs/mbd.md#start-up: the same settle for every method and tolerance, so
  // all runs of a case start from the same released state.
  if (params.settle_s > 0) {
    model.set_phase(ChainModel::Phase::settle);
    // The settle is fixed work (a few thousand steps), outside the user's cap.
    auto settle = detail::make_bdf(model, model.settle_start_s(), y.data(), opt.settle_rtol, kSettleStepCap, false,
                                   opt.linear_solver);
    settle->advance_to(model.spinup_start_s(), y.data());
    const std::string bad = model.state_problem(y.data());
    if (!bad.empty()) throw RunFailure(model.spinup_start_s(), "settling: " + bad);
  }
  if (params.start.active) start_at_speed(model, y, opt, stats);
}

HoldSteadiness hold_steadiness(const std::vector<Sample>& hold, double window_s) {
  if (hold.empty() || !(window_s > 0) || hold.front().t_s > -window_s + 1e-9 || hold.back().t_s < -1e-9)
    throw std::invalid_argument("hold samples do not cover the window");
  HoldSteadiness h;
  h.window_s = window_s;
  double lo = INFINITY, hi = -INFINITY;
  double sum[2][4] = {};  // halves x (omega2, torque, F_ax1, F_ax2)
  int count[2] = {0, 0};
  for (const Sample& s : hold) {
    if (s.t_s < -window_s - 1e-9) continue;
    lo = std::min(lo, s.omega_rad_s[1]);
    hi = std::max(hi, s.omega_rad_s[1]);
    const int half = s.t_s < -0.5 * window_s ? 0 : 1;
    const double v[4] = {s.omega_rad_s[1], s.tau_in_Nm, s.F_ax_N[0], s.F_ax_N[1]};
    for (int k = 0; k < 4; ++k) sum[half][k] += v[k];
    ++count[half];
  }
  double mean[2][4], all[4];
  for (int k = 0; k < 4; ++k) {
    for (int half = 0; half < 2; ++half) mean[half][k] = sum[half][k] / std::max(1, count[half]);
    all[k] = (sum[0][k] + sum[1][k]) / std::max(1, count[0] + count[1]);
  }
  auto change = [&](int k) { return std::fabs(mean[1][k] - mean[0][k]) / std::max(1e-300, std::fabs(all[k])); };
  h.omega2_mean_rad_s = all[0];
  h.omega2_range_rel = (hi - lo) / std::max(1e-300, std::fabs(all[0]));
  h.holding_torque_mean_Nm = all[1];
  h.holding_torque_change_rel = change(1);
  for (int j = 0; j < 2; ++j) {
    h.F_ax_mean_N[j] = all[2 + j];
    h.F_ax_change_rel[j] = change(2 + j);
  }
  return h;
}

RunStats simulate(const MbdParams& params, const RunOptions& opt, const SampleSink& on_sample,
                  const ProgressSink& on_progress) {
  if (!(opt.t_end_s > 0) || !std::isfinite(opt.t_end_s)) throw std::invalid_argument("t_end must be > 0");
  if (!(opt.sample_s > 0) || !std::isfinite(opt.sample_s)) throw std::invalid_argument("sample interval must be > 0");
  if (opt.method == Method::bdf && !(opt.rtol > 0 && opt.rtol < 1)) throw std::invalid_argument("rtol in (0, 1)");
  if (opt.method == Method::rk4 && !(opt.dt_s > 0)) throw std::invalid_argument("dt must be > 0");
  if (opt.method == Method::rk4 && std::llround(opt.t_end_s / opt.dt_s) > opt.max_steps)
    throw std::invalid_argument("t_end / dt = " + std::to_string(std::llround(opt.t_end_s / opt.dt_s)) +
                                " steps exceeds the step cap");
  ChainModel model(params);
  RunStats stats;
  stats.states = model.size();
  stats.jacobian_nnz = model.pattern().nnz();
  std::vector<double> y = model.initial_state();

  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  const std::clock_t cpu_start = std::clock();
  const auto cpu_seconds = [&] { return static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC; };
  detail::settle_and_start(model, y, opt, stats);
  const auto t_released = clock::now();
  stats.settle_wall_s = std::chrono::duration<double>(t_released - t_start).count();
  stats.settle_cpu_s = cpu_seconds();
  model.set_phase(ChainModel::Phase::run);
  if (params.hold1.active) y[static_cast<std::size_t>(model.pulley_speed(0))] = params.hold1.omega_rad_s;
  if (params.hold2.active) y[static_cast<std::size_t>(model.pulley_speed(1))] = params.hold2.omega_rad_s;
  model.reset_ledger(y.data());
  stats.energy0_J = model.energy_J(y.data());
  const double floor_J = model.tolerance_energy_J();
  stats.ledger_floor_J = floor_J;

  double sample_s = opt.sample_s;
  long long samples_after_0 = 0;
  std::unique_ptr<detail::Integrator> integ;
  if (opt.method == Method::rk4) {
    // Samples fall on steps.
    const long long per = std::max<long long>(1, std::llround(opt.sample_s / opt.dt_s));
    sample_s = static_cast<double>(per) * opt.dt_s;
    integ = detail::make_rk4(model, 0.0, y.data(), opt.dt_s, opt.max_steps);
  } else {
    integ = detail::make_bdf(model, 0.0, y.data(), opt.rtol, opt.max_steps, false, opt.linear_solver);
  }
  samples_after_0 = static_cast<long long>(std::ceil(opt.t_end_s / sample_s - 1e-9));

  auto emit = [&](double t) {
    const std::string bad = model.state_problem(y.data());
    if (!bad.empty()) throw RunFailure(t, bad);
    const Sample s = model.sample(t, y.data());
    const double res = std::fabs(ledger_residual_J(s, stats.energy0_J)) / ledger_scale_J(s, stats.energy0_J, floor_J);
    if (!std::isfinite(res)) throw RunFailure(t, "energy ledger is not finite");
    stats.ledger_residual_max_rel = std::max(stats.ledger_residual_max_rel, res);
    if (res > opt.ledger_tol) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "energy ledger residual %.3g (relative) exceeds %.3g", res, opt.ledger_tol);
      throw RunFailure(t, buf);
    }
    ++stats.samples;
    if (on_sample) on_sample(s, model, y.data());
    if (on_progress) on_progress(t);
  };
  try {
    emit(0.0);
    for (long long k = 1; k <= samples_after_0; ++k) {
      const double t = std::min(opt.t_end_s, static_cast<double>(k) * sample_s);
      integ->advance_to(t, y.data());
      emit(t);
    }
  } catch (RunFailure& e) {
    static_cast<SolverCounters&>(stats) = integ->counters();
    stats.wall_s = std::chrono::duration<double>(clock::now() - t_start).count();
    stats.cpu_s = cpu_seconds();
    e.stats = stats;
    throw;
  }
  static_cast<SolverCounters&>(stats) = integ->counters();
  stats.wall_s = std::chrono::duration<double>(clock::now() - t_start).count();
  stats.cpu_s = cpu_seconds();
  return stats;
}

}  // namespace cvt::mbd
