// `cvtplant lyapunov`: Lyapunov spectrum of a scene from its equations
// (Benettin + QR, docs/analysis.md#benettin), with confidence intervals, the
// convergence table, the trace check and a verdict.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "commands.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/systems.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "model_resolve.hpp"
#include "registry.hpp"

namespace {

using namespace cvt::analysis;

struct Verdict {
  std::string classification;
  std::vector<std::string> reasons;
};

// docs/analysis.md#spectrum-verdict: an exponent is "zero" if its CI covers 0
// or |lambda| <= 1e-3 (the resolution of a finite run); "positive"/"negative"
// if the CI excludes 0 by that margin.
Verdict spectrum_verdict(const SpectrumResult& r) {
  Verdict v;
  const std::size_t n = r.exponents.size();
  int pos = 0, zero = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double lo = r.exponents[i] - r.ci95[i], hi = r.exponents[i] + r.ci95[i];
    if (lo > 1e-3)
      ++pos;
    else if (hi >= -1e-3)
      ++zero;
  }
  char buf[256];
  std::snprintf(buf, sizeof buf, "%d exponent(s) positive, %d consistent with zero (95%% CI), %d negative", pos, zero,
                static_cast<int>(n) - pos - zero);
  v.reasons.push_back(buf);
  // A zero exponent that a continuous symmetry explains says nothing about the
  // attractor (docs/analysis.md#rom-lyapunov): it is not counted.
  if (r.symmetry_zero_exponents > 0 && zero >= r.symmetry_zero_exponents) {
    zero -= r.symmetry_zero_exponents;
    std::snprintf(buf, sizeof buf, "%d zero exponent(s) explained by a symmetry, not counted", r.symmetry_zero_exponents);
    v.reasons.push_back(buf);
  }
  if (r.is_map) {
    v.classification = pos > 0 ? "chaotic" : (zero > 0 ? "inconclusive" : "fixed_point_or_periodic");
    return v;
  }
  if (pos == 0 && zero == 0) {
    v.classification = "fixed_point";
    if (r.symmetry_zero_exponents > 0)
      std::snprintf(buf, sizeof buf,
                    "all other exponents negative: a relative equilibrium (constant slip while the speeds grow, "
                    "|f(x)| = %.3g at the end)",
                    r.final_speed);
    else
      std::snprintf(buf, sizeof buf, "all exponents negative; final |f(x)| = %.3g", r.final_speed);
    v.reasons.push_back(buf);
  } else if (pos == 0 && zero == 1) {
    v.classification = "periodic";
    v.reasons.push_back("one neutral exponent (the flow direction) and the rest negative: a stable limit cycle");
  } else if (pos == 0 && zero >= 2) {
    v.classification = "quasi_periodic";
    v.reasons.push_back("two or more neutral exponents and no positive one: motion on a torus (or too short a run)");
  } else if (pos >= 1 && zero >= 1) {
    v.classification = "chaotic";
    v.reasons.push_back("a positive exponent besides the neutral flow-direction exponent");
  } else {
    v.classification = "inconclusive";
    v.reasons.push_back("a positive exponent but no neutral one: an autonomous flow must have a zero exponent, so the "
                        "run is not converged (increase --t-end or decrease --dt)");
  }
  if (!r.smooth_along_orbit) {
    v.classification = "inconclusive";
    v.reasons.push_back("the orbit met a kink of the vector field: the exponents are not reliable (see notes)");
  }
  std::snprintf(buf, sizeof buf, "lambda_1(t) = a + b/t fit: a = %.3g +- %.2g", r.lambda1_extrapolated,
                1.96 * r.lambda1_extrapolated_se);
  v.reasons.push_back(buf);
  return v;
}

nlohmann::json to_json(const SpectrumResult& r) {
  nlohmann::json j;
  j["exponents"] = r.exponents;
  j["ci"] = r.ci95;
  j["ci_level"] = 0.95;
  j["batch_sd"] = r.batch_sd;
  j["sum"] = r.sum;
  j[r.is_map ? "mean_log_abs_det_jacobian" : "mean_trace_jacobian"] = r.trace_mean;
  j["sum_minus_trace"] = r.sum - r.trace_mean;
  nlohmann::json conv = nlohmann::json::array();
  for (const auto& row : r.convergence) conv.push_back({{r.is_map ? "t_iter" : "t_s", row.t}, {"exponents", row.exponents}});
  j["convergence"] = conv;
  j["lambda1_extrapolated"] = r.lambda1_extrapolated;
  j["lambda1_extrapolated_ci"] = 1.96 * r.lambda1_extrapolated_se;
  if (!r.is_map) {
    j["flow_direction_rate"] = r.flow_direction_rate;
    j["final_speed"] = r.final_speed;
    j["zero_index"] = r.zero_index;
  }
  j["x_final"] = r.x_final;
  j["steps"] = r.steps;
  // Flows count time in seconds, maps in iterations: the suffix says which.
  const std::string u = r.is_map ? "_iter" : "_s";
  j["dt" + u] = r.dt;
  j["t_transient" + u] = r.t_transient;
  j["t_warmup" + u] = r.t_warmup;
  j["t_end" + u] = r.t_end;
  j["t_renorm" + u] = r.t_renorm;
  j["reliable"] = r.smooth_along_orbit;
  j["symmetry_zero_exponents"] = r.symmetry_zero_exponents;
  if (!r.notes.empty()) j["notes"] = r.notes;
  if (!r.diagnostics.empty()) j["diagnostics"] = r.diagnostics;
  if (!r.jacobian_eigen_real_final.empty()) j["jacobian_eigenvalues_real_final"] = r.jacobian_eigen_real_final;
  return j;
}

