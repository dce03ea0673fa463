#pragma once
// The lumps' contact with the radial DOF (docs/rom.md#wedging, seed Eq. 7):
// each lump slips over the flank with the tangential v_t,i and the radial
// g_r,i = rho' / cos(beta_i); the friction force opposes the slip velocity
// in the flank plane and its radial part changes the normal force:
//   q_i = phi(|v_i|) / |v_i|,  |v_i| = sqrt(v_t,i^2 + g_r,i^2)  (q = phi'(0) at |v| = 0)
//   N_i = (F_lumps load_i) / (1 + tan(beta_i) q_i g_r,i)
//   F_i = -q_i v_t,i N_i,  F_r,i = -q_i g_r,i N_i
// With rho' = 0 the tangential force is the flat law's, -phi(v_t) N.
//
// Its Jacobian (docs/rom.md#wedging-jacobian) is the chain rule through each
// lump's partials in (v_t, g_r, N0) (RomWedgeContact::Jac): the pieces
// report how the slip speeds, the driver radius and the lumps' axial force
// move with the states, and finish() combines them.
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/plant/feature/drive_train.hpp"
#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_formulas.hpp"

namespace cvt {

template <class Cfg>
class RomWedgeContact {
  using T = typename Cfg::Scalar;
  using L = typename Cfg::Layout;
  using Core = RomDriveTrain<Cfg>;
  static constexpr int N = Cfg::N;

 public:
  static constexpr bool kWedge = true;

  // A lump's contact forces and their partial derivatives with respect to
  // (v_t, g_r, N0).
  struct LumpPartials {
    T F{}, Fr{};
    T dF[3]{}, dFr[3]{};
  };
  // What the shared contact keeps: each lump's tangential slip and its
  // forces with their partials, what the Jacobian, the right-hand side and
  // the power terms at the state need (docs/rom.md#cost).
  struct Cache {
    T v_t1{}, v_t2{};  // tangential slip speeds [m/s]
    LumpPartials lump1{}, lump2{};
  };

  // tan(beta_i) of each lump (set-up, from the flank angles) and phi'(0),
  // the limit of q at |v| = 0.
  RomWedgeContact(const Core& k, const double* tan_beta)
      : tan1_(T(tan_beta[0])), tan2_(T(tan_beta[1])), q0_(friction_characteristic_slope(k.friction, T(0))) {}

  // The forces at slip speeds v1, v2, radial speed rho' and lumps' axial force fl.
  template <class S>
  void forces(const Core& k, const S& v1, const S& v2, const S& rhod, const S& fl, S& F1, S& F2, S& Fr1,
              S& Fr2) const {
    lump_contact(k, v1, rhod * S(k.inv_cos1), normal_force(fl, S(k.load1)), S(tan1_), F1, Fr1);
    lump_contact(k, v2, rhod * S(k.inv_cos2), normal_force(fl, S(k.load2)), S(tan2_), F2, Fr2);
  }
  void evaluate(const Core& k, const T& v1, const T& v2, const T& rhod, const T& fl, Cache& c) const {
    c.v_t1 = v1;
    c.v_t2 = v2;
    c.lump1 = lump_contact_partials(k, v1, rhod * k.inv_cos1, normal_force(fl, k.load1), tan1_);
    c.lump2 = lump_contact_partials(k, v2, rhod * k.inv_cos2, normal_force(fl, k.load2), tan2_);
  }
  static void forces(const Core&, const Cache& c, const T&, T& F1, T& F2, T& Fr1, T& Fr2) {
    F1 = c.lump1.F;
    F2 = c.lump2.F;
    Fr1 = c.lump1.Fr;
    Fr2 = c.lump2.Fr;
  }
  static const T& slip1(const Cache& c) { return c.v_t1; }
  static const T& slip2(const Cache& c) { return c.v_t2; }

