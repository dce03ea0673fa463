// IAAFT surrogates and the rank test (docs/analysis.md#surrogates).
#include "cvtplant/analysis/surrogates.hpp"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <random>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/neighbours.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

namespace {

bool five_smooth(std::size_t n) {
  for (std::size_t p : {2u, 3u, 5u})
    while (n % p == 0) n /= p;
  return n == 1;
}

// A uniform index in [0, n) from the generator's raw 32-bit output: the same
// sequence with every standard library (std::uniform_int_distribution is not
// specified bit for bit).
std::size_t draw(std::mt19937& g, std::size_t n) {
  const std::uint64_t r = (static_cast<std::uint64_t>(g()) << 32) | g();
  return static_cast<std::size_t>(r % n);
}

}  // namespace

Segment end_matched_segment(const std::vector<double>& x, double min_fraction) {
  const std::size_t N = x.size();
  if (N < 64) throw InputError("end matching: too few points (" + std::to_string(N) + ", need 64)");
  if (!(min_fraction > 0 && min_fraction <= 1)) throw InputError("end matching: min_fraction must be in (0, 1]");
  const double var = stddev(x) * stddev(x);
  if (!(var > 0)) throw InputError("end matching: the series is constant");
  const std::size_t min_len = std::max<std::size_t>(64, static_cast<std::size_t>(std::ceil(min_fraction * N)));
  Segment best;
  best.mismatch = INFINITY;
  for (std::size_t len = N; len >= min_len; --len) {
    if (!five_smooth(len)) continue;
    for (std::size_t a = 0; a + len <= N; ++a) {
      const std::size_t b = a + len - 1;
      const double jump = x[a] - x[b];
      const double slope = (x[a + 1] - x[a]) - (x[b] - x[b - 1]);
      const double g = (jump * jump + slope * slope) / (static_cast<double>(len) * var);
      if (g < best.mismatch) best = Segment{a, len, g};
    }
  }
  return best;
}

Surrogate iaaft(const std::vector<double>& x, std::uint64_t seed, int max_iterations) {
  const std::size_t n = x.size();
  if (n < 16) throw InputError("IAAFT: too few points");
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spec;
  fft.fwd(spec, x);
  std::vector<double> amplitude(n);
  for (std::size_t k = 0; k < n; ++k) amplitude[k] = std::abs(spec[k]);
  std::vector<double> sorted = x;
  std::sort(sorted.begin(), sorted.end());

  std::mt19937 gen(static_cast<std::mt19937::result_type>(seed ^ (seed >> 32)));
  Surrogate s;
  s.x = x;
  for (std::size_t i = n - 1; i > 0; --i) std::swap(s.x[i], s.x[draw(gen, i + 1)]);  // Fisher-Yates

  std::vector<std::size_t> order(n), previous(n, n);
  std::vector<double> y;
  for (int it = 1; it <= max_iterations; ++it) {
    fft.fwd(spec, s.x);
    for (std::size_t k = 0; k < n; ++k) {
      const double a = std::abs(spec[k]);
      spec[k] = a > 0 ? spec[k] * (amplitude[k] / a) : std::complex<double>(amplitude[k], 0.0);
    }
    fft.inv(y, spec);
    // Rank-order remap: the k-th smallest of y gets the k-th smallest of x
    // (ties by index, so the result is deterministic).
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return y[i] < y[j] || (y[i] == y[j] && i < j); });
    for (std::size_t k = 0; k < n; ++k) s.x[order[k]] = sorted[k];
    s.iterations = it;
    if (order == previous) break;
    previous = order;
  }
  fft.fwd(spec, s.x);
  double num = 0, den = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = std::abs(spec[k]) - amplitude[k];
    num += d * d;
    den += amplitude[k] * amplitude[k];
  }
  s.spectrum_error = den > 0 ? std::sqrt(num / den) : 0.0;
  return s;
}

double time_reversal_asymmetry(const std::vector<double>& x, int lag) {
  if (lag < 1 || static_cast<std::size_t>(lag) + 2 > x.size()) throw InputError("time-reversal asymmetry: bad lag");
  double s2 = 0, s3 = 0;
  const std::size_t n = x.size() - static_cast<std::size_t>(lag);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = x[i + lag] - x[i];
    s2 += d * d;
    s3 += d * d * d;
  }
  s2 /= static_cast<double>(n);
  s3 /= static_cast<double>(n);
  return s2 > 0 ? s3 / std::pow(s2, 1.5) : 0.0;
}

