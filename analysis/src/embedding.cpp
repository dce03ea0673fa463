#include "cvtplant/analysis/embedding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/neighbours.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {
namespace {

// FNN and Cao need each row's nearest neighbour in dimension m = 1, 2, ...
// with one spare sample per row for coordinate m + 1 (the rows of
// delay_embed(x, m, tau, tau)). The rows are searched in the tree's leaf
// order (consecutive queries then share the tree's nodes and leaves in
// cache), the answers kept by row for the callers' sums in row order. The
// neighbour found in dimension m - 1 is a candidate in dimension m (its
// distance only grows by the new coordinate), so it starts the search with a
// bound; the answer is the one an unhinted search gives (the nearest, the
// lowest index among equals).
class DimensionNeighbours {
 public:
  DimensionNeighbours(const std::vector<double>& x, int tau)
      : nn_(x, tau), nbr_(x.size(), kNone), dist_(x.size()), n_(x.size()), tau_(static_cast<std::size_t>(tau)) {}
  // Searches dimension m (Theiler window w); returns its rows.
  std::size_t search(int m, int w) {
    const std::size_t rows = n_ - static_cast<std::size_t>(m) * tau_;
    nn_.set_dimension(m, rows);
    for (std::size_t p = 0; p < nn_.size(); ++p) {
      const std::size_t i = nn_.row_of(p);
      if (i >= rows) continue;
      std::size_t j = 0;
      const bool ok = nn_.nearest(p, w, j, dist_[i], nbr_[i] == kNone ? DelayNeighbours::kNoHint : nbr_[i]);
      nbr_[i] = ok && j < kNone ? static_cast<std::uint32_t>(j) : kNone;
    }
    return rows;
  }
  // Row i's neighbour and its distance in the dimension searched last.
  bool neighbour(std::size_t i, std::size_t& j, double& d) const {
    if (nbr_[i] == kNone) return false;
    j = nbr_[i];
    d = dist_[i];
    return true;
  }

 private:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  DelayNeighbours nn_;
  std::vector<std::uint32_t> nbr_;
  std::vector<double> dist_;
  std::size_t n_, tau_;
};

}  // namespace

// docs/analysis.md#ami: histogram estimate with equal-width bins over the range.
AmiResult average_mutual_information(const std::vector<double>& x, int max_lag, int bins) {
  validate_series(x, 16, "ami");
  const std::size_t n = x.size();
  max_lag = std::clamp(max_lag, 1, static_cast<int>(n / 4));
  if (bins <= 0) bins = std::clamp(static_cast<int>(std::lround(std::cbrt(static_cast<double>(n)))), 8, 64);
  AmiResult r;
  r.bins = bins;
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  const double lo = *lo_it, width = (*hi_it - lo) / bins;
  std::vector<int> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = std::min(bins - 1, static_cast<int>((x[i] - lo) / width));
  std::vector<double> joint(static_cast<std::size_t>(bins) * bins), pa(bins), pb(bins);
  for (int lag = 0; lag <= max_lag; ++lag) {
    std::fill(joint.begin(), joint.end(), 0.0);
    std::fill(pa.begin(), pa.end(), 0.0);
    std::fill(pb.begin(), pb.end(), 0.0);
    const std::size_t cnt = n - static_cast<std::size_t>(lag);
    for (std::size_t i = 0; i < cnt; ++i) {
      joint[static_cast<std::size_t>(b[i]) * bins + b[i + lag]] += 1;
      pa[b[i]] += 1;
      pb[b[i + lag]] += 1;
    }
    double I = 0;
    for (int p = 0; p < bins; ++p)
      for (int q = 0; q < bins; ++q) {
        const double j = joint[static_cast<std::size_t>(p) * bins + q];
        if (j > 0) I += j / cnt * std::log(j * cnt / (pa[p] * pb[q]));
      }
    r.ami.push_back(I);
  }
  const double m = mean(x);
  double c0 = 0;
  for (double v : x) c0 += (v - m) * (v - m);
  for (int lag = 0; lag <= max_lag; ++lag) {
    double c = 0;
    for (std::size_t i = 0; i + lag < n; ++i) c += (x[i] - m) * (x[i + lag] - m);
    r.acf.push_back(c / c0);
  }
  // A minimum counts if it is the lowest value over the next max(2, lag/2)
  // lags (histogram MI is jagged) and above twice the estimator's bias
  // (B-1)^2/(2N) (a decorrelated series only has noise minima).
  const double bias = static_cast<double>((bins - 1) * (bins - 1)) / (2.0 * static_cast<double>(n));
  for (int lag = 1; lag < max_lag && r.tau_ami == 0; ++lag) {
    if (!(r.ami[lag] < r.ami[lag - 1]) || r.ami[lag] <= 2 * bias) continue;
    const int ahead = std::min(max_lag, lag + std::max(2, lag / 2));
    bool lowest = true;
    for (int j = lag + 1; j <= ahead; ++j) lowest = lowest && r.ami[lag] <= r.ami[j];
    if (lowest && ahead > lag) r.tau_ami = lag;
  }
  for (int lag = 1; lag <= max_lag; ++lag)
    if (r.acf[lag] <= 0) {
      r.tau_acf_zero = lag;
      break;
    }
  if (r.tau_ami > 0) {
    r.tau = r.tau_ami;
    r.method = "ami_first_minimum";
  } else {
    int t = 0;
    for (int lag = 1; lag <= max_lag; ++lag)
      if (r.ami[lag] <= r.ami[0] / std::exp(1.0)) {
        t = lag;
        break;
      }
    if (t > 0) {
      r.tau = t;
      r.method = "ami_1_over_e";
    } else if (r.tau_acf_zero > 0) {
      r.tau = r.tau_acf_zero;
      r.method = "acf_zero";
    } else {
      r.tau = 1;
      r.method = "fallback_1";
    }
  }
  return r;
}

