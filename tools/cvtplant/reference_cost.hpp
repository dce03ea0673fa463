#pragma once
// The multibody reference's work, estimated before it runs (docs/cli.md#caps):
// `mbd`, `mbd figures`, `validate` and `calibrate` refuse a run whose
// estimate is above the step cap, and give the integrator that cap, so no
// run goes on for hours unasked. Deterministic: counts of integrator steps,
// never wall time.
#include <string>

namespace cvtcli {

struct ReferenceWork {
  double steps = 0;  // the estimate
  std::string how;   // how it was estimated, for the message
};

// Measured BDF steps per simulated second at rtol 5e-7, the top of each
// set's range. The seed's Table 1: 33,748 and 44,794 over 10 s of the seed
// cases (docs/mbd.md#speed), 9,174 to 49,560 over the validation scenes
// (docs/validation.md). The production-like set's stiffer chain: 130,000 to
// 177,000 (docs/mbd-production.md#cost).
constexpr double kSeedBdfStepsPerSecond = 50000.0;
constexpr double kProductionBdfStepsPerSecond = 180000.0;

// BDF after the release: t_end x `steps_per_s` at rtol >= 5e-7, times
// (5e-7 / rtol)^(1/7) below (4.7x at 1e-11).
ReferenceWork bdf_work(double t_end_s, double rtol, double steps_per_s = kSeedBdfStepsPerSecond);
// RK4: exactly t_end / dt steps.
ReferenceWork rk4_work(double t_end_s, double dt_s);

// The cap when --max-steps is not given: 20 times the estimate (at least
// 1e4), at most 1e8 (about 50 minutes of the reference's CPU time).
double automatic_step_cap(const ReferenceWork& w);

// The step cap a run gets: `given_cap` when the user gave --max-steps, else
// the automatic one. Throws UsageError when the estimate is above it ("the
// run needs an estimated 2.1e+08 BDF steps (...), above the cap of 1e+08;
// raise it with --max-steps"). `what` names the run ("scene tip-in's reference").
long long step_cap(const ReferenceWork& w, bool given, double given_cap, const std::string& what = "the run");

}  // namespace cvtcli
