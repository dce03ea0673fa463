#pragma once
// The planar multibody chain CVT of seed section 2 as a first-order ODE
// y' = f(t, y) (docs/mbd.md#equations-of-motion):
//   N links, each a planar rigid body (x, y, theta) with velocities;
//   two pulleys, each one rotational DOF (angle, speed);
//   in clamped-sheave mode one axial DOF (opening, rate) per movable sheave;
//   five energy-ledger integrals (input work, load work, friction loss,
//   damping loss, clamping work), integrated with the states.
// Offline code: heap and exceptions are fine here.
#include <cstdint>
#include <string>
#include <vector>

#include "cvtplant/mbd/elements.hpp"
#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/mbd/params.hpp"

namespace cvt::mbd {

// Compressed sparse column pattern of the Jacobian (structurally every
// entry that can be non-zero in any configuration, plus the diagonal).
struct SparsePattern {
  int n = 0;
  std::vector<std::int64_t> col_start;  // n + 1
  std::vector<std::int64_t> row;        // nnz
  std::int64_t nnz() const { return col_start.empty() ? 0 : col_start.back(); }
};

// One output sample (docs/mbd.md#outputs). Pulley j = 0 driver, 1 driven.
struct Sample {
  double t_s = 0;
  double omega_rad_s[2] = {0, 0};
  double phi_rad[2] = {0, 0};
  double ratio = 0;               // omega1 / omega2 (NaN while omega2 = 0)
  double F_ax_N[2] = {0, 0};      // sum of the bolt forces on each pulley
  double chain_torque_Nm[2] = {0, 0};  // moment of the contact forces on each pulley
  double tau_in_Nm = 0;           // torque on the driver (a speed hold: the holding torque)
  double tau_load_Nm = 0;         // load torque on the driven pulley (or its holding torque)
  double slip_m_s[2] = {0, 0};    // pulley surface speed minus chain speed, mean over the wrap
  // The same per bolt, its smallest and largest value over the wrap (NaN when
  // no bolt is in the wrap): the whole wrap slides forward where the smallest
  // is positive (docs/mbd.md#outputs).
  double slip_min_m_s[2] = {0, 0}, slip_max_m_s[2] = {0, 0};
  double tension_tight_N = 0;     // upper strand (into the driver wrap); NaN if no free joint
  double tension_slack_N = 0;     // lower strand
  int wrap_links[2] = {0, 0};     // links whose bolt is compressed by each pulley
  // Running radius: mean radius of the bolts in each wrap (NaN when none);
  // their ratio r2 / r1 is the geometric ratio (docs/mbd.md#outputs).
  double radius_m[2] = {0, 0};
  double sheave_opening_m[2] = {0, 0};
  double clamp_N[2] = {0, 0};     // clamping force (clamped mode)
  // Energy ledger, from the release (t = 0): W_in - W_load - D_fric - D_damp
  // + W_clamp = (E_kin + E_el)(t) - (E_kin + E_el)(0).
  double W_in_J = 0, W_load_J = 0, D_friction_J = 0, D_damping_J = 0, W_clamp_J = 0;
  double E_kin_J = 0, E_el_J = 0;
};

// One link at one instant (per-link output, pictures).
struct LinkState {
  double x_m, y_m, theta_rad;
  double rear_x_m, rear_y_m, front_x_m, front_y_m;  // pins; the bolt is at the front pin
  int pulley;          // -1 free, 0 driver, 1 driven (bolt compressed)
  double bolt_force_N;
  double slip_m_s;     // |g|, slip speed of the bolt on the sheave (0 when free)
  double tension_N;    // force in the joint to the next link
};

// Why a right-hand side could not be evaluated (the first bad quantity).
struct Fault {
  bool set = false;
  double t_s = 0;
  std::string quantity;
};

class ChainModel {
 public:
  explicit ChainModel(const MbdParams& p);

  // docs/mbd.md#start-up. Settle: both pulleys held at rest, friction off,
  // drag on the links, no loads. Spin-up (a start at speed): friction on, both
  // pulley speeds imposed along a smooth ramp to the start speeds. Hold: the
  // driver held at its start speed, the driven pulley free under the load at
  // t = 0. Run: the loads (or speed holds) of the parameters.
  enum class Phase { settle, spinup, hold, run };
  void set_phase(Phase ph) { phase_ = ph; }
  Phase phase() const { return phase_; }

  int links() const { return n_links_; }
  int size() const { return n_; }  // ODE states, ledger included
  const DriveGeometry& geometry() const { return geo_; }
  const MbdParams& params() const { return p_; }