// docs/analysis.md#fnn: Kennel et al. (1992), Rtol and Atol criteria, R_A = std(x).
FnnResult false_nearest_neighbours(const std::vector<double>& x, const FnnOptions& opt) {
  if (opt.m_max < 1 || opt.tau < 1) throw InputError("fnn: need m_max >= 1 and tau >= 1");
  const std::size_t need = static_cast<std::size_t>(opt.m_max) * opt.tau + 20;
  validate_series(x, need, "fnn");
  FnnResult r;
  r.theiler = opt.theiler >= 0 ? opt.theiler : default_theiler(x);
  const double ra = stddev(x);
  bool found = false;
  DimensionNeighbours nn(x, opt.tau);
  for (int m = 1; m <= opt.m_max; ++m) {
    const std::size_t rows = nn.search(m, r.theiler);
    std::size_t valid = 0, f_any = 0, f_r = 0, f_a = 0;
    for (std::size_t i = 0; i < rows; ++i) {
      std::size_t j;
      double d;
      if (!nn.neighbour(i, j, d) || !(d > 0)) continue;
      const double extra = std::abs(x[i + static_cast<std::size_t>(m) * opt.tau] - x[j + static_cast<std::size_t>(m) * opt.tau]);
      const bool c1 = extra / d > opt.rtol;
      const bool c2 = std::sqrt(d * d + extra * extra) / ra > opt.atol;
      ++valid;
      f_r += c1;
      f_a += c2;
      f_any += (c1 || c2);
    }
    if (valid == 0) throw InputError("fnn: no valid neighbour pairs (duplicate points or too few points)");
    r.m.push_back(m);
    r.fraction.push_back(static_cast<double>(f_any) / valid);
    r.fraction_rtol.push_back(static_cast<double>(f_r) / valid);
    r.fraction_atol.push_back(static_cast<double>(f_a) / valid);
    if (!found && r.fraction.back() <= opt.threshold) {
      r.dimension = m;
      found = true;
    }
  }
  r.reached = found;
  if (!found) r.dimension = opt.m_max;
  return r;
}

// docs/analysis.md#cao: Cao (1997) E1/E2 with the Euclidean norm (Cao uses the
// maximum norm; see the doc for why this does not change the reading).
CaoResult cao(const std::vector<double>& x, const CaoOptions& opt) {
  if (opt.m_max < 1 || opt.tau < 1) throw InputError("cao: need m_max >= 1 and tau >= 1");
  validate_series(x, static_cast<std::size_t>(opt.m_max + 1) * opt.tau + 20, "cao");
  CaoResult r;
  r.theiler = opt.theiler >= 0 ? opt.theiler : default_theiler(x);
  std::vector<double> E, Es;
  DimensionNeighbours nn(x, opt.tau);
  for (int m = 1; m <= opt.m_max + 1; ++m) {
    const std::size_t rows = nn.search(m, r.theiler);
    double sum_a = 0, sum_s = 0;
    std::size_t cnt = 0;
    for (std::size_t i = 0; i < rows; ++i) {
      std::size_t j;
      double d;
      if (!nn.neighbour(i, j, d) || !(d > 0)) continue;
      const double extra = x[i + static_cast<std::size_t>(m) * opt.tau] - x[j + static_cast<std::size_t>(m) * opt.tau];
      sum_a += std::sqrt(d * d + extra * extra) / d;
      sum_s += std::abs(extra);
      ++cnt;
    }
    if (cnt == 0) throw InputError("cao: no valid neighbour pairs");
    E.push_back(sum_a / cnt);
    Es.push_back(sum_s / cnt);
  }
  bool found = false;
  for (int m = 1; m <= opt.m_max; ++m) {
    r.m.push_back(m);
    r.e1.push_back(E[m] / E[m - 1]);
    r.e2.push_back(Es[m] / Es[m - 1]);
    if (!found && r.e1.back() >= opt.e1_threshold) {
      r.dimension = m;
      found = true;
    }
  }
  r.reached = found;
  if (!found) r.dimension = opt.m_max;
  return r;
}

}  // namespace cvt::analysis
