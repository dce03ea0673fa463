// The plant's lumped parameters fitted to multibody reference runs
// (docs/validation.md#calibration).
#include "cvtplant/validation/calibration.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/LevenbergMarquardt>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/manoeuvre.hpp"
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
  c.every = every;
  c.reference = reference.series.select(reference.series.size(), std::size_t(every));
  c.quantities.assign(std::begin(kFitQuantities), std::end(kFitQuantities));
  for (const FitQuantity& q : c.quantities) c.scale.push_back(reference_scale(c.reference.*(q.column)));
  cases_.push_back(std::move(c));
}

void Calibration::add_measured_case(const std::string& name, const cvt::Scene& plant_scene, const MeasuredLog& log,
                                    int every) {
  std::string why;
  if (!measured_fits_scene(log, plant_scene, why)) throw InputError(log.source + ": " + why);
  CalibrationCase c;
  c.name = name;
  c.scene = plant_scene;
  c.every = every;
  c.measured = std::make_shared<const MeasuredLog>(log);
  measured_start(log, c.scene.initial);
  // Its start speeds are fitted too (docs/validation.md#measured-csv): two
  // unknowns after the parameters and the cases before it.
  c.start_unknown = static_cast<int>(fit_.size()) + 2 * measured_count_++;
  c.reference = measured_series(log, every);
  c.quantities = {kFitQuantities[0], kFitQuantities[1]};
  if (log.has_ratio()) c.quantities.push_back(kRatioQuantity);
  for (const FitQuantity& q : c.quantities) c.scale.push_back(reference_scale(c.reference.*(q.column)));
  cases_.push_back(std::move(c));
}

void Calibration::add_manoeuvre_case(const Manoeuvre& m, const cvt::Scene& plant_scene, const ReferenceRun& reference,
                                     int every, bool held_out) {
  if ((plant_scene.features & cvt::rom_feature::wedging) == 0)
    throw InputError("manoeuvre " + m.name + ": the plant needs the wedging feature (a variable ratio)");
  CalibrationCase c;
  c.name = m.name;
  c.scene = plant_scene;
  c.every = every;
  c.manoeuvre = std::make_shared<const Manoeuvre>(m);
  c.manoeuvre_reference = std::make_shared<const Series>(reference.series);
  c.held_out = held_out;
  c.reference = reference.series.select(reference.series.size(), std::size_t(every));
  c.quantities.assign(std::begin(kFitQuantities), std::end(kFitQuantities));
  c.quantities.push_back(kRatioQuantity);
  for (const FitQuantity& q : c.quantities) c.scale.push_back(reference_scale(c.reference.*(q.column)));
  cases_.push_back(std::move(c));
}

int Calibration::residual_count() const {
  int n = 0;
  for (const auto& c : cases_)
    if (!c.held_out) n += static_cast<int>(c.quantities.size() * c.reference.size());
  return n;
}

void Calibration::apply(const double* theta, cvt::RomParams& p) const {
  for (std::size_t i = 0; i < fit_.size(); ++i)
    set(p, *fit_[i].row, fitted_value(fit_[i].fit, get(base_, *fit_[i].row), theta[i]));
}

// One case's residuals at theta into f (its quantities' in turn); false
// (and the penalty) where the plant cannot run the parameters.
bool Calibration::case_residuals(const CalibrationCase& c, const double* theta, double* f) const {
  cvt::Scene s = c.scene;
  apply(theta, s.params);
  if (c.measured != nullptr) {
    s.initial.omega1_rad_s += theta[c.start_unknown];
    s.initial.omega2_rad_s += theta[c.start_unknown + 1];
  }
  const std::size_t n = c.reference.size();
  const std::size_t every = static_cast<std::size_t>(c.every);
  Series p;
  bool ok = c.measured != nullptr || cvt::validate_scene(s).ok;
  if (ok) {
    try {
      if (c.measured != nullptr)
        p = measured_plant_run(s, *c.measured, c.every);
      else if (c.manoeuvre != nullptr)
        p = plant_manoeuvre(*c.manoeuvre, s, c.manoeuvre_reference.get()).select(n * every, every);
      else
        p = plant_run(s, s.frame_s).select(n * every, every);
    } catch (const RunError&) {
      ok = false;
    }
  }
  if (!ok || p.size() < n) {
    // A parameter set the plant cannot run (its watchdog trips): a large,
    // smooth penalty keeps the optimiser away.
    const double w = 1.0 / std::sqrt(static_cast<double>(n));
    for (std::size_t i = 0; i < c.quantities.size() * n; ++i) f[i] = 10.0 * w;
    return false;
  }
  for (std::size_t q = 0; q < c.quantities.size(); ++q) {
    const auto col = c.quantities[q].column;
    relative_residuals(p.*col, c.reference.*col, c.scale[q], f + q * n);
  }
  return true;
}

