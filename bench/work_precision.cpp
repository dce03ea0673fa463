// Work-precision of the offline solvers on the plant (docs/performance.md):
// the adaptive RODAS4 (scene/adaptive_runner.hpp) against Boost.Odeint's
// rosenbrock4 with dense output and SUNDIALS CVODE (BDF, dense direct
// solver), all three on the same right-hand side (CvtRom::derivative) and
// analytic Jacobian (CvtRom::jacobian), tolerances swept, each run's error
// measured at the frame times against an independent reference (the fixed-
// step plant with 1024 ROS2 substeps per frame), cost as CPU time and counts
// of right-hand sides, Jacobians and LU factorisations.
// Second table: the cost of single frames, the real-time frame stepper
// against the peers advancing one frame at a time.
//
//   work_precision wp  [--t-end S] [--quick]   work-precision rows (CSV, stdout)
//   work_precision frames [--t-end S]          per-frame cost rows (CSV, stdout)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/scene/adaptive_runner.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

namespace odeint = boost::numeric::odeint;
// Frames of a run, row-major: frames() rows of n states in SI units.
struct Trace {
  int n = 0;
  std::vector<double> v;
  long frames() const { return n > 0 ? static_cast<long>(v.size()) / n : 0; }
  void add(const double* x, int count) {
    n = count;
    v.insert(v.end(), x, x + count);
  }
};

double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Work {
  long steps = 0, rhs = 0, jac = 0, lu = 0;
};

struct Point {
  std::string solver;
  double tol = 0, error = 0, cpu_s_per_s = 0;
  Work work;
  bool ok = true;
};

// docs/performance.md#error; infinite if the run stopped early.
double rel_rms(const Trace& ref, const Trace& out, std::uint32_t features) {
  if (out.frames() != ref.frames()) return INFINITY;
  return cvt::trajectory_relative_rms(ref.v.data(), out.v.data(), ref.frames(), ref.n, features);
}

template <std::uint32_t F>
struct Problem {
  using Plant = cvt::CvtRom<double, F>;
  using State = typename Plant::State;
  using Jac = typename Plant::Jacobian;
  static constexpr int N = Plant::kStates;
  cvt::Scene scene;
  Plant plant;
  State x0;
  State floor;  // absolute-tolerance floors (adaptive_atol_floor)
  long frames;

  explicit Problem(const cvt::Scene& s) : scene(s), plant(s.params) {
    plant.inputs = cvt::scene_inputs_at<double>(s, 0.0);
    x0 = plant.initial_state(s.initial);
    for (int i = 0; i < N; ++i) floor(i) = cvt::adaptive_atol_floor(F, i);
    frames = cvt::scene_frames(s);
  }
  // Appends x in SI units to a trace.
  void log(Trace& t, const State& x) const {
    const auto y = plant.to_si(x);
    t.add(y.data(), N);
  }
};

// The reference: the frame stepper with `sub` ROS2 substeps per frame.
template <std::uint32_t F>
Trace reference(const Problem<F>& p, int sub) {
  cvt::RomSimConfig c = cvt::sim_config_of(p.scene);
  c.method = cvt::Method::ros2;
  c.substeps = sub;
  c.w_slope_floor = false;
  c.watchdog_energy = false;
  Trace t;
  cvt::run_scene<double, F>(p.scene, c, [&](long, double, const cvt::RomSimulator<double, F>& sim) {
    const auto x = sim.state_si();
    t.add(x.data(), static_cast<int>(x.size()));
    return true;
  });
  return t;
}

template <std::uint32_t F>
Trace run_rodas4(const Problem<F>& p, double tol, Work& w, bool& ok) {
  cvt::AdaptiveConfig c;
  c.rtol = c.atol = tol;
  // The peers produce the states at the frames only: no energy ledger here.
  c.energy = false;
  cvt::AdaptiveRun<F> run(p.scene.params, c);
  Trace t;
  t.v.reserve(static_cast<std::size_t>((p.frames + 1) * Problem<F>::N));
  const cvt::AdaptiveStatus st = run.run(p.scene, p.scene.frame_s, [&](long, double, const cvt::AdaptiveFrame<F>& fr) {
    p.log(t, fr.state());
    return true;
  });
  ok = st == cvt::AdaptiveStatus::ok;
  const cvt::Rodas4Work& k = run.work();
  w = Work{k.accepted + k.rejected, k.rhs, k.jacobians, k.factorizations};
  return t;
}