cvtcli::Action register_lyapunov(CLI::App& app) {
  auto* sub = app.add_subcommand("lyapunov", "Lyapunov spectrum of a scene from its equations (Benettin/QR)");
  struct Args {
    std::string scene, x0;
    std::vector<std::string> params;
    double t_transient = -1, t_warmup = -1, t_end = -1, dt = -1, t_renorm = -1;
    int batches = 20;
    bool json = false, dt_check = false, list = false;
    cvtcli::Caps caps;
  };
  auto a = std::make_shared<Args>();
  sub->add_option("--scene", a->scene,
                  "lorenz, rossler, oscillator-coulomb, oscillator-stribeck, henon, logistic (see --list), or a "
                  "plant scene with constant inputs: built-in (see `cvtplant scenes`) or a TOML scene file");
  sub->add_option("--x0", a->x0, "initial state, comma-separated (default: the scene's; oscillators: 0,3,0,6)");
  sub->add_option("--param", a->params, "override a scene parameter, name=value (repeatable)");
  cvtcli::add_real(sub, "--t-transient", a->t_transient, {0, 1e9}, "discarded time [s] (maps: iterations)");
  cvtcli::add_real(sub, "--t-warmup", a->t_warmup, {0, 1e9}, "deviation-vector warm-up [s], not accumulated");
  cvtcli::add_real(sub, "--t-end", a->t_end, {0, 1e9, true}, "accumulation time [s] (maps: iterations)");
  cvtcli::add_real(sub, "--dt", a->dt, {1e-9, 1}, "RK4 step [s]");
  cvtcli::add_real(sub, "--t-renorm", a->t_renorm, {0, 1e6, true},
                   "QR interval [s] (default: the scene's; max(dt, 0.05) for the reference systems, 1e-3 for the ROM)");
  cvtcli::add_int(sub, "--batches", a->batches, 2, 1000, "batches for the confidence interval");
  sub->add_flag("--dt-check", a->dt_check, "repeat with dt/2 and report the change of each exponent");
  sub->add_flag("--list", a->list, "list scenes and their parameters");
  sub->add_flag("--json", a->json, "machine-readable output");
  cvtcli::add_caps(sub, a->caps, true, false);
  return [a]() -> int {
    try {
      if (a->list) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& s : models())
          j.push_back({{"name", s.name}, {"description", s.description}, {"map", s.is_map}, {"params", s.default_params},
                       {"x0", s.default_x0}, {"states", s.state_names}});
        if (a->json) {
          cvtcli::print_json(j);
        } else {
          for (const auto& s : models()) std::printf("%-22s %s\n", s.name.c_str(), s.description.c_str());
        }
        return 0;
      }
      if (a->scene.empty()) throw cvtcli::UsageError{"--scene is required (see --list)"};
      const auto model = cvtcli::resolve_model(a->scene);
      const Model& s = *model;
      const Params p = merge_params(s, cvtcli::parse_assignments(a->params, "--param"));
      const std::vector<double> x0 =
          a->x0.empty() ? s.default_x0 : cvtcli::parse_list(a->x0, static_cast<std::size_t>(s.dim), "--x0");
      BenettinOptions o = s.defaults;
      if (a->t_transient >= 0) o.t_transient = a->t_transient;
      if (a->t_warmup >= 0) o.t_warmup = a->t_warmup;
      if (a->t_end >= 0) o.t_end = a->t_end;
      if (a->dt >= 0) o.dt = a->dt;
      if (a->t_renorm >= 0) o.t_renorm = a->t_renorm;
      o.batches = a->batches;
      if (!(o.t_end > 0)) throw cvtcli::UsageError{"--t-end must be > 0"};
      if (!s.is_map && !(o.dt > 0)) throw cvtcli::UsageError{"--dt must be > 0"};
      if (o.batches < 2 || o.batches > 1000) throw cvtcli::UsageError{"--batches must be in 2..1000"};
      if (s.is_map && o.t_end < o.batches) throw cvtcli::UsageError{"--t-end must be at least --batches iterations"};
      // Work before the run: every step of transient, warm-up and accumulation
      // (dt/2 check: twice as many again). A plant scene may shorten dt for its
      // stiffness; the library refuses that run against the same cap.
      const double runs = a->dt_check && !s.is_map ? 3.0 : 1.0;
      const double span = o.t_transient + o.t_warmup + o.t_end;
      cvtcli::require_steps(runs * (s.is_map ? span : span / o.dt), a->caps,
                            s.is_map ? "--t-transient + --t-warmup + --t-end iterations"
                                     : std::string("(--t-transient + --t-warmup + --t-end) / --dt") +
                                           (runs > 1 ? ", three times with --dt-check" : ""));
      o.max_steps = a->caps.max_steps;
      // One bar over all runs (the --dt-check run at dt/2 counts twice).
      cvtcli::Progress progress("lyapunov " + s.name, 100.0 * runs, "");
      double run_base = 0, run_weight = 100;
      o.progress = [&](double done, double total) {
        progress.update(run_base + run_weight * done / std::max(1.0, total));
      };
      SpectrumResult r;
      try {
        r = s.spectrum(p, x0, o);
      } catch (const LimitError& e) {
        throw cvtcli::UsageError{std::string(e.what()) + "; raise it with --max-steps"};
      } catch (const std::invalid_argument& e) {
        throw cvtcli::UsageError{e.what()};
      } catch (const InputError& e) {
        throw cvtcli::UsageError{e.what()};
      } catch (const std::runtime_error& e) {
        throw cvtcli::RunError{e.what()};
      }
      const Verdict v = spectrum_verdict(r);
      nlohmann::json j;
      j["subcommand"] = "lyapunov";
      j.update(to_json(r));
      j["scene"] = s.name;
      j["exponent_unit"] = s.is_map ? "1/iteration" : "1/s";
      j["ci_method"] = "batch means over " + std::to_string(o.batches) + " equal batches, Student t";
      j["params"] = p;
      j["x0"] = x0;
      j["classification"] = v.classification;
      j["evidence"] = v.reasons;
      if (a->dt_check && !s.is_map) {
        // Halve the step actually used (ROM scenes shorten --dt from their
        // stiffness) and keep the QR interval.
        BenettinOptions o2 = o;
        o2.dt = r.dt / 2;
        o2.t_renorm = r.t_renorm;
        run_base = 100;
        run_weight = 200;
        SpectrumResult r2;
        try {
          r2 = s.spectrum(p, x0, o2);
        } catch (const LimitError& e) {
          throw cvtcli::UsageError{std::string("dt/2 run: ") + e.what() + "; raise it with --max-steps"};
        } catch (const std::runtime_error& e) {
          throw cvtcli::RunError{std::string("dt/2 run: ") + e.what()};
        }
        std::vector<double> diff;
        double worst = 0;
        for (std::size_t i = 0; i < r.exponents.size(); ++i) {
          diff.push_back(r2.exponents[i] - r.exponents[i]);
          worst = std::max(worst, std::abs(diff.back()));
        }
        j["dt_check"] = {{"dt_half_s", o2.dt}, {"exponents_dt_half", r2.exponents}, {"difference", diff}, {"max_abs_difference", worst}};
      }
      progress.finish();
      if (a->json) {
        cvtcli::print_json(j);
        return 0;
      }
      std::printf("scene %s, dt %g, transient %g, warm-up %g, accumulated %g\n", s.name.c_str(), r.dt, r.t_transient,
                  r.t_warmup, r.t_end);
      for (std::size_t i = 0; i < r.exponents.size(); ++i)
        std::printf("  lambda_%zu = %+.6f +- %.6f\n", i + 1, r.exponents[i], r.ci95[i]);
      std::printf("  sum %.6f, mean %s %.6f\n", r.sum, r.is_map ? "ln|det J|" : "trace J", r.trace_mean);
      std::printf("convergence (t: exponents)\n");
      for (const auto& row : r.convergence) {
        std::printf("  %12g:", row.t);
        for (double e : row.exponents) std::printf(" %+.6f", e);
        std::printf("\n");
      }
      if (!r.jacobian_eigen_real_final.empty()) {
        std::printf("real parts of the eigenvalues of J at the final state:");
        for (double e : r.jacobian_eigen_real_final) std::printf(" %+.6f", e);
        std::printf("\n");
      }
      for (const auto& note : r.notes) std::printf("note: %s\n", note.c_str());
      std::printf("classification: %s\n", v.classification.c_str());
      for (const auto& s2 : v.reasons) std::printf("  - %s\n", s2.c_str());
      if (j.contains("dt_check"))
        std::printf("dt/2 check: max |change| %.3g\n", j["dt_check"]["max_abs_difference"].get<double>());
      return 0;
    } catch (const InputError& e) {
      throw cvtcli::UsageError{e.what()};
    }
  };
}

static const bool registered = cvtcli::add_registrar(&register_lyapunov);

}  // namespace
