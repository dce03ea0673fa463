#include "cvtplant/analysis/wolf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/neighbours.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {
namespace {

constexpr double kHalfPi = 1.57079632679489661923;
// Wolf et al. look up to five times the replacement scale before they give up
// on a small separation (docs/analysis.md#wolf).
constexpr int kRadiusSteps = 5;

void check_options(const WolfOptions& o) {
  if (o.m < 1 || o.tau < 1) throw InputError("lle-wolf: need m >= 1 and tau >= 1");
  if (!(o.dt > 0) || !std::isfinite(o.dt)) throw InputError("lle-wolf: dt must be > 0");
  if (o.evolve == 0 || o.evolve < -1) throw InputError("lle-wolf: the evolution time must be >= 1 sample");
  if (o.theiler < -1) throw InputError("lle-wolf: the Theiler window must be >= 0");
  if (!(o.max_angle_rad > 0 && o.max_angle_rad <= kHalfPi))
    throw InputError("lle-wolf: the largest replacement angle must be in (0, pi/2] rad");
  if (o.batches < 2) throw InputError("lle-wolf: need at least 2 batches");
  for (double s : {o.scale_min, o.scale_max})
    if (!(s == -1 || (s > 0 && std::isfinite(s))))
      throw InputError("lle-wolf: the separation scales must be > 0 (or -1 for the default)");
}

// A candidate replacement: its row, distance and angle to the old separation.
struct Candidate {
  std::size_t row;
  double dist, angle;
};

}  // namespace