  // The chain rule of the friction forces' partials dF_i/dx_j and dFr_i/dx_j.
  class Jac {
   public:
    Jac(const Core& k, const Cache& c, const T& /*fl*/, const T& rip, bool rippled, const T& w1, bool)
        : k_(k), c_(c), w1_(w1), rip_(rip), rippled_(Cfg::kPolygon && rippled) {
      // The arrays a plant type never writes are left out: the entry lump's
      // own slip (the creep) comes with the tension feature, the lumps' own
      // axial force (the link ripple) with the polygon.
      #pragma GCC unroll 16
      for (int j = 0; j < N; ++j) dvt_[j] = dr1e_[j] = dfax_[j] = T(0);
      if constexpr (Cfg::kTension) {
        #pragma GCC unroll 16
        for (int j = 0; j < N; ++j) dv0_[j] = T(0);
      }
      if constexpr (Cfg::kPolygon) {
        #pragma GCC unroll 16
        for (int j = 0; j < N; ++j) dfl_[j] = T(0);
      }
    }

    void slip(int lump, int col, const T& dv) {
      // Only the entry lump has a slip speed of its own (the creep, feature
      // tension); both share the rest.
      (void)lump;
      if constexpr (Cfg::kTension) dv0_[col] += dv;
      else (void)col, (void)dv;
    }
    void slip_both(int col, const T& dv) { dvt_[col] += dv; }
    void slip_unit(int, int) {}  // d v_t,i / d xd_i = 1: added in finish()
    void driver_radius(int col, const T& d) {
      dr1e_[col] = d;
      dvt_[col] += -d * w1_;
    }
    void axial(int col, const T& d) { dfax_[col] += d; }
    void lumps_force(int col, const T& d) {
      if constexpr (Cfg::kPolygon) dfl_[col] += d;
      else (void)col, (void)d;
    }

    // Inlined, so that the arrays above stay in registers and the columns
    // the pieces never wrote cost no loads.
    [[gnu::always_inline]] void finish() {
      constexpr int kV[2] = {L::kV1, L::kV2};
      const T inv_cos[2] = {k_.inv_cos1, k_.inv_cos2};
      const T load[2] = {k_.load1, k_.load2};
      Fsum_ = T(0);
      #pragma GCC unroll 2
      for (int i = 0; i < 2; ++i) {
        const LumpPartials& P = i == 0 ? c_.lump1 : c_.lump2;
        Fsum_ += P.F;
        #pragma GCC unroll 16
        for (int j = 0; j < N; ++j) {
          T dn = load[i] * dfax_[j];
          if constexpr (Cfg::kPolygon) {
            if (rippled_) dn = load[i] * (rip_ * dfax_[j] + dfl_[j]);
          }
          T dv = dvt_[j];
          if constexpr (Cfg::kTension) {
            if (i == 0) dv = dv + dv0_[j];
          }
          dF[i][j] = P.dF[0] * dv + P.dF[2] * dn;
          dR[i][j] = P.dFr[0] * dv + P.dFr[2] * dn;
        }
        dF[i][kV[i]] += P.dF[0];
        dR[i][kV[i]] += P.dFr[0];
        dF[i][L::kRhoDot] += P.dF[1] * inv_cos[i];
        dR[i][L::kRhoDot] += P.dFr[1] * inv_cos[i];
      }
    }

    // J1 w1' = tau_in - r1e (F1 + F2) with r1e = (r1 + rho) cos(psi); a held
    // pulley's row is zero, like the dual-number Jacobian's.
    void driver_row(const T& r1e, typename Cfg::Jacobian& J) const {
      const T inv_J1 = k_.inv_J1;
      #pragma GCC unroll 16
      for (int j = 0; j < N; ++j)
        J(L::kW1, j) = k_.hold1 ? T(0) : -(r1e * (dF[0][j] + dF[1][j]) + Fsum_ * dr1e_[j]) * inv_J1;
    }

    T dF[2][N], dR[2][N];

   private:
    const Core& k_;
    const Cache& c_;
    T w1_, rip_;
    bool rippled_;
    T Fsum_{};
    T dvt_[N], dv0_[N], dr1e_[N], dfax_[N], dfl_[N];
  };

