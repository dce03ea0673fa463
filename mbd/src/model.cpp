// The chain model's right-hand side, Jacobian and outputs (docs/mbd.md).
#include "cvtplant/mbd/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "cvtplant/autodiff/dual.hpp"
#include "cvtplant/physics/seed.hpp"
#include "cvtplant/plant/rom_formulas.hpp"

namespace cvt::mbd {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("mbd parameters: ") + what);
}

// Pulley speed beyond which a run is reported as a runaway [rad/s].
constexpr double kRunawaySpeed_rad_s = 1e4;

}  // namespace

double TimeProfile::at(double t_s) const {
  if (points.empty()) return 0.0;
  if (t_s <= points.front().first) return points.front().second;
  if (t_s >= points.back().first) return points.back().second;
  const auto hi = std::upper_bound(points.begin(), points.end(), t_s,
                                   [](double t, const std::pair<double, double>& p) { return t < p.first; });
  const auto lo = hi - 1;
  const double w = (t_s - lo->first) / (hi->first - lo->first);
  return lo->second + w * (hi->second - lo->second);
}

ChainModel::ChainModel(const MbdParams& p) : p_(p), geo_(p.r1_m, p.r2_m, p.center_distance_m) {
  require(p.links >= 3, "at least 3 links");
  require(p.link_mass_kg > 0 && p.link_length_m > 0 && p.J1_kgm2 > 0 && p.J2_kgm2 > 0, "masses, inertias, L > 0");
  require(p.joint_stiffness_N_m > 0 && p.joint_damping_Ns_m >= 0, "k > 0, p >= 0");
  require(p.bolt_stiffness_N_m > 0 && p.beta0_rad > 0 && p.beta0_rad < 0.5 * kPi, "K_b > 0, 0 < beta0 < 90 deg");
  require(p.link_length_m * p.links < 2.0 * geo_.pitch_line_m, "the links must fit the pitch line");
  require(p.settle_s >= 0 && p.settle_drag_Ns_m >= 0, "settle time and drag >= 0");
  auto valid_profile = [](const TimeProfile& f) {
    for (std::size_t k = 0; k < f.points.size(); ++k)
      if (!std::isfinite(f.points[k].first) || !std::isfinite(f.points[k].second) ||
          (k > 0 && !(f.points[k].first > f.points[k - 1].first)))
        return false;
    return true;
  };
  require(!p.tau_in_Nm.empty() && valid_profile(p.tau_in_Nm) && !p.tau_load_Nm.empty() && valid_profile(p.tau_load_Nm),
          "torque profiles: finite values at increasing times");
  const RoadLoad& road = p.road;
  require(std::isfinite(road.T0_Nm) && road.T0_Nm >= 0 && std::isfinite(road.cv_Nms_rad) && road.cv_Nms_rad >= 0 &&
              std::isfinite(road.ca_Nms2_rad2) && road.ca_Nms2_rad2 >= 0 && std::isfinite(road.w_eps_rad_s) &&
              road.w_eps_rad_s > 0,
          "road load: T0, c_v, c_a >= 0, w_eps > 0");
  if (p.start.active)
    require(std::isfinite(p.start.omega1_rad_s) && std::isfinite(p.start.omega2_rad_s) && p.start.spinup_s > 0 &&
                p.start.hold_s >= 0 && std::isfinite(p.start.spinup_s + p.start.hold_s),
            "start at speed: finite speeds, spin-up time > 0, hold time >= 0");
  if (p.sheaves == SheaveMode::clamped) {
    require(!p.clamp1_N.empty(), "clamped sheaves need the driver clamping force");
    for (const TimeProfile* f : {&p.clamp1_N, &p.clamp2_N})
      for (std::size_t k = 0; k < f->points.size(); ++k)
        require(f->points[k].second > 0 && (k == 0 || f->points[k].first > f->points[k - 1].first),
                "clamping forces > 0 at increasing times");
    require(p.sheave_mass_kg > 0 && p.sheave_damping_Ns_m >= 0, "sheave mass > 0, damping >= 0");
    require(p.sheave_stop_m > 0 && p.sheave_stop_N_m >= 0, "sheave stops > 0");
    require(p.start_r1_m == 0 || (std::fabs(p.start_r1_m - p.r1_m) * 2.0 * std::tan(p.beta0_rad) < p.sheave_stop_m),
            "start radius within the driver's stops");
  } else {
    require(p.start_r1_m == 0, "a start radius needs clamped sheaves");
  }
  n_links_ = p.links;
  sheave_base_ = 6 * n_links_ + 4;
  ledger_base_ = sheave_base_ + (clamped() ? 4 : 0);
  n_ = ledger_base_ + 5;
  inertia_ = p.link_inertia();
  inv_w_eps_ = 1.0 / p.road.w_eps_rad_s;  // as the real-time plant (plant/feature/road_load.hpp)
  thrust_ratio_ = geo_.wrap_rad[1] / geo_.wrap_rad[0];
  force_.assign(3 * static_cast<std::size_t>(n_links_), 0.0);
  cos_.assign(static_cast<std::size_t>(n_links_), 1.0);
  sin_.assign(static_cast<std::size_t>(n_links_), 0.0);

  chain_.half_length_m = 0.5 * p.link_length_m;
  chain_.k_N_m = p.joint_stiffness_N_m;
  chain_.p_Ns_m = p.joint_damping_Ns_m;
  chain_.c_rot_Nms = p.joint_rot_damping_Nms_rad;
  chain_.Kb_N_m = p.bolt_stiffness_N_m;
  chain_.friction = p.friction;
  settle_chain_ = chain_;
  settle_chain_.friction.law = FrictionLaw::constant;
  settle_chain_.friction.mu0 = 0.0;
  // docs/mbd.md#sheave-deformation: Eq. 4 with r, r' the driver and driven
  // pitch radii for both pulleys; zeta from each wrap's entry point.
  const double ratio = p.r1_m / p.r2_m;
  const double amp = p.sheave_deformation ? seed::deformation_amplitude_rad(ratio) : 0.0;
  const double centre = seed::deformation_centre_rad(ratio);
  for (int j = 0; j < 2; ++j) {
    detail::PulleyConst& pc = pulley_[j];
    pc.ox_m = geo_.centre[j].x;
    pc.oy_m = geo_.centre[j].y;
    pc.width_at_axis_m = 2.0 * geo_.r_m[j] * sin(p.beta0_rad) / cos(p.beta0_rad);
    pc.beta0_rad = p.beta0_rad;
    pc.cos_beta0 = cos(p.beta0_rad);
    pc.sin_beta0 = sin(p.beta0_rad);
    pc.half_amp_rad = 0.5 * amp;
    require(std::fabs(pc.half_amp_rad) <= 0.01, "sheave deformation amplitude Delta/2 within 0.01 rad");
    pc.wx = cos(geo_.entry_angle_rad[j] + centre);
    pc.wy = sin(geo_.entry_angle_rad[j] + centre);
    // Fixed groove: a bolt is compressed only inside r tan(beta0)/tan(beta_min)
    // (0.11 % above r); a movable sheave can close the groove, so allow more.
    pc.reject_radius_m = clamped() ? geo_.r_m[j] + 0.05 : geo_.r_m[j] * 1.01;
  }
  build_pattern();
}