// docs/analysis.md#wolf
WolfResult lle_wolf(const std::vector<double>& x, const WolfOptions& opt) {
  check_options(opt);
  validate_series(x, 100, "lle-wolf");
  WolfResult r;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double extent = *hi - *lo;
  r.m = opt.m;
  r.tau = opt.tau;
  r.theiler = opt.theiler >= 0 ? opt.theiler : default_theiler(x);
  r.evolve = opt.evolve > 0 ? opt.evolve
                            : std::max(1, static_cast<int>(std::lround(mean_period_samples(x) / 4)));
  r.scale_max = opt.scale_max > 0 ? opt.scale_max : 0.1 * extent;
  r.scale_min = opt.scale_min > 0 ? opt.scale_min : 1e-3 * extent;
  r.max_angle_rad = opt.max_angle_rad;
  if (!(r.scale_min < r.scale_max)) {
    char b[160];
    std::snprintf(b, sizeof b, "lle-wolf: the smallest separation (%g) must be below the replacement scale (%g)",
                  r.scale_min, r.scale_max);
    throw InputError(b);
  }

  const Embedding e = delay_embed(x, opt.m, opt.tau);
  r.points = e.n;
  const std::size_t T = static_cast<std::size_t>(r.evolve);
  // Every step needs its reference and neighbour rows T samples on.
  const std::size_t min_steps = static_cast<std::size_t>(5 * opt.batches);
  if (e.n <= T || (e.n - 1) / T < min_steps || e.n <= static_cast<std::size_t>(2 * r.theiler + 10))
    throw InputError("lle-wolf: too few points (" + std::to_string(x.size()) + ") for m=" + std::to_string(opt.m) +
                     ", tau=" + std::to_string(opt.tau) + ", evolution " + std::to_string(r.evolve) +
                     " samples and Theiler window " + std::to_string(r.theiler) + " (need " +
                     std::to_string(min_steps) + " evolution steps)");
  const std::size_t n_ref = e.n - T;
  const NeighbourIndex index(e, n_ref);
  const int m = e.m;

  std::vector<std::uint32_t> found;
  std::vector<Candidate> cands;
  // The candidates around row i within `radius` and above scale_min, with
  // their angle to the separation `v` of length `dv` (0: no direction).
  auto gather = [&](std::size_t i, double radius, const double* v, double dv) {
    index.within(i, radius, r.theiler, found);
    cands.clear();
    for (std::uint32_t k : found) {
      const double d = euclid(e.row(i), e.row(k), m);
      if (d < r.scale_min) continue;
      double angle = 0;
      if (dv > 0) {
        double dot = 0;
        for (int c = 0; c < m; ++c) dot += v[c] * (e.row(k)[c] - e.row(i)[c]);
        // The separation is a direction up to its sign: the angle between
        // the lines, as in Wolf et al.'s program.
        angle = std::acos(std::min(1.0, std::abs(dot) / (dv * d)));
      }
      cands.push_back({k, d, angle});
    }
  };
  // The nearest candidate within `radius` and `angle` (rows: ties to the lowest).
  auto nearest_of = [&](double radius, double angle, Candidate& best) {
    bool any = false;
    for (const Candidate& c : cands)
      if (c.dist <= radius && c.angle <= angle &&
          (!any || c.dist < best.dist || (c.dist == best.dist && c.row < best.row))) {
        best = c;
        any = true;
      }
    return any;
  };

  // The first neighbour: the nearest point of row 0 within the scales.
  std::size_t i = 0, j = 0;
  {
    gather(0, kRadiusSteps * r.scale_max, nullptr, 0);
    Candidate c{};
    bool ok = false;
    for (int z = 1; z <= kRadiusSteps && !ok; ++z) ok = nearest_of(z * r.scale_max, kHalfPi, c);
    if (!ok) {
      std::size_t k;
      double d;
      if (!index.nearest(0, r.theiler, k, d) || !(d > 0))
        throw InputError("lle-wolf: the first point has no neighbour outside the Theiler window");
      c.row = k;
    }
    j = c.row;
  }

  std::vector<double> logs;
  double angle_sum = 0, log_scale_sum = 0;
  std::vector<double> v(static_cast<std::size_t>(m));
  while (i < n_ref) {
    const double d0 = euclid(e.row(i), e.row(j), m);
    const std::size_t i1 = i + T, j1 = j + T;
    const double d1 = euclid(e.row(i1), e.row(j1), m);
    if (d1 > 0) {
      logs.push_back(std::log(d1 / d0));
      log_scale_sum += std::log(d0);
    } else {
      ++r.collapsed;  // repeated samples: no stretch to log
    }
    i = i1;
    if (i >= n_ref) break;
    // Keep the evolved neighbour while it stays within the scales and can be
    // followed another step.
    if (d1 >= r.scale_min && d1 <= r.scale_max && j1 < n_ref) {
      j = j1;
      ++r.kept;
      continue;
    }
    for (int c = 0; c < m; ++c) v[c] = e.row(j1)[c] - e.row(i1)[c];
    Candidate best{};
    gather(i1, r.scale_max, v.data(), d1);
    if (nearest_of(r.scale_max, r.max_angle_rad, best)) {
      ++r.replaced;
    } else {
      // Wolf et al.'s relaxation: look farther out, then accept wider angles.
      gather(i1, kRadiusSteps * r.scale_max, v.data(), d1);
      bool ok = false;
      for (double a = r.max_angle_rad; !ok; a = std::min(2 * a, kHalfPi)) {
        for (int z = 1; z <= kRadiusSteps && !ok; ++z) ok = nearest_of(z * r.scale_max, a, best);
        if (a >= kHalfPi) break;
      }
      if (ok) {
        ++r.relaxed;
      } else if (j1 < n_ref && d1 > 0) {
        best = {j1, d1, 0};  // nothing near: follow the old neighbour on
        ++r.unreplaced;
      } else {
        std::size_t k;
        double d;
        if (!index.nearest(i1, r.theiler, k, d) || !(d > 0))
          throw InputError("lle-wolf: a reference point has no neighbour outside the Theiler window");
        best = {k, d, 0};
        ++r.unreplaced;
      }
    }
    angle_sum += best.angle;
    j = best.row;
  }

  if (logs.size() < static_cast<std::size_t>(opt.batches))
    throw InputError("lle-wolf: fewer evolution steps with a separation than batches (repeated samples?)");
  r.steps = static_cast<int>(logs.size());
  const double step_s = static_cast<double>(T) * opt.dt;
  double total = 0;
  r.running.reserve(logs.size());
  for (std::size_t s = 0; s < logs.size(); ++s) {
    total += logs[s];
    r.running.push_back(total / (static_cast<double>(s + 1) * step_s));
  }
  r.lambda = total / (static_cast<double>(logs.size()) * step_s);
  // Batch means over contiguous runs of steps (docs/analysis.md#wolf).
  const std::size_t B = static_cast<std::size_t>(opt.batches);
  double bm = 0, bs = 0;
  for (std::size_t b = 0; b < B; ++b) {
    const std::size_t a = b * logs.size() / B, z = (b + 1) * logs.size() / B;
    double s = 0;
    for (std::size_t k = a; k < z; ++k) s += logs[k];
    r.batch_lambda.push_back(s / (static_cast<double>(z - a) * step_s));
    bm += r.batch_lambda.back();
  }
  bm /= static_cast<double>(B);
  for (double l : r.batch_lambda) bs += (l - bm) * (l - bm);
  r.ci95 = t95(static_cast<int>(B) - 1) * std::sqrt(bs / static_cast<double>(B - 1)) / std::sqrt(static_cast<double>(B));
  const int moves = r.replaced + r.relaxed + r.unreplaced;
  r.mean_angle_rad = moves > 0 ? angle_sum / moves : 0;
  r.mean_log_scale = log_scale_sum / static_cast<double>(logs.size());
  return r;
}

}  // namespace cvt::analysis
