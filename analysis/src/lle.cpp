#include "cvtplant/analysis/lle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/neighbours.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

// docs/analysis.md#scaling-region
ScalingFit fit_scaling_region(const std::vector<double>& y, double dt) {
  ScalingFit best;
  const int K = static_cast<int>(y.size()) - 1;
  if (K < 4) return best;
  std::vector<double> t(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) t[k] = static_cast<double>(k) * dt;
  // Saturation level: the mean of the last quarter; the fit must end before
  // the curve has covered 90% of the rise from y(0) (docs: saturation).
  double sat = 0;
  const int q = std::max(1, K / 4);
  for (int k = K - q + 1; k <= K; ++k) sat += y[k];
  sat /= q;
  const double y_max = *std::max_element(y.begin(), y.end());
  const double rise = std::max(sat, y_max) - y[0];
  int k_stop = K;
  if (rise > 1.0) {
    for (int k = 1; k <= K; ++k)
      if (y[k] >= y[0] + 0.9 * rise) {
        k_stop = k;
        break;
      }
  }
  const int min_len = std::max(4, k_stop / 5);
  if (rise <= 1.0 || k_stop < min_len) {
    // No exponential growth to speak of: fit the whole curve, the slope is
    // then a bound on |lambda| rather than an estimate (docs).
    const LineFit f = fit_line(t.data(), y.data(), y.size());
    best.slope = f.slope;
    best.slope_se = f.slope_se;
    best.r2 = f.r2;
    best.k_begin = 0;
    best.k_end = K;
    best.growth_efolds = y[K] - y[0];
    best.ci95 = 1.96 * f.slope_se;
    best.scaling_region = false;
    return best;
  }
  // Longest window with R^2 >= 0.99; ties broken by R^2. Windows start in
  // the first half of [0, k_stop] so the initial alignment transient can be
  // skipped.
  struct Cand {
    int a, b;
    LineFit f;
  };
  std::vector<Cand> cands;
  const int step = std::max(1, k_stop / 100);
  for (int a = 0; a <= k_stop / 2; a += step)
    for (int b = a + min_len; b <= k_stop; b += step) {
      const LineFit f = fit_line(t.data() + a, y.data() + a, static_cast<std::size_t>(b - a + 1));
      if (f.slope > 0) cands.push_back({a, b, f});
    }
  if (cands.empty()) {
    const LineFit f = fit_line(t.data(), y.data(), static_cast<std::size_t>(k_stop + 1));
    best.slope = f.slope;
    best.slope_se = f.slope_se;
    best.r2 = f.r2;
    best.k_end = k_stop;
    best.ci95 = 1.96 * f.slope_se;
    return best;
  }
  double r2_req = 0.99;
  bool any = std::any_of(cands.begin(), cands.end(), [&](const Cand& c) { return c.f.r2 >= r2_req; });
  if (!any) {
    r2_req = 0;
    for (const auto& c : cands) r2_req = std::max(r2_req, c.f.r2);
    r2_req -= 0.01;
  }
  const Cand* pick = nullptr;
  for (const auto& c : cands) {
    if (c.f.r2 < r2_req) continue;
    if (!pick || (c.b - c.a) > (pick->b - pick->a) || ((c.b - c.a) == (pick->b - pick->a) && c.f.r2 > pick->f.r2))
      pick = &c;
  }
  // Sensitivity: slopes of all qualifying windows at least 80% as long.
  double lo = pick->f.slope, hi = pick->f.slope;
  for (const auto& c : cands)
    if (c.f.r2 >= r2_req && (c.b - c.a) >= 0.8 * (pick->b - pick->a)) {
      lo = std::min(lo, c.f.slope);
      hi = std::max(hi, c.f.slope);
    }
  best.slope = pick->f.slope;
  best.slope_se = pick->f.slope_se;
  best.r2 = pick->f.r2;
  best.k_begin = pick->a;
  best.k_end = pick->b;
  best.window_spread = hi - lo;
  best.growth_efolds = y[pick->b] - y[pick->a];
  best.ci95 = 1.96 * std::max(best.slope_se, best.window_spread / 2);
  best.scaling_region = best.growth_efolds >= 1.0;
  return best;
}

