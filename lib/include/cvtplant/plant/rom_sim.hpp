#pragma once
// Frame stepper for the reduced-order plant: fixed-step integration with a
// fixed number of substeps per frame, the energy ledger and the stability
// watchdog (docs/rom.md#frame-stepping, #energy-balance, #watchdog).
// Heap-free; the cost per frame does not depend on the state.
#include <cstdint>
#include <limits>
#include <type_traits>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/cvt_rom.hpp"
#include "cvtplant/plant/feature/driven_clamp.hpp"
#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/plant/rom_watchdog.hpp"

namespace cvt {

struct RomSimConfig {
  Method method = Method::ros2;
  int substeps = 1;            // integrator steps per frame
  double frame_s = 1e-3;
  // The energy ledger (docs/rom.md#energy-balance) and with it the energy
  // check of the watchdog: about a tenth of a frame, the scene's choice
  // (docs/rom.md#cost). Off, energy() stays at its reset value and only the
  // essential checks run (non-finite or saturated states, speed limits,
  // radial travel, step resolution: docs/rom.md#watchdog).
  bool energy_ledger = true;
  bool watchdog_energy = true;
  double energy_rel_tol = 0.05;  // residual > rel * scale + abs  ->  energy_growth
  double energy_abs_tol_J = 1.0;
  // W of the implicit methods with the friction slope floor
  // (docs/rom.md#slope-floor; the wedging plants add it to their full J);
  // no effect on the explicit methods.
  bool w_slope_floor = true;
  // Wedging: a frame that starts on a radial end stop, or close enough to
  // reach it within the frame at its radial speed, is taken with this many
  // times the substeps, so the stop's 2.8 ms ring is resolved only where it
  // can act (docs/rom.md#end-stop); 1 = never.
  int stop_substeps = 2;
  // The refined frame evaluates its Jacobian and W for its first substep
  // only and its other substeps keep that W (ROS2 keeps its order with any
  // W), so a frame on the stop costs 1.5 frames, not 2 (docs/rom.md#end-stop);
  // false evaluates both for every substep, for comparisons.
  bool stop_keep_w = true;
};

// Features: the feature bits compiled in; Runtime: the stateless ones carried
// and switched at set-up by `features` (CvtRom; the host dispatch,
// docs/rom.md#build-time).
template <class T, std::uint32_t Features = 0, std::uint32_t Runtime = 0>
class RomSimulator {
 public:
  using Scalar = T;
  using Plant = CvtRom<T, Features, Runtime>;
  using State = typename Plant::State;
  using Acc = typename Plant::Acc;

  RomSimulator(const RomParams& p, const RomSimConfig& c, std::uint32_t features = Features)
      : plant_(p, features),
        cfg_(c),
        // The plant integrates in its own time unit (RomUnits; 1 s except
        // fixed point); the ledger stays in seconds.
        h_(T(c.frame_s / static_cast<double>(c.substeps < 1 ? 1 : c.substeps) / Plant::U::time_s)),
        h_acc_(Acc(c.frame_s / static_cast<double>(c.substeps < 1 ? 1 : c.substeps))),
        rel_tol_(Acc(c.energy_rel_tol)),
        abs_tol_(Acc(c.energy_abs_tol_J)),
        driven_(p, c.frame_s),
        frame_(T(c.frame_s / Plant::U::time_s)),
        speed_limit_(T(p.speed_limit_rad_s)),
        resolved_speed_(T(rom_polygon_resolved_speed_rad_s(
            p, c.frame_s / static_cast<double>(c.substeps < 1 ? 1 : c.substeps)))) {
    x_.setZero();
  }

