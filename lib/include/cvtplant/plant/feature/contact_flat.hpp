#pragma once
// The lumps' contact without the radial DOF (docs/rom.md#contact): each
// lump slides along the flank in the tangential direction only,
//   F_i = -phi(v_rel_i) N_i,  N_i = F_lumps load_i,  load_i = 2 s_i f / cos(beta_i)
// (phi: seed Eq. 6 / Eq. 9). With the radial DOF the friction is a vector in
// the flank plane instead (feature/contact_wedge.hpp).
//
// Its Jacobian is the chain rule from the partials the pieces report
// (RomFlatContact::Jac): a piece says how a slip speed, the driver radius or
// the lumps' axial force moves with a state, and the law turns that into the
// friction forces' partials dF_i/dx_j. The products are ordered so that no
// intermediate leaves q16.16 (docs/rom.md#fixed-point).
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/plant/feature/drive_train.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_formulas.hpp"

namespace cvt {

template <class Cfg>
class RomFlatContact {
  using T = typename Cfg::Scalar;
  using L = typename Cfg::Layout;
  using Core = RomDriveTrain<Cfg>;
  static constexpr int N = Cfg::N;

 public:
  static constexpr bool kWedge = false;
  RomFlatContact(const Core&, const double*) {}

  // What the shared contact keeps: the slip speeds and the friction
  // characteristic with its slope at each, evaluated once per state.
  struct Cache {
    T v_rel1{}, v_rel2{};  // slip speeds [m/s]
    FrictionEval<T> lump1{}, lump2{};
  };

  // F_i at slip speeds v1, v2 and lumps' axial force fl (any scalar S).
  template <class S>
  static void forces(const Core& k, const S& v1, const S& v2, const S& /*rho_dot*/, const S& fl, S& F1, S& F2, S& Fr1,
                     S& Fr2) {
    // Friction grouping as in StickSlipOscillator (docs/rom.md#holds).
    F1 = lump_friction(friction_characteristic(k.friction, v1), normal_force(fl, S(k.load1)));
    F2 = lump_friction(friction_characteristic(k.friction, v2), normal_force(fl, S(k.load2)));
    Fr1 = Fr2 = S(T(0));
  }
  static void evaluate(const Core& k, const T& v1, const T& v2, const T& /*rho_dot*/, const T& /*fl*/, Cache& c) {
    c.v_rel1 = v1;
    c.v_rel2 = v2;
    c.lump1 = friction_characteristic_and_slope(k.friction, v1);
    c.lump2 = friction_characteristic_and_slope(k.friction, v2);
  }
  // The same forces from the cache (bit for bit those of forces()).
  static void forces(const Core& k, const Cache& c, const T& fl, T& F1, T& F2, T& Fr1, T& Fr2) {
    F1 = lump_friction(c.lump1.phi, normal_force(fl, k.load1));
    F2 = lump_friction(c.lump2.phi, normal_force(fl, k.load2));
    Fr1 = Fr2 = T(0);
  }
  static const T& slip1(const Cache& c) { return c.v_rel1; }
  static const T& slip2(const Cache& c) { return c.v_rel2; }