namespace {

struct Prepared {
  Embedding e;
  int theiler;
  int k_max;
  std::size_t n_ref;  // points that can be followed k_max steps
};

Prepared prepare(const std::vector<double>& x, const LleOptions& opt, const char* what) {
  if (opt.m < 1 || opt.tau < 1) throw InputError(std::string(what) + ": need m >= 1 and tau >= 1");
  if (!(opt.dt > 0)) throw InputError(std::string(what) + ": dt must be > 0");
  validate_series(x, 100, what);
  Prepared p;
  p.theiler = opt.theiler >= 0 ? opt.theiler : default_theiler(x);
  p.e = delay_embed(x, opt.m, opt.tau);
  if (opt.k_max > 0) {
    p.k_max = opt.k_max;
  } else {
    // Default horizon: 5 mean periods, at most a quarter of the points.
    p.k_max = static_cast<int>(std::lround(5 * mean_period_samples(x)));
    p.k_max = std::clamp(p.k_max, 20, std::max<int>(20, static_cast<int>(p.e.n / 4)));
  }
  if (p.e.n <= static_cast<std::size_t>(p.k_max + 2 * p.theiler + 10))
    throw InputError(std::string(what) + ": too few points (" + std::to_string(x.size()) + ") for m=" +
                     std::to_string(opt.m) + ", tau=" + std::to_string(opt.tau) + ", horizon " +
                     std::to_string(p.k_max) + " and Theiler window " + std::to_string(p.theiler));
  p.n_ref = p.e.n - static_cast<std::size_t>(p.k_max);
  return p;
}

void follow_pairs(const Prepared& p, const std::vector<std::size_t>& nn, LleResult& r) {
  const int m = p.e.m;
  std::vector<double> sum(static_cast<std::size_t>(p.k_max) + 1, 0.0);
  r.pairs.assign(static_cast<std::size_t>(p.k_max) + 1, 0);
  for (std::size_t i = 0; i < p.n_ref; ++i) {
    const std::size_t j = nn[i];
    if (j == std::numeric_limits<std::size_t>::max()) continue;
    for (int k = 0; k <= p.k_max; ++k) {
      const double d = euclid(p.e.row(i + k), p.e.row(j + k), m);
      if (d > 0) {
        sum[k] += std::log(d);
        ++r.pairs[k];
      }
    }
  }
  r.divergence.resize(sum.size());
  for (std::size_t k = 0; k < sum.size(); ++k)
    r.divergence[k] = r.pairs[k] > 0 ? sum[k] / r.pairs[k] : 0.0;
}

}  // namespace

namespace {

// A result that carries the embedding's window, horizon and size.
LleResult result_of(const Prepared& p) {
  LleResult r;
  r.theiler = p.theiler;
  r.k_max = p.k_max;
  r.points = p.e.n;
  return r;
}

// docs/analysis.md#rosenstein, with each reference point's nearest
// neighbour outside the Theiler window found by nearest(p, nn) (none:
// the largest size_t).
template <class Nearest>
LleResult rosenstein(const std::vector<double>& x, const LleOptions& opt, Nearest&& nearest) {
  const Prepared p = prepare(x, opt, "lle");
  LleResult r = result_of(p);
  std::vector<std::size_t> nn(p.n_ref, std::numeric_limits<std::size_t>::max());
  nearest(p, nn);
  follow_pairs(p, nn, r);
  r.fit = fit_scaling_region(r.divergence, opt.dt);
  return r;
}

}  // namespace

