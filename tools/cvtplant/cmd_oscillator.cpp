// `cvtplant oscillator`: the seed's 2-DOF stick-slip oscillator (Eq. 9) run
// with a fixed-step method in any scalar type (docs/cli.md#oscillator).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "cvtplant/files/interrupt.hpp"
#include "registry.hpp"
#include "cvtplant/analysis/csv_writer.hpp"
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace {

struct Options {
  std::string friction = "coulomb";
  std::string x0 = "0,0,0,0";
  double t_end_s = 10.0;
  double dt_s = 1e-4;
  std::string integrator = "rk4";
  std::string scalar = "double";
  std::string csv;
  int every = 1;
  bool json = false;
  // Settling test on the last window (docs/cli.md#oscillator-summary).
  double settle_window_s = 1.0;
  cvtcli::Caps caps;
};

struct Summary {
  double final_state[4] = {0, 0, 0, 0};
  bool finite = true;
  bool write_failed = false;
  bool saturated = false;  // fixed point: the state left the range its arithmetic holds
  bool settled = false;
  double x1_min = 0, x1_max = 0, v_abs_max = 0;
  long window_steps = 0;  // steps in the last window (none: its figures were not computed)
  bool interrupted = false;  // SIGINT or SIGTERM stopped the run after a whole row
  double period_s = 0;  // 0 if no oscillation detected
  long steps = 0;
  double wall_s = 0;
  double dt_actual_s = 0;  // the step taken: --dt rounded to the scalar (q16.16: a multiple of 2^-16 s)
};

// Largest magnitude the right-hand side of seed Eq. 9 forms at state x
// (docs/cli.md#oscillator-fixed-point): per mass, the friction force at its
// largest coefficient, the ground spring and damper and the coupling element,
// divided by the mass. In q16.16 every one of them must stay below 32768 or
// it saturates; the run keeps them below half of that so the RK4 stages,
// which evaluate the right-hand side up to a step ahead, stay in range too.
double rhs_magnitude(const cvt::OscillatorParams<double>& p, const double x[4]) {
  const double mu_max = p.friction.law == cvt::FrictionLaw::case2 ? p.friction.mu0 * p.friction.sigma : p.friction.mu0;
  const double mid = p.k2_N_m * std::fabs(x[0] - x[2]) + p.c2_Ns_m * std::fabs(x[1] - x[3]);
  double worst = 0;
  for (int i = 0; i < 2; ++i) {
    const double m = i == 0 ? p.m1_kg : p.m2_kg;
    const double ground = p.k1_N_m * std::fabs(x[2 * i]) + p.c1_Ns_m * std::fabs(x[2 * i + 1]);
    worst = std::max({worst, (mu_max * m * p.g_m_s2 + ground + mid) / m, ground, mid, std::fabs(x[2 * i + 1])});
  }
  return worst;
}
constexpr double kFixedHeadroom = 16384.0;  // half the q16.16 range

template <class T>
Summary run(const Options& o, const cvt::FrictionParams<double>& fr, const double x0[4], std::FILE* csv) {
  using Osc = cvt::StickSlipOscillator<T>;
  const auto pd = cvt::OscillatorParams<double>::seed_section3(fr);
  const Osc sys(pd.template cast<T>());
  cvt::Method method{};
  cvt::parse_method(o.integrator.c_str(), method);
  typename Osc::State x;
  for (int i = 0; i < 4; ++i) x(i) = cvt::from_double<T>(x0[i]);
  const T h = cvt::from_double<T>(o.dt_s);
  const double h_actual = cvt::to_double(h);  // fixed point rounds the step
  const long n = std::lround(o.t_end_s / h_actual);
  const long window_start = std::max<long>(0, n - std::lround(o.settle_window_s / h_actual));

  Summary s;
  s.dt_actual_s = h_actual;
  s.x1_min = 1e300;
  s.x1_max = -1e300;
  // Period from upward zero crossings of v1 in the second half of the run
  // (the stick-slip cycle reverses the masses every period).
  double last_cross_t = -1, first_cross_t = -1;
  int crossings = 0;
  double prev_v1 = cvt::to_double(x(1));
  const double v_mid = 0.0;

  // Shortest round-trip numbers, buffered (docs/cli.md#csv-numbers).
  cvt::analysis::CsvWriter w(csv);
  if (csv != nullptr) {
    for (const char* h : {"t", "x1", "v1", "x2", "v2", "F1", "F2"}) w.text(h);
    w.end_row();
  }
  auto write_row = [&](double t) {
    if (csv == nullptr) return;
    const T v = sys.params().belt_speed_m_s;
    w.num(t);
    for (int k = 0; k < 4; ++k) w.num(cvt::to_double(x(k)));
    w.num(cvt::to_double(sys.friction_force_N(T(x(1) - v), T(sys.params().m1_kg * sys.params().g_m_s2))));
    w.num(cvt::to_double(sys.friction_force_N(T(x(3) - v), T(sys.params().m2_kg * sys.params().g_m_s2))));
    w.end_row();
  };
  write_row(0.0);
  // No bar when the CSV itself goes to stdout: on a terminal the two would interleave.
  // The loop polls the interruption flag itself, between rows.
  cvtcli::Progress progress("oscillator", csv == stdout ? 0.0 : o.t_end_s, "s", stderr,
                            cvtcli::Progress::Interrupts::polled_by_caller);

  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 1; i <= n; ++i) {
    cvt::step(method, sys, x, h);
    const double t = static_cast<double>(i) * h_actual;
    const double v1 = cvt::to_double(x(1));
    if (!std::isfinite(v1) || !std::isfinite(cvt::to_double(x(0)))) {
      s.finite = false;
      s.steps = i;
      break;
    }
    if constexpr (cvt::is_fixed_point_v<T>) {
      const double xs[4] = {cvt::to_double(x(0)), v1, cvt::to_double(x(2)), cvt::to_double(x(3))};
      if (rhs_magnitude(pd, xs) > kFixedHeadroom) {
        s.saturated = true;
        s.steps = i;
        break;
      }
    }
    if (i >= window_start) {
      const double x1 = cvt::to_double(x(0));
      if (s.window_steps++ == 0) s.x1_min = s.x1_max = x1;
      s.x1_min = std::min(s.x1_min, x1);
      s.x1_max = std::max(s.x1_max, x1);
      s.v_abs_max = std::max({s.v_abs_max, std::fabs(v1), std::fabs(cvt::to_double(x(3)))});
    }
    if (prev_v1 < v_mid && v1 >= v_mid && t > 0.5 * o.t_end_s) {
      if (first_cross_t < 0) first_cross_t = t;
      last_cross_t = t;
      ++crossings;
    }
    prev_v1 = v1;
    if ((i & 16383) == 0) progress.update(t);
    // A signal: this step is the last, its row written whole.
    const bool stop = cvt::files::interrupted();
    if (csv != nullptr && (i % o.every == 0 || stop)) {
      write_row(t);
      // Closed pipe, full disk: stop, the caller reports it (a failed block
      // write shows on the FILE).
      if (!cvtcli::output_ok(csv)) {
        s.write_failed = true;
        s.steps = i;
        break;
      }
    }
    s.steps = i;
    if (stop) {
      s.interrupted = true;
      break;
    }
  }
  w.flush();
  if (csv != nullptr && !s.write_failed && !cvtcli::output_ok(csv)) s.write_failed = true;
  progress.finish();
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (int i = 0; i < 4; ++i) s.final_state[i] = cvt::to_double(x(i));
  // Settled: the last window shows neither motion nor drift at the resolution
  // that matters to the seed's figures (1e-4 m, 1e-3 m/s).
  s.settled = s.finite && s.window_steps > 0 && (s.x1_max - s.x1_min) < 1e-4 && s.v_abs_max < 1e-3;
  if (!s.settled && crossings >= 2) s.period_s = (last_cross_t - first_cross_t) / (crossings - 1);
  return s;
}