// Residuals: for each fitted case and quantity, relative_residuals of the
// plant against the reference, so each case's sum of squares is the sum of
// its quantities' squared relative RMS errors (compare.hpp, as `validate`).
void Calibration::residuals(const double* theta, double* f) {
  ++evals_;
  long k = 0;
  for (const auto& c : cases_) {
    if (c.held_out) continue;
    if (!case_residuals(c, theta, f + k)) ++faults_;
    k += static_cast<long>(c.quantities.size() * c.reference.size());
  }
}

// The residuals for Eigen's Levenberg-Marquardt, with its Jacobian by
// forward differences (the steps of Eigen's NumericalDiff at epsfcn 1e-6),
// under a cap on plant evaluations: an evaluation past `limit` is refused
// (LM then stops with UserAsked). The last point evaluated is remembered,
// so the Jacobian at a point the optimiser has just evaluated costs n
// evaluations, not n + 1.
struct CalibrationFunctor : Eigen::DenseFunctor<double> {
  Calibration* cal;
  const std::function<void(long)>* on_eval;
  long limit = 0;
  mutable Eigen::VectorXd last_x, last_f;
  mutable bool have_last = false;

  CalibrationFunctor(Calibration* c, const std::function<void(long)>* tick, int n, int m)
      : Eigen::DenseFunctor<double>(n, m), cal(c), on_eval(tick) {}

  bool cached(const InputType& x) const { return have_last && last_x.size() == x.size() && last_x == x; }

  void evaluate(const InputType& x, ValueType& f) const {
    cal->residuals(x.data(), f.data());
    last_x = x;
    last_f = f;
    have_last = true;
    if (*on_eval) (*on_eval)(cal->evals_);
  }

  int operator()(const InputType& x, ValueType& f) const {
    if (cached(x)) {
      f = last_f;
      return 0;
    }
    if (cal->evals_ + 1 > limit) return -1;
    evaluate(x, f);
    return 0;
  }

  int df(const InputType& x0, JacobianType& jac) const {
    const long n = x0.size();
    if (cal->evals_ + n + (cached(x0) ? 0 : 1) > limit) return -1;
    ValueType f0(values()), f1(values());
    if (operator()(x0, f0) < 0) return -1;
    const double eps = std::sqrt(std::max(1e-6, Eigen::NumTraits<double>::epsilon()));
    InputType x = x0;
    for (long j = 0; j < n; ++j) {
      double h = eps * std::fabs(x[j]);
      if (h == 0.0) h = eps;
      x[j] += h;
      evaluate(x, f1);
      x[j] = x0[j];
      jac.col(j) = (f1 - f0) / h;
    }
    // Counted as evaluations by LM (its own cap is not used).
    return static_cast<int>(n);
  }
};

std::vector<double> Calibration::start_residuals() {
  std::vector<double> theta(static_cast<std::size_t>(unknown_count()), 0.0),
      f(static_cast<std::size_t>(residual_count()));
  residuals(theta.data(), f.data());
  return f;
}

int Calibration::unknown_count() const { return static_cast<int>(fit_.size()) + 2 * measured_count_; }

long Calibration::min_evaluations() const { return static_cast<long>(unknown_count()) + 2; }

