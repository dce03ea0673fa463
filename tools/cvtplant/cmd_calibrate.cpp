// `cvtplant calibrate`: the plant's lumped parameters fitted to multibody
// reference runs by least squares (Eigen's Levenberg-Marquardt), with their
// uncertainty from the Jacobian at the optimum (docs/validation.md#calibration).
#include <Eigen/Dense>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <unsupported/Eigen/NumericalDiff>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "scene_file.hpp"
#include "validation.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace cvtcli::validation {

namespace {

// A fitted parameter: its name in the parameter file and where it lives.
// The unknown is log(value / start) for a positive value, or the change of
// logit(value) for a share in (0, 1), so every value stays in its range.
struct Fittable {
  const char* name;
  double cvt::RomParams::*field;
  bool share = false;
};

constexpr Fittable kFittable[] = {
    {"k1_N_m", &cvt::RomParams::k1_N_m},
    {"c1_Ns_m", &cvt::RomParams::c1_Ns_m},
    {"k2_N_m", &cvt::RomParams::k2_N_m},
    {"c2_Ns_m", &cvt::RomParams::c2_Ns_m},
    {"lump_mass_kg", &cvt::RomParams::lump_mass_kg},
    {"r1_m", &cvt::RomParams::r1_m},
    {"r2_m", &cvt::RomParams::r2_m},
    {"normal_load_factor", &cvt::RomParams::normal_load_factor},
    {"entry_load_share", &cvt::RomParams::entry_load_share, true},
    {"wrap_tension_share", &cvt::RomParams::wrap_tension_share, true},
    // The chain's tension state (docs/rom.md#tension); wrap_excess_share is fitted positive.
    {"chain_mass_kg_m", &cvt::RomParams::chain_mass_kg_m},
    {"chain_stiffness_N", &cvt::RomParams::chain_stiffness_N},
    {"creep_gain", &cvt::RomParams::creep_gain},
    {"stop_tension_N", &cvt::RomParams::stop_tension_N},
    {"stop_tension_share", &cvt::RomParams::stop_tension_share, true},
    {"centrifugal_gain", &cvt::RomParams::centrifugal_gain},
    {"wrap_excess_share", &cvt::RomParams::wrap_excess_share},
};

double fitted_value(const Fittable& f, double start, double theta) {
  if (!f.share) return start * std::exp(theta);
  const double z = std::log(start / (1.0 - start)) + theta;
  return 1.0 / (1.0 + std::exp(-z));
}

// d value / d theta (one standard deviation of theta to one of the value).
double value_slope(const Fittable& f, double value) { return f.share ? value * (1.0 - value) : value; }

struct Options {
  std::string scenes = "seed-case1,seed-case2,gross-slip";
  std::string fit = "k1_N_m,c1_Ns_m,k2_N_m,c2_Ns_m,lump_mass_kg,r1_m,r2_m";
  std::string out;
  std::string header;  // the same values as a C++ header for the built-in scenes
  std::string function = "apply";  // the header's function, cvt::calibrated::NAME(RomParams&)
  std::string out_dir = "validation";
  std::string start;  // parameter file to start from
  std::string sheaves = "scene";  // the reference's sheaves: each scene's, or one mode for all
  double t_end_s = 0;
  double rtol = 5e-7;
  long long max_steps = 20000000;
  int every = 10;
  int max_evals = 400;
  bool json = false;
};

struct Case {
  std::string name;
  cvt::Scene scene;
  Series reference;  // every `every`-th sample
  double scale[4];   // RMS of the reference's omega1, omega2, F_ax1, torque
};


double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

// Residuals: for each case and sample, the plant's error in omega1, omega2,
// F_ax1 and the torque on the driver, each over its RMS in the reference and
// over sqrt(samples), so each case's sum of squares is the sum of the four
// squared relative RMS errors of `cvtplant validate`.
struct Problem {
  std::vector<Case> cases;
  std::vector<const Fittable*> fit;
  cvt::RomParams base;  // the start's values of the fitted fields
  int every = 10;
  long evals = 0, faults = 0;

  int residual_count() const {
    int n = 0;
    for (const auto& c : cases) n += 4 * static_cast<int>(c.reference.size());
    return n;
  }

