#pragma once
// Lyapunov spectra from the equations (docs/analysis.md#benettin): Benettin's
// method, QR re-orthonormalisation of the variational equations, classical
// RK4 on the augmented system [x, Y] with fixed step dt.
//
// A flow is any type with (the same concept as cvt::integrate, system.hpp)
//   static constexpr int kStates;
//   template <class S> void derivative(const Eigen::Matrix<S,N,1>&, Eigen::Matrix<S,N,1>&) const;
//   void jacobian(const Eigen::Matrix<double,N,1>&, Eigen::Matrix<double,N,N>&) const;
// A map has kStates, step(x, x_next) and jacobian(x, J).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"
#include "cvtplant/integrate/explicit_rk.hpp"

namespace cvt::analysis {

struct BenettinOptions {
  double dt = 0.01;            // RK4 step (flows)
  double t_transient = 100;    // discarded: state only (flows: time; maps: iterations)
  double t_warmup = 10;        // deviation vectors evolved and re-orthonormalised, not accumulated
  double t_end = 1000;         // accumulation length
  double t_renorm = -1;        // QR interval (flows); -1: max(dt, 0.05) rounded to whole steps
  int batches = 20;            // batch means for the confidence interval
  // Cap on the steps (maps: iterations) of one run, checked before it
  // starts (LimitError); 0: only the 1e15 that keeps the counts exact.
  double max_steps = 0;
  // Called every few thousand steps with (steps done, steps in all), e.g. by
  // a progress bar; empty: not called.
  std::function<void(double done, double total)> progress;
};

namespace detail {
// Refuses, before any step, a run whose step count exceeds the cap.
inline void check_work(double steps, const BenettinOptions& opt, double dt) {
  const double cap = opt.max_steps > 0 && opt.max_steps < 1e15 ? opt.max_steps : 1e15;
  if (!(steps <= cap)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "lyapunov: the run needs %.3g steps (dt %g), above the cap of %g", steps, dt, cap);
    throw LimitError(buf, steps);
  }
}
}  // namespace detail

struct ConvergenceRow {
  double t = 0;
  std::vector<double> exponents;
};

struct SpectrumResult {
  std::vector<double> exponents;  // descending
  std::vector<double> ci95;       // half-widths, batch means + Student t
  std::vector<double> batch_sd;   // spread of the batch estimates
  double sum = 0;                 // sum of exponents
  double trace_mean = 0;          // time average of trace(J) (maps: of ln|det J|)
  std::vector<ConvergenceRow> convergence;  // cumulative estimates at T/64 .. T
  // lambda_1(t) = a + b/t fitted over the convergence rows with t >= T/16:
  // a regular orbit's neutral exponent decays like 1/t (docs).
  double lambda1_extrapolated = 0, lambda1_extrapolated_se = 0;
  // (1/T) ln(|f(x_T)| / |f(x_0)|): growth of the flow direction, the exact
  // neutral exponent for a bounded orbit away from fixed points (flows only).
  double flow_direction_rate = 0;
  double final_speed = 0;         // |f(x_T)|: ~0 at a fixed point
  int zero_index = -1;            // exponent closest to 0 (flows), -1 for maps
  std::vector<double> x_final;
  long steps = 0;
  double dt = 0, t_transient = 0, t_warmup = 0, t_end = 0, t_renorm = 0;
  bool is_map = false;
  // Filled by scenes that know more about their equations (docs/analysis.md#rom-lyapunov):
  int symmetry_zero_exponents = 0;  // exponents that are 0 by a continuous symmetry, besides the flow's own
  bool smooth_along_orbit = true;   // false: the orbit met a kink of the vector field (spectrum unreliable)
  std::vector<std::string> notes;
  std::map<std::string, double> diagnostics;
  // Real parts of the eigenvalues of J(x_final), descending: at a (relative)
  // equilibrium the exponents converge to exactly these (empty if not computed).
  std::vector<double> jacobian_eigen_real_final;
};