LleResult lle_rosenstein(const std::vector<double>& x, const LleOptions& opt) {
  return rosenstein(x, opt, [](const Prepared& p, std::vector<std::size_t>& nn) {
    const NeighbourIndex index(p.e, p.n_ref);
    std::size_t found = 0;
    for (std::size_t i = 0; i < p.n_ref; ++i) {
      std::size_t j;
      double d;
      if (index.nearest(i, p.theiler, j, d) && d > 0) {
        nn[i] = j;
        ++found;
      }
    }
    if (found < 10) throw InputError("lle: fewer than 10 neighbour pairs outside the Theiler window");
  });
}

LleResult lle_rosenstein_naive(const std::vector<double>& x, const LleOptions& opt) {
  return rosenstein(x, opt, [](const Prepared& p, std::vector<std::size_t>& nn) {
    for (std::size_t i = 0; i < p.n_ref; ++i) {
      double best = std::numeric_limits<double>::max();
      for (std::size_t j = 0; j < p.n_ref; ++j) {
        if (std::labs(static_cast<long>(i) - static_cast<long>(j)) <= p.theiler) continue;
        const double d = euclid(p.e.row(i), p.e.row(j), p.e.m);
        if (d > 0 && d < best) {
          best = d;
          nn[i] = j;
        }
      }
    }
  });
}

// docs/analysis.md#kantz: S(k) = < ln( mean_{j in U_i} ||y_{i+k} - y_{j+k}|| ) >_i
LleResult lle_kantz(const std::vector<double>& x, const LleOptions& opt) {
  const Prepared p = prepare(x, opt, "lle-kantz");
  LleResult r = result_of(p);
  const NeighbourIndex index(p.e, p.n_ref);
  const std::size_t n_refs = std::min<std::size_t>(p.n_ref, static_cast<std::size_t>(std::max(10, opt.max_refs)));
  const double stride = static_cast<double>(p.n_ref) / static_cast<double>(n_refs);
  double eps = opt.eps;
  if (!(eps > 0)) {
    // Default radius: median distance to the 10th neighbour (docs).
    std::vector<double> d;
    for (std::size_t s = 0; s < std::min<std::size_t>(n_refs, 500); ++s)
      d.push_back(index.kth_distance(static_cast<std::size_t>(s * (p.n_ref / std::min<std::size_t>(n_refs, 500))), 10));
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    eps = d[d.size() / 2];
    if (!(eps > 0)) throw InputError("lle-kantz: could not set a neighbourhood radius (duplicate points?)");
  }
  r.eps = eps;
  std::vector<double> sum(static_cast<std::size_t>(p.k_max) + 1, 0.0);
  r.pairs.assign(static_cast<std::size_t>(p.k_max) + 1, 0);
  std::vector<double> acc(static_cast<std::size_t>(p.k_max) + 1);
  std::vector<std::uint32_t> nb;
  double total_nb = 0;
  std::size_t used = 0;
  for (std::size_t s = 0; s < n_refs; ++s) {
    const std::size_t i = static_cast<std::size_t>(s * stride);
    index.within(i, eps, p.theiler, nb);
    if (nb.empty()) continue;
    ++used;
    total_nb += static_cast<double>(nb.size());
    std::fill(acc.begin(), acc.end(), 0.0);
    for (std::uint32_t j : nb)
      for (int k = 0; k <= p.k_max; ++k) acc[k] += euclid(p.e.row(i + k), p.e.row(j + k), p.e.m);
    for (int k = 0; k <= p.k_max; ++k) {
      const double mean_d = acc[k] / static_cast<double>(nb.size());
      if (mean_d > 0) {
        sum[k] += std::log(mean_d);
        ++r.pairs[k];
      }
    }
  }
  if (used < 10) throw InputError("lle-kantz: fewer than 10 reference points have neighbours within eps");
  r.mean_neighbours = total_nb / static_cast<double>(used);
  r.divergence.resize(sum.size());
  for (std::size_t k = 0; k < sum.size(); ++k) r.divergence[k] = r.pairs[k] > 0 ? sum[k] / r.pairs[k] : 0.0;
  r.fit = fit_scaling_region(r.divergence, opt.dt);
  return r;
}

}  // namespace cvt::analysis
