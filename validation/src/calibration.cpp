// The plant's lumped parameters fitted to multibody reference runs
// (docs/validation.md#calibration).
#include "cvtplant/validation/calibration.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <unsupported/Eigen/NumericalDiff>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/plant.hpp"

namespace cvt::validation {

namespace {

// The parameters calibrate may fit: the plant's lumped, effective values (the
// others are physical values the reference shares, or flags), by their row
// of scene/scene_params.hpp, and how.
struct Fittable {
  const char* key;  // "params.<key>"
  ParamFit fit;
};
constexpr Fittable kFittable[] = {
    {"r1_m", ParamFit::positive},
    {"r2_m", ParamFit::positive},
    {"lump_mass_kg", ParamFit::positive},
    {"k1_N_m", ParamFit::positive},
    {"c1_Ns_m", ParamFit::positive},
    {"k2_N_m", ParamFit::positive},
    {"c2_Ns_m", ParamFit::positive},
    {"entry_load_share", ParamFit::share},
    {"normal_load_factor", ParamFit::positive},
    {"wrap_tension_share", ParamFit::share},
    {"chain_mass_kg_m", ParamFit::positive},
    {"centrifugal_gain", ParamFit::positive},
    {"chain_stiffness_N", ParamFit::positive},
    {"creep_gain", ParamFit::positive},
    {"stop_tension_N", ParamFit::positive},
    {"stop_tension_share", ParamFit::share},
    // eta_w is a share by its name but fitted as a positive value.
    {"wrap_excess_share", ParamFit::positive},
};

// The row of a [params] key, or nullptr.
const cvt::SceneParamInfo* params_row(const std::string& key) {
  for (const cvt::SceneParamInfo& r : cvt::kSceneParams)
    if (r.kind == cvt::SceneParamKind::real && std::string(r.name) == "params." + key) return &r;
  return nullptr;
}

// The unknown of a fitted value: log(value / start) for a positive value,
// the change of logit(value) for a share in (0, 1), so every value stays in
// its range whatever the optimiser tries.
double fitted_value(ParamFit fit, double start, double theta) {
  if (fit != ParamFit::share) return start * std::exp(theta);
  const double z = std::log(start / (1.0 - start)) + theta;
  return 1.0 / (1.0 + std::exp(-z));
}

// d value / d theta (one standard deviation of theta to one of the value).
double value_slope(ParamFit fit, double value) { return fit == ParamFit::share ? value * (1.0 - value) : value; }

double get(const cvt::RomParams& p, const cvt::SceneParamInfo& row) {
  cvt::Scene s;
  s.params = p;
  return row.get(s);
}

void set(cvt::RomParams& p, const cvt::SceneParamInfo& row, double v) {
  cvt::Scene s;
  s.params = p;
  row.set(s, v);
  p = s.params;
}

}  // namespace

std::vector<std::string> fittable_names() {
  std::vector<std::string> out;
  for (const Fittable& f : kFittable) {
    if (params_row(f.key) == nullptr) throw std::logic_error(std::string("no [params] row ") + f.key);
    out.emplace_back(f.key);
  }
  return out;
}

double CalibrationResult::rms_residual_start() const { return std::sqrt(cost_start / residuals); }
double CalibrationResult::rms_residual_end() const { return std::sqrt(cost_end / residuals); }

Calibration::Calibration(const std::vector<std::string>& fit, const cvt::RomParams& start) : base_(start) {
  for (const auto& name : fit) {
    const Fittable* f = nullptr;
    for (const Fittable& c : kFittable)
      if (name == c.key) f = &c;
    const cvt::SceneParamInfo* row = f != nullptr ? params_row(name) : nullptr;
    if (row == nullptr) throw InputError("unknown parameter '" + name + "'");
    for (const auto& g : fit_)
      if (g.name == name) throw InputError("'" + name + "' given twice");
    fit_.push_back({name, f->fit, row});
  }
  if (fit_.empty()) throw InputError("no parameter");
  // A share at an end of its range (0 or 1: a term switched off) has no
  // logit; its fit starts from the middle.
  for (const auto& f : fit_) {
    const double v = get(base_, *f.row);
    if (f.fit == ParamFit::share && !(v > 0.0 && v < 1.0)) set(base_, *f.row, 0.5);
  }
}

void Calibration::add_case(const std::string& name, const cvt::Scene& plant_scene, const ReferenceRun& reference,
                           int every) {
  CalibrationCase c;
  c.name = name;
  c.scene = plant_scene;
  every_ = every;
  c.reference = reference.series.select(reference.series.size(), std::size_t(every));
  for (int q = 0; q < kFitQuantityCount; ++q) c.scale[q] = reference_scale(c.reference.*(kFitQuantities[q].column));
  cases_.push_back(std::move(c));
}

int Calibration::residual_count() const {
  int n = 0;
  for (const auto& c : cases_) n += kFitQuantityCount * static_cast<int>(c.reference.size());
  return n;
}

void Calibration::apply(const double* theta, cvt::RomParams& p) const {
  for (std::size_t i = 0; i < fit_.size(); ++i)
    set(p, *fit_[i].row, fitted_value(fit_[i].fit, get(base_, *fit_[i].row), theta[i]));
}

// Residuals: for each case and quantity, relative_residuals of the plant
// against the reference, so each case's sum of squares is the sum of its
// quantities' squared relative RMS errors (compare.hpp, as `validate`).
void Calibration::residuals(const double* theta, double* f) {
  ++evals_;
  long k = 0;
  for (const auto& c : cases_) {
    cvt::Scene s = c.scene;
    apply(theta, s.params);
    const std::size_t n = c.reference.size();
    Series p;
    bool ok = cvt::validate_scene(s).ok;
    if (ok) {
      try {
        p = plant_run(s, s.frame_s).select(n * std::size_t(every_), std::size_t(every_));
      } catch (const RunError&) {
        ok = false;
      }
    }
    if (!ok || p.size() < n) {
      // A parameter set the plant cannot run (its watchdog trips): a large,
      // smooth penalty keeps the optimiser away.
      ++faults_;
      const double w = 1.0 / std::sqrt(static_cast<double>(n));
      for (std::size_t i = 0; i < kFitQuantityCount * n; ++i) f[k++] = 10.0 * w;
      continue;
    }
    for (int q = 0; q < kFitQuantityCount; ++q) {
      const auto col = kFitQuantities[q].column;
      relative_residuals(p.*col, c.reference.*col, c.scale[q], f + k);
      k += static_cast<long>(n);
    }
  }
}

struct CalibrationFunctor : Eigen::DenseFunctor<double> {
  Calibration* cal;
  const std::function<void(long)>* on_eval;
  CalibrationFunctor(Calibration* c, const std::function<void(long)>* tick, int n, int m)
      : Eigen::DenseFunctor<double>(n, m), cal(c), on_eval(tick) {}
  int operator()(const InputType& x, ValueType& f) const {
    cal->residuals(x.data(), f.data());
    if (*on_eval) (*on_eval)(cal->evals_);
    return 0;
  }
};

std::vector<double> Calibration::start_residuals() {
  std::vector<double> theta(fit_.size(), 0.0), f(static_cast<std::size_t>(residual_count()));
  residuals(theta.data(), f.data());
  return f;
}

CalibrationResult Calibration::run(int max_evals, const std::function<void(long)>& on_eval) {
  const int n = static_cast<int>(fit_.size());
  const int m = residual_count();
  if (m == 0) throw InputError("no scene to fit on");
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd f0(m);
  residuals(theta.data(), f0.data());

  CalibrationFunctor fn(this, &on_eval, n, m);
  Eigen::NumericalDiff<CalibrationFunctor> nd(fn, 1e-6);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<CalibrationFunctor>> lm(nd);
  lm.setMaxfev(max_evals);
  lm.setXtol(1e-8);
  lm.setFtol(1e-10);
  const auto status = lm.minimize(theta);

  Eigen::VectorXd f1(m);
  residuals(theta.data(), f1.data());
  CalibrationResult r;
  r.status = static_cast<int>(status);
  r.iterations = static_cast<long>(lm.iterations());
  r.residuals = m;
  r.cost_start = f0.squaredNorm();
  r.cost_end = f1.squaredNorm();
  // Jacobian at the optimum, in the unknowns theta: dvalue = value_slope dtheta.
  Eigen::MatrixXd J(m, n);
  nd.df(theta, J);
  const double dof = std::max(1, m - n);
  const double s2 = r.cost_end / dof;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(J.transpose() * J);
  const Eigen::VectorXd ev = es.eigenvalues();
  const double ev_max = std::max(ev.maxCoeff(), 1e-300);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  std::vector<bool> identifiable(static_cast<std::size_t>(n), true);
  for (int i = 0; i < n; ++i) {
    if (ev[i] > 1e-12 * ev_max) {
      cov += es.eigenvectors().col(i) * es.eigenvectors().col(i).transpose() / ev[i];
    } else {
      // A direction the residuals do not see: the parameters in it cannot be
      // told from the reference runs.
      for (int j = 0; j < n; ++j)
        if (std::fabs(es.eigenvectors()(j, i)) > 1e-3) identifiable[static_cast<std::size_t>(j)] = false;
    }
  }
  r.fitted = base_;
  apply(theta.data(), r.fitted);
  // Counted after the final residuals and the Jacobian, as the optimiser's
  // own runs are.
  r.evaluations = evals_;
  r.faults = faults_;
  for (int i = 0; i < n; ++i) {
    const Fitted& f = fit_[static_cast<std::size_t>(i)];
    FittedParam p;
    p.name = f.name;
    p.start = get(base_, *f.row);
    p.value = get(r.fitted, *f.row);
    p.sigma = value_slope(f.fit, p.value) * std::sqrt(std::max(0.0, s2 * cov(i, i)));
    p.sigma_rel = p.sigma / p.value;
    p.identifiable = identifiable[static_cast<std::size_t>(i)];
    r.params.push_back(p);
  }
  long k = 0;
  for (const auto& c : cases_) {
    const long len = static_cast<long>(c.reference.size());
    CaseErrors e;
    e.scene = c.name;
    for (int q = 0; q < kFitQuantityCount; ++q) {
      e.rel_rms_start[q] = f0.segment(k, len).norm();
      e.rel_rms_end[q] = f1.segment(k, len).norm();
      k += len;
    }
    r.cases.push_back(e);
  }
  return r;
}

bool is_cpp_identifier(const std::string& name) {
  bool ident = !name.empty() && !(name[0] >= '0' && name[0] <= '9');
  for (const char ch : name)
    ident = ident && ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_');
  return ident;
}

namespace {

std::string format(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* f, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, f);
  const int n = std::vsnprintf(buf, sizeof buf, f, ap);
  va_end(ap);
  if (n < static_cast<int>(sizeof buf)) return buf;
  std::string s(static_cast<std::size_t>(n) + 1, '\0');
  va_start(ap, f);
  std::vsnprintf(s.data(), s.size(), f, ap);
  va_end(ap);
  s.pop_back();
  return s;
}

}  // namespace