  // theta: the unknowns of fitted_value.
  void apply(const Eigen::VectorXd& theta, cvt::RomParams& p) const {
    for (std::size_t i = 0; i < fit.size(); ++i)
      p.*(fit[i]->field) = fitted_value(*fit[i], base.*(fit[i]->field), theta[long(i)]);
  }

  void residuals(const Eigen::VectorXd& theta, Eigen::VectorXd& f) {
    ++evals;
    long k = 0;
    for (const auto& c : cases) {
      cvt::Scene s = c.scene;
      apply(theta, s.params);
      const double w = 1.0 / std::sqrt(static_cast<double>(c.reference.size()));
      Series p;
      bool ok = cvt::validate_scene(s).ok;
      if (ok) {
        try {
          p = plant_run(s, s.frame_s).select(c.reference.size() * std::size_t(every), std::size_t(every));
        } catch (const RunError&) {
          ok = false;
        }
      }
      // A reference that stopped early (RunFailure) is fitted up to there.
      if (!ok || p.size() < c.reference.size()) {
        // A parameter set the plant cannot run (its watchdog trips): a large,
        // smooth penalty keeps the optimiser away.
        ++faults;
        for (std::size_t i = 0; i < 4 * c.reference.size(); ++i) f[k++] = 10.0 * w;
        continue;
      }
      const std::vector<double>* pv[4] = {&p.omega1_rad_s, &p.omega2_rad_s, &p.F_ax1_N, &p.torque_driver_Nm};
      const std::vector<double>* rv[4] = {&c.reference.omega1_rad_s, &c.reference.omega2_rad_s,
                                          &c.reference.F_ax1_N, &c.reference.torque_driver_Nm};
      for (int q = 0; q < 4; ++q)
        for (std::size_t i = 0; i < c.reference.size(); ++i)
          f[k++] = w * ((*pv[q])[i] - (*rv[q])[i]) / c.scale[q];
    }
  }
};

struct Functor : Eigen::DenseFunctor<double> {
  Problem* pb;
  std::function<void()> tick;
  Functor(Problem* p, int n, int m) : Eigen::DenseFunctor<double>(n, m), pb(p) {}
  int operator()(const InputType& x, ValueType& f) const {
    pb->residuals(x, f);
    if (tick) tick();
    return 0;
  }
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// The command that reproduces a fit (the parameter file's header).
std::string command_line(const Options& o) {
  std::ostringstream s;
  s << "cvtplant calibrate --scene " << o.scenes << " --fit " << o.fit;
  if (!o.start.empty()) s << " --start " << o.start;
  if (o.sheaves != "scene") s << " --sheaves " << o.sheaves;
  if (o.t_end_s > 0) s << " --t-end " << o.t_end_s;
  s << " --rtol " << o.rtol << " --every " << o.every << " --max-evals " << o.max_evals << " --out " << o.out;
  if (!o.header.empty()) s << " --header " << o.header;
  if (o.function != "apply") s << " --function " << o.function;
  return s.str();
}

Action register_calibrate(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "Fit the plant's lumped parameters to multibody reference runs (docs/validation.md#calibration)");
  sub->add_option("--scene", opt->scenes, "Scenes to fit on, comma-separated (each one the reference can run)")
      ->capture_default_str();
  sub->add_option("--fit", opt->fit,
                  "Parameters to fit, comma-separated: k1_N_m, c1_Ns_m, k2_N_m, c2_Ns_m, lump_mass_kg, r1_m, r2_m, "
                  "normal_load_factor, entry_load_share, wrap_tension_share, chain_mass_kg_m, chain_stiffness_N, "
                  "creep_gain, centrifugal_gain, stop_tension_N, stop_tension_share, wrap_excess_share")
      ->capture_default_str();
  sub->add_option("--out", opt->out, "Write the fitted parameters as a parameter file (TOML [params])");
  sub->add_option("--header", opt->header,
                  "Also write them as a C++ header with cvt::calibrated::apply(RomParams&) (the built-in scenes')");
  sub->add_option("--out-dir", opt->out_dir, "Directory of the reference cache (shared with validate)")
      ->capture_default_str();
  sub->add_option("--function", opt->function,
                  "The header's function name, cvt::calibrated::NAME(RomParams&) (one header per fitted set)")
      ->capture_default_str();
  sub->add_option("--start", opt->start, "Start from a parameter file's values (default: the scenes' own)");
  add_sheaves_option(sub, opt->sheaves);
  sub->add_option("--t-end", opt->t_end_s, "Shorten every run to this simulated time [s]");
  sub->add_option("--rtol", opt->rtol, "Reference's BDF relative tolerance, [1e-11, 1e-3]")->capture_default_str();
  sub->add_option("--max-steps", opt->max_steps, "Cap on the reference's integrator steps per scene")
      ->capture_default_str();
  sub->add_option("--every", opt->every, "Fit on every N-th sample, [1, 1000]")->capture_default_str();
  sub->add_option("--max-evals", opt->max_evals, "Cap on plant evaluations of the optimiser, [1, 100000]")
      ->capture_default_str();
  sub->add_flag("--json", opt->json, "Print the result as JSON");
  return [opt, sub]() -> int {
    const Options& o = *opt;
    if (sub->count("--t-end") > 0 && !(o.t_end_s > 0 && o.t_end_s <= 3600))
      throw UsageError{"--t-end: must be in (0, 3600] s"};
    if (!(o.rtol >= 1e-11 && o.rtol <= 1e-3)) throw UsageError{"--rtol: outside [1e-11, 1e-3]"};
    if (!(o.every >= 1 && o.every <= 1000)) throw UsageError{"--every: outside [1, 1000]"};
    if (!(o.max_evals >= 1 && o.max_evals <= 100000)) throw UsageError{"--max-evals: outside [1, 100000]"};
    if (!(o.max_steps >= 1 && o.max_steps <= 1000000000000LL)) throw UsageError{"--max-steps: outside [1, 1e12]"};
    {
      bool ident = !o.function.empty() && !(o.function[0] >= '0' && o.function[0] <= '9');
      for (const char ch : o.function)
        ident = ident && ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_');
      if (!ident) throw UsageError{"--function: not a C++ identifier: '" + o.function + "'"};
    }
    Problem pb;
    pb.every = o.every;
    for (const auto& name : split(o.fit)) {
      const Fittable* f = nullptr;
      for (const auto& c : kFittable)
        if (name == c.name) f = &c;
      if (f == nullptr) throw UsageError{"--fit: unknown parameter '" + name + "'"};
      for (const auto* g : pb.fit)
        if (g == f) throw UsageError{"--fit: '" + name + "' given twice"};
      pb.fit.push_back(f);
    }
    if (pb.fit.empty()) throw UsageError{"--fit: no parameter"};
    const auto names = split(o.scenes);
    if (names.empty()) throw UsageError{"--scene: no scene"};
    std::vector<std::shared_ptr<LoadedScene>> loaded;
    std::vector<cvt::Scene> plant_scenes;
    for (const auto& n : names) {
      auto l = resolve_scene(n);
      std::string why;
      if (!reference_params(l->scene, sheave_choice(o.sheaves), why))
        throw UsageError{"--scene " + n + ": the reference cannot run " + why};
      loaded.push_back(l);
      // --start moves the plant's parameters only; the reference runs the scene.
      plant_scenes.push_back(l->scene);
      if (!o.start.empty()) apply_params_file(o.start, plant_scenes.back());
    }
    // The fitted values are shared by every scene: they start from the first's.
    pb.base = plant_scenes.front().params;
    // A share at an end of its range (0 or 1: a term switched off) has no
    // logit; its fit starts from the middle.
    for (const auto* f : pb.fit)
      if (f->share && !(pb.base.*(f->field) > 0.0 && pb.base.*(f->field) < 1.0)) pb.base.*(f->field) = 0.5;
    try {
      cvt::analysis::ensure_dir(o.out_dir);
      cvt::analysis::ensure_dir(o.out_dir + "/reference-cache");
    } catch (const cvt::analysis::InputError& e) {
      throw UsageError{std::string("--out-dir: ") + e.what()};
    }
    double ref_cpu = 0;
    for (std::size_t li = 0; li < loaded.size(); ++li) {
      Case c;
      c.name = loaded[li]->name;
      c.scene = plant_scenes[li];
      if (o.t_end_s > 0) c.scene.t_end_s = std::min(o.t_end_s, c.scene.t_end_s);
      cvt::Scene ref_scene = loaded[li]->scene;
      ref_scene.t_end_s = c.scene.t_end_s;
      std::string why;
      const auto mp = reference_params(ref_scene, sheave_choice(o.sheaves), why);
      cvt::mbd::RunOptions ro;
      ro.t_end_s = c.scene.t_end_s;
      ro.rtol = o.rtol;
      ro.sample_s = c.scene.frame_s;
      ro.max_steps = o.max_steps;
      const ReferenceRun rr =
          reference_run(*mp, ro, o.out_dir + "/reference-cache", "calibrate " + c.name + ": reference");
      ref_cpu += rr.cpu_s;
      c.reference = rr.series.select(rr.series.size(), std::size_t(o.every));
      const std::vector<double>* rv[4] = {&c.reference.omega1_rad_s, &c.reference.omega2_rad_s,
                                          &c.reference.F_ax1_N, &c.reference.torque_driver_Nm};
      for (int q = 0; q < 4; ++q) c.scale[q] = std::max(rms(*rv[q]), 1e-9);
      pb.cases.push_back(std::move(c));
    }
    const int n = static_cast<int>(pb.fit.size());
    const int m = pb.residual_count();
    Eigen::VectorXd theta = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd f0(m);
    pb.residuals(theta, f0);
    const double cost0 = f0.squaredNorm();

    Functor fn(&pb, n, m);
    Progress progress("calibrate", o.max_evals, "plant runs");
    fn.tick = [&]() { progress.update(static_cast<double>(pb.evals)); };
    Eigen::NumericalDiff<Functor> nd(fn, 1e-6);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<Functor>> lm(nd);
    lm.setMaxfev(o.max_evals);
    lm.setXtol(1e-8);
    lm.setFtol(1e-10);
    const auto status = lm.minimize(theta);
    progress.finish();

    Eigen::VectorXd f1(m);
    pb.residuals(theta, f1);
    const double cost1 = f1.squaredNorm();
    // Jacobian at the optimum, in theta = log(value/start): dvalue = value dtheta.
    Eigen::MatrixXd J(m, n);
    nd.df(theta, J);
    const double dof = std::max(1, m - n);
    const double s2 = cost1 / dof;
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
    cvt::RomParams fitted = pb.base;
    pb.apply(theta, fitted);

    nlohmann::json j;
    j["subcommand"] = "calibrate";
    j["scenes"] = names;
    j["sheaves"] = o.sheaves;
    j["optimiser"] = "Eigen LevenbergMarquardt (forward-difference Jacobian)";
    j["status"] = static_cast<int>(status);
    j["plant_evaluations"] = pb.evals;
    j["plant_faults"] = pb.faults;
    j["iterations"] = lm.iterations();
    j["residuals"] = m;
    j["cost_start"] = cost0;
    j["cost_end"] = cost1;
    j["rms_residual_start"] = std::sqrt(cost0 / m);
    j["rms_residual_end"] = std::sqrt(cost1 / m);
    j["reference_cpu_s"] = ref_cpu;
    nlohmann::json params = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
      const auto* f = pb.fit[static_cast<std::size_t>(i)];
      const double v = fitted.*(f->field);
      const double sigma = value_slope(*f, v) * std::sqrt(std::max(0.0, s2 * cov(i, i)));
      const bool idf = identifiable[static_cast<std::size_t>(i)];
      params.push_back({{"name", f->name},
                        {"start", pb.base.*(f->field)},
                        {"value", v},
                        {"sigma", idf ? nlohmann::json(sigma) : nlohmann::json(nullptr)},
                        {"sigma_rel", idf ? nlohmann::json(sigma / v) : nlohmann::json(nullptr)},
                        {"identifiable", idf}});
    }
    j["parameters"] = params;
    // The four relative RMS errors of each case at the start and the end.
    nlohmann::json per_case = nlohmann::json::array();
    {
      long k = 0;
      for (const auto& c : pb.cases) {
        const long len = static_cast<long>(c.reference.size());
        nlohmann::json e;
        e["scene"] = c.name;
        const char* q[4] = {"omega1", "omega2", "F_ax1", "torque_driver"};
        for (int qi = 0; qi < 4; ++qi) {
          e[q[qi]] = {{"rel_rms_start", f0.segment(k, len).norm()}, {"rel_rms_end", f1.segment(k, len).norm()}};
          k += len;
        }
        per_case.push_back(e);
      }
    }
    j["cases"] = per_case;