namespace detail {

// Re-orthonormalise Y = QR with positive diag(R); returns ln R_ii in `logs`.
template <int N>
void qr_renorm(Eigen::Matrix<double, N, N>& Y, Eigen::Matrix<double, N, 1>& logs) {
  Eigen::HouseholderQR<Eigen::Matrix<double, N, N>> qr(Y);
  Eigen::Matrix<double, N, N> Q = qr.householderQ() * Eigen::Matrix<double, N, N>::Identity();
  const auto& R = qr.matrixQR();
  for (int i = 0; i < Y.cols(); ++i) {
    const double r = R(i, i);
    if (r < 0) Q.col(i) = -Q.col(i);
    logs(i) = std::log(std::abs(r));
  }
  Y = Q;
}

// The variational system of a flow for Benettin's method: z = [x, Y, q] with
// x' = f(x), Y' = J(x) Y (N x N, column-major) and q' = trace J(x), so one RK4
// step advances the state, the deviation vectors and the trace integral with
// the same weights (the trace mean checks the exponents' sum). z is a dynamic
// vector: its N + N^2 + 1 entries only meet elementwise in the RK4 stages,
// and fixed sizes of up to 157 entries would cost minutes of compile time
// per plant size; x, J and Y stay fixed-size.
template <class Flow>
struct Variational {
  static constexpr int N = Flow::kStates;
  using Scalar = double;
  static constexpr int kStates = Eigen::Dynamic;
  static constexpr int kSize = N + N * N + 1;
  static constexpr int kTrace = N + N * N;
  using State = Eigen::VectorXd;
  const Flow& flow;

  void derivative(const State& z, State& dz) const {
    dz.resize(kSize);
    const Eigen::Matrix<double, N, 1> x = z.template head<N>();
    Eigen::Matrix<double, N, 1> f;
    Eigen::Matrix<double, N, N> J;
    flow.derivative(x, f);
    flow.jacobian(x, J);
    const Eigen::Matrix<double, N, N> Y = Eigen::Map<const Eigen::Matrix<double, N, N>>(z.data() + N);
    Eigen::Matrix<double, N, N> JY;
    JY.noalias() = J * Y;
    dz.template head<N>() = f;
    Eigen::Map<Eigen::Matrix<double, N, N>> dY(dz.data() + N);
    dY = JY;
    dz(kTrace) = J.trace();
  }
};

inline void finish_stats(SpectrumResult& r, const std::vector<std::vector<double>>& batch, int n) {
  const int B = static_cast<int>(batch.size());
  r.ci95.assign(n, 0.0);
  r.batch_sd.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double m = 0;
    for (const auto& b : batch) m += b[i];
    m /= B;
    double v = 0;
    for (const auto& b : batch) v += (b[i] - m) * (b[i] - m);
    const double sd = B > 1 ? std::sqrt(v / (B - 1)) : 0.0;
    r.batch_sd[i] = sd;
    r.ci95[i] = B > 1 ? t95(B - 1) * sd / std::sqrt(static_cast<double>(B)) : 0.0;
  }
  r.sum = 0;
  for (double e : r.exponents) r.sum += e;
  // 1/t extrapolation of lambda_1 (docs/analysis.md#convergence).
  std::vector<double> xs, ys;
  const double T = r.convergence.empty() ? 0 : r.convergence.back().t;
  for (const auto& row : r.convergence)
    if (row.t >= T / 16 - 1e-12) {
      xs.push_back(1.0 / row.t);
      ys.push_back(row.exponents[0]);
    }
  if (xs.size() >= 3) {
    const LineFit f = fit_line(xs.data(), ys.data(), xs.size());
    r.lambda1_extrapolated = f.intercept;
    // se of the intercept: se_slope * sqrt(mean(x^2)).
    double mx2 = 0;
    for (double v : xs) mx2 += v * v;
    r.lambda1_extrapolated_se = f.slope_se * std::sqrt(mx2 / xs.size());
  } else if (!r.exponents.empty()) {
    r.lambda1_extrapolated = r.exponents[0];
  }
}

// One batch's exponents, the sums of its log stretches over its length tb;
// the sums start again from zero.
template <int N>
void push_batch(std::vector<std::vector<double>>& batch, Eigen::Matrix<double, N, 1>& batch_acc, double tb) {
  std::vector<double> b(N);
  for (int i = 0; i < N; ++i) b[i] = batch_acc(i) / tb;
  batch.push_back(b);
  batch_acc.setZero();
}

// The running estimate acc / t (sorted) as a convergence row, when `done`
// of the n_acc accumulated steps reaches next_conv (which then doubles) or
// the end.
template <int N>
void convergence_row(SpectrumResult& r, const Eigen::Matrix<double, N, 1>& acc, long done, long n_acc, double t,
                     long& next_conv) {
  if (done < next_conv && done != n_acc) return;
  ConvergenceRow row;
  row.t = t;
  for (int i = 0; i < N; ++i) row.exponents.push_back(acc(i) / row.t);
  std::sort(row.exponents.rbegin(), row.exponents.rend());
  r.convergence.push_back(row);
  while (next_conv <= done) next_conv *= 2;
  if (next_conv > n_acc) next_conv = n_acc;
}

}  // namespace detail