std::string params_file_text(const CalibrationResult& r, const std::string& command, const std::string& scenes) {
  std::string s = "# The real-time plant's lumped parameters fitted to the multibody reference\n";
  s += format("# (docs/validation.md#calibration). Written by:\n#   %s\n", command.c_str());
  s += format("# Least squares over the scenes %s: %d residuals, cost %.6g -> %.6g\n", scenes.c_str(), r.residuals,
              r.cost_start, r.cost_end);
  s += format("# (rms residual %.4g -> %.4g); one standard deviation from the Jacobian at the optimum.\n",
              r.rms_residual_start(), r.rms_residual_end());
  s += "[params]\n";
  for (const auto& p : r.params) {
    if (p.identifiable)
      s += format("%s = %.17g  # +- %.3g (%.2g %%), start %.10g\n", p.name.c_str(), p.value, p.sigma,
                  100.0 * p.sigma_rel, p.start);
    else
      s += format("%s = %.17g  # not identifiable from these runs, start %.10g\n", p.name.c_str(), p.value, p.start);
  }
  return s;
}

std::string header_text(const CalibrationResult& r, const std::string& command, const std::string& function) {
  if (!is_cpp_identifier(function)) throw InputError("not a C++ identifier: '" + function + "'");
  std::string s = "#pragma once\n// The real-time plant's lumped parameters fitted to the multibody reference\n";
  s += format("// (docs/validation.md#calibration), written with the parameter file by:\n//   %s\n", command.c_str());
  s += format("// rms residual %.4g -> %.4g over %d residuals.\n", r.rms_residual_start(), r.rms_residual_end(),
              r.residuals);
  s += "#include \"cvtplant/plant/rom_params.hpp\"\n\nnamespace cvt::calibrated {\n\n";
  s += format("constexpr void %s(RomParams& p) {\n", function.c_str());
  // A fittable [params] key is its RomParams member's name, in SI.
  for (const auto& p : r.params) s += format("  p.%s = %.17g;\n", p.name.c_str(), p.value);
  s += "}\n\n}  // namespace cvt::calibrated\n";
  return s;
}

}  // namespace cvt::validation
