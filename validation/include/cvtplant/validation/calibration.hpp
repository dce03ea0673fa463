#pragma once
// The plant's lumped parameters fitted to multibody reference runs by least
// squares (docs/validation.md#calibration): Eigen's Levenberg-Marquardt on
// the relative residuals of compare.hpp, the uncertainty of each value from
// the Jacobian at the optimum, and the parameter file and C++ header that
// carry the result.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/manoeuvre.hpp"
#include "cvtplant/validation/measured.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// How calibrate fits a parameter (docs/validation.md#calibration): as a
// positive value on a log scale, or as a share in (0, 1) on a logit scale.
enum class ParamFit : std::uint8_t { positive, share };

// The quantities fitted, in the order of the residual vector within a case.
struct FitQuantity {
  const char* name;  // as the report names it
  std::vector<double> Series::*column;
};
inline constexpr FitQuantity kFitQuantities[] = {{"omega1", &Series::omega1_rad_s},
                                                 {"omega2", &Series::omega2_rad_s},
                                                 {"F_ax1", &Series::F_ax1_N},
                                                 {"torque_driver", &Series::torque_driver_Nm}};
inline constexpr int kFitQuantityCount = 4;
// A measured log's (docs/validation.md#measured-csv): the speeds, and the
// geometric ratio where the log has one.
inline constexpr FitQuantity kRatioQuantity{"ratio", &Series::ratio_geom};

// The parameters calibrate can fit, by their [params] key: the plant's
// lumped, effective values (the others are physical values the reference
// shares); each is a row of scene/scene_params.hpp.
std::vector<std::string> fittable_names();

// One case of the fit: the plant's scene (its parameters the start's) and
// the samples it is fitted to, a reference run's or a measured log's (then
// the plant is driven by the log's inputs).
struct CalibrationCase {
  std::string name;
  cvt::Scene scene;
  Series reference;  // every `every`-th sample of the reference run or the log
  int every = 1;
  std::vector<FitQuantity> quantities;  // kFitQuantities, or a log's
  std::vector<ReferenceScale> scale;    // one per quantity
  std::shared_ptr<const MeasuredLog> measured;  // null: a reference run's case
  int start_unknown = -1;  // a log's: the index of its start speeds' changes among the unknowns
  // A suite's manoeuvre (null: none): the plant runs it with the
  // reference's holding clamping (manoeuvre_reference, every sample).
  std::shared_ptr<const Manoeuvre> manoeuvre;
  std::shared_ptr<const Series> manoeuvre_reference;
  bool held_out = false;  // reported at the start and the result, never fitted
};

struct FittedParam {
  std::string name;
  double start = 0, value = 0;
  double sigma = 0, sigma_rel = 0;  // one standard deviation (meaningful where identifiable)
  bool identifiable = true;
};

struct CaseErrors {
  std::string scene;
  bool measured = false;  // a measured log's case
  bool held_out = false;  // not fitted (a suite's held-out manoeuvre)
  // A measured log's: its start speeds as fitted and one standard
  // deviation of each [rad/s].
  struct StartSpeeds {
    double omega1_rad_s = 0, omega2_rad_s = 0, sigma1_rad_s = 0, sigma2_rad_s = 0;
  } start_speeds;
  // The relative RMS error of each of the case's quantities (their names in
  // `quantities`) at the start and the end.
  std::vector<const char*> quantities;
  std::vector<double> rel_rms_start, rel_rms_end;
};

struct CalibrationResult {
  int status = 0;  // Eigen's LevenbergMarquardtSpace::Status
  long evaluations = 0, faults = 0;  // plant runs of the fit, and those the plant could not run
  long held_out_faults = 0;  // held-out runs (two each, besides `evaluations`) the plant could not run
  long iterations = 0;
  int residuals = 0;
  double cost_start = 0, cost_end = 0;  // sums of squares of the residuals
  std::vector<FittedParam> params;
  std::vector<CaseErrors> cases;
  cvt::RomParams fitted;  // the first case's parameters with the fitted values