// docs/mbd.md#clamped-sheaves: the ratio end stops, a stiff spring beyond +-sheave_stop_m.
double ChainModel::stop_force(double opening_m) const {
  if (opening_m > p_.sheave_stop_m) return -p_.sheave_stop_N_m * (opening_m - p_.sheave_stop_m);
  if (opening_m < -p_.sheave_stop_m) return -p_.sheave_stop_N_m * (opening_m + p_.sheave_stop_m);
  return 0.0;
}

double ChainModel::clamp_force(int j, double t_s) const {
  if (!clamped()) return 0.0;
  if (j == 0) return p_.clamp1_N.at(t_s);
  return p_.clamp2_N.empty() ? thrust_ratio_ * p_.clamp1_N.at(t_s) : p_.clamp2_N.at(t_s);
}

void ChainModel::hold_inputs(double clamp1_N, double clamp2_N, double tau_in_Nm, double tau_load_Nm) {
  p_.clamp1_N = TimeProfile::constant(clamp1_N);
  p_.clamp2_N = TimeProfile::constant(clamp2_N);
  p_.tau_in_Nm = TimeProfile::constant(tau_in_Nm);
  p_.tau_load_Nm = TimeProfile::constant(tau_load_Nm);
}

double ChainModel::tolerance_scale(int i) const {
  // docs/mbd.md#tolerances
  if (i < 6 * n_links_) {
    switch (i % 6) {
      case 0: case 1: return 0.1;    // m: 0.1 um at rtol 1e-6, against mm of bolt compression
      case 2: return 1.0;            // rad, absolute (link angles grow without bound)
      case 3: case 4: return 1.0;    // m/s
      default: return p_.tolerance_link_rate_rad_s;  // rad/s
    }
  }
  if (i < sheave_base_) return 1.0;  // pulley angle [rad], speed [rad/s]
  if (i < ledger_base_) return (i - sheave_base_) % 2 == 0 ? 0.01 : 0.1;  // sheave m, m/s
  return 1.0;                        // J
}

double ChainModel::tolerance_relative(int i) const {
  if (i < 6 * n_links_ && i % 6 == 2) return 0.0;
  return 1.0;
}

double ChainModel::tolerance_energy_J() const {
  double e = 0;
  for (int i = 0; i < n_links_; ++i) {
    const double v = tolerance_scale(6 * i + 3), w = tolerance_scale(6 * i + 5);
    e += p_.link_mass_kg * v * v + 0.5 * inertia_ * w * w;  // two translational components
  }
  const double w1 = tolerance_scale(pulley_speed(0)), w2 = tolerance_scale(pulley_speed(1));
  return e + 0.5 * p_.J1_kgm2 * w1 * w1 + 0.5 * p_.J2_kgm2 * w2 * w2;
}