double prediction_error(const std::vector<double>& x, const PredictionOptions& o) {
  if (o.m < 1 || o.tau < 1 || o.horizon < 1 || o.neighbours < 1 || o.theiler < 0 || o.max_refs < 1)
    throw InputError("prediction error: m, tau, horizon, neighbours, max_refs must be >= 1 and theiler >= 0");
  const double sd = stddev(x);
  if (!(sd > 0)) throw InputError("prediction error: the series is constant");
  // Rows whose future x[i + (m-1) tau + horizon] exists.
  const Embedding e = delay_embed(x, o.m, o.tau, static_cast<std::size_t>(o.horizon));
  const std::size_t last = static_cast<std::size_t>(o.m - 1) * o.tau + o.horizon;
  if (e.n < static_cast<std::size_t>(4 * o.neighbours + 2 * o.theiler + 2))
    throw InputError("prediction error: too few points for the embedding");
  NeighbourIndex index(e);
  const std::size_t refs = std::min<std::size_t>(e.n, static_cast<std::size_t>(o.max_refs));
  const double step = static_cast<double>(e.n) / static_cast<double>(refs);
  double sum = 0;
  std::size_t used = 0;
  std::vector<std::uint32_t> cand;
  std::vector<std::pair<double, std::size_t>> near;
  // A starting radius: twice the median, over a few reference points, of
  // the nearest neighbour's distance outside the Theiler window. Each
  // reference point widens it until it has `neighbours` rows.
  std::vector<double> probe;
  for (std::size_t r = 0; r < 25; ++r) {
    std::size_t j = 0;
    double d = 0;
    if (index.nearest((r * e.n) / 25, o.theiler, j, d)) probe.push_back(d);
  }
  double eps0 = 1e-12 * sd;
  if (!probe.empty()) {
    std::nth_element(probe.begin(), probe.begin() + static_cast<long>(probe.size() / 2), probe.end());
    eps0 = std::max(eps0, 2.0 * probe[probe.size() / 2]);
  }
  for (std::size_t r = 0; r < refs; ++r) {
    const std::size_t i = static_cast<std::size_t>(static_cast<double>(r) * step);
    double eps = eps0;
    for (int tries = 0; tries < 60; ++tries) {
      index.within(i, eps, o.theiler, cand);
      if (cand.size() >= static_cast<std::size_t>(o.neighbours)) break;
      eps *= 1.5;
    }
    if (cand.size() < static_cast<std::size_t>(o.neighbours)) continue;
    near.clear();
    for (std::uint32_t j : cand) near.push_back({euclid(e.row(i), e.row(j), o.m), j});
    std::partial_sort(near.begin(), near.begin() + o.neighbours, near.end());
    double pred = 0;
    for (int k = 0; k < o.neighbours; ++k) pred += x[near[static_cast<std::size_t>(k)].second + last];
    pred /= o.neighbours;
    const double err = pred - x[i + last];
    sum += err * err;
    ++used;
  }
  if (used == 0) throw InputError("prediction error: no reference point has neighbours");
  return std::sqrt(sum / static_cast<double>(used)) / sd;
}

namespace {

void rank(SurrogateStatistic& s, double alpha) {
  const int n = static_cast<int>(s.surrogates.size());
  int below = 0, above = 0;
  for (double v : s.surrogates) {
    if (v < s.data) ++below;
    if (v > s.data) ++above;
  }
  s.rank_low = below + 1;
  s.rank_high = above + 1;
  const double total = n + 1;
  if (s.tail == "lower")
    s.p = s.rank_low / total;
  else if (s.tail == "upper")
    s.p = s.rank_high / total;
  else
    s.p = std::min(1.0, 2.0 * std::min(s.rank_low, s.rank_high) / total);
  s.significant = s.p <= alpha;
}

}  // namespace

SurrogateTest surrogate_test(const std::vector<double>& x_in, const SurrogateTestOptions& o) {
  if (o.count < 1 || o.count > 10000) throw InputError("surrogates: count must be in 1..10000");
  validate_series(x_in, 200, "surrogates");
  SurrogateTest t;
  t.count = o.count;
  t.seed = o.seed;
  t.segment = end_matched_segment(x_in, o.min_fraction);
  const std::vector<double> x = zscore(std::vector<double>(x_in.begin() + static_cast<long>(t.segment.begin),
                                                           x_in.begin() + static_cast<long>(t.segment.begin + t.segment.length)));
  PredictionOptions po;
  po.m = o.m;
  po.tau = o.tau;
  po.horizon = o.horizon;
  po.theiler = o.theiler;
  LleOptions lo;
  lo.m = o.m;
  lo.tau = o.tau;
  lo.theiler = o.theiler;
  lo.dt = o.dt;
  SurrogateStatistic tra, nlpe, lam;
  tra.name = "time_reversal_asymmetry";
  tra.tail = "two-sided";
  nlpe.name = "prediction_error";
  nlpe.tail = "lower";
  lam.name = "rosenstein_exponent";
  lam.tail = "upper";
  const int lag = std::max(1, o.tau);
  tra.data = time_reversal_asymmetry(x, lag);
  nlpe.data = prediction_error(x, po);
  if (o.exponent) {
    lo.k_max = -1;
    const LleResult r = lle_rosenstein(x, lo);
    lam.data = r.fit.slope;
    lo.k_max = r.k_max;  // the same horizon for every surrogate
  }
  for (int k = 0; k < o.count; ++k) {
    const Surrogate s = iaaft(x, o.seed + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(k + 1));
    t.max_iterations_used = std::max(t.max_iterations_used, s.iterations);
    t.worst_spectrum_error = std::max(t.worst_spectrum_error, s.spectrum_error);
    tra.surrogates.push_back(time_reversal_asymmetry(s.x, lag));
    nlpe.surrogates.push_back(prediction_error(s.x, po));
    if (o.exponent) lam.surrogates.push_back(lle_rosenstein(s.x, lo).fit.slope);
  }
  rank(tra, o.alpha);
  rank(nlpe, o.alpha);
  t.statistics = {tra, nlpe};
  if (o.exponent) {
    rank(lam, o.alpha);
    t.statistics.push_back(lam);
  }
  t.nonlinear = tra.significant || nlpe.significant;
  return t;
}

}  // namespace cvt::analysis