  double rms_residual_start() const;
  double rms_residual_end() const;
};

class Calibration {
 public:
  // fit: names of fittable_names(); start: the parameters the fit starts
  // from (a share at 0 or 1, a term switched off, starts from 0.5). Throws
  // InputError for an unknown name, a name given twice or none.
  Calibration(const std::vector<std::string>& fit, const cvt::RomParams& start);

  // A scene to fit on: its plant scene and its reference run, of which
  // every `every`-th sample is fitted (a reference that stopped early is
  // fitted up to there).
  void add_case(const std::string& name, const cvt::Scene& plant_scene, const ReferenceRun& reference, int every);
  // A measured log to fit on (docs/validation.md#measured-csv): the plant of
  // plant_scene driven by the log's inputs, its speeds (and geometric ratio,
  // where the log has one) against the log's on every `every`-th row.
  // Throws InputError if the scene cannot be driven by the log.
  // The start speeds are fitted with the parameters (two unknowns more),
  // from measured_start's.
  void add_measured_case(const std::string& name, const cvt::Scene& plant_scene, const MeasuredLog& log, int every);
  // A suite's manoeuvre (docs/validation.md#calibration-suite): the plant of
  // plant_scene (with wedging, else InputError) through m as plant_manoeuvre
  // runs it with the reference's holding clamping, against the reference's
  // omega1, omega2, F_ax1, torque on the driver and geometric ratio on every
  // `every`-th sample. A held-out one is not fitted: its errors at the
  // start and at the result are reported (two plant runs more).
  void add_manoeuvre_case(const Manoeuvre& m, const cvt::Scene& plant_scene, const ReferenceRun& reference, int every,
                          bool held_out);

  // Runs the fit with at most max_evals plant evaluations in all (each a
  // run of every case's plant): the start, the optimiser's steps and
  // Jacobians, and the residuals and Jacobian at the result. The optimiser
  // stops with status 9 (Eigen's UserAsked) when its share is spent.
  // on_eval gets the count after each. Throws InputError when max_evals is
  // below min_evaluations().
  CalibrationResult run(int max_evals, const std::function<void(long evaluations)>& on_eval = {});
  // The fewest evaluations a fit can make: the start, and n + 1 at the
  // result (n the unknowns: the fitted parameters, and two start speeds per
  // measured log).
  long min_evaluations() const;

  // The residual vector at the start's values (for tests and reports): per
  // case, per quantity, per sample; its squared norm is the sum over the
  // cases and quantities of rel_rms^2.
  std::vector<double> start_residuals();

 private:
  struct Fitted {
    std::string name;
    ParamFit fit;
    const cvt::SceneParamInfo* row;
  };
  std::vector<Fitted> fit_;
  cvt::RomParams base_;
  std::vector<CalibrationCase> cases_;
  long evals_ = 0, faults_ = 0;
  int measured_count_ = 0;

  friend struct CalibrationFunctor;
  int residual_count() const;
  int unknown_count() const;
  void apply(const double* theta, cvt::RomParams& p) const;
  void residuals(const double* theta, double* f);
  bool case_residuals(const CalibrationCase& c, const double* theta, double* f) const;
};

// Whether name can be the header's function name: a C++ identifier of at
// most 64 characters, not a keyword nor reserved to the implementation.
bool is_cpp_identifier(const std::string& name);

// The parameter file of a fit (TOML [params], each value with its
// uncertainty and the command that wrote it in comments); `command` is that
// command, `scenes` the scenes fitted on.
std::string params_file_text(const CalibrationResult& r, const std::string& command, const std::string& scenes);

// The same values to the last digit as a C++ header for the built-in scenes
// (lib/ reads no files): constexpr void cvt::calibrated::FUNCTION(RomParams&).
std::string header_text(const CalibrationResult& r, const std::string& command, const std::string& function);

}  // namespace cvt::validation