// The plant for Boost.Odeint's rosenbrock4, in variables scaled by the
// tolerance floors (y = x / floor), which gives its scalar absolute
// tolerance the per-state meaning of the others'. The scaling is a diagonal
// product on the same right-hand side and Jacobian.
template <std::uint32_t F>
struct BoostOde {
  using V = boost::numeric::ublas::vector<double>;
  using M = boost::numeric::ublas::matrix<double>;
  static constexpr int N = Problem<F>::N;
  const Problem<F>* p;
  Work* w;
  typename Problem<F>::State unscaled(const V& y) const {
    typename Problem<F>::State x;
    for (int i = 0; i < N; ++i) x(i) = y[i] * p->floor(i);
    return x;
  }
  V scaled(const typename Problem<F>::State& x) const {
    V y(N);
    for (int i = 0; i < N; ++i) y[i] = x(i) / p->floor(i);
    return y;
  }
  struct Rhs {
    const BoostOde* o;
    void operator()(const V& y, V& dydt, double) const {
      typename Problem<F>::State f;
      o->p->plant.derivative(o->unscaled(y), f);
      for (int i = 0; i < N; ++i) dydt[i] = f(i) / o->p->floor(i);
      ++o->w->rhs;
    }
  };
  struct Jac {
    const BoostOde* o;
    void operator()(const V& y, M& J, double, V& dfdt) const {
      typename Problem<F>::Jac Jx;
      o->p->plant.jacobian(o->unscaled(y), Jx);
      for (int i = 0; i < N; ++i) {
        dfdt[i] = 0.0;
        for (int j = 0; j < N; ++j) J(i, j) = Jx(i, j) * o->p->floor(j) / o->p->floor(i);
      }
      ++o->w->jac;
      ++o->w->lu;  // rosenbrock4 factorises once per Jacobian
    }
  };
  std::pair<Rhs, Jac> system() const { return {Rhs{this}, Jac{this}}; }
};

// Boost.Odeint rosenbrock4 with its dense output, sampled at the frames.
template <std::uint32_t F>
Trace run_boost(const Problem<F>& p, double tol, Work& w, bool& ok) {
  using V = boost::numeric::ublas::vector<double>;
  constexpr int N = Problem<F>::N;
  const BoostOde<F> ode{&p, &w};
  V y = ode.scaled(p.x0);
  std::vector<double> times;
  for (long k = 0; k <= p.frames; ++k) times.push_back(static_cast<double>(k) * p.scene.frame_s);
  Trace t;
  t.v.reserve(times.size() * N);
  auto stepper = odeint::make_dense_output<odeint::rosenbrock4<double>>(tol, tol);
  try {
    w.steps = static_cast<long>(odeint::integrate_times(
        stepper, ode.system(), y, times.begin(), times.end(), 1e-6,
        [&](const V& yy, double) { p.log(t, ode.unscaled(yy)); }));
    ok = true;
  } catch (const std::exception&) {
    ok = false;
  }
  return t;
}

// CVODE BDF with the dense direct solver and the analytic Jacobian,
// absolute tolerance tol x floor per state, output at each frame time
// (CV_NORMAL: interpolated from its history).
template <std::uint32_t F>
struct Cvode {
  static constexpr int N = Problem<F>::N;
  const Problem<F>& p;
  Work* w;
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr, atol = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;

  static int rhs(double, N_Vector yv, N_Vector fv, void* ud) {
    auto* self = static_cast<Cvode*>(ud);
    typename Problem<F>::State x, f;
    for (int i = 0; i < N; ++i) x(i) = NV_Ith_S(yv, i);
    self->p.plant.derivative(x, f);
    for (int i = 0; i < N; ++i) NV_Ith_S(fv, i) = f(i);
    ++self->w->rhs;
    return 0;
  }
  static int jac(double, N_Vector yv, N_Vector, SUNMatrix J, void* ud, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<Cvode*>(ud);
    typename Problem<F>::State x;
    typename Problem<F>::Jac Jx;
    for (int i = 0; i < N; ++i) x(i) = NV_Ith_S(yv, i);
    self->p.plant.jacobian(x, Jx);
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) SM_ELEMENT_D(J, i, j) = Jx(i, j);
    ++self->w->jac;
    return 0;
  }

  Cvode(const Problem<F>& prob, double tol, Work* work) : p(prob), w(work) {
    SUNContext_Create(nullptr, &ctx);
    y = N_VNew_Serial(N, ctx);
    atol = N_VNew_Serial(N, ctx);
    for (int i = 0; i < N; ++i) {
      NV_Ith_S(y, i) = p.x0(i);
      NV_Ith_S(atol, i) = tol * p.floor(i);
    }
    mem = CVodeCreate(CV_BDF, ctx);
    CVodeInit(mem, rhs, 0.0, y);
    CVodeSVtolerances(mem, tol, atol);
    CVodeSetUserData(mem, this);
    A = SUNDenseMatrix(N, N, ctx);
    LS = SUNLinSol_Dense(y, A, ctx);
    CVodeSetLinearSolver(mem, LS, A);
    CVodeSetJacFn(mem, jac);
    CVodeSetMaxNumSteps(mem, 100000000);
  }
  ~Cvode() {
    CVodeFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(A);
    N_VDestroy(y);
    N_VDestroy(atol);
    SUNContext_Free(&ctx);
  }
  // To t_out; with `stop`, never integrating beyond it (a real-time loop
  // does not know the next frame's inputs).
  bool advance(double t_out, bool stop = false) {
    double t = 0;
    if (stop) CVodeSetStopTime(mem, t_out);
    return CVode(mem, t_out, y, &t, CV_NORMAL) >= 0;
  }
  typename Problem<F>::State state() const {
    typename Problem<F>::State x;
    for (int i = 0; i < N; ++i) x(i) = NV_Ith_S(y, i);
    return x;
  }
  void stats() {
    long v = 0;
    CVodeGetNumSteps(mem, &v);
    w->steps = v;
    CVodeGetNumLinSolvSetups(mem, &v);
    w->lu = v;
  }
};