std::vector<double> ChainModel::initial_state() const {
  // docs/mbd.md#start-up: front pins (bolts) evenly along the pitch line, the
  // rear pin of each link on the pitch line a chord L behind its front pin.
  // Started at another driver radius: along that ratio's line of the same
  // length, the sheaves opened so the unloaded bolts touch there.
  std::vector<double> y(static_cast<std::size_t>(n_), 0.0);
  const bool moved = p_.start_r1_m > 0;
  const double r1s = moved ? p_.start_r1_m : geo_.r_m[0];
  const double r2s = moved ? driven_radius_for(r1s, geo_.pitch_line_m, geo_.center_distance_m) : geo_.r_m[1];
  const DriveGeometry line(r1s, r2s, geo_.center_distance_m);
  if (moved) {
    y[static_cast<std::size_t>(sheave_opening(0))] = 2.0 * tan(p_.beta0_rad) * (geo_.r_m[0] - r1s);
    y[static_cast<std::size_t>(sheave_opening(1))] = 2.0 * tan(p_.beta0_rad) * (geo_.r_m[1] - r2s);
  }
  const double spacing = line.pitch_line_m / n_links_;
  const double L = p_.link_length_m;
  for (int i = 0; i < n_links_; ++i) {
    const double s_front = i * spacing;
    const Vec2 f = line.pitch_point(s_front);
    double lo = s_front - 2.0 * L, hi = s_front;  // chord grows as the rear point moves back
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      const Vec2 r = line.pitch_point(mid);
      const double d = std::hypot(f.x - r.x, f.y - r.y);
      (d > L ? lo : hi) = mid;
    }
    const Vec2 r = line.pitch_point(0.5 * (lo + hi));
    double* q = &y[static_cast<std::size_t>(6 * i)];
    q[0] = 0.5 * (f.x + r.x);
    q[1] = 0.5 * (f.y + r.y);
    q[2] = std::atan2(f.y - r.y, f.x - r.x);
  }
  return y;
}

void ChainModel::reset_ledger(double* y) const {
  for (int k = 0; k < 5; ++k) y[ledger(k)] = 0.0;
}

// docs/rom.md#road-load: the real-time plant's law, the same function.
double ChainModel::load_torque(double t_s, double omega2_rad_s, double* slope) const {
  const double tau = p_.tau_load_Nm.at(t_s);
  const RoadLoad& r = p_.road;
  if (!r.active()) {
    if (slope != nullptr) *slope = 0.0;
    return tau;
  }
  if (slope != nullptr) {
    using D1 = Dual<double, 1>;
    *slope = road_load_torque<D1>(D1(tau), D1(r.T0_Nm), D1(inv_w_eps_), D1(r.cv_Nms_rad), D1(r.ca_Nms2_rad2),
                                  D1::variable(omega2_rad_s, 0))
                 .d[0];
  }
  return road_load_torque<double>(tau, r.T0_Nm, inv_w_eps_, r.cv_Nms_rad, r.ca_Nms2_rad2, omega2_rad_s);
}

// docs/mbd.md#start-at-speed: omega_j x (3 x^2 - 2 x^3), x the fraction of the
// spin-up gone: zero acceleration at both ends.
double ChainModel::spinup_speed(int j, double t_s, double* rate) const {
  const double w0 = j == 0 ? p_.start.omega1_rad_s : p_.start.omega2_rad_s;
  const double T = p_.start.spinup_s;
  const double x = std::clamp((t_s - spinup_start_s()) / T, 0.0, 1.0);
  if (rate != nullptr) *rate = w0 * 6.0 * x * (1.0 - x) / T;
  return w0 * x * x * (3.0 - 2.0 * x);
}

ChainModel::Drive ChainModel::drive(int j, double t_s, double omega_rad_s) const {
  Drive d;  // held at a constant speed
  switch (phase_) {
    case Phase::settle: break;
    case Phase::spinup: spinup_speed(j, t_s, &d.rate); break;
    case Phase::hold:
      if (j == 1) {
        d.held = false;
        d.torque_Nm = load_torque(0.0, omega_rad_s, &d.slope);
      }
      break;
    case Phase::run:
      if (j == 0 && !p_.hold1.active) {
        d.held = false;
        d.torque_Nm = p_.tau_in_Nm.at(t_s);
      } else if (j == 1 && !p_.hold2.active) {
        d.held = false;
        d.torque_Nm = load_torque(t_s, omega_rad_s, &d.slope);
      }
      break;
  }
  return d;
}