CalibrationResult Calibration::run(int max_evals, const std::function<void(long)>& on_eval) {
  const int n = unknown_count();
  const int m = residual_count();
  if (m == 0) throw InputError("no scene to fit on");
  if (max_evals < min_evaluations())
    throw InputError("a fit of " + std::to_string(n) + " parameter(s) needs at least " +
                     std::to_string(min_evaluations()) +
                     " plant evaluations (the start, and the residuals and the Jacobian at the result), not " +
                     std::to_string(max_evals));
  CalibrationFunctor fn(this, &on_eval, n, m);
  // The evaluations at the result (its residuals and its Jacobian) are
  // kept out of the optimiser's share, so the whole fit stays within
  // max_evals plant evaluations.
  fn.limit = max_evals - (n + 1);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd f0(m);
  fn(theta, f0);

  Eigen::LevenbergMarquardt<CalibrationFunctor> lm(fn);
  lm.setMaxfev(std::numeric_limits<int>::max());
  lm.setXtol(1e-8);
  lm.setFtol(1e-10);
  const auto status = lm.minimize(theta);

  fn.limit = max_evals;
  Eigen::VectorXd f1(m);
  fn(theta, f1);
  // Jacobian at the optimum, in the unknowns theta: dvalue = value_slope dtheta.
  Eigen::MatrixXd J(m, n);
  fn.df(theta, J);
  CalibrationResult r;
  r.status = static_cast<int>(status);
  r.iterations = static_cast<long>(lm.iterations());
  r.residuals = m;
  r.cost_start = f0.squaredNorm();
  r.cost_end = f1.squaredNorm();
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
  for (int i = 0; i < static_cast<int>(fit_.size()); ++i) {
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
    e.measured = c.measured != nullptr;
    if (c.measured != nullptr) {
      // The log's start speeds as fitted (additive unknowns: one standard
      // deviation is the root of the covariance's diagonal entry).
      const int u = c.start_unknown;
      e.start_speeds = {c.scene.initial.omega1_rad_s + theta[u], c.scene.initial.omega2_rad_s + theta[u + 1],
                        std::sqrt(std::max(0.0, s2 * cov(u, u))), std::sqrt(std::max(0.0, s2 * cov(u + 1, u + 1)))};
    }
    e.held_out = c.held_out;
    if (c.held_out) {
      // Not fitted: its plant runs at the start and at the result, for the
      // report only (not counted in `evaluations`).
      const std::size_t size = c.quantities.size() * c.reference.size();
      std::vector<double> f_start(size), f_end(size);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      if (!case_residuals(c, zero.data(), f_start.data())) ++r.held_out_faults;
      if (!case_residuals(c, theta.data(), f_end.data())) ++r.held_out_faults;
      for (std::size_t q = 0; q < c.quantities.size(); ++q) {
        e.quantities.push_back(c.quantities[q].name);
        const auto part = [&](const std::vector<double>& f) {
          return Eigen::Map<const Eigen::VectorXd>(f.data() + q * c.reference.size(), len).norm();
        };
        e.rel_rms_start.push_back(part(f_start));
        e.rel_rms_end.push_back(part(f_end));
      }
      r.cases.push_back(e);
      continue;
    }
    for (const FitQuantity& q : c.quantities) {
      e.quantities.push_back(q.name);
      e.rel_rms_start.push_back(f0.segment(k, len).norm());
      e.rel_rms_end.push_back(f1.segment(k, len).norm());
      k += len;
    }
    r.cases.push_back(e);
  }
  return r;
}

namespace {

// C++17's keywords and alternative tokens: not names of a function.
constexpr const char* kCppKeywords[] = {
    "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
    "char", "char16_t", "char32_t", "char8_t", "class", "co_await", "co_return", "co_yield", "compl", "concept",
    "const", "const_cast", "consteval", "constexpr", "constinit", "continue", "decltype", "default", "delete", "do",
    "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for", "friend",
    "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq", "nullptr",
    "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast", "requires",
    "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct", "switch",
    "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename", "union",
    "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq"};

}  // namespace

bool is_cpp_identifier(const std::string& name) {
  bool ident = !name.empty() && name.size() <= 64 && !(name[0] >= '0' && name[0] <= '9');
  for (const char ch : name)
    ident = ident && ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_');
  if (!ident) return false;
  // Reserved to the implementation: a leading underscore and a capital, or
  // two underscores anywhere.
  if ((name[0] == '_' && name.size() > 1 && name[1] >= 'A' && name[1] <= 'Z') ||
      name.find("__") != std::string::npos)
    return false;
  for (const char* k : kCppKeywords)
    if (name == k) return false;
  return true;
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

namespace {

// Whether a fit was on measured logs (docs/validation.md#measured-csv).
bool on_logs(const CalibrationResult& r) {
  for (const auto& c : r.cases)
    if (c.measured) return true;
  return false;
}

}  // namespace

std::string params_file_text(const CalibrationResult& r, const std::string& command, const std::string& scenes) {
  std::string s = on_logs(r) ? "# The real-time plant's lumped parameters fitted to measured logs\n"
                             : "# The real-time plant's lumped parameters fitted to the multibody reference\n";
  s += format("# (docs/validation.md#%s). Written by:\n#   %s\n", on_logs(r) ? "measured-csv" : "calibration",
              command.c_str());
  s += format("# Least squares over the %s %s: %d residuals, cost %.6g -> %.6g\n", on_logs(r) ? "logs" : "scenes",
              scenes.c_str(), r.residuals, r.cost_start, r.cost_end);
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
  std::string s = std::string("#pragma once\n// The real-time plant's lumped parameters fitted to ") +
                  (on_logs(r) ? "measured logs\n" : "the multibody reference\n");
  s += format("// (docs/validation.md#%s), written with the parameter file by:\n//   %s\n",
              on_logs(r) ? "measured-csv" : "calibration", command.c_str());
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