// docs/analysis.md#benettin
template <class Flow>
SpectrumResult lyapunov_flow(const Flow& sys, const Eigen::Matrix<double, Flow::kStates, 1>& x0,
                             const BenettinOptions& opt) {
  constexpr int N = Flow::kStates;
  using V = Eigen::Matrix<double, N, 1>;
  using M = Eigen::Matrix<double, N, N>;
  if (!(opt.dt > 0) || !(opt.t_end > 0) || opt.t_transient < 0 || opt.t_warmup < 0)
    throw std::invalid_argument("lyapunov: need dt > 0, t_end > 0, t_transient >= 0, t_warmup >= 0");
  if (opt.batches < 2) throw std::invalid_argument("lyapunov: need at least 2 batches");
  detail::check_work((opt.t_transient + opt.t_warmup + opt.t_end) / opt.dt, opt, opt.dt);
  SpectrumResult r;
  const double h = opt.dt;
  const long renorm_steps =
      std::max(1L, std::lround((opt.t_renorm > 0 ? opt.t_renorm : std::max(opt.dt, 0.05)) / h));
  r.dt = h;
  r.t_renorm = renorm_steps * h;
  const long n_trans = std::lround(opt.t_transient / h);
  const long n_warm = std::lround(opt.t_warmup / h / renorm_steps) * renorm_steps;
  long n_acc = std::lround(opt.t_end / h / renorm_steps);
  n_acc = std::max<long>(n_acc, opt.batches) / opt.batches * opt.batches;  // whole batches of QR intervals
  const long qr_per_batch = n_acc / opt.batches;
  n_acc *= renorm_steps;
  r.t_transient = n_trans * h;
  r.t_warmup = n_warm * h;
  r.t_end = n_acc * h;

  V x = x0;
  auto check = [&](long step) {
    if (!x.allFinite())
      throw std::runtime_error("lyapunov: state became non-finite at step " + std::to_string(step) +
                               " (dt too large for this system?)");
  };
  // Transient: state only.
  const double all_steps = static_cast<double>(n_trans + n_warm + n_acc);
  for (long s = 0; s < n_trans; ++s) {
    step_rk4(sys, x, h);
    if ((s & 1023) == 0) check(s);
    if ((s & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(s), all_steps);
  }
  check(n_trans);
  // RK4 (the core's, integrate/explicit_rk.hpp) on the variational system
  // z = [x, Y, integral of trace J] (detail::Variational).
  using Aug = detail::Variational<Flow>;
  const Aug aug{sys};
  typename Aug::State z = Aug::State::Zero(Aug::kSize);
  z.template head<N>() = x;
  Eigen::Map<M> Y(z.data() + N);
  Y.setIdentity();
  double& trace_int = z(Aug::kTrace);
  trace_int = 0;
  V logs, acc = V::Zero(), batch_acc = V::Zero();
  std::vector<std::vector<double>> batch;
  V f0;
  sys.derivative(x, f0);
  const long total = n_warm + n_acc;
  long next_conv = std::max(1L, n_acc / 64);
  long qr_count = 0;
  for (long s = 0; s < total; ++s) {
    const bool accumulating = s >= n_warm;
    if (s == n_warm) {
      x = z.template head<N>();
      sys.derivative(x, f0);
      trace_int = 0;  // the trace is integrated over the accumulation only
    }
    step_rk4(aug, z, h);
    if ((s & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(n_trans + s), all_steps);
    if ((s + 1) % renorm_steps == 0) {
      x = z.template head<N>();
      check(n_trans + s);
      M Yq = Y;
      detail::qr_renorm<N>(Yq, logs);
      Y = Yq;
      if (accumulating) {
        acc += logs;
        batch_acc += logs;
        ++qr_count;
        if (qr_count % qr_per_batch == 0) detail::push_batch<N>(batch, batch_acc, qr_per_batch * renorm_steps * h);
        const long done = s + 1 - n_warm;
        detail::convergence_row<N>(r, acc, done, n_acc, done * h, next_conv);
      }
    }
  }
  // QR keeps the columns ordered by growth on average; sort for safety.
  for (int i = 0; i < N; ++i) r.exponents.push_back(acc(i) / r.t_end);
  std::vector<int> order(N);
  for (int i = 0; i < N; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return r.exponents[a] > r.exponents[b]; });
  std::vector<double> sorted;
  std::vector<std::vector<double>> bsorted(batch.size(), std::vector<double>(N));
  for (int i = 0; i < N; ++i) {
    sorted.push_back(r.exponents[order[i]]);
    for (std::size_t b = 0; b < batch.size(); ++b) bsorted[b][i] = batch[b][order[i]];
  }
  r.exponents = sorted;
  r.trace_mean = trace_int / r.t_end;
  x = z.template head<N>();
  V fT;
  sys.derivative(x, fT);
  r.final_speed = fT.norm();
  r.flow_direction_rate = (f0.norm() > 0 && fT.norm() > 0) ? std::log(fT.norm() / f0.norm()) / r.t_end : 0.0;
  int zi = 0;
  for (int i = 1; i < N; ++i)
    if (std::abs(r.exponents[i]) < std::abs(r.exponents[zi])) zi = i;
  r.zero_index = zi;
  r.x_final.assign(x.data(), x.data() + N);
  r.steps = n_trans + total;
  detail::finish_stats(r, bsorted, N);
  return r;
}

// Maps: t_* options are iteration counts (docs/analysis.md#benettin-maps).
template <class Map>
SpectrumResult lyapunov_map(const Map& sys, const Eigen::Matrix<double, Map::kStates, 1>& x0,
                            const BenettinOptions& opt) {
  constexpr int N = Map::kStates;
  using V = Eigen::Matrix<double, N, 1>;
  using M = Eigen::Matrix<double, N, N>;
  if (!(opt.t_end >= opt.batches) || opt.t_transient < 0 || opt.t_warmup < 0)
    throw std::invalid_argument("lyapunov: maps need t_end >= batches iterations");
  detail::check_work(opt.t_transient + opt.t_warmup + opt.t_end, opt, 1);
  SpectrumResult r;
  r.is_map = true;
  r.dt = 1;
  r.t_renorm = 1;
  const long n_trans = std::lround(opt.t_transient), n_warm = std::lround(opt.t_warmup);
  const long n_acc = std::lround(opt.t_end) / opt.batches * opt.batches;
  const long per_batch = n_acc / opt.batches;
  r.t_transient = static_cast<double>(n_trans);
  r.t_warmup = static_cast<double>(n_warm);
  r.t_end = static_cast<double>(n_acc);
  V x = x0, xn;
  const double all_steps = static_cast<double>(n_trans + n_warm + n_acc);
  for (long s = 0; s < n_trans; ++s) {
    sys.step(x, xn);
    x = xn;
    if ((s & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(s), all_steps);
  }
  if (!x.allFinite()) throw std::runtime_error("lyapunov: map orbit diverged during the transient");
  M Y = M::Identity(), J;
  V logs, acc = V::Zero(), bacc = V::Zero();
  double logdet = 0;
  std::vector<std::vector<double>> batch;
  long next_conv = std::max(1L, n_acc / 64);
  for (long s = 0; s < n_warm + n_acc; ++s) {
    if ((s & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(n_trans + s), all_steps);
    sys.jacobian(x, J);
    sys.step(x, xn);
    x = xn;
    Y = (J * Y).eval();
    detail::qr_renorm<N>(Y, logs);
    if (!x.allFinite()) throw std::runtime_error("lyapunov: map orbit diverged at iteration " + std::to_string(s));
    if (s < n_warm) continue;
    acc += logs;
    bacc += logs;
    logdet += std::log(std::abs(J.determinant()));
    const long done = s + 1 - n_warm;
    if (done % per_batch == 0) detail::push_batch<N>(batch, bacc, static_cast<double>(per_batch));
    detail::convergence_row<N>(r, acc, done, n_acc, static_cast<double>(done), next_conv);
  }
  std::vector<int> order(N);
  for (int i = 0; i < N; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return acc(a) > acc(b); });
  std::vector<std::vector<double>> bsorted(batch.size(), std::vector<double>(N));
  for (int i = 0; i < N; ++i) {
    r.exponents.push_back(acc(order[i]) / r.t_end);
    for (std::size_t b = 0; b < batch.size(); ++b) bsorted[b][i] = batch[b][order[i]];
  }
  r.trace_mean = logdet / r.t_end;
  r.x_final.assign(x.data(), x.data() + N);
  r.steps = n_trans + n_warm + n_acc;
  detail::finish_stats(r, bsorted, N);
  return r;
}

}  // namespace cvt::analysis