  // Wedging: the driven (secondary) clamping command [N], saturated to
  // [0, F_max] like the driver's; the driven actuator follows it with the
  // actuator lag, one update per frame (docs/rom.md#driven-clamping). The
  // default is the set-up value RomParams::driven_clamp_N; reset() starts
  // the actuator at the command. No effect without wedging.
  void set_driven_clamp_command(double f_N) { driven_.set_command(f_N); }
  double driven_clamp_command_N() const { return driven_.command_N(); }
  // The driven clamping force F_ax2 the plant applies now [N].
  double driven_clamp_N() const { return driven_.force_N(); }
  // Frames taken again with stop_substeps (docs/rom.md#end-stop).
  long stop_refined_frames() const { return stop_refined_; }

  // Starts a run. u0 sets the axial equilibrium of the initial state.
  void reset(const RomInitial& x0, const RomInputs<T>& u0) {
    plant_.inputs = u0;
    x_ = plant_.initial_state(x0);
    fault_ = RomFault::none;
    carry_.clear();
    driven_.reset();
    plant_.set_driven_clamp_N(driven_.force_N());
    stop_refined_ = 0;
    ledger_ = EnergyLedger<Acc>{};
    if (cfg_.energy_ledger) ledger_.stored0_J = ledger_.stored_J = plant_.stored_energy(x_);
    frames_ = 0;
    refresh_contact();
  }

  // One frame with inputs held constant (zero-order hold). Returns the
  // (latched) fault state; a faulted simulator keeps its last good state.
  RomFault step_frame(const RomInputs<T>& u) {
    if (fault_ != RomFault::none) return fault_;
    fault_ = rom_input_fault(u.tau_in_Nm, u.tau_load_Nm, u.clamp_N);
    if (fault_ != RomFault::none) return fault_;
    // docs/rom.md#tension: without the actuator the clamping input sets the
    // chain's axial force and with it the creep, which the contact carries; a
    // new command makes the contact of the frame's start stale.
    if constexpr (Plant::Layout::kTension && !Plant::Layout::kAxial) {
      if (!plant_.tension().fixed_sheaves() && !(u.clamp_N == plant_.inputs.clamp_N)) contact_stale_ = true;
    }
    plant_.inputs = u;
    if (contact_stale_) refresh_contact();
    const State x_prev = x_;
    const EnergyLedger<Acc> ledger_prev = ledger_;
    const Carry carry_prev = carry_;
    const double driven_prev = driven_.force_N();
    auto roll_back = [&](RomFault why) {
      x_ = x_prev;
      ledger_ = ledger_prev;
      // The contact of x_prev is evaluated again when it is next needed
      // (only reset() clears the fault): copying it on every frame for the
      // rare roll-back cost tens of instructions a frame (docs/rom.md#cost).
      contact_stale_ = true;
      carry_ = carry_prev;
      driven_.set_force(driven_prev);
      plant_.set_driven_clamp_N(driven_prev);
      fault_ = why;
      return fault_;
    };
    if constexpr (Plant::Layout::kWedge) update_driven_clamp();
    const int n = cfg_.substeps < 1 ? 1 : cfg_.substeps;
    RomFault f = RomFault::none;
    if constexpr (Plant::Layout::kWedge) {
      // docs/rom.md#end-stop: a frame that starts near a stop takes the
      // finer steps.
      if (cfg_.stop_substeps > 1 && near_stop(x_prev)) f = integrate_stop(n);
      else f = integrate(n, h_, h_acc_);
    } else {
      f = integrate(n, h_, h_acc_);
    }
    if (f != RomFault::none) return roll_back(f);
    if (cfg_.energy_ledger) ledger_.stored_J = plant_.stored_energy(x_);
    ++frames_;
    // Pulleys within the model's speed range; with chordal action, a link
    // phase slow enough for the step to resolve the link passing
    // (docs/rom.md#polygon; its rate is w1, or with the tension feature the
    // chain's link passing, docs/rom.md#link-ripple).
    if (abs_of(x_(Plant::Layout::kW1)) > speed_limit_ || abs_of(x_(Plant::Layout::kW2)) > speed_limit_)
      return roll_back(RomFault::speed_out_of_range);
    if constexpr (Plant::Layout::kPolygon) {
      if (abs_of(phase_rate()) > resolved_speed_) return roll_back(RomFault::step_unresolved);
    }
    // docs/rom.md#tension: in fixed point kappa m' v_c^2 saturates beyond the Q
    // range, and what the tension law makes of it means nothing.
    if constexpr (Plant::Layout::kTension && Plant::U::kScaled) {
      if (abs_of(x_(Plant::Layout::kW2)) > plant_.tension().speed_limit())
        return roll_back(RomFault::tension_out_of_range);
    }
    if (cfg_.energy_ledger && cfg_.watchdog_energy) {
      const Acc r = ledger_.residual_J();
      if (!(r == r) || r > rel_tol_ * ledger_.scale_J() + abs_tol_) roll_back(RomFault::energy_growth);
    }
    return fault_;
  }