  // docs/rom.md#slope-floor for the W of the wedging plants: adds to J the
  // part of the floor that acts through the tangential slip speed, dF_i/dv_t,i
  // raised by (floor - phi') F_lumps load_i on the rows of w1 and xd_i and the
  // columns w1, w2, xd_i. An approximation of the same floor (the normal
  // force's radial factor and the radial row are left out), which a W-method
  // allows.
  void add_w_slope_floor(const Core& k, const Cache& c, const T& r1e, const T& r2, const T& fl,
                         typename Cfg::Jacobian& J) const {
    const int v_col[2] = {L::kV1, L::kV2};
    const T load[2] = {k.load1, k.load2};
    const T vt[2] = {c.v_t1, c.v_t2};
    for (int i = 0; i < 2; ++i) {
      if (!(abs(vt[i]) < k.floor_speed)) continue;
      const T slope = friction_characteristic_slope(k.friction, vt[i]);
      if (!(slope < k.slope_floor)) continue;
      // Extra dF_i/dv_t (negative: friction opposes slip).
      const T dg = -Cfg::per_tau(k.slope_floor - slope) * normal_force(fl, load[i]);
      // d v_t,i / dx: -r1e in w1, r2 in w2 (no column for a held pulley),
      // 1 in xd_i; the columns in ascending order, each only where nonzero.
      auto add = [&](int col, const T& dv) {
        if (dv == T(0)) return;
        const T dF = dg * dv;
        if (!k.hold1) J(L::kW1, col) -= r1e * dF * k.inv_J1;
        J(v_col[i], col) += dF * k.inv_m;
      };
      if (!k.hold1) add(L::kW1, -r1e);
      if (!k.hold2) add(L::kW2, r2);
      add(v_col[i], T(1));
    }
  }

 private:
  // One lump's forces: tangential slip vt, radial slip along the flank gr,
  // N0 = F_lumps load_i, tb = tan(beta_i).
  template <class S>
  void lump_contact(const Core& k, const S& vt, const S& gr, const S& N0, const S& tb, S& F, S& Fr) const {
    const S s2 = vt * vt + gr * gr;
    // phi(|v|)/|v|; its limit phi'(0) at |v| = 0, where sqrt has no derivative.
    S q(q0_);
    if (s2 > S(T(1e-24))) {
      const S speed = sqrt(s2);
      q = friction_characteristic(k.friction, speed) / speed;
    }
    S Nn;
    contact_forces(q, vt, gr, N0, tb, Nn, F, Fr);
  }

  // Seed Eq. 7 solved for N: N (1 + tan(beta) q gr) = N0, F = -q vt N,
  // Fr = -q gr N. 1 + tan(beta) q gr >= 1 - mu_max tan(beta) > 0 (validate_scene).
  template <class S>
  static void contact_forces(const S& q, const S& vt, const S& gr, const S& N0, const S& tb, S& Nn, S& F, S& Fr) {
    Nn = N0 / (S(T(1)) + tb * q * gr);
    F = -q * vt * Nn;
    Fr = -q * gr * Nn;
  }

  LumpPartials lump_contact_partials(const Core& k, const T& vt, const T& gr, const T& N0, const T& tb) const {
    const T s2 = vt * vt + gr * gr;
    T q(q0_), dq_vt(0), dq_gr(0);
    if (s2 > T(1e-24)) {
      const T speed = sqrt(s2);
      const FrictionEval<T> e = friction_characteristic_and_slope(k.friction, speed);
      q = e.phi / speed;
      // dq/ds = (phi'(s) - q) / s and ds/dv = v / s.
      const T dq_s = (e.slope - q) / speed;
      dq_vt = dq_s * (vt / speed);
      dq_gr = dq_s * (gr / speed);
    }
    LumpPartials r;
    T Nn;
    contact_forces(q, vt, gr, N0, tb, Nn, r.F, r.Fr);
    const T inv_d = T(1) / (T(1) + tb * q * gr);
    // N = N0 / D with D = 1 + tb q gr.
    const T dN_vt = -Nn * tb * gr * dq_vt * inv_d;
    const T dN_gr = -Nn * tb * (q + gr * dq_gr) * inv_d;
    r.dF[0] = -(dq_vt * vt * Nn + q * Nn + q * vt * dN_vt);
    r.dF[1] = -(dq_gr * vt * Nn + q * vt * dN_gr);
    r.dF[2] = -q * vt * inv_d;
    r.dFr[0] = -(dq_vt * gr * Nn + q * gr * dN_vt);
    r.dFr[1] = -(dq_gr * gr * Nn + q * Nn + q * gr * dN_gr);
    r.dFr[2] = -q * gr * inv_d;
    return r;
  }

  T tan1_, tan2_, q0_;
};

}  // namespace cvt