template <std::uint32_t F>
Trace run_cvode(const Problem<F>& p, double tol, Work& w, bool& ok) {
  Cvode<F> cv(p, tol, &w);
  Trace t;
  t.v.reserve(static_cast<std::size_t>((p.frames + 1) * Problem<F>::N));
  p.log(t, p.x0);
  ok = true;
  for (long k = 1; k <= p.frames && ok; ++k) {
    ok = cv.advance(static_cast<double>(k) * p.scene.frame_s);
    p.log(t, cv.state());
  }
  cv.stats();
  return t;
}

// Runs fn until `min_s` of CPU time has passed (at least 3, at most 25
// runs); the median CPU time of one run.
template <class Fn>
double median_cpu(Fn&& fn, double min_s) {
  std::vector<double> ts;
  double total = 0;
  while ((ts.size() < 3 || total < min_s) && ts.size() < 25) {
    const double t0 = cpu_now();
    fn();
    const double dt = cpu_now() - t0;
    ts.push_back(dt);
    total += dt;
  }
  std::sort(ts.begin(), ts.end());
  return ts[ts.size() / 2];
}

template <std::uint32_t F>
void work_precision(const cvt::Scene& s, bool quick) {
  const Problem<F> p(s);
  const Trace ref = reference(p, quick ? 64 : 1024);
  // The reference's own error: against the run with half its substeps
  // (ROS2 is order 2: that difference is about 3x the reference's error).
  const Trace ref_half = reference(p, quick ? 32 : 512);
  std::printf("%s,reference,0,%.4e,0,0,0,0,0,ok\n", s.name, rel_rms(ref, ref_half, F) / 3.0);
  std::fflush(stdout);
  const double min_s = quick ? 0.0 : 0.3;
  std::vector<double> tols;
  const double lo = quick ? 1e-6 : 1e-11;
  for (double tol = 1e-2; tol >= lo * 0.99; tol /= std::sqrt(10.0)) tols.push_back(tol);
  auto emit = [&](const char* solver, double tol, auto&& runner) {
    Work w;
    bool ok = true;
    const Trace out = runner(p, tol, w, ok);
    const double err = rel_rms(ref, out, F);
    const double cpu = median_cpu(
        [&] {
          Work w2;
          bool ok2 = true;
          (void)runner(p, tol, w2, ok2);
        },
        min_s);
    std::printf("%s,%s,%.3e,%.4e,%.6e,%ld,%ld,%ld,%ld,%s\n", s.name, solver, tol, err, cpu / s.t_end_s, w.steps,
                w.rhs, w.jac, w.lu, ok ? "ok" : "failed");
    std::fflush(stdout);
  };
  for (double tol : tols) {
    emit("rodas4", tol, [](const Problem<F>& pp, double tt, Work& ww, bool& oo) { return run_rodas4(pp, tt, ww, oo); });
    emit("odeint-rosenbrock4", tol,
         [](const Problem<F>& pp, double tt, Work& ww, bool& oo) { return run_boost(pp, tt, ww, oo); });
    emit("cvode-bdf", tol, [](const Problem<F>& pp, double tt, Work& ww, bool& oo) { return run_cvode(pp, tt, ww, oo); });
  }
}

// Per-frame cost: each frame timed on its own (steady clock), median, 99.9th
// percentile and maximum in ns.
void frame_stats(const char* scene, const char* solver, std::vector<double>& ns, double err) {
  std::sort(ns.begin(), ns.end());
  const std::size_t n = ns.size();
  const std::size_t i999 = std::min(n - 1, static_cast<std::size_t>(std::ceil(0.999 * static_cast<double>(n))) - 1);
  std::printf("%s,%s,%zu,%.0f,%.0f,%.0f,%.3e\n", scene, solver, n, ns[n / 2], ns[i999], ns[n - 1], err);
  std::fflush(stdout);
}