double ChainModel::applied_torque(int j, const Drive& d, double chain_moment) const {
  // A free pulley: the load case's torque. A held one: whatever gives it the
  // imposed acceleration, from J1 w1' = tau_in + M1 and J2 w2' = M2 - tau_load.
  if (!d.held) return d.torque_Nm;
  return j == 0 ? p_.J1_kgm2 * d.rate - chain_moment : chain_moment - p_.J2_kgm2 * d.rate;
}

// docs/mbd.md#equations-of-motion
void ChainModel::link_trig(const double* y) const {
  for (int i = 0; i < n_links_; ++i) {
    cos_[static_cast<std::size_t>(i)] = cos(y[6 * i + 2]);
    sin_[static_cast<std::size_t>(i)] = sin(y[6 * i + 2]);
  }
}

detail::JointForces<double> ChainModel::joint(const double* y, int i) const {
  const int b = (i + 1 == n_links_) ? 0 : i + 1;
  const auto a = static_cast<std::size_t>(i), bb = static_cast<std::size_t>(b);
  return detail::joint_forces<double>(chain(), y + 6 * i, cos_[a], sin_[a], y + 6 * b, cos_[bb], sin_[bb]);
}

detail::ContactForces<double> ChainModel::contact(const double* y, int i, int j, double omega, double opening) const {
  const auto a = static_cast<std::size_t>(i);
  return detail::contact_forces<double>(chain(), pulley_[j], y + 6 * i, cos_[a], sin_[a], omega, opening);
}

bool ChainModel::rhs(double t_s, const double* y, double* dydt) const {
  std::fill(force_.begin(), force_.end(), 0.0);
  link_trig(y);
  double moment[2] = {0, 0}, axial[2] = {0, 0};
  double p_damp = 0, p_fric = 0;
  for (int i = 0; i < n_links_; ++i) {
    const int b = (i + 1 == n_links_) ? 0 : i + 1;
    const auto a = static_cast<std::size_t>(i), bb = static_cast<std::size_t>(b);
    const auto jf =
        detail::joint_forces<double, false>(chain(), y + 6 * i, cos_[a], sin_[a], y + 6 * b, cos_[bb], sin_[bb]);
    for (int k = 0; k < 3; ++k) {
      force_[3 * i + k] += jf.fa[k];
      force_[3 * b + k] += jf.fb[k];
    }
    p_damp += jf.dissipation_W;
  }
  double omega[2], opening[2] = {0, 0};
  for (int j = 0; j < 2; ++j) {
    omega[j] = y[pulley_speed(j)];
    if (clamped()) opening[j] = y[sheave_opening(j)];
  }
  for (int i = 0; i < n_links_; ++i) {
    for (int j = 0; j < 2; ++j) {
      const auto cf = contact(y, i, j, omega[j], opening[j]);
      if (!cf.active) continue;
      for (int k = 0; k < 3; ++k) force_[3 * i + k] += cf.f[k];
      moment[j] += cf.pulley_moment_Nm;
      axial[j] += cf.bolt_force_N;
      p_fric += cf.dissipation_W;
    }
  }
  const bool settling = phase_ == Phase::settle;
  const double inv_m = 1.0 / p_.link_mass_kg, inv_I = 1.0 / inertia_;
  for (int i = 0; i < n_links_; ++i) {
    const double* q = y + 6 * i;
    double* d = dydt + 6 * i;
    d[0] = q[3];
    d[1] = q[4];
    d[2] = q[5];
    double fx = force_[3 * i], fy = force_[3 * i + 1];
    if (settling) {
      fx -= p_.settle_drag_Ns_m * q[3];
      fy -= p_.settle_drag_Ns_m * q[4];
    }
    d[3] = fx * inv_m;
    d[4] = fy * inv_m;
    d[5] = force_[3 * i + 2] * inv_I;
  }
  const Drive d1 = drive(0, t_s, omega[0]), d2 = drive(1, t_s, omega[1]);
  const double tau_in = applied_torque(0, d1, moment[0]);
  const double tau_load = applied_torque(1, d2, moment[1]);
  dydt[pulley_angle(0)] = omega[0];
  dydt[pulley_angle(1)] = omega[1];
  dydt[pulley_speed(0)] = d1.held ? d1.rate : (tau_in + moment[0]) / p_.J1_kgm2;
  dydt[pulley_speed(1)] = d2.held ? d2.rate : (moment[1] - tau_load) / p_.J2_kgm2;
  double p_clamp = 0;
  if (clamped()) {
    // docs/mbd.md#clamped-sheaves: m_s s'' = F_ax - F_clamp(t) - c_s s'
    for (int j = 0; j < 2; ++j) {
      if (j == 0 && driver_sheave_locked()) {
        dydt[sheave_opening(0)] = 0.0;
        dydt[sheave_rate(0)] = 0.0;
        continue;
      }
      const double rate = y[sheave_rate(j)];
      const double clamp = clamp_force(j, t_s);
      dydt[sheave_opening(j)] = rate;
      dydt[sheave_rate(j)] =
          (axial[j] - clamp - p_.sheave_damping_Ns_m * rate + stop_force(y[sheave_opening(j)])) / p_.sheave_mass_kg;
      p_damp += p_.sheave_damping_Ns_m * rate * rate;
      p_clamp -= clamp * rate;
    }
  }
  // docs/mbd.md#energy-ledger
  dydt[ledger(0)] = tau_in * omega[0];
  dydt[ledger(1)] = tau_load * omega[1];
  dydt[ledger(2)] = p_fric;
  dydt[ledger(3)] = p_damp;
  dydt[ledger(4)] = p_clamp;
  for (int i = 0; i < n_; ++i) {
    if (std::isfinite(dydt[i])) continue;
    // The latest fault is kept: a solver may try a bad iterate, recover, and
    // only fail for good later.
    fault_.set = true;
    fault_.t_s = t_s;
    if (i < 6 * n_links_)
      fault_.quantity = "acceleration of link " + std::to_string(i / 6) + " (non-finite force)";
    else if (i < sheave_base_)
      fault_.quantity = std::string("acceleration of the ") + (i < pulley_angle(1) ? "driver" : "driven") + " pulley";
    else if (i < ledger_base_)
      fault_.quantity = "acceleration of a movable sheave";
    else
      fault_.quantity = "energy ledger rate";
    return false;
  }
  return true;
}

