#pragma once
// Small helpers shared by the multibody tests: run a case and keep what a
// check needs (samples, link states at chosen times).
#include <cmath>
#include <vector>

#include "cvtplant/mbd/run.hpp"

namespace cvt::mbd::testing {

struct Recorded {
  RunStats stats;
  std::vector<Sample> samples;
  std::vector<std::vector<LinkState>> links;  // at the samples listed in links_at
  std::vector<double> links_t;
};

// Runs p with o; keeps every sample and the link states at the first sample
// at or after each time in links_at (ascending).
inline Recorded record(const MbdParams& p, const RunOptions& o, const std::vector<double>& links_at = {}) {
  Recorded r;
  std::size_t next = 0;
  r.stats = simulate(p, o, [&](const Sample& s, const ChainModel& m, const double* y) {
    r.samples.push_back(s);
    while (next < links_at.size() && s.t_s >= links_at[next] - 1e-12) {
      r.links.push_back(m.link_states(y));
      r.links_t.push_back(s.t_s);
      ++next;
    }
  });
  return r;
}

// The full state (ledger included) at the sample at time t of a run of p.
inline std::vector<double> state_at(const MbdParams& p, double t, RunOptions o = {}) {
  std::vector<double> y;
  o.t_end_s = t;
  o.sample_s = t;
  simulate(p, o, [&](const Sample& s, const ChainModel& m, const double* yy) {
    if (s.t_s >= t - 1e-12) y.assign(yy, yy + m.size());
  });
  return y;
}

// Seed case 2 on clamped sheaves, the driver's clamping ramped from 3.3 to
// 4 kN over the first second: the clamped configuration the solver checks run.
inline MbdParams clamped_case2() {
  MbdParams p = seed_case(2);
  p.sheaves = SheaveMode::clamped;
  p.clamp1_N.points = {{0.0, 3300.0}, {1.0, 4000.0}};
  return p;
}

inline double rel_diff(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(a), std::fabs(b)); }

// The seed's geometry, restated here from Table 1 so the checks do not lean
// on the model's own constants.
constexpr double kPi = 3.14159265358979323846;
constexpr double kR1 = 0.0762, kR2 = 0.1143, kC = 0.5, kL = 0.03, kBeta0 = 15.0 * kPi / 180.0, kMu0 = 0.25;
inline double wrap_driver_rad() { return kPi - 2.0 * std::asin((kR2 - kR1) / kC); }
inline double wrap_driven_rad() { return kPi + 2.0 * std::asin((kR2 - kR1) / kC); }

}  // namespace cvt::mbd::testing
