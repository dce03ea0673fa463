#pragma once
// The driven (secondary) clamping actuator of the radial DOF
// (docs/rom.md#driven-clamping): the driver's hydraulic lag,
//   tau_h F_ax2' = sat(F_cmd2, 0, F_max) - F_ax2,
// advanced once per frame by its exact discretisation
//   F_ax2 <- F_ax2 + (F_cmd2 - F_ax2) (1 - exp(-frame / tau_h))            [N]
// and held over the frame: no integrator state, one multiply-add per frame.
// F_ax2 acts on the chain as the potential -2 tan(beta0) F_ax2 (r2 - r2_m)
// (feature/radial.hpp); a change of F_ax2 at a fixed state changes that
// potential by exactly the work the actuator does, which the frame stepper
// books (rom_sim.hpp). A constant command gives the same bits as the
// constant set-up value RomParams::driven_clamp_N.
#include "cvtplant/math/detmath.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

class RomDrivenClamp {
 public:
  RomDrivenClamp(const RomParams& p, double frame_s)
      : command_N_(p.driven_clamp_N),
        force_N_(p.driven_clamp_N),
        lag_(1.0 - dm::exp(-frame_s / p.actuator_tau_s)),
        max_N_(p.clamp_max_N) {}

  // The command, saturated to [0, F_max] like the driver's.
  void set_command(double f_N) { command_N_ = f_N < 0.0 ? 0.0 : (f_N > max_N_ ? max_N_ : f_N); }
  double command_N() const { return command_N_; }
  double force_N() const { return force_N_; }
  // A run starts with the actuator at its command.
  void reset() { force_N_ = command_N_; }
  void set_force(double force_N) { force_N_ = force_N; }
  // The force after one more frame of the lag (the force itself once the
  // actuator has settled: nothing to book, the plant's constant stays).
  double next_force_N() const { return force_N_ + (command_N_ - force_N_) * lag_; }

 private:
  double command_N_, force_N_, lag_, max_N_;
};

}  // namespace cvt