void ChainModel::build_pattern() {
  // docs/mbd.md#bdf-and-the-jacobian: links couple to their two neighbours through the
  // joints and to both pulleys (and sheaves) through the contacts.
  std::vector<std::vector<int>> cols(static_cast<std::size_t>(n_));
  auto add = [&](int r, int c) { cols[static_cast<std::size_t>(c)].push_back(r); };
  for (int r = 0; r < n_; ++r) add(r, r);
  for (int i = 0; i < n_links_; ++i) {
    for (int k = 0; k < 3; ++k) add(6 * i + k, 6 * i + 3 + k);
    const int nb[3] = {(i + n_links_ - 1) % n_links_, i, (i + 1) % n_links_};
    for (int k = 3; k < 6; ++k) {
      for (int m : nb)
        for (int c = 0; c < 6; ++c) add(6 * i + k, 6 * m + c);
      for (int j = 0; j < 2; ++j) {
        add(6 * i + k, pulley_speed(j));
        if (clamped()) add(6 * i + k, sheave_opening(j));
      }
    }
  }
  for (int j = 0; j < 2; ++j) {
    add(pulley_angle(j), pulley_speed(j));
    for (int c = 0; c < 6 * n_links_; ++c) add(pulley_speed(j), c);
    if (clamped()) {
      add(pulley_speed(j), sheave_opening(j));
      add(sheave_opening(j), sheave_rate(j));
      for (int i = 0; i < n_links_; ++i)
        for (int k = 0; k < 3; ++k) add(sheave_rate(j), 6 * i + k);
      add(sheave_rate(j), sheave_opening(j));
    }
  }
  // Ledger rows (docs/mbd.md#bdf-and-the-jacobian): exact Newton corrections for the
  // integrals too. Nothing depends on them, so KLU's block triangular form
  // keeps them out of the factorisation's fill.
  for (int c = 0; c < 6 * n_links_; ++c)
    for (int k = 0; k < 4; ++k) add(ledger(k), c);
  for (int j = 0; j < 2; ++j) {
    add(ledger(0), pulley_speed(j));
    add(ledger(1), pulley_speed(j));
    add(ledger(2), pulley_speed(j));
    if (clamped()) {
      for (int k = 0; k < 5; ++k) {
        add(ledger(k), sheave_opening(j));
        add(ledger(k), sheave_rate(j));
      }
    }
  }
  pattern_.n = n_;
  pattern_.col_start.assign(static_cast<std::size_t>(n_) + 1, 0);
  pattern_.row.clear();
  index_.assign(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_), -1);
  for (int c = 0; c < n_; ++c) {
    auto& rows = cols[static_cast<std::size_t>(c)];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (int r : rows) {
      index_[static_cast<std::size_t>(r) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(c)] =
          static_cast<std::int32_t>(pattern_.row.size());
      pattern_.row.push_back(r);
    }
    pattern_.col_start[static_cast<std::size_t>(c) + 1] = static_cast<std::int64_t>(pattern_.row.size());
  }
}