  // The plant's features: those compiled in and those switched on at set-up.
  std::uint32_t features() const { return plant_.features(); }
  RomOutputs<T> outputs() const { return plant_.outputs(x_); }
  // The state in the plant's units (RomUnits: SI except fixed point, whose
  // displacements are in 2^-10 m); state_si() converts for logs.
  const State& state() const { return x_; }
  Eigen::Matrix<double, Plant::kStates, 1> state_si() const { return plant_.to_si(x_); }
  // Writable state, for tests and harnesses that place the plant. The cached
  // friction belongs to the state, so the next frame evaluates it afresh.
  State& mutable_state() {
    contact_stale_ = true;
    return x_;
  }
  const Plant& plant() const { return plant_; }
  // The plant, for callers that evaluate it on states of their own (the
  // analysis toolkit); the inputs set here hold until the next frame.
  Plant& mutable_plant() { return plant_; }
  const EnergyLedger<Acc>& energy() const { return ledger_; }
  RomFault fault() const { return fault_; }
  long frames() const { return frames_; }
  // Substep in the plant's time unit (seconds except fixed point).
  T substep() const { return h_; }

 private:
  // Friction of the current state (docs/rom.md#cost).
  using Contact = typename Plant::Contact;
  // Rounding remainders of the fixed-point increments (integrate/increment.hpp).
  using Carry = IncrementCarry<T, Plant::kStates>;

  void refresh_contact() {
    contact_ = plant_.contact(x_);
    contact_stale_ = false;
  }
  // The link phase's rate at the current state (docs/rom.md#link-ripple).
  T phase_rate() const { return plant_.phase_rate(x_, contact_); }
  RomPower<Acc> power_now() const { return plant_.power(x_, contact_); }
  void advance_substep(const T& h, RomWUse use) {
    if (cfg_.method == Method::ros2 || cfg_.method == Method::linear_implicit_euler) {
      if constexpr (Plant::Layout::kWedge) {
        auto step = [&](auto use_c) {
          rom_step_implicit_with<decltype(use_c)::value>(cfg_.method, plant_, x_, h, contact_, cfg_.w_slope_floor,
                                                         kept_.J, kept_.w, &carry_);
        };
        if (use == RomWUse::kept_w) step(std::integral_constant<RomWUse, RomWUse::kept_w>{});
        else step(std::integral_constant<RomWUse, RomWUse::fresh>{});
      } else {
        (void)use;
        rom_step_implicit(cfg_.method, plant_, x_, h, contact_, cfg_.w_slope_floor, &carry_);
      }
    } else {
      rom_step(cfg_.method, plant_, x_, h, cfg_.w_slope_floor, &carry_);
    }
  }

  // One substep of h, checked (non-finite or saturated state, radial travel).
  // The friction at the new state serves the ledger's power term and the
  // next substep's Jacobian and right-hand side (docs/rom.md#cost).
  RomFault substep(const T& h, RomWUse use) {
    advance_substep(h, use);
    plant_.wrap(x_);
    RomFault f = rom_state_fault(x_);
    if (f == RomFault::none && !plant_.radius_in_range(x_)) f = RomFault::radius_out_of_range;
    if (f == RomFault::none) refresh_contact();
    return f;
  }