  // The chain rule of the friction forces' partials dF_i/dx_j, per time unit.
  class Jac {
   public:
    // fl: the lumps' axial force at x; rip = d F_lumps / d F_ax (1 + A cos
    // theta with the link ripple, else 1). With `w_slope_floor` the slope
    // inside the sign's regularisation layer is raised to at least its value
    // at the layer's edge (docs/rom.md#slope-floor).
    Jac(const Core& k, const Cache& c, const T& fl, const T& rip, bool rippled, const T& w1, bool w_slope_floor)
        : k_(k), c_(c), w1_(w1) {
      N1_ = normal_force(fl, k.load1);
      N2_ = normal_force(fl, k.load2);
      T s1 = c.lump1.slope, s2 = c.lump2.slope;
      if (w_slope_floor) {
        if (abs(c.v_rel1) < k.floor_speed && s1 < k.slope_floor) s1 = k.slope_floor;
        if (abs(c.v_rel2) < k.floor_speed && s2 < k.slope_floor) s2 = k.slope_floor;
      }
      // dF_i/dv_rel_i = -phi'(v_rel) N_i, per time unit: phi' N alone (5e6
      // N s/m at 3.3 kN) would not fit q16.16, phi' per time unit does.
      g_[0] = -Cfg::per_tau(s1) * N1_;
      g_[1] = -Cfg::per_tau(s2) * N2_;
      // dF_i/dF_lumps = -phi_i load_i, and through the ripple's factor dF_i/dF_ax.
      n0_[0] = -c.lump1.phi * k.load1;
      n0_[1] = -c.lump2.phi * k.load2;
      n_[0] = rippled ? n0_[0] * rip : n0_[0];
      n_[1] = rippled ? n0_[1] * rip : n0_[1];
      #pragma GCC unroll 16
      for (int j = 0; j < N; ++j) dF[0][j] = dF[1][j] = T(0);
    }

    // d v_rel,i / d x_col = dv (one lump, or both).
    void slip(int lump, int col, const T& dv) { dF[lump][col] += g_[lump] * dv; }
    void slip_both(int col, const T& dv) {
      slip(0, col, dv);
      slip(1, col, dv);
    }
    // d v_rel,i / d x_col = 1.
    void slip_unit(int lump, int col) { dF[lump][col] += g_[lump]; }
    // d r1e / d x_col = d: the slip speeds move with -d w1, the driver's
    // friction torque with d (F1 + F2).
    void driver_radius(int col, const T& d) {
      slip_both(col, -d * w1_);
      r_col_[nr_] = col;
      r_val_[nr_] = d;
      ++nr_;
    }
    // d F_ax / d x_col = d (the axial force before the link ripple).
    void axial(int col, const T& d) {
      dF[0][col] += Cfg::per_tau(n_[0] * d);
      dF[1][col] += Cfg::per_tau(n_[1] * d);
    }
    // d F_lumps / d x_col = d (the lumps' axial force itself).
    void lumps_force(int col, const T& d) {
      dF[0][col] += Cfg::per_tau(n0_[0] * d);
      dF[1][col] += Cfg::per_tau(n0_[1] * d);
    }
    const T& slip_gain(int lump) const { return g_[lump]; }

    // A held pulley's speed never changes: its column is left out (zero), so
    // the LU pivots stay those of seed Eq. 9 (docs/rom.md#jacobian).
    void finish() {
      if (k_.hold1) dF[0][L::kW1] = dF[1][L::kW1] = T(0);
      if (k_.hold2) dF[0][L::kW2] = dF[1][L::kW2] = T(0);
    }

    // J1 w1' = tau_in - r1e (F1 + F2): the driver row (zero when held).
    void driver_row(const T& r1e, typename Cfg::Jacobian& J) const {
      const T inv_J1 = k_.inv_J1;
      if (k_.hold1) {
        #pragma GCC unroll 16
        for (int j = 0; j < N; ++j) J(L::kW1, j) = T(0);
        return;
      }
      #pragma GCC unroll 16
      for (int j = 0; j < N; ++j) J(L::kW1, j) = -r1e * (dF[0][j] + dF[1][j]) * inv_J1;
      if (nr_ > 0) {
        const T F1 = lump_friction(c_.lump1.phi, N1_);
        const T F2 = lump_friction(c_.lump2.phi, N2_);
        for (int i = 0; i < nr_; ++i) J(L::kW1, r_col_[i]) += Cfg::per_tau(-r_val_[i] * (F1 + F2) * inv_J1);
      }
    }

    T dF[2][N];

   private:
    const Core& k_;
    const Cache& c_;
    T w1_;
    T N1_, N2_, g_[2], n0_[2], n_[2];
    int nr_ = 0;
    int r_col_[2] = {0, 0};
    T r_val_[2] = {};
  };
};

}  // namespace cvt
