#pragma once
// A scene on the adaptive solver (docs/numerics.md#adaptive): RODAS4
// (integrate/rodas4.hpp) on the plant's right-hand side, analytic Jacobian
// and block-eliminated W solve (plant/rom_step.hpp), for runs whose inputs
// are known in advance. It solves the same problem as the frame stepper
// (scene_runner.hpp): inputs sampled at each frame's start and held over the
// frame. Where the held inputs change (a step, every frame of a ramp or a
// sine) the step ends exactly on that frame boundary and the method restarts
// from there; in between it steps over as many frames as its error estimate
// allows. Frames are dense-output samples at the frame times, so a log has
// the same rows as the frame stepper's.
//
// Per frame, as the frame stepper does: the outputs and the energy ledger's
// trapezoid on the power terms at the frame ends (with the frame's inputs),
// the state, speed-limit and energy checks (docs/rom.md#watchdog). A fault
// reports the last good state at the frame where it occurred.
// Double precision, plants without wedging (whose driven actuator and end
// stops change the plant every frame: they keep the frame stepper).
// Heap-free; the same arithmetic in the same order on every run.
#include <cstdint>

#include "cvtplant/integrate/rodas4.hpp"
#include "cvtplant/plant/cvt_rom.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/plant/rom_watchdog.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt {

struct AdaptiveConfig {
  double rtol = 1e-6;
  // Absolute tolerance of state i: atol x its floor (adaptive_atol_floor),
  // so one number sets it for states in rad/s, m, m/s, N and rad.
  double atol = 1e-6;
  long max_steps = 100000000;  // attempted steps over the run
  // The energy ledger and its watchdog (the power terms at every frame's
  // end); off, a frame is the dense output and the state checks only.
  bool energy = true;
  double first_step_s = 0;     // 0: chosen from f(x0) (rodas4_first_step)
};

enum class AdaptiveStatus : std::uint8_t {
  ok,
  fault,           // the plant faulted (RomFault, as the frame stepper reports it)
  step_too_small,  // the error estimate asked for a step below 1e-14 of the time
  step_cap,        // AdaptiveConfig::max_steps reached
  stopped,         // the caller's on_frame returned false
};

inline constexpr const char* adaptive_status_name(AdaptiveStatus s) {
  switch (s) {
    case AdaptiveStatus::ok: return "ok";
    case AdaptiveStatus::fault: return "fault";
    case AdaptiveStatus::step_too_small: return "step-too-small";
    case AdaptiveStatus::step_cap: return "step-cap";
    case AdaptiveStatus::stopped: return "stopped";
  }
  return "?";
}

// Floor of each state's absolute tolerance per unit of AdaptiveConfig::atol:
// 1 rad/s, 1 um, 1 mm/s, 1 N and 1 mrad, sizes below which a state's error
// does not matter to any output (docs/numerics.md#adaptive).
inline double adaptive_atol_floor(std::uint32_t features, int i) {
  const RomStateIndex s = rom_state_index(features);
  if (i == s.w1 || i == s.w2) return 1.0;
  if (i == s.x1 || i == s.x2 || i == s.delta || i == s.rho) return 1e-6;
  if (i == s.xd1 || i == s.xd2 || i == s.delta_dot || i == s.rho_dot) return 1e-3;
  if (i == s.psi) return 1e-3;
  return 1.0;  // F_h [N]
}

// The error of a trajectory against a reference, both sampled at the same
// frames (`frames` rows of `n` states, row-major, SI units): the RMS over
// frames and states of (x - x_ref) / scale_i, where scale_i is state i's
// largest magnitude in the reference, at least its tolerance floor
// adaptive_atol_floor (a state that stays at rounding noise, like an axial
// speed at rest, is not divided by that noise). Used by the tests and the
// work-precision benchmark (docs/performance.md#error).
inline double trajectory_relative_rms(const double* ref, const double* x, long frames, int n,
                                      std::uint32_t features) {
  double scale[32];
  for (int i = 0; i < n && i < 32; ++i) scale[i] = adaptive_atol_floor(features, i);
  for (long k = 0; k < frames; ++k)
    for (int i = 0; i < n && i < 32; ++i) {
      const double a = dm::abs(ref[k * n + i]);
      if (a > scale[i]) scale[i] = a;
    }
  double sum = 0;
  for (long k = 0; k < frames; ++k)
    for (int i = 0; i < n && i < 32; ++i) {
      const double e = (x[k * n + i] - ref[k * n + i]) / scale[i];
      sum += e * e;
    }
  const double count = static_cast<double>(frames) * static_cast<double>(n < 32 ? n : 32);
  return count > 0 ? dm::sqrt(sum / count) : 0.0;
}