double ns_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
}

template <std::uint32_t F>
void frames(const cvt::Scene& s, double peer_tol) {
  const Problem<F> p(s);
  const Trace ref = reference(p, 1024);
  {  // the real-time frame stepper, the scene's own method and substeps
    cvt::RomSimulator<double, F> sim(s.params, cvt::sim_config_of(s));
    sim.reset(s.initial, cvt::scene_inputs_at<double>(s, 0.0));
    Trace t;
    p.log(t, sim.state());
    std::vector<double> ns;
    for (long k = 0; k < p.frames; ++k) {
      const auto u = cvt::scene_inputs_at<double>(s, static_cast<double>(k) * s.frame_s);
      const auto t0 = std::chrono::steady_clock::now();
      sim.step_frame(u);
      ns.push_back(ns_since(t0));
      p.log(t, sim.state());
    }
    frame_stats(s.name, "fixed-step-ros2", ns, rel_rms(ref, t, F));
  }
  {  // rosenbrock4 with step-size control, stopping at each frame end
    Work w;
    const BoostOde<F> ode{&p, &w};
    auto y = ode.scaled(p.x0);
    auto stepper = odeint::make_controlled<odeint::rosenbrock4<double>>(peer_tol, peer_tol);
    Trace t;
    p.log(t, p.x0);
    std::vector<double> ns;
    double dt = 1e-6;
    for (long k = 0; k < p.frames; ++k) {
      const double t0s = static_cast<double>(k) * s.frame_s;
      const auto t0 = std::chrono::steady_clock::now();
      double tt = t0s;
      const double te = t0s + s.frame_s;
      while (tt < te) {
        double h = std::min(dt, te - tt);
        while (stepper.try_step(ode.system(), y, tt, h) != odeint::success) {
        }
        dt = h;
      }
      ns.push_back(ns_since(t0));
      p.log(t, ode.unscaled(y));
    }
    frame_stats(s.name, "odeint-rosenbrock4", ns, rel_rms(ref, t, F));
  }
  {  // CVODE, stopping at each frame end, as a real-time loop must
    Work w;
    Cvode<F> cv(p, peer_tol, &w);
    Trace t;
    p.log(t, p.x0);
    std::vector<double> ns;
    for (long k = 1; k <= p.frames; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      cv.advance(static_cast<double>(k) * s.frame_s, true);
      ns.push_back(ns_since(t0));
      p.log(t, cv.state());
    }
    frame_stats(s.name, "cvode-bdf", ns, rel_rms(ref, t, F));
  }
}

// The scene's inputs and parameters on the plant of mask F (seed-case1: the
// seed case under its clamping actuator, tools/scenes/seed-case1-clamped.toml;
// the built-in runs the tension plant, which the adaptive runner lacks).
template <std::uint32_t F, class Fn>
void for_scene(const char* name, double t_end, Fn&& fn) {
  cvt::Scene s = *cvt::find_builtin_scene(name);
  s.features = F;
  if (t_end > 0) s.t_end_s = t_end;
  fn(s);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  double t_end = -1;
  bool quick = false;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--t-end") == 0 && i + 1 < argc) t_end = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else {
      std::fprintf(stderr, "work_precision: unknown option '%s'\n", argv[i]);
      return 2;
    }
  }
  namespace f = cvt::rom_feature;
  if (mode == "wp") {
    std::printf("scene,solver,tol,error,cpu_s_per_sim_s,steps,rhs,jacobians,factorizations,status\n");
    for_scene<f::axial>("seed-case1", t_end, [&](const cvt::Scene& s) { work_precision<f::axial>(s, quick); });
    for_scene<f::axial>("seed-case2", t_end, [&](const cvt::Scene& s) { work_precision<f::axial>(s, quick); });
    for_scene<0>("gross-slip", t_end, [&](const cvt::Scene& s) { work_precision<0>(s, quick); });
    for_scene<0>("oscillator-stribeck", t_end < 0 ? -1 : 5 * t_end,
              [&](const cvt::Scene& s) { work_precision<0>(s, quick); });
    return 0;
  }
  if (mode == "frames") {
    std::printf("scene,solver,frames,median_ns,p99_9_ns,max_ns,error\n");
    for_scene<f::axial>("seed-case1", t_end, [&](const cvt::Scene& s) { frames<f::axial>(s, 1e-4); });
    return 0;
  }
  std::fprintf(stderr, "usage: work_precision wp|frames [--t-end S] [--quick]\n");
  return 2;
}