  // Layout (docs/mbd.md#state).
  static int link_state(int i, int k) { return 6 * i + k; }  // k: x, y, theta, vx, vy, omega
  int pulley_angle(int j) const { return 6 * n_links_ + 2 * j; }
  int pulley_speed(int j) const { return 6 * n_links_ + 2 * j + 1; }
  int sheave_opening(int j) const { return sheave_base_ + 2 * j; }  // clamped only
  int sheave_rate(int j) const { return sheave_base_ + 2 * j + 1; }
  int ledger(int k) const { return ledger_base_ + k; }  // 0 W_in, 1 W_load, 2 D_fric, 3 D_damp, 4 W_clamp
  bool clamped() const { return p_.sheaves == SheaveMode::clamped; }
  // The driver sheave held at its opening (the start's ratio lock) in this phase.
  bool driver_sheave_locked() const {
    return clamped() && p_.start_ratio_lock && phase_ != Phase::run;
  }
  // Error-weight scale of state i (docs/mbd.md#tolerances): the solver's
  // weight is 1 / (rtol (a_i |y_i| + scale_i)).
  double tolerance_scale(int i) const;
  double tolerance_relative(int i) const;
  // Kinetic energy of the system with every velocity at its tolerance scale
  // [J]: the energy resolution the absolute tolerances describe.
  double tolerance_energy_J() const;

  // The chain wrapped on the pitch line, at rest, pulleys at zero.
  std::vector<double> initial_state() const;
  // Sets the ledger integrals to zero (at the release).
  void reset_ledger(double* y) const;

  // dy/dt. Returns false when a force is not finite (fault() says which).
  bool rhs(double t_s, const double* y, double* dydt) const;
  const Fault& fault() const { return fault_; }

  const SparsePattern& pattern() const { return pattern_; }
  // Jacobian values in pattern() order, from the elements' dual-number
  // derivatives (exact for the smoothed model).
  void jacobian(double t_s, const double* y, double* values) const;

  Sample sample(double t_s, const double* y) const;
  double energy_J(const double* y) const;  // E_kin + E_el
  std::vector<LinkState> link_states(const double* y) const;

  // Checks a state for what no physical run reaches (non-finite, a joint
  // stretched beyond 2 L, a link off the drive, runaway speed). Returns the
  // quantity's description, empty if the state is fine.
  std::string state_problem(const double* y) const;

  double clamp_force(int j, double t_s) const;
  // Replaces the input profiles by constants from now on (the stepping
  // interface's zero-order hold, docs/mbd.md#stepping): clamping forces
  // (clamped sheaves), input torque, load torque (the road load still added).
  void hold_inputs(double clamp1_N, double clamp2_N, double tau_in_Nm, double tau_load_Nm);
  // Load torque on the driven pulley at t and its speed w2: tau_load(t) plus
  // the road load (docs/rom.md#road-load), and its slope d/dw2.
  double load_torque(double t_s, double omega2_rad_s, double* slope = nullptr) const;
  // Start-up times (docs/mbd.md#start-up): the settle runs from settle_start_s()
  // to spinup_start_s(), the spin-up to hold_start_s(), the hold to 0.
  double settle_start_s() const { return -(p_.settle_s + p_.start.duration_s()); }
  double spinup_start_s() const { return -p_.start.duration_s(); }
  double hold_start_s() const { return p_.start.active ? -p_.start.hold_s : 0.0; }
  // Imposed speed of pulley j during the spin-up at t, and its rate.
  double spinup_speed(int j, double t_s, double* rate = nullptr) const;
  double stop_force(double opening_m) const;  // the movable sheave's end stops [N]

 private:
  void build_pattern();
  // How the drive turns pulley j in the current phase (docs/mbd.md#equations-of-motion):
  // held (its speed imposed; rate the imposed acceleration) or free under
  // torque_Nm (the input torque on the driver, the load torque on the driven)
  // with slope d torque / d omega_j.
  struct Drive {
    bool held = true;
    double rate = 0;
    double torque_Nm = 0, slope = 0;
  };
  Drive drive(int j, double t_s, double omega_rad_s) const;
  // The torque the drive applies (held: what holds the speed), booked as input
  // (driver) or load (driven) work.
  double applied_torque(int j, const Drive& d, double chain_moment) const;

  MbdParams p_;
  DriveGeometry geo_;
  Phase phase_ = Phase::run;
  int n_links_, n_, sheave_base_, ledger_base_;
  double inertia_;
  double inv_w_eps_;     // 1 / w_eps of the road load
  double thrust_ratio_;  // theta2 / theta1: static clamp ratio for the driven default
  SparsePattern pattern_;
  std::vector<std::int32_t> index_;  // dense (row * n + col) -> position in pattern, -1 if absent
  detail::ChainConst chain_;
  detail::ChainConst settle_chain_;  // the same without friction (docs/mbd.md#start-up)
  const detail::ChainConst& chain() const { return phase_ == Phase::settle ? settle_chain_ : chain_; }
  detail::PulleyConst pulley_[2];
  mutable Fault fault_;
  // Right-hand side scratch: forces (3 per link), cosine and sine of each link angle.
  mutable std::vector<double> force_, cos_, sin_;
  void link_trig(const double* y) const;  // fills cos_, sin_
  detail::JointForces<double> joint(const double* y, int i) const;  // joint i -> i+1 (after link_trig)
  detail::ContactForces<double> contact(const double* y, int i, int j, double omega, double opening) const;
};

}  // namespace cvt::mbd
