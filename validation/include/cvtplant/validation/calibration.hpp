#pragma once
// The plant's lumped parameters fitted to multibody reference runs by least
// squares (docs/validation.md#calibration): Eigen's Levenberg-Marquardt on
// the relative residuals of compare.hpp, the uncertainty of each value from
// the Jacobian at the optimum, and the parameter file and C++ header that
// carry the result.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/compare.hpp"
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

// The parameters calibrate can fit, by their [params] key: the plant's
// lumped, effective values (the others are physical values the reference
// shares); each is a row of scene/scene_params.hpp.
std::vector<std::string> fittable_names();

// One scene of the fit: the plant's scene (its parameters the start's) and
// the reference's samples it is fitted to.
struct CalibrationCase {
  std::string name;
  cvt::Scene scene;
  Series reference;  // every `every`-th sample of the reference run
  std::array<ReferenceScale, kFitQuantityCount> scale;
};

struct FittedParam {
  std::string name;
  double start = 0, value = 0;
  double sigma = 0, sigma_rel = 0;  // one standard deviation (meaningful where identifiable)
  bool identifiable = true;
};

struct CaseErrors {
  std::string scene;
  // The relative RMS error of each kFitQuantities entry at the start and the end.
  std::array<double, kFitQuantityCount> rel_rms_start{}, rel_rms_end{};
};

struct CalibrationResult {
  int status = 0;  // Eigen's LevenbergMarquardtSpace::Status
  long evaluations = 0, faults = 0;  // plant runs of the fit, and those the plant could not run
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

  // Runs the fit with at most max_evals plant evaluations of the optimiser;
  // on_eval gets the count after each.
  CalibrationResult run(int max_evals, const std::function<void(long evaluations)>& on_eval = {});

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
  int every_ = 1;
  long evals_ = 0, faults_ = 0;

  friend struct CalibrationFunctor;
  int residual_count() const;
  void apply(const double* theta, cvt::RomParams& p) const;
  void residuals(const double* theta, double* f);
};

// Whether name is a C++ identifier (the header's function name).
bool is_cpp_identifier(const std::string& name);

// The parameter file of a fit (TOML [params], each value with its
// uncertainty and the command that wrote it in comments); `command` is that
// command, `scenes` the scenes fitted on.
std::string params_file_text(const CalibrationResult& r, const std::string& command, const std::string& scenes);

// The same values to the last digit as a C++ header for the built-in scenes
// (lib/ reads no files): constexpr void cvt::calibrated::FUNCTION(RomParams&).
std::string header_text(const CalibrationResult& r, const std::string& command, const std::string& function);

}  // namespace cvt::validation