// The plant as RODAS4 sees it: the right-hand side at the held inputs.
template <std::uint32_t F>
struct RomOde {
  using Plant = CvtRom<double, F>;
  using Scalar = double;
  static constexpr int kStates = Plant::kStates;
  const Plant* plant;
  void derivative(const typename Plant::State& x, typename Plant::State& dxdt) const { plant->derivative(x, dxdt); }
};

template <std::uint32_t F>
class AdaptiveRun;

// What on_frame sees of a frame: the names of the frame stepper's view
// (IRomSimulator), so one callback serves both.
template <std::uint32_t F>
class AdaptiveFrame {
 public:
  using Plant = CvtRom<double, F>;
  RomOutputs<double> outputs() const { return plant_->outputs(x_); }
  const EnergyLedger<double>& energy() const { return ledger_; }
  RomFault fault() const { return fault_; }
  void state_si(double* x) const {
    const auto y = plant_->to_si(x_);
    for (int i = 0; i < Plant::kStates; ++i) x[i] = y(i);
  }
  int state_count() const { return Plant::kStates; }
  std::uint32_t features() const { return F; }
  const typename Plant::State& state() const { return x_; }

 private:
  template <std::uint32_t>
  friend class AdaptiveRun;
  const Plant* plant_ = nullptr;
  typename Plant::State x_;
  EnergyLedger<double> ledger_{};
  RomFault fault_ = RomFault::none;
};

template <std::uint32_t F>
class AdaptiveRun {
  static_assert(!RomLayout<F>::kWedge, "wedging plants keep the frame stepper (docs/numerics.md#adaptive)");

 public:
  using Plant = CvtRom<double, F>;
  using State = typename Plant::State;
  using Jacobian = typename Plant::Jacobian;

  AdaptiveRun(const RomParams& p, const AdaptiveConfig& c) : plant_(p), cfg_(c) {
    for (int i = 0; i < Plant::kStates; ++i) atol_(i) = c.atol * adaptive_atol_floor(F, i);
    frame_.plant_ = &plant_;
  }

  const Rodas4Work& work() const { return work_; }
  // Time reached when the run stopped [s].
  double time_s() const { return t_; }

