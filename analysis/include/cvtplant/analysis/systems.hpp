#pragma once
// Reference systems with public Lyapunov spectra (docs/analysis.md#references)
// and the registry of models used by `cvtplant lyapunov --scene`, trajectories
// and sweeps.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cvtplant/analysis/lyapunov.hpp"

namespace cvt::analysis {

struct Lorenz {
  using Scalar = double;
  static constexpr int kStates = 3;
  double sigma = 10, rho = 28, beta = 8.0 / 3.0;
  template <class S>
  void derivative(const Eigen::Matrix<S, 3, 1>& x, Eigen::Matrix<S, 3, 1>& d) const {
    d(0) = S(sigma) * (x(1) - x(0));
    d(1) = x(0) * (S(rho) - x(2)) - x(1);
    d(2) = x(0) * x(1) - S(beta) * x(2);
  }
  void jacobian(const Eigen::Vector3d& x, Eigen::Matrix3d& J) const {
    J << -sigma, sigma, 0, rho - x(2), -1, -x(0), x(1), x(0), -beta;
  }
};

struct Rossler {
  using Scalar = double;
  static constexpr int kStates = 3;
  double a = 0.2, b = 0.2, c = 5.7;
  template <class S>
  void derivative(const Eigen::Matrix<S, 3, 1>& x, Eigen::Matrix<S, 3, 1>& d) const {
    d(0) = -x(1) - x(2);
    d(1) = x(0) + S(a) * x(1);
    d(2) = S(b) + x(2) * (x(0) - S(c));
  }
  void jacobian(const Eigen::Vector3d& x, Eigen::Matrix3d& J) const {
    J << 0, -1, -1, 1, a, 0, x(2), 0, x(0) - c;
  }
};

struct Henon {
  static constexpr int kStates = 2;
  double a = 1.4, b = 0.3;
  void step(const Eigen::Vector2d& x, Eigen::Vector2d& n) const {
    n(0) = 1 - a * x(0) * x(0) + x(1);
    n(1) = b * x(0);
  }
  void jacobian(const Eigen::Vector2d& x, Eigen::Matrix2d& J) const { J << -2 * a * x(0), 1, b, 0; }
};

struct Logistic {
  static constexpr int kStates = 1;
  double r = 4;
  void step(const Eigen::Matrix<double, 1, 1>& x, Eigen::Matrix<double, 1, 1>& n) const {
    n(0) = r * x(0) * (1 - x(0));
  }
  void jacobian(const Eigen::Matrix<double, 1, 1>& x, Eigen::Matrix<double, 1, 1>& J) const {
    J(0, 0) = r * (1 - 2 * x(0));
  }
};

using Params = std::map<std::string, double>;

// A model: equations with named parameters whose Lyapunov spectrum and
// trajectories the toolkit computes. Not a plant scene (cvt::Scene, inputs
// over time for a frame-by-frame run): a ROM scene with constant inputs
// becomes a model through rom_model() (rom_scenes.hpp).
// Reports (work done, total work) to a progress display; empty: not called.
using ProgressFn = std::function<void(double done, double total)>;

struct Model {
  std::string name;
  std::string description;
  bool is_map = false;
  int dim = 0;
  std::vector<std::string> state_names;
  std::vector<double> default_x0;
  Params default_params;
  BenettinOptions defaults;  // dt, transient, warm-up, t_end that resolve the scene
  std::function<SpectrumResult(const Params&, const std::vector<double>& x0, const BenettinOptions&)> spectrum;
  // Samples the state every `sample_dt` (maps: every iteration) for t in
  // (t_transient, t_transient + t_end]; rows of `dim` values. `progress`,
  // if set, is called every few thousand steps with (steps done, steps).
  std::vector<double> trajectory(const Params& p, const std::vector<double>& x0, double dt, double t_transient,
                                 double t_end, double sample_dt, const ProgressFn& progress = {}) const {
    return trajectory_fn(p, x0, dt, t_transient, t_end, sample_dt, progress);
  }
  std::function<std::vector<double>(const Params&, const std::vector<double>& x0, double dt, double t_transient,
                                     double t_end, double sample_dt, const ProgressFn& progress)>
      trajectory_fn;
};

const std::vector<Model>& models();
// Throws InputError listing the known names.
const Model& find_model(const std::string& name);
// True if the registry has a model of that name.
bool has_model(const std::string& name);
void register_model(Model s);
// Merges overrides into the scene's defaults; unknown names throw InputError.
Params merge_params(const Model& s, const Params& overrides);

}  // namespace cvt::analysis
