#pragma once
// The manoeuvre suites (docs/validation.md#suite): the runs `cvtplant
// validate --suite` compares the plant with the reference on, each split
// into the manoeuvres a calibration may fit and the held-out ones it must
// never see; and the manoeuvres the maps are made of
// (docs/validation.md#maps).
#include <string>
#include <vector>

#include "cvtplant/mbd/params.hpp"
#include "cvtplant/validation/manoeuvre.hpp"

namespace cvt::validation {

struct Suite {
  std::string name, summary;
  std::vector<Manoeuvre> fit, held_out;
  // The runs whose reference uncertainty is measured (one of each kind);
  // a run of another name takes its kind's (docs/validation.md#uncertainty).
  std::vector<std::string> uncertainty_runs;
};

// The suites by name: "controller" (the production set's envelope: steady
// holds, clamping-ratio steps, a ratio sweep, a kick-down, a clamping
// reduction into gross slip and back; held-out runs), "ci" (one hold and
// one clamping step from one start, a few seconds of reference).
std::vector<std::string> suite_names();
Suite suite_by_name(const std::string& name);  // throws InputError naming the suites

// The driven clamping a production-like controller sets for a torque at a
// ratio: the clamping range's floor, or the capacity at the set's safety
// factor where that is higher (docs/mbd-production.md#envelope).
double controller_clamp2_N(double torque_Nm, double ratio);

// An operating point with the controller's driven clamping for its torque.
OperatingPoint controller_point(double omega1_rad_s, double ratio, double torque_Nm);

// A steady hold: released with the holding clamping, t_end_s long.
Manoeuvre hold_manoeuvre(double omega1_rad_s, double ratio, double torque_Nm, double t_end_s);
// A step of ln(F1/F2) by `delta` at t = at_s (a 1 ms ramp) from a hold.
Manoeuvre clamp_step_manoeuvre(const OperatingPoint& op, double delta, double at_s, double t_end_s);

}  // namespace cvt::validation