  // n substeps of h (plant time units; hacc the same in seconds), with the
  // ledger's trapezoid on the power terms at the substep ends when the
  // ledger is on (inputs constant over the frame, docs/rom.md#energy-balance).
  // With `keep_w` the substeps after the first keep its W (RomWUse::kept_w).
  RomFault integrate(int n, const T& h, const Acc& hacc, bool keep_w = false) {
    const RomWUse later = keep_w ? RomWUse::kept_w : RomWUse::fresh;
    if (!cfg_.energy_ledger) {
      for (int i = 0; i < n; ++i)
        if (const RomFault f = substep(h, i == 0 ? RomWUse::fresh : later); f != RomFault::none) return f;
      return RomFault::none;
    }
    RomPower<Acc> p0 = power_now();
    for (int i = 0; i < n; ++i) {
      if (const RomFault f = substep(h, i == 0 ? RomWUse::fresh : later); f != RomFault::none) return f;
      const RomPower<Acc> p1 = power_now();
      ledger_.add_trapezoid(p0, p1, hacc * Acc(0.5));
      p0 = p1;
    }
    return RomFault::none;
  }

  // The frame in n x stop_substeps steps of one W (docs/rom.md#end-stop).
  RomFault integrate_stop(int n) {
    const int m = n * cfg_.stop_substeps;
    const double hs = cfg_.frame_s / static_cast<double>(m);
    ++stop_refined_;
    return integrate(m, T(hs / Plant::U::time_s), Acc(hs), cfg_.stop_keep_w);
  }

  // The chain on a radial end stop, or close enough to reach it within a
  // frame at its present radial speed (wedging): a bounce shorter than a
  // frame starts and ends off the stop (docs/rom.md#end-stop).
  bool near_stop(const State& x) const {
    using L = typename Plant::Layout;
    if constexpr (L::kWedge) {
      const T rho = x(L::kRho), rhod = x(L::kRhoDot);
      const T reach = (rho < T(0) ? -rho : rho) + (rhod < T(0) ? -rhod : rhod) * frame_;
      return !(reach < plant_.radial().travel());
    } else {
      (void)x;
      return false;
    }
  }

  // docs/rom.md#driven-clamping: the driven actuator's frame update
  // (feature/driven_clamp.hpp). The driven clamping acts on the chain as a
  // potential, -2 tan(beta0) F_ax2 (r2 - r2_m); changing F_ax2 at a fixed
  // state changes that potential by exactly the work the actuator books
  // here, so the ledger stays closed.
  void update_driven_clamp() {
    const double next = driven_.next_force_N();
    if (next == driven_.force_N()) return;
    if (!cfg_.energy_ledger) {
      driven_.set_force(next);
      plant_.set_driven_clamp_N(next);
      return;
    }
    const Acc before = plant_.stored_energy(x_);
    driven_.set_force(next);
    plant_.set_driven_clamp_N(next);
    ledger_.actuator_J += plant_.stored_energy(x_) - before;
  }
  static T abs_of(const T& v) { return v < T(0) ? -v : v; }

  Plant plant_;
  RomSimConfig cfg_;
  T h_;
  Acc h_acc_;
  Acc rel_tol_, abs_tol_;
  State x_;
  RomFault fault_ = RomFault::none;
  EnergyLedger<Acc> ledger_{};
  Contact contact_{};
  // Wedging: the Jacobian and W of the last implicit substep, which the
  // substeps of a frame refined at the end stop keep (docs/rom.md#end-stop).
  struct KeptW {
    typename Plant::Jacobian J = Plant::Jacobian::Zero();
    RomWSolver<T, Features> w;
  };
  struct NoKeptW {};
  std::conditional_t<Plant::Layout::kWedge, KeptW, NoKeptW> kept_{};
  Carry carry_{};
  bool contact_stale_ = true;
  long frames_ = 0;
  RomDrivenClamp driven_;
  T frame_;  // one frame in the plant's time unit
  long stop_refined_ = 0;
  T speed_limit_, resolved_speed_;
};

}  // namespace cvt