cvtcli::Action register_oscillator(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "oscillator", "Run the seed's 2-DOF stick-slip oscillator (Eq. 9, section-3 parameters)");
  sub->add_option("--friction", opt->friction, "Friction law: coulomb (constant mu0) or stribeck (section 3)")
      ->check(CLI::IsMember({"coulomb", "stribeck"}));
  sub->add_option("--x0", opt->x0, "Initial state X1,V1,X2,V2 [m, m/s, m, m/s]");
  cvtcli::add_real(sub, "--t-end", opt->t_end_s, {0, 1e6, true}, "Simulated time [s]")->required();
  cvtcli::add_real(sub, "--dt", opt->dt_s, {1e-9, 1}, "Fixed step [s], at most --t-end");
  sub->add_option("--integrator", opt->integrator,
                  "euler | semi-implicit-euler | heun | rk4 | linear-implicit-euler | ros2");
  sub->add_option("--scalar", opt->scalar, "double | float | fixed (q16.16)")
      ->check(CLI::IsMember({"double", "float", "fixed"}));
  sub->add_option("--csv", opt->csv, "Write the trajectory as CSV (t,x1,v1,x2,v2,F1,F2); '-' for stdout");
  cvtcli::add_int(sub, "--every", opt->every, 1, 1000000000, "Write every N-th step to the CSV");
  sub->add_flag("--json", opt->json, "Print a JSON summary instead of the text one");
  cvtcli::add_caps(sub, opt->caps, true, false);

  return [opt, sub]() -> int {
    const Options& o = *opt;
    cvt::Method m{};
    if (!cvt::parse_method(o.integrator.c_str(), m))
      throw cvtcli::UsageError{"--integrator: unknown method '" + o.integrator + "'"};
    if (o.dt_s > o.t_end_s) throw cvtcli::UsageError{"--dt: must be <= --t-end"};
    cvtcli::require_steps(std::round(o.t_end_s / o.dt_s), o.caps, "--t-end / --dt");
    if (o.json && o.csv == "-") throw cvtcli::UsageError{"--json and --csv - both write to stdout; give --csv a file"};
    if (o.scalar == "fixed" && o.dt_s < 4.0 / 65536.0)
      throw cvtcli::UsageError{"--dt: q16.16 steps are multiples of 2^-16 s; below 4 of them (6.1e-5 s) the "
                               "increments are too coarse (use --dt >= 6.1e-5)"};
    const std::vector<double> x0 = cvtcli::parse_list(o.x0, 4, "--x0");
    const auto fr = o.friction == "coulomb" ? cvt::friction_presets::oscillator_coulomb<double>()
                                             : cvt::friction_presets::oscillator_stribeck<double>();
    if (o.scalar == "fixed") {
      const double load = rhs_magnitude(cvt::OscillatorParams<double>::seed_section3(fr), x0.data());
      if (load > kFixedHeadroom) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      "--x0: the right-hand side reaches %.4g at this state; q16.16 holds %.0f with the headroom "
                      "its steps need (use --scalar double or float)",
                      load, kFixedHeadroom);
        throw cvtcli::UsageError{msg};
      }
    }
    std::FILE* csv = sub->count("--csv") == 0 ? nullptr : cvtcli::open_output(o.csv, "--csv");
    Summary s;
    if (o.scalar == "double") s = run<double>(o, fr, x0.data(), csv);
    else if (o.scalar == "float") s = run<float>(o, fr, x0.data(), csv);
    else s = run<cvt::q16_16>(o, fr, x0.data(), csv);
    cvtcli::close_output(csv);
    // With the CSV on stdout the text summary goes to stderr: stdout holds data only.
    std::FILE* info = csv == stdout ? stderr : stdout;

    const double x_eq = cvt::StickSlipOscillator<double>(cvt::OscillatorParams<double>::seed_section3(fr))
                            .sliding_equilibrium_m();
    const char* behaviour = s.interrupted   ? "interrupted"
                            : !s.finite     ? "diverged"
                            : s.saturated   ? "saturated"
                            : s.settled     ? "settled"
                            : s.period_s > 0 ? "oscillating"
                                             : "moving";
    const double t_reached = static_cast<double>(s.steps) * s.dt_actual_s;
    // Not computed (docs/cli.md#nulls): the last window's figures of a run
    // that never reached it, a cost per step of no step.
    const bool window = s.window_steps > 0 && !s.interrupted;
    const double ns_step = s.steps > 0 ? 1e9 * s.wall_s / static_cast<double>(s.steps) : std::nan("");
    if (o.json) {
      nlohmann::json j;
      j["subcommand"] = "oscillator";
      j["status"] = s.interrupted ? "interrupted" : (!s.finite || s.saturated) ? "failed" : "ok";
      j["t_reached_s"] = t_reached;
      j["friction"] = o.friction;
      j["integrator"] = o.integrator;
      j["scalar"] = o.scalar;
      j["dt_s"] = o.dt_s;
      j["dt_actual_s"] = s.dt_actual_s;
      j["t_end_s"] = o.t_end_s;
      j["steps"] = s.steps;
      j["final_state"] = {{"x1_m", s.final_state[0]}, {"v1_m_s", s.final_state[1]}, {"x2_m", s.final_state[2]},
                          {"v2_m_s", s.final_state[3]}};
      j["finite"] = s.finite;
      j["settled"] = window ? nlohmann::json(s.settled) : nlohmann::json(nullptr);
      j["behaviour"] = behaviour;
      j["sliding_equilibrium_m"] = x_eq;
      j["last_window"] = {{"window_s", o.settle_window_s},
                          {"x1_peak_to_peak_m", window ? nlohmann::json(s.x1_max - s.x1_min) : nlohmann::json(nullptr)},
                          {"max_abs_velocity_m_s", window ? nlohmann::json(s.v_abs_max) : nlohmann::json(nullptr)}};
      j["period_s"] = s.period_s > 0 ? nlohmann::json(s.period_s) : nlohmann::json(nullptr);
      j["wall_s"] = s.wall_s;
      j["ns_per_step"] = cvtcli::json_number(ns_step);
      cvtcli::print_json(j);
    } else {
      std::fprintf(info, "Stick-slip oscillator (seed Eq. 9), %s friction, %s, dt = %g s, %s\n", o.friction.c_str(),
                  o.integrator.c_str(), o.dt_s, o.scalar.c_str());
      std::fprintf(info, "  start      [x1 v1 x2 v2] = [%g %g %g %g]\n", x0[0], x0[1], x0[2], x0[3]);
      std::fprintf(info, "  after %g s [x1 v1 x2 v2] = [%.6f %.6f %.6f %.6f]\n", t_reached, s.final_state[0],
                  s.final_state[1], s.final_state[2], s.final_state[3]);
      std::fprintf(info, "  behaviour: %s", behaviour);
      if (s.settled) std::fprintf(info, " (sliding equilibrium x* = %.6f m)", x_eq);
      if (s.period_s > 0)
        std::fprintf(info, " (period %.4f s, x1 peak-to-peak %.4f m over the last %g s)", s.period_s, s.x1_max - s.x1_min,
                    o.settle_window_s);
      std::fprintf(info, "\n  %ld steps in %.3f s wall (%s ns/step)\n", s.steps, s.wall_s,
                   cvtcli::text_number(ns_step, "%.0f").c_str());
    }
    if (s.interrupted) {
      char at[64];
      std::snprintf(at, sizeof at, "t = %.6g s", t_reached);
      throw cvtcli::Interrupted{at, true};
    }
    if (!s.finite || s.saturated) {
      char buf[200];
      if (!s.finite)
        std::snprintf(buf, sizeof buf,
                      "the state became non-finite at step %ld (t = %g s): the step is too large for this integrator",
                      s.steps, static_cast<double>(s.steps) * s.dt_actual_s);
      else
        std::snprintf(buf, sizeof buf,
                      "the state left the q16.16 range at step %ld (t = %g s): the right-hand side exceeds %.0f "
                      "(use --scalar double or float)",
                      s.steps, static_cast<double>(s.steps) * s.dt_actual_s, kFixedHeadroom);
      throw cvtcli::RunError{buf};
    }
    return 0;
  };
}

const bool registered = cvtcli::add_registrar(&register_oscillator);

}  // namespace
