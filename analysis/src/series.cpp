#include "cvtplant/analysis/series.hpp"

#include <algorithm>
#include <cmath>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/physics/seed.hpp"

namespace cvt::analysis {

namespace {

// 2^-e with 2^(e-1) <= max |x| < 2^e (1 for an all-zero series). Multiplying
// by a power of two is exact, so the statistics below are computed on
// x * 2^-e, whose magnitudes are below 1: squares and sums cannot overflow
// (1e300) or underflow (1e-300) whatever the series' scale, and for series of
// ordinary scale the results are bit for bit those of the plain formulas.
double pow2_normaliser(const std::vector<double>& x) {
  double peak = 0;
  for (double v : x) peak = std::max(peak, std::abs(v));
  if (!(peak > 0) || !std::isfinite(peak)) return 1.0;
  int e = 0;
  std::frexp(peak, &e);
  return std::ldexp(1.0, -e);
}

double scaled_mean(const std::vector<double>& x, double k) {
  double s = 0;
  for (double v : x) s += v * k;
  return x.empty() ? 0.0 : s / static_cast<double>(x.size());
}

double scaled_stddev(const std::vector<double>& x, double k, double m_scaled) {
  double s = 0;
  for (double v : x) s += (v * k - m_scaled) * (v * k - m_scaled);
  return x.empty() ? 0.0 : std::sqrt(s / static_cast<double>(x.size()));
}

}  // namespace

double mean(const std::vector<double>& x) {
  const double k = pow2_normaliser(x);
  return scaled_mean(x, k) / k;
}

double stddev(const std::vector<double>& x) {
  const double k = pow2_normaliser(x);
  return scaled_stddev(x, k, scaled_mean(x, k)) / k;
}

void validate_series(const std::vector<double>& x, std::size_t min_points, const std::string& what) {
  if (x.size() < min_points)
    throw InputError(what + ": too few points (" + std::to_string(x.size()) + ", need at least " +
                     std::to_string(min_points) + ")");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) throw InputError(what + ": sample " + std::to_string(i) + " is not finite");
  double scale = 0;
  for (double v : x) scale = std::max(scale, std::abs(v));
  const double s = stddev(x);
  if (!(s > 1e-12 * std::max(scale, 1e-300)))
    throw InputError(what + ": series is constant (std " + std::to_string(s) + ")");
}

// In the normalised units of pow2_normaliser: the z-scores are scale-free,
// so a series and the same series times 1e300 give the same z-scores.
std::vector<double> zscore(const std::vector<double>& x) {
  const double k = pow2_normaliser(x);
  const double m = scaled_mean(x, k), s = scaled_stddev(x, k, m);
  if (!(s > 0)) throw InputError("series is constant");
  std::vector<double> out(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) out[i] = (x[i] * k - m) / s;
  return out;
}

Embedding delay_embed(const std::vector<double>& x, int m, int tau, std::size_t extra) {
  if (m < 1 || tau < 1) throw InputError("embedding needs m >= 1 and tau >= 1");
  const std::size_t span = static_cast<std::size_t>(m - 1) * static_cast<std::size_t>(tau) + extra;
  if (x.size() <= span + 1)
    throw InputError("too few points (" + std::to_string(x.size()) + ") for embedding m=" + std::to_string(m) +
                     " tau=" + std::to_string(tau));
  Embedding e;
  e.m = m;
  e.tau = tau;
  e.n = x.size() - span;
  e.data.resize(e.n * static_cast<std::size_t>(m));
  for (std::size_t i = 0; i < e.n; ++i)
    for (int k = 0; k < m; ++k) e.data[i * m + k] = x[i + static_cast<std::size_t>(k) * tau];
  return e;
}

Embedding from_rows(const std::vector<double>& rows, int dim) {
  Embedding e;
  e.m = dim;
  e.tau = 1;
  e.n = rows.size() / static_cast<std::size_t>(dim);
  e.data = rows;
  e.data.resize(e.n * dim);
  return e;
}

void fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  const double pi = kPi;
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = -2 * pi / static_cast<double>(len);
    for (std::size_t i = 0; i < n; i += len) {
      for (std::size_t k = 0; k < len / 2; ++k) {
        // Twiddle recomputed per k: accuracy over speed for long transforms.
        const std::complex<double> w(std::cos(ang * k), std::sin(ang * k));
        const std::complex<double> u = a[i + k], v = a[i + k + len / 2] * w;
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
      }
    }
  }
}

Spectrum periodogram(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::size_t nfft = 1;
  while (nfft < 2 * n) nfft <<= 1;
  const double m = mean(x);
  const double pi = kPi;
  std::vector<std::complex<double>> a(nfft, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2 * pi * static_cast<double>(i) / static_cast<double>(n > 1 ? n - 1 : 1));
    a[i] = (x[i] - m) * w;
  }
  fft(a);
  Spectrum s;
  s.freq.resize(nfft / 2 + 1);
  s.power.resize(nfft / 2 + 1);
  for (std::size_t k = 0; k <= nfft / 2; ++k) {
    s.freq[k] = static_cast<double>(k) / static_cast<double>(nfft);
    s.power[k] = std::norm(a[k]);
  }
  return s;
}

// docs/analysis.md#spectral-lines
Lines spectral_lines(const std::vector<double>& x, double dt, int count, double min_Hz) {
  Lines r;
  const Spectrum s = periodogram(x);
  const std::size_t K = s.power.size();
  if (K < 4) return r;
  r.resolution_Hz = s.freq[1] / dt;
  double pmax = 0;
  for (std::size_t k = 1; k < K; ++k)
    if (s.freq[k] / dt >= min_Hz) pmax = std::max(pmax, s.power[k]);
  if (!(pmax > 0)) return r;
  std::vector<std::pair<double, double>> pk;  // (power, Hz)
  for (std::size_t k = 2; k + 1 < K; ++k) {
    if (s.freq[k] / dt < min_Hz || s.power[k] < 0.01 * pmax) continue;
    if (!(s.power[k] > s.power[k - 1] && s.power[k] >= s.power[k + 1])) continue;
    const double a = std::log(s.power[k - 1]), b = std::log(s.power[k]), c = std::log(s.power[k + 1]);
    const double den = a - 2 * b + c;
    const double delta = den != 0 ? 0.5 * (a - c) / den : 0.0;
    pk.push_back({s.power[k], (s.freq[k] + delta * s.freq[1]) / dt});
  }
  std::sort(pk.rbegin(), pk.rend());
  if (pk.size() > static_cast<std::size_t>(std::max(count, 0))) pk.resize(static_cast<std::size_t>(std::max(count, 0)));
  for (const auto& p : pk) {
    r.Hz.push_back(p.second);
    r.power_rel.push_back(p.first / pmax);
  }
  return r;
}

double mean_period_samples(const std::vector<double>& x) {
  const Spectrum s = periodogram(x);
  double num = 0, den = 0;
  for (std::size_t k = 1; k < s.freq.size(); ++k) {
    num += s.freq[k] * s.power[k];
    den += s.power[k];
  }
  if (!(num > 0)) return 1.0;
  return den / num;
}

int default_theiler(const std::vector<double>& x) {
  const double p = mean_period_samples(x);
  const int cap = std::max<int>(1, static_cast<int>(x.size() / 20));
  return std::clamp(static_cast<int>(std::lround(p)), 1, cap);
}

LineFit fit_line(const double* x, const double* y, std::size_t n) {
  LineFit f;
  f.n = n;
  if (n < 2) return f;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0)) return f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  const double sse = std::max(0.0, syy - f.slope * sxy);
  f.r2 = syy > 0 ? 1.0 - sse / syy : 1.0;
  f.slope_se = n > 2 ? std::sqrt(sse / static_cast<double>(n - 2) / sxx) : 0.0;
  return f;
}

double t95(int dof) {
  // Table of the two-sided 95% quantile; beyond 30 the normal limit plus a
  // 1/dof correction is within 0.2%.
  static const double tab[] = {0,     12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                               2.201, 2.179,  2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080,
                               2.074, 2.069,  2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return tab[1];
  if (dof <= 30) return tab[dof];
  return 1.959964 + 2.4 / static_cast<double>(dof);
}

}  // namespace cvt::analysis