void ChainModel::jacobian(double t_s, const double* y, double* values) const {
  std::fill(values, values + pattern_.nnz(), 0.0);
  const auto at = [&](int r, int c) -> double& {
    return values[index_[static_cast<std::size_t>(r) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(c)]];
  };
  const double inv_mass[3] = {1.0 / p_.link_mass_kg, 1.0 / p_.link_mass_kg, 1.0 / inertia_};
  const bool settling = phase_ == Phase::settle;
  for (int i = 0; i < n_links_; ++i) {
    for (int k = 0; k < 3; ++k) at(6 * i + k, 6 * i + 3 + k) = 1.0;
    if (settling) {
      at(6 * i + 3, 6 * i + 3) -= p_.settle_drag_Ns_m * inv_mass[0];
      at(6 * i + 4, 6 * i + 4) -= p_.settle_drag_Ns_m * inv_mass[1];
    }
  }
  using D12 = Dual<double, 12>;
  for (int i = 0; i < n_links_; ++i) {
    const int b = (i + 1 == n_links_) ? 0 : i + 1;
    D12 a_d[6], b_d[6];
    for (int k = 0; k < 6; ++k) {
      a_d[k] = D12::variable(y[6 * i + k], k);
      b_d[k] = D12::variable(y[6 * b + k], 6 + k);
    }
    const D12 ca = cos(a_d[2]), sa = sin(a_d[2]);
    const D12 cb = cos(b_d[2]), sb = sin(b_d[2]);
    const auto jf = detail::joint_forces<D12, false>(chain(), a_d, ca, sa, b_d, cb, sb);
    for (int v = 0; v < 12; ++v) {
      const int col = v < 6 ? 6 * i + v : 6 * b + (v - 6);
      for (int k = 0; k < 3; ++k) {
        at(6 * i + 3 + k, col) += jf.fa[k].d[v] * inv_mass[k];
        at(6 * b + 3 + k, col) += jf.fb[k].d[v] * inv_mass[k];
      }
      at(ledger(3), col) += jf.dissipation_W.d[v];
    }
  }
  using D8 = Dual<double, 8>;
  double moment[2] = {0, 0};
  for (int j = 0; j < 2; ++j) {
    const double omega_j = y[pulley_speed(j)];
    const Drive dj = drive(j, t_s, omega_j);
    const bool pulley_free = !dj.held;
    // Power of the drive on pulley j, booked in ledger 0 (driver) or 1 (driven):
    // free pulleys run under a torque of time and speed, held ones at an
    // imposed speed.
    const int power_row = ledger(j);
    const double sign_j = j == 0 ? -1.0 : 1.0;  // tau_in = -M1, tau_load = +M2 when held
    const double inv_J = 1.0 / (j == 0 ? p_.J1_kgm2 : p_.J2_kgm2);
    const D8 w = D8::variable(y[pulley_speed(j)], 6);
    const D8 s = clamped() ? D8::variable(y[sheave_opening(j)], 7) : D8(0.0);
    for (int i = 0; i < n_links_; ++i) {
      D8 q[6];
      for (int k = 0; k < 6; ++k) q[k] = D8::variable(y[6 * i + k], k);
      const D8 cq = cos(q[2]), sq = sin(q[2]);
      const auto cf = detail::contact_forces<D8>(chain(), pulley_[j], q, cq, sq, w, s);
      if (!cf.active) continue;
      moment[j] += cf.pulley_moment_Nm.v;
      const int nv = clamped() ? 8 : 7;
      for (int v = 0; v < nv; ++v) {
        const int col = v < 6 ? 6 * i + v : v == 6 ? pulley_speed(j) : sheave_opening(j);
        for (int k = 0; k < 3; ++k) at(6 * i + 3 + k, col) += cf.f[k].d[v] * inv_mass[k];
        if (pulley_free) at(pulley_speed(j), col) += cf.pulley_moment_Nm.d[v] * inv_J;
        else if (!settling) at(power_row, col) += sign_j * omega_j * cf.pulley_moment_Nm.d[v];
        at(ledger(2), col) += cf.dissipation_W.d[v];
        if (clamped() && v != 6 && !(v >= 3 && v < 6) && !(j == 0 && driver_sheave_locked()))
          at(sheave_rate(j), col) += cf.bolt_force_N.d[v] / p_.sheave_mass_kg;
      }
    }
    if (pulley_free) {
      // The load's own slope (road load): J2 w2' = M2 - tau_load(w2).
      at(pulley_speed(j), pulley_speed(j)) += (j == 0 ? 1.0 : -1.0) * dj.slope * inv_J;
    }
    if (!settling) {
      // d(tau omega)/d omega = tau + omega dtau/domega: the drive's torque (a
      // held pulley's: the holding torque, its slope through M above).
      const double torque = applied_torque(j, dj, moment[j]);
      at(power_row, pulley_speed(j)) += pulley_free ? torque + omega_j * dj.slope : torque;
    }
    if (clamped() && j == 0 && driver_sheave_locked()) {
      at(sheave_opening(0), sheave_rate(0)) = 0.0;  // held: both rates zero whatever the state
    } else if (clamped()) {
      const double rate = y[sheave_rate(j)];
      at(sheave_opening(j), sheave_rate(j)) = 1.0;
      at(sheave_rate(j), sheave_rate(j)) = -p_.sheave_damping_Ns_m / p_.sheave_mass_kg;
      if (std::fabs(y[sheave_opening(j)]) > p_.sheave_stop_m)
        at(sheave_rate(j), sheave_opening(j)) -= p_.sheave_stop_N_m / p_.sheave_mass_kg;
      at(ledger(3), sheave_rate(j)) += 2.0 * p_.sheave_damping_Ns_m * rate;
      at(ledger(4), sheave_rate(j)) -= clamp_force(j, t_s);
    }
  }
  for (int j = 0; j < 2; ++j) at(pulley_angle(j), pulley_speed(j)) = 1.0;
}

