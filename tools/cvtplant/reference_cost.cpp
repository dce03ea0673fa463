// The multibody reference's work before it runs (docs/cli.md#caps).
#include "reference_cost.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "options.hpp"

namespace cvtcli {

namespace {

constexpr double kBdfRtolRef = 5e-7;
// Over the first second of the seed cases the steps grow as rtol^(-1/7):
// 4.7x from 5e-7 to 1e-11 (case 2: 20,197 -> 94,818).
constexpr double kBdfRtolExponent = 1.0 / 7.0;
constexpr double kCapFactor = 20.0;
constexpr double kCapFloor = 1e4;
constexpr double kCapCeiling = 1e8;

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

ReferenceWork bdf_work(double t_end_s, double rtol, double steps_per_s) {
  const double factor = rtol < kBdfRtolRef ? std::pow(kBdfRtolRef / rtol, kBdfRtolExponent) : 1.0;
  const double rate = steps_per_s * factor;
  return {t_end_s * rate, g(t_end_s) + " s x " + fmt_count(std::round(rate)) + " BDF steps per simulated second at rtol " +
                              g(rtol)};
}

ReferenceWork rk4_work(double t_end_s, double dt_s) {
  return {std::round(t_end_s / dt_s), "t_end / dt = " + g(t_end_s) + " s / " + g(dt_s) + " s of RK4"};
}

double automatic_step_cap(const ReferenceWork& w) {
  return std::min(kCapCeiling, std::max(kCapFloor, std::ceil(kCapFactor * w.steps)));
}

long long step_cap(const ReferenceWork& w, bool given, double given_cap, const std::string& what) {
  const double cap = given ? given_cap : automatic_step_cap(w);
  if (w.steps > cap)
    throw UsageError{what + " needs an estimated " + fmt_count(w.steps) + " integrator steps (" + w.how +
                     "), above the cap of " + fmt_count(cap) + "; raise it with --max-steps"};
  return static_cast<long long>(cap);
}

}  // namespace cvtcli