    if (!o.out.empty()) {
      std::FILE* f = open_output(o.out);
      std::fprintf(f, "# The real-time plant's lumped parameters fitted to the multibody reference\n");
      std::fprintf(f, "# (docs/validation.md#calibration). Written by:\n#   %s\n", command_line(o).c_str());
      std::fprintf(f, "# Least squares over the scenes %s: %d residuals, cost %.6g -> %.6g\n", o.scenes.c_str(), m,
                   cost0, cost1);
      std::fprintf(f, "# (rms residual %.4g -> %.4g); one standard deviation from the Jacobian at the optimum.\n",
                   std::sqrt(cost0 / m), std::sqrt(cost1 / m));
      std::fprintf(f, "[params]\n");
      for (const auto& p : params) {
        const double v = p["value"].get<double>();
        if (p["identifiable"].get<bool>())
          std::fprintf(f, "%s = %.17g  # +- %.3g (%.2g %%), start %.10g\n", p["name"].get<std::string>().c_str(), v,
                       p["sigma"].get<double>(), 100.0 * p["sigma_rel"].get<double>(), p["start"].get<double>());
        else
          std::fprintf(f, "%s = %.17g  # not identifiable from these runs, start %.10g\n",
                       p["name"].get<std::string>().c_str(), v, p["start"].get<double>());
      }
      close_output(f);
    }
    if (!o.header.empty()) {
      // The built-in scenes' copy (lib/ is heap-free and reads no files):
      // the same values to the last digit as the parameter file.
      std::FILE* f = open_output(o.header);
      std::fprintf(f, "#pragma once\n// The real-time plant's lumped parameters fitted to the multibody reference\n");
      std::fprintf(f, "// (docs/validation.md#calibration), written with the parameter file by:\n//   %s\n",
                   command_line(o).c_str());
      std::fprintf(f, "// rms residual %.4g -> %.4g over %d residuals.\n", std::sqrt(cost0 / m), std::sqrt(cost1 / m),
                   m);
      std::fprintf(f, "#include \"cvtplant/plant/rom_params.hpp\"\n\nnamespace cvt::calibrated {\n\n");
      std::fprintf(f, "constexpr void %s(RomParams& p) {\n", o.function.c_str());
      for (const auto& p : params)
        std::fprintf(f, "  p.%s = %.17g;\n", p["name"].get<std::string>().c_str(), p["value"].get<double>());
      std::fprintf(f, "}\n\n}  // namespace cvt::calibrated\n");
      close_output(f);
    }
    if (o.json) {
      print_json(j);
    } else {
      std::printf("Calibration on %s: %ld plant runs, %d residuals, rms residual %.4g -> %.4g\n", o.scenes.c_str(),
                  pb.evals, m, std::sqrt(cost0 / m), std::sqrt(cost1 / m));
      std::printf("| parameter | start | fitted | 1 sigma |\n|---|---|---|---|\n");
      for (const auto& p : params) {
        std::printf("| %s | %.6g | %.6g | ", p["name"].get<std::string>().c_str(), p["start"].get<double>(),
                    p["value"].get<double>());
        if (p["identifiable"].get<bool>())
          std::printf("%.3g (%.2g %%) |\n", p["sigma"].get<double>(), 100.0 * p["sigma_rel"].get<double>());
        else
          std::printf("not identifiable |\n");
      }
      std::printf("\n| scene | quantity | relative RMS error, start | after the fit |\n|---|---|---|---|\n");
      for (const auto& c : per_case)
        for (const char* q : {"omega1", "omega2", "F_ax1", "torque_driver"})
          std::printf("| %s | %s | %.2f %% | %.2f %% |\n", c["scene"].get<std::string>().c_str(), q,
                      100.0 * c[q]["rel_rms_start"].get<double>(), 100.0 * c[q]["rel_rms_end"].get<double>());
    }
    return 0;
  };
}

const bool registered = add_registrar(&register_calibrate);

}  // namespace

}  // namespace cvtcli::validation
