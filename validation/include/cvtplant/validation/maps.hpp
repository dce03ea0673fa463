#pragma once
// The maps a controls engineer reads a shifting CVT by, made on the
// multibody reference and on the plant from the same manoeuvres, cell by
// cell (docs/validation.md#maps): the steady thrust-ratio map, the shift
// rate against ln(F1/F2) beside the creep-mode law of Carbone, Mangialardi,
// Bonsen et al. (2007), the traction curve and the clamping at gross-slip
// onset against torque.
#include <string>
#include <vector>

#include "cvtplant/mbd/run.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/manoeuvre.hpp"

namespace cvt::validation {

// kappa = F1/F2, the driver over the driven clamping that holds a ratio at a
// torque: the reference's from its ratio lock, the plant's from its trial
// releases (manoeuvre.hpp). torque_ratio = T cos(beta0) / (2 mu0 F2 r1).
struct ThrustCell {
  double ratio = 0, torque_Nm = 0, clamp2_N = 0, torque_ratio = 0;
  double kappa_ref = 0, kappa_plant = 0;
  double ratio_ref = 0, ratio_plant = 0;  // geometric ratio at the release
  double drift_ref_per_s = 0;  // the reference's d(r2/r1)/dt over its 0.3 s hold at kappa_ref
  double error() const { return (kappa_plant - kappa_ref) / kappa_ref; }
};

// The shift rate d(r2/r1)/dt (least squares over 10-50 ms after a step of
// ln(F1/F2) by delta from the reference's hold), per delta; the fitted line
// rate = slope (delta - delta0) and its R^2; the creep-mode law's
// coefficient slope / omega1 [1/rad] (rate proportional to the primary
// speed, linear in the log of the force ratio).
struct ShiftCell {
  double omega1_rad_s = 0, ratio = 0, torque_Nm = 0, clamp2_N = 0;
  std::vector<double> delta, rate_ref, rate_plant;
  double slope_ref = 0, slope_plant = 0, delta0_ref = 0, delta0_plant = 0, r2_ref = 0, r2_plant = 0;
  double error() const { return (slope_plant - slope_ref) / slope_ref; }
};

// One step of a torque staircase at a clamping level: the transmitted
// torque and the driver's relative slip (v1 - v_chain) / v1, means over the
// step's last 20 ms; NaN once a model is in gross slip.
struct TractionPoint {
  double clamp2_N = 0, torque_cmd_Nm = 0, torque_ratio = 0;
  double torque_ref_Nm = 0, slip_ref = 0, torque_plant_Nm = 0, slip_plant = 0;
};

// Both clampings lowered together at a torque until the whole driver wrap
// slides (kGrossSlip_m_s): the driven clamping then; the closed form is
// the capacity T cos(beta0) / (2 mu0 r1) on the release's running radius.
struct OnsetPoint {
  double torque_Nm = 0;
  double clamp_ref_N = 0, clamp_plant_N = 0, clamp_closed_N = 0;  // NaN: no gross slip in the run
  double error() const { return (clamp_plant_N - clamp_ref_N) / clamp_ref_N; }
};

struct Maps {
  std::vector<ThrustCell> thrust;
  std::vector<ShiftCell> shift;
  std::vector<TractionPoint> traction;
  std::vector<OnsetPoint> onset;
  double reference_cpu_s = 0;
  int reference_runs = 0, from_cache = 0;
};

// The manoeuvres the maps are made of (their reference runs are cached like
// any manoeuvre's; the thrust map's holds are the controller suite's).
std::vector<Manoeuvre> map_manoeuvres();

// A shift-rate cell's manoeuvres (one per step of ln(F1/F2)) and its
// fitted slope from their runs in that order; an onset run and the driven
// clamping at its first sample in gross slip (NaN: none). For the
// uncertainty runs of a cell (suite_check.hpp).
std::vector<Manoeuvre> shift_cell_manoeuvres(double omega1_rad_s, double ratio);
double shift_slope(const std::vector<Manoeuvre>& cell, const std::vector<ReferenceRun>& runs);
Manoeuvre onset_manoeuvre(double torque_Nm);
double onset_clamp2_N(const Series& s);

// The maps of the reference (configuration c) and of the plant (scene
// `plant`, as plant_manoeuvre takes it).
Maps make_maps(const cvt::Scene& plant, const ReferenceConfig& c, const std::string& cache_dir,
               const cvt::mbd::ProgressSink& on_progress = {});

// The least-squares slope of y against t over t in [from_s, to_s] [1/s].
double slope_over(const std::vector<double>& t, const std::vector<double>& y, double from_s, double to_s);

// thrust-ratio.csv, shift-rate.csv, traction.csv, gross-slip-onset.csv in
// dir; with figures, a PNG of each (gnuplot). Returns the paths written.
std::vector<std::string> write_maps(const Maps& m, const std::string& dir, bool figures);

}  // namespace cvt::validation
