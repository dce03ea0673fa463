// Benettin's two-trajectory method on a restartable flow (docs/analysis.md#two-trajectory).
#include "cvtplant/analysis/two_trajectory.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

namespace {

double weighted_norm(const std::vector<double>& d, const std::vector<double>& w) {
  double s = 0;
  for (std::size_t i = 0; i < d.size(); ++i) s += (w[i] * d[i]) * (w[i] * d[i]);
  return std::sqrt(s);
}

}  // namespace

TwoTrajectoryResult largest_exponent_two_trajectories(RestartableFlow& flow, const std::vector<double>& w,
                                                      const TwoTrajectoryOptions& o) {
  if (!(o.t_renorm_s > 0) || o.warmup < 0 || o.intervals < 2 || o.batches < 2 || o.batches > o.intervals ||
      !(o.delta0 > 0 && o.delta0 < 1))
    throw std::invalid_argument("two trajectories: t_renorm > 0, intervals >= batches >= 2, 0 < delta0 < 1");
  const std::vector<double> y0 = flow.state();
  if (w.size() != y0.size()) throw std::invalid_argument("two trajectories: one weight per state");
  bool any = false;
  for (double v : w) {
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument("two trajectories: weights must be >= 0");
    any = any || v > 0;
  }
  if (!any) throw std::invalid_argument("two trajectories: every weight is zero");
  // The first direction: Gaussian in the weighted coordinates (a fixed seed;
  // the raw 32-bit draws through Box-Muller, the same with every library).
  std::mt19937 gen(static_cast<std::mt19937::result_type>(o.seed ^ (o.seed >> 32)));
  auto uniform = [&] { return (static_cast<double>(gen()) + 0.5) / 4294967296.0; };
  std::vector<double> u(y0.size(), 0.0);
  for (std::size_t i = 0; i < u.size(); ++i)
    if (w[i] > 0) u[i] = std::sqrt(-2 * std::log(uniform())) * std::cos(6.283185307179586 * uniform());
  {
    double n = 0;
    for (double v : u) n += v * v;
    n = std::sqrt(n);
    for (double& v : u) v /= n;
  }
  TwoTrajectoryResult r;
  double sum = 0;
  std::vector<double> d(y0.size());
  for (int k = 0; k < o.warmup + o.intervals; ++k) {
    const double t0 = flow.t_s();
    const std::vector<double> y = flow.state();
    std::vector<double> yp = y;
    for (std::size_t i = 0; i < y.size(); ++i)
      if (w[i] > 0) yp[i] += o.delta0 * u[i] / w[i];
    // Both from a restart at t0, so the integrator treats them alike.
    flow.restart(t0, y);
    flow.advance(o.t_renorm_s);
    const double t1 = flow.t_s();
    const std::vector<double> y1 = flow.state();
    flow.restart(t0, yp);
    flow.advance(o.t_renorm_s);
    const std::vector<double> y1p = flow.state();
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = w[i] > 0 ? y1p[i] - y1[i] : 0.0;
    const double dist = weighted_norm(d, w);
    if (!(dist > 0) || !std::isfinite(dist))
      throw std::runtime_error("two trajectories: the deviation vanished or is not finite at t = " + std::to_string(t1));
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = w[i] * d[i] / dist;
    flow.restart(t1, y1);
    if (o.progress) o.progress(k + 1, o.warmup + o.intervals);
    if (k < o.warmup) continue;
    const double g = std::log(dist / o.delta0);
    r.stretch.push_back(g);
    r.max_stretch = std::max(r.max_stretch, std::fabs(g));
    sum += g;
    ++r.intervals;
    r.t_s.push_back(r.intervals * o.t_renorm_s);
    r.cumulative.push_back(sum / (r.intervals * o.t_renorm_s));
  }
  r.lambda = sum / (r.intervals * o.t_renorm_s);
  // Batch means: equal batches of consecutive intervals (the last takes the remainder).
  const int per = r.intervals / o.batches;
  for (int b = 0; b < o.batches; ++b) {
    const int from = b * per, to = b + 1 == o.batches ? r.intervals : (b + 1) * per;
    double s = 0;
    for (int k = from; k < to; ++k) s += r.stretch[static_cast<std::size_t>(k)];
    r.batch_lambda.push_back(s / ((to - from) * o.t_renorm_s));
  }
  double m = 0, v = 0;
  for (double x : r.batch_lambda) m += x;
  m /= o.batches;
  for (double x : r.batch_lambda) v += (x - m) * (x - m);
  v /= (o.batches - 1);
  r.ci95 = t95(o.batches - 1) * std::sqrt(v / o.batches);
  return r;
}

}  // namespace cvt::analysis