  // Runs scene s (frame length frame_s) from its start:
  // on_frame(long frame, double t_s, const AdaptiveFrame<F>&) -> bool after
  // every frame and at t = 0, as run_frames does.
  template <class OnFrame>
  AdaptiveStatus run(const Scene& s, double frame_s, OnFrame&& on_frame) {
    work_ = Rodas4Work{};
    RomInputs<double> u = scene_inputs_at<double>(s, 0.0);
    plant_.inputs = u;
    State x = plant_.initial_state(s.initial);
    frame_.x_ = x;
    frame_.fault_ = RomFault::none;
    frame_.ledger_ = EnergyLedger<double>{};
    frame_.ledger_.stored0_J = frame_.ledger_.stored_J = plant_.stored_energy(x);
    t_ = 0.0;
    if (!on_frame(0L, 0.0, static_cast<const AdaptiveFrame<F>&>(frame_))) return AdaptiveStatus::stopped;
    const long n = static_cast<long>(s.t_end_s / frame_s + 0.5);
    const double speed_limit = plant_.params().speed_limit_rad_s;
    double h = cfg_.first_step_s;
    long k = 0;
    while (k < n) {
      // The segment [t_k, t_j] over which the held inputs stay the same.
      u = scene_inputs_at<double>(s, static_cast<double>(k) * frame_s);
      long j = k + 1;
      while (j < n && same_inputs(scene_inputs_at<double>(s, static_cast<double>(j) * frame_s), u)) ++j;
      const RomFault uf = rom_input_fault(u.tau_in_Nm, u.tau_load_Nm, u.clamp_N);
      if (uf != RomFault::none) return fail(uf, k, frame_s, on_frame);
      plant_.inputs = u;
      const double t_seg = static_cast<double>(j) * frame_s;
      RomPower<double> p0{};
      if (cfg_.energy) p0 = plant_.power(x);
      long next = k + 1;  // next frame to sample
      double t = static_cast<double>(k) * frame_s;
      if (!(h > 0.0)) h = first_step(x, t_seg - t);
      bool last_rejected = false;
      typename Plant::Contact c = plant_.contact(x);
      State f0;
      Jacobian J;
      plant_.derivative(x, c, f0);
      plant_.jacobian(x, c, J, false);
      ++work_.rhs;
      ++work_.jacobians;
      while (next <= j) {
        if (work_.accepted + work_.rejected >= cfg_.max_steps) {
          t_ = t;
          return AdaptiveStatus::step_cap;
        }
        // Land on the segment's end exactly; stretch a step that would leave
        // a sliver of under a tenth of itself.
        bool to_end = false;
        double hs = h;
        if (t + 1.1 * hs >= t_seg) {
          hs = t_seg - t;
          to_end = true;
        }
        if (!(hs > 1e-14 * (t_seg > 1.0 ? t_seg : 1.0))) {
          t_ = t;
          return AdaptiveStatus::step_too_small;
        }
        State x_new;
        Rodas4Dense<RomOde<F>> dense;
        const RomOde<F> ode{&plant_};
        const double err = rodas4_step(ode, x, f0, J, hs, w_, atol_, cfg_.rtol, x_new, &dense, work_);
        const double fac = rodas4_step_factor(err, last_rejected);
        if (!(err <= 1.0)) {
          ++work_.rejected;
          last_rejected = true;
          h = hs * fac;
          continue;
        }
        ++work_.accepted;
        last_rejected = false;
        const double t_new = to_end ? t_seg : t + hs;
        // The frames inside the step, from the dense output; the phase of the
        // chordal action is wrapped after interpolation (it is continuous
        // within the step).
        while (next <= j && (next == j ? to_end : static_cast<double>(next) * frame_s <= t_new)) {
          const double tf = static_cast<double>(next) * frame_s;
          State xf = (next == j) ? x_new : dense.at((tf - t) / hs);
          plant_.wrap(xf);
          if (cfg_.energy) {
            const RomPower<double> p1 = plant_.power(xf);
            frame_.ledger_.add_trapezoid(p0, p1, 0.5 * frame_s);
            frame_.ledger_.stored_J = plant_.stored_energy(xf);
            p0 = p1;
          }
          RomFault fault = rom_state_fault(xf);
          if (fault == RomFault::none && (dm::abs(xf(RomLayout<F>::kW1)) > speed_limit ||
                                          dm::abs(xf(RomLayout<F>::kW2)) > speed_limit))
            fault = RomFault::speed_out_of_range;
          if (fault == RomFault::none && cfg_.energy && sim_config_energy_check(frame_.ledger_))
            fault = RomFault::energy_growth;
          if (fault != RomFault::none) {
            t_ = tf;
            return fail(fault, next - 1, frame_s, on_frame);
          }
          frame_.x_ = xf;
          t_ = tf;
          if (!on_frame(next, tf, static_cast<const AdaptiveFrame<F>&>(frame_))) return AdaptiveStatus::stopped;
          ++next;
        }
        x = x_new;
        plant_.wrap(x);
        t = t_new;
        // The step after a landing on the segment's end keeps the size the
        // error estimate asked for, not the shortened one.
        h = to_end ? (hs * fac > h ? hs * fac : h) : hs * fac;
        if (next <= j) {
          c = plant_.contact(x);
          plant_.derivative(x, c, f0);
          plant_.jacobian(x, c, J, false);
          ++work_.rhs;
          ++work_.jacobians;
        }
      }
      k = j;
    }
    return AdaptiveStatus::ok;
  }

 private:
  static bool same_inputs(const RomInputs<double>& a, const RomInputs<double>& b) {
    return a.tau_in_Nm == b.tau_in_Nm && a.tau_load_Nm == b.tau_load_Nm && a.clamp_N == b.clamp_N;
  }

  // The frame stepper's energy watchdog with its default tolerances
  // (RomSimConfig): residual above 5 % of the flows plus 1 J.
  static bool sim_config_energy_check(const EnergyLedger<double>& e) {
    const RomSimConfig d;
    const double r = e.residual_J();
    return !(r == r) || r > d.energy_rel_tol * e.scale_J() + d.energy_abs_tol_J;
  }

  // First step: 1 % of the time in which f(x0) changes x0 by its tolerance
  // scale, at most the segment (Hairer & Wanner's first guess, without the
  // second derivative).
  double first_step(const State& x, double span) const {
    State f;
    plant_.derivative(x, f);
    double d0 = 0, d1 = 0;
    for (int i = 0; i < Plant::kStates; ++i) {
      const double sc = atol_(i) + cfg_.rtol * dm::abs(x(i));
      d0 += (x(i) / sc) * (x(i) / sc);
      d1 += (f(i) / sc) * (f(i) / sc);
    }
    double h = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * dm::sqrt(d0 / d1);
    if (h > span) h = span;
    return h;
  }

  template <class OnFrame>
  AdaptiveStatus fail(RomFault f, long frame, double frame_s, OnFrame& on_frame) {
    frame_.fault_ = f;
    on_frame(frame + 1, static_cast<double>(frame + 1) * frame_s, static_cast<const AdaptiveFrame<F>&>(frame_));
    return AdaptiveStatus::fault;
  }

  Plant plant_;
  AdaptiveConfig cfg_;
  State atol_;
  RomWSolver<double, F> w_;
  Rodas4Work work_{};
  AdaptiveFrame<F> frame_;
  double t_ = 0.0;
};

}  // namespace cvt
