#include "cvtplant/analysis/test01.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/series.hpp"
#include "cvtplant/physics/seed.hpp"

namespace cvt::analysis {

// docs/analysis.md#test01
Test01Result test01(const std::vector<double>& x_in, const Test01Options& opt) {
  if (opt.subsample < 1) throw InputError("test01: subsample must be >= 1");
  if (opt.n_c < 1) throw InputError("test01: n_c must be >= 1");
  std::vector<double> phi;
  for (std::size_t i = 0; i < x_in.size() && static_cast<int>(phi.size()) < opt.max_points;
       i += static_cast<std::size_t>(opt.subsample))
    phi.push_back(x_in[i]);
  validate_series(phi, 100, "test01 (after subsampling)");
  const std::size_t N = phi.size();
  const std::size_t ncut = N / 10;
  const double pi = kPi;
  const double phi_mean = mean(phi);
  std::mt19937 gen(opt.seed);
  std::uniform_real_distribution<double> uc(pi / 5, 4 * pi / 5);
  std::vector<double> p(N), q(N), ks;
  std::vector<double> xi(ncut), D(ncut);
  for (std::size_t n = 0; n < ncut; ++n) xi[n] = static_cast<double>(n + 1);
  for (int ic = 0; ic < opt.n_c; ++ic) {
    const double c = uc(gen);
    double ps = 0, qs = 0;
    for (std::size_t j = 0; j < N; ++j) {
      ps += phi[j] * std::cos(static_cast<double>(j + 1) * c);
      qs += phi[j] * std::sin(static_cast<double>(j + 1) * c);
      p[j] = ps;
      q[j] = qs;
    }
    for (std::size_t n = 1; n <= ncut; ++n) {
      double s = 0;
      for (std::size_t j = 0; j + n < N; ++j) {
        const double dp = p[j + n] - p[j], dq = q[j + n] - q[j];
        s += dp * dp + dq * dq;
      }
      const double M = s / static_cast<double>(N - n);
      const double osc = phi_mean * phi_mean * (1 - std::cos(static_cast<double>(n) * c)) / (1 - std::cos(c));
      D[n - 1] = M - osc;
    }
    const LineFit f = fit_line(xi.data(), D.data(), ncut);
    // Correlation coefficient from the fit: sign(slope) * sqrt(R^2).
    const double k = (f.slope >= 0 ? 1.0 : -1.0) * std::sqrt(std::max(0.0, f.r2));
    ks.push_back(k);
  }
  std::sort(ks.begin(), ks.end());
  Test01Result r;
  auto quant = [&](double qq) { return ks[static_cast<std::size_t>(qq * static_cast<double>(ks.size() - 1) + 0.5)]; };
  r.k_median = quant(0.5);
  r.k_q25 = quant(0.25);
  r.k_q75 = quant(0.75);
  r.points = static_cast<int>(N);
  r.subsample = opt.subsample;
  return r;
}

}  // namespace cvt::analysis
