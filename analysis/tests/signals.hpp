#pragma once
// Test signals: sampled reference systems, sines and seeded noise.
#include <cmath>
#include <random>
#include <vector>

#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/integrate/explicit_rk.hpp"

namespace testsig {

// Lorenz x sampled every 0.01 after a 50-time-unit transient (RK4 dt=0.005).
inline std::vector<double> lorenz_x(std::size_t n, double sample_dt = 0.01) {
  cvt::analysis::Lorenz s;
  Eigen::Vector3d x(1, 1, 1);
  const double h = 0.005;
  const int every = static_cast<int>(std::lround(sample_dt / h));
  for (int i = 0; i < 10000; ++i) cvt::step_rk4(s, x, h);
  std::vector<double> out;
  for (std::size_t i = 0; out.size() < n; ++i) {
    cvt::step_rk4(s, x, h);
    if ((i + 1) % every == 0) out.push_back(x(0));
  }
  return out;
}

inline std::vector<double> henon_x(std::size_t n) {
  double x = 0.1, y = 0.1;
  std::vector<double> out;
  for (std::size_t i = 0; i < n + 1000; ++i) {
    const double xn = 1 - 1.4 * x * x + y;
    y = 0.3 * x;
    x = xn;
    if (i >= 1000) out.push_back(x);
  }
  return out;
}

inline std::vector<double> sine(std::size_t n, double period_samples, double phase = 0.3) {
  std::vector<double> out(n);
  const double w = 2 * 3.14159265358979323846 / period_samples;
  for (std::size_t i = 0; i < n; ++i) out[i] = std::sin(w * static_cast<double>(i) + phase);
  return out;
}

inline std::vector<double> white_noise(std::size_t n, unsigned seed = 7) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> d(0, 1);
  std::vector<double> out(n);
  for (auto& v : out) v = d(gen);
  return out;
}

}  // namespace testsig