double ChainModel::energy_J(const double* y) const {
  const Sample s = sample(0.0, y);
  return s.E_kin_J + s.E_el_J;
}

Sample ChainModel::sample(double t_s, const double* y) const {
  Sample out;
  out.t_s = t_s;
  double omega[2], opening[2] = {0, 0};
  for (int j = 0; j < 2; ++j) {
    omega[j] = y[pulley_speed(j)];
    out.omega_rad_s[j] = omega[j];
    out.phi_rad[j] = y[pulley_angle(j)];
    if (clamped()) {
      opening[j] = y[sheave_opening(j)];
      out.sheave_opening_m[j] = opening[j];
      out.clamp_N[j] = clamp_force(j, t_s);
    }
  }
  out.ratio = omega[1] != 0.0 ? omega[0] / omega[1] : kNaN;
  double e_kin = 0.5 * p_.J1_kgm2 * omega[0] * omega[0] + 0.5 * p_.J2_kgm2 * omega[1] * omega[1];
  double e_el = 0;
  link_trig(y);
  std::vector<int> in_contact(static_cast<std::size_t>(n_links_), -1);
  double slip_sum[2] = {0, 0}, radius_sum[2] = {0, 0};
  double slip_lo[2] = {INFINITY, INFINITY}, slip_hi[2] = {-INFINITY, -INFINITY};
  for (int i = 0; i < n_links_; ++i) {
    const double* q = y + 6 * i;
    e_kin += 0.5 * p_.link_mass_kg * (q[3] * q[3] + q[4] * q[4]) + 0.5 * inertia_ * q[5] * q[5];
    for (int j = 0; j < 2; ++j) {
      const auto cf = contact(y, i, j, omega[j], opening[j]);
      if (!cf.active) continue;
      in_contact[static_cast<std::size_t>(i)] = j;
      out.F_ax_N[j] += cf.bolt_force_N;
      out.chain_torque_Nm[j] += cf.pulley_moment_Nm;
      out.wrap_links[j] += 1;
      slip_sum[j] -= cf.slip_t_m_s;  // surface speed minus bolt speed
      radius_sum[j] += cf.radius_m;
      slip_lo[j] = std::min(slip_lo[j], -cf.slip_t_m_s);
      slip_hi[j] = std::max(slip_hi[j], -cf.slip_t_m_s);
      e_el += cf.potential_J;
    }
  }
  for (int j = 0; j < 2; ++j) {
    const bool any = out.wrap_links[j] > 0;
    out.slip_m_s[j] = any ? slip_sum[j] / out.wrap_links[j] : kNaN;
    out.radius_m[j] = any ? radius_sum[j] / out.wrap_links[j] : kNaN;
    out.slip_min_m_s[j] = any ? slip_lo[j] : kNaN;
    out.slip_max_m_s[j] = any ? slip_hi[j] : kNaN;
  }
  double t_sum[2] = {0, 0};
  int t_count[2] = {0, 0};
  for (int i = 0; i < n_links_; ++i) {
    const int b = (i + 1 == n_links_) ? 0 : i + 1;
    const auto jf = joint(y, i);
    e_el += jf.potential_J;
    if (in_contact[static_cast<std::size_t>(i)] >= 0 || in_contact[static_cast<std::size_t>(b)] >= 0) continue;
    // docs/mbd.md#outputs: a joint between two free links belongs to the upper
    // (tight) strand if it lies above the line of centres.
    const double ymid = 0.5 * (y[6 * i + 1] + y[6 * b + 1]);
    const int strand = ymid > 0 ? 0 : 1;
    t_sum[strand] += jf.tension_N;
    t_count[strand] += 1;
  }
  out.tension_tight_N = t_count[0] > 0 ? t_sum[0] / t_count[0] : kNaN;
  out.tension_slack_N = t_count[1] > 0 ? t_sum[1] / t_count[1] : kNaN;
  out.tau_in_Nm = applied_torque(0, drive(0, t_s, omega[0]), out.chain_torque_Nm[0]);
  out.tau_load_Nm = applied_torque(1, drive(1, t_s, omega[1]), out.chain_torque_Nm[1]);
  if (clamped())
    for (int j = 0; j < 2; ++j) {
      const double rate = y[sheave_rate(j)];
      e_kin += 0.5 * p_.sheave_mass_kg * rate * rate;
      const double over = std::fabs(y[sheave_opening(j)]) - p_.sheave_stop_m;
      if (over > 0) e_el += 0.5 * p_.sheave_stop_N_m * over * over;
    }
  out.E_kin_J = e_kin;
  out.E_el_J = e_el;
  out.W_in_J = y[ledger(0)];
  out.W_load_J = y[ledger(1)];
  out.D_friction_J = y[ledger(2)];
  out.D_damping_J = y[ledger(3)];
  out.W_clamp_J = y[ledger(4)];
  return out;
}

std::vector<LinkState> ChainModel::link_states(const double* y) const {
  std::vector<LinkState> out(static_cast<std::size_t>(n_links_));
  const double h = 0.5 * p_.link_length_m;
  link_trig(y);
  for (int i = 0; i < n_links_; ++i) {
    const double* q = y + 6 * i;
    LinkState& l = out[static_cast<std::size_t>(i)];
    l.x_m = q[0];
    l.y_m = q[1];
    l.theta_rad = q[2];
    const double c = cos_[static_cast<std::size_t>(i)], s = sin_[static_cast<std::size_t>(i)];
    l.front_x_m = q[0] + h * c;
    l.front_y_m = q[1] + h * s;
    l.rear_x_m = q[0] - h * c;
    l.rear_y_m = q[1] - h * s;
    l.pulley = -1;
    l.bolt_force_N = 0;
    l.slip_m_s = 0;
    for (int j = 0; j < 2; ++j) {
      const double opening = clamped() ? y[sheave_opening(j)] : 0.0;
      const auto cf = contact(y, i, j, y[pulley_speed(j)], opening);
      if (!cf.active) continue;
      l.pulley = j;
      l.bolt_force_N = cf.bolt_force_N;
      const double vx = q[3] - h * s * q[5], vy = q[4] + h * c * q[5];
      const double rx = l.front_x_m - geo_.centre[j].x, ry = l.front_y_m - geo_.centre[j].y;
      const double w = y[pulley_speed(j)];
      l.slip_m_s = std::hypot(vx + w * ry, vy - w * rx);
    }
    l.tension_N = joint(y, i).tension_N;
  }
  return out;
}

std::string ChainModel::state_problem(const double* y) const {
  for (int i = 0; i < n_; ++i)
    if (!std::isfinite(y[i])) {
      if (i < 6 * n_links_) return "state of link " + std::to_string(i / 6) + " is not finite";
      if (i < ledger_base_) return "pulley or sheave state is not finite";
      return "energy ledger integral is not finite";
    }
  const double L = p_.link_length_m;
  link_trig(y);
  for (int i = 0; i < n_links_; ++i) {
    const double* q = y + 6 * i;
    for (int j = 0; j < 2; ++j) {
      // The bolt (front pin) deeper than half the pitch radius has gone
      // through the groove to where the hub would be.
      const double bx = q[0] + 0.5 * L * cos_[static_cast<std::size_t>(i)] - geo_.centre[j].x;
      const double by = q[1] + 0.5 * L * sin_[static_cast<std::size_t>(i)] - geo_.centre[j].y;
      if (std::hypot(bx, by) < 0.5 * geo_.r_m[j])
        return "link " + std::to_string(i) + " sank to the hub of the " + (j == 0 ? "driver" : "driven") +
               " pulley (bolt radius " + std::to_string(std::hypot(bx, by)) + " m)";
    }
  }
  for (int i = 0; i < n_links_; ++i) {
    const int b = (i + 1 == n_links_) ? 0 : i + 1;
    const double stretch = joint(y, i).stretch_m;
    if (stretch > 2.0 * L)
      return "joint " + std::to_string(i) + "-" + std::to_string(b) + " stretched to " + std::to_string(stretch) +
             " m (more than 2 L: the chain has come apart)";
    const double* q = y + 6 * i;
    const double d0 = std::hypot(q[0] - geo_.centre[0].x, q[1] - geo_.centre[0].y);
    const double d1 = std::hypot(q[0] - geo_.centre[1].x, q[1] - geo_.centre[1].y);
    if (std::min(d0 - geo_.r_m[0], d1 - geo_.r_m[1]) > 0.5 * geo_.center_distance_m)
      return "link " + std::to_string(i) + " left the drive (" + std::to_string(q[0]) + ", " + std::to_string(q[1]) +
             ") m";
  }
  for (int j = 0; j < 2; ++j) {
    if (std::fabs(y[pulley_speed(j)]) > kRunawaySpeed_rad_s)
      return std::string(j == 0 ? "driver" : "driven") + " pulley speed " + std::to_string(y[pulley_speed(j)]) +
             " rad/s beyond 1e4 rad/s (runaway)";
    if (clamped() && y[sheave_opening(j)] > 0.8 * pulley_[j].width_at_axis_m)
      return std::string(j == 0 ? "driver" : "driven") + " sheave opened to " +
             std::to_string(y[sheave_opening(j)]) + " m: the chain reached the shaft";
  }
  return {};
}

}  // namespace cvt::mbd
