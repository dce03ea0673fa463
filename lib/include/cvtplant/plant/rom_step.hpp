#pragma once
// The linearly implicit methods (ROS2, linearly implicit Euler) of
// integrate/rosenbrock.hpp for the reduced-order plant, with the solve of
// W = I - a J done by block elimination instead of a dense LU
// (docs/rom.md#structured-solve): the same steps with another W solver; only
// the order of the arithmetic of the linear solve differs, so results agree
// with the dense LU to rounding.
// A dense 9x9 LU is most of a frame on a Cortex-M4F; the elimination leaves
// a 4x4 LU (the two pulley speeds and the two lump velocities), written out,
// and with wedging a 6x6 one instead of the dense 11x11.
//
// Structure used (docs/rom.md#structured-solve), for a = gamma h:
//   kinematic rows p (x1, x2, psi; with wedging also delta, rho): J(p, .)
//     has one entry, J(p, c(p)), with c(x_i) = xd_i, c(psi) = w1,
//     c(delta) = deltadot, c(rho) = rhodot, so k_p = f_p + a J(p, c(p)) k_c(p);
//   axial rows (F_h, delta, deltadot) without wedging: depend on the axial
//     states only, a 3x3 block solved first by two scalar divisions;
//     with wedging only the actuator row F_h stands alone (the bolt force
//     depends on rho, and the contact on delta);
//   the core rows (w1, w2, xd1, xd2; with wedging also deltadot, rhodot)
//     then form a dense 4x4 (6x6) system;
//   with chordal action and the tension feature the phase row psi' =
//     (2 alpha / L) v_c kL / (kL + T_s) has entries in w2, x_i, xd_i,
//     delta and with wedging rho, rho' (docs/rom.md#link-ripple): with the
//     kinematic k_p substituted it reads
//     k_psi = f_psi + sum_p a J(psi, p) f_p [+ a J(psi, delta) k_delta]
//     + sum_c g_c k_c over the core columns, substituted into the core rows
//     like a kinematic row.
#include <cstdint>
#include <type_traits>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/integrate/rosenbrock.hpp"
#include "cvtplant/plant/cvt_rom.hpp"

namespace cvt {

template <class T, std::uint32_t F>
class RomWSolver {
  using L = RomLayout<F>;
  using Vec = Eigen::Matrix<T, L::kStates, 1>;
  using Jac = Eigen::Matrix<T, L::kStates, L::kStates>;
  static constexpr bool kWedge = L::kWedge;
  // Core states, solved as one dense system: the pulley speeds and lump
  // velocities, and with wedging the bolt and radial velocities.
  static constexpr int kM = kWedge ? 6 : 4;
  static constexpr int kCore[6] = {L::kW1, L::kW2, L::kV1, L::kV2, kWedge ? L::kDeltaDot : 0, kWedge ? L::kRhoDot : 0};
  // Kinematic states (x1, x2, [delta, rho with wedging], [psi]) and the core
  // column (index into kCore) each integrates.
  // The phase row with the tension feature is not kinematic (see above).
  static constexpr bool kPhaseRow = L::kPolygon && L::kTension;
  static constexpr int kNumKin = 2 + (kWedge ? 2 : 0) + (L::kPolygon && !kPhaseRow ? 1 : 0);
  static constexpr int kKin[5] = {L::kX1, L::kX2, kWedge ? L::kDelta : L::kPsi, kWedge ? L::kRho : 0, L::kPsi};
  static constexpr int kKinCore[5] = {2, 3, kWedge ? 4 : 0, 5, 0};

 public:
  // W = I - a J for the Jacobian J at the step's start. Reads only the
  // entries the structure above names: the core rows, the kinematic rows'
  // entries and the axial block (CvtRom::jacobian_entries writes those).
  void factor(const Jac& J, const T& a_ref) {
    // By value: a reference could alias the stores below, and be read again after each.
    const T a = a_ref;
    #pragma GCC unroll 8
    for (int p = 0; p < kNumKin; ++p) kin_[p] = a * J(kKin[p], kCore[kKinCore[p]]);
    if constexpr (kPhaseRow) {
      // k_psi's coefficients: the core columns, and the kinematic ones
      // through k_p = f_p + kin_p k_c(p).
      #pragma GCC unroll 8
      for (int p = 0; p < kNumKin; ++p) ph_.x[p] = a * J(L::kPsi, kKin[p]);
      #pragma GCC unroll 8
      for (int c = 0; c < kM; ++c) ph_.c[c] = a * J(L::kPsi, kCore[c]);
      #pragma GCC unroll 8
      for (int p = 0; p < kNumKin; ++p) ph_.c[kKinCore[p]] += ph_.x[p] * kin_[p];
      // Without wedging delta is in the axial block, solved first.
      if constexpr (L::kAxial && !kWedge) ph_.d = a * J(L::kPsi, L::kDelta);
    }
    #pragma GCC unroll 8
    for (int r = 0; r < kM; ++r) {
      #pragma GCC unroll 8
      for (int c = 0; c < kM; ++c) lu_[r][c] = (r == c ? T(1) : T(0)) - a * J(kCore[r], kCore[c]);
      // Substituting k_p = f_p + kin_p k_c(p) into the core rows.
      #pragma GCC unroll 8
      for (int p = 0; p < kNumKin; ++p) {
        wcp_[r][p] = -a * J(kCore[r], kKin[p]);
        lu_[r][kKinCore[p]] += wcp_[r][p] * kin_[p];
      }
      if constexpr (kPhaseRow) {
        ph_.w[r] = -a * J(kCore[r], L::kPsi);
        #pragma GCC unroll 8
        for (int c = 0; c < kM; ++c) lu_[r][c] += ph_.w[r] * ph_.c[c];
      }
      if constexpr (kWedge) wca_[r] = -a * J(kCore[r], L::kFh);  // the bolt row's actuator force
      else if constexpr (L::kAxial) wca_[r] = -a * J(kCore[r], L::kDelta);  // F_ax = K_ax delta
    }
    factor_lu();
    if constexpr (kWedge) {
      w_hh_ = T(1) - a * J(L::kFh, L::kFh);
    } else if constexpr (L::kAxial) {
      // W_AA = [[w_hh 0 0] [0 1 -a J_d,dd] [w_dh w_dd w_dd,dd]]
      w_hh_ = T(1) - a * J(L::kFh, L::kFh);
      w_d_dd_ = -a * J(L::kDelta, L::kDeltaDot);
      w_dh_ = -a * J(L::kDeltaDot, L::kFh);
      w_dd_ = -a * J(L::kDeltaDot, L::kDelta);
      w_dd_piv_ = (T(1) - a * J(L::kDeltaDot, L::kDeltaDot)) - w_dd_ * w_d_dd_;
    }
  }

  // k = W^-1 f.
  Vec solve(const Vec& f) const {
    Vec k;
    // The axial value the core rows see: k_delta without wedging (its block
    // is solved first), k_Fh with wedging (the actuator row stands alone).
    T k_axial(0);
    if constexpr (kWedge) {
      k(L::kFh) = f(L::kFh) / w_hh_;
      k_axial = k(L::kFh);
    } else if constexpr (L::kAxial) {
      k(L::kFh) = f(L::kFh) / w_hh_;
      k(L::kDeltaDot) = (f(L::kDeltaDot) - w_dh_ * k(L::kFh) - w_dd_ * f(L::kDelta)) / w_dd_piv_;
      k_axial = f(L::kDelta) - w_d_dd_ * k(L::kDeltaDot);
      k(L::kDelta) = k_axial;
    }
    // The phase row's part that does not depend on the core unknowns.
    [[maybe_unused]] T f_psi(0);
    if constexpr (kPhaseRow) {
      f_psi = f(L::kPsi);
      #pragma GCC unroll 8
      for (int p = 0; p < kNumKin; ++p) f_psi += ph_.x[p] * f(kKin[p]);
      if constexpr (L::kAxial && !kWedge) f_psi += ph_.d * k_axial;
    }
    T rhs[kM];
    #pragma GCC unroll 8
    for (int r = 0; r < kM; ++r) {
      T v = f(kCore[r]);
      #pragma GCC unroll 8
      for (int p = 0; p < kNumKin; ++p) v -= wcp_[r][p] * f(kKin[p]);
      if constexpr (L::kAxial) v -= wca_[r] * k_axial;
      if constexpr (kPhaseRow) v -= ph_.w[r] * f_psi;
      rhs[r] = v;
    }
    T kc[kM];
    solve_lu(rhs, kc);
    #pragma GCC unroll 8
    for (int r = 0; r < kM; ++r) k(kCore[r]) = kc[r];
    #pragma GCC unroll 8
    for (int p = 0; p < kNumKin; ++p) k(kKin[p]) = f(kKin[p]) + kin_[p] * kc[kKinCore[p]];
    if constexpr (kPhaseRow) {
      T v = f_psi;
      #pragma GCC unroll 8
      for (int c = 0; c < kM; ++c) v += ph_.c[c] * kc[c];
      k(L::kPsi) = v;
    }
    return k;
  }

 private:
  // LU with partial pivoting of the core matrix, in place (Doolittle, unit
  // lower triangle). Written out because Eigen's general PartialPivLU costs
  // 1,400 instructions per 4x4 on the M4F.
  void factor_lu() {
    #pragma GCC unroll 8
    for (int i = 0; i < kM; ++i) perm_[i] = i;
    #pragma GCC unroll 8
    for (int k = 0; k < kM; ++k) {
      int piv = k;
      T big = abs(lu_[k][k]);
      #pragma GCC unroll 8
      for (int i = k + 1; i < kM; ++i) {
        const T v = abs(lu_[i][k]);
        if (v > big) {
          big = v;
          piv = i;
        }
      }
      if (piv != k) {
        #pragma GCC unroll 8
        for (int j = 0; j < kM; ++j) {
          const T t = lu_[k][j];
          lu_[k][j] = lu_[piv][j];
          lu_[piv][j] = t;
        }
        const int t = perm_[k];
        perm_[k] = perm_[piv];
        perm_[piv] = t;
      }
      // A zero pivot (singular W) would give inf/NaN (float) or a saturated
      // value (fixed); the simulator's watchdog reports either.
      #pragma GCC unroll 8
      for (int i = k + 1; i < kM; ++i) {
        const T l = lu_[i][k] / lu_[k][k];
        lu_[i][k] = l;
        #pragma GCC unroll 8
        for (int j = k + 1; j < kM; ++j) lu_[i][j] -= l * lu_[k][j];
      }
    }
  }

  void solve_lu(const T (&b)[kM], T (&x)[kM]) const {
    T y[kM];
    #pragma GCC unroll 8
    for (int i = 0; i < kM; ++i) {
      T v = b[perm_[i]];
      #pragma GCC unroll 8
      for (int j = 0; j < i; ++j) v -= lu_[i][j] * y[j];
      y[i] = v;
    }
    #pragma GCC unroll 8
    for (int i = kM - 1; i >= 0; --i) {
      T v = y[i];
      #pragma GCC unroll 8
      for (int j = i + 1; j < kM; ++j) v -= lu_[i][j] * x[j];
      x[i] = v / lu_[i][i];
    }
  }

  // Written by factor() before solve() reads them; not initialised, since a
  // solver is made for every step and zeroing it cost 60 instructions there.
  T kin_[5];
  T wcp_[kM][5];
  T wca_[kM];
  T w_hh_, w_d_dd_, w_dh_, w_dd_, w_dd_piv_;
  // The phase row with the tension feature (kPhaseRow): its coefficients of
  // f_x_i, k_delta and the core unknowns, and the core rows' W(r, psi).
  struct PhaseRow {
    T x[5], d, c[kM], w[kM];
  };
  struct NoPhaseRow {};
  std::conditional_t<kPhaseRow, PhaseRow, NoPhaseRow> ph_;
  T lu_[kM][kM];
  int perm_[kM];
};

// A W solver already factored for this step's a = gamma h: factor() keeps
// it, solve() is the kept solver's. The further substeps of a frame refined
// at the end stop take the W of its first substep (docs/rom.md#end-stop):
// ROS2 is a W-method and keeps its order with any W, so they need neither a
// Jacobian nor a factorisation.
template <class WSolver>
class FactoredW {
 public:
  explicit FactoredW(const WSolver& w) : w_(w) {}
  template <class Jac, class T>
  void factor(const Jac&, const T&) {}
  template <class Vec>
  Vec solve(const Vec& f) const {
    return w_.solve(f);
  }

 private:
  const WSolver& w_;
};

// What a step of rom_step_implicit_with evaluates afresh (docs/rom.md#end-stop):
// the Jacobian at x and W, or nothing (the W of a step of the same h kept).
enum class RomWUse : std::uint8_t { fresh, kept_w };

// One ROS2 or linearly implicit Euler step from a state whose contact is
// already evaluated (c = sys.contact(x)), with the caller's Jacobian and W
// solver, which keep what `Use` says they hold and hold this step's after it.
// `w_slope_floor` builds W with the friction slope floor of
// docs/rom.md#slope-floor; without it W = I - gamma h J exactly. `carry`
// keeps the fixed-point rounding remainders from step to step
// (integrate/increment.hpp); floating point ignores it.
template <class Plant>
using RomWSolverOf = RomWSolver<typename Plant::Scalar, Plant::kFeatures>;

template <RomWUse Use, class Plant>
void rom_step_implicit_with(Method m, const Plant& sys, typename Plant::State& x, const typename Plant::Scalar& h,
                            const typename Plant::Contact& c, bool w_slope_floor, typename Plant::Jacobian& J,
                            RomWSolverOf<Plant>& w, CarryOf<Plant>* carry = nullptr) {
  // Only the entries the W solver reads are written.
  if constexpr (Use == RomWUse::fresh) sys.jacobian_entries(x, c, J, w_slope_floor);
  typename Plant::State f;
  sys.derivative(x, c, f);
  if constexpr (Use == RomWUse::kept_w) {
    FactoredW<RomWSolverOf<Plant>> kept(w);
    if (m == Method::linear_implicit_euler) step_linear_implicit_euler_with(sys, x, h, J, kept, f, carry);
    else step_ros2_with(sys, x, h, J, kept, f, carry);
  } else {
    if (m == Method::linear_implicit_euler) step_linear_implicit_euler_with(sys, x, h, J, w, f, carry);
    else step_ros2_with(sys, x, h, J, w, f, carry);
  }
}

// The same with a Jacobian and W of its own: the simulator's step
// (docs/rom.md#cost), which shares the contact with the energy ledger.
template <class Plant>
void rom_step_implicit(Method m, const Plant& sys, typename Plant::State& x, const typename Plant::Scalar& h,
                       const typename Plant::Contact& c, bool w_slope_floor, CarryOf<Plant>* carry = nullptr) {
  typename Plant::Jacobian J;
  RomWSolverOf<Plant> w;
  rom_step_implicit_with<RomWUse::fresh>(m, sys, x, h, c, w_slope_floor, J, w, carry);
}

// One step of `m` on the plant: ROS2 and linearly implicit Euler through
// RomWSolver, the explicit methods through the generic integrators;
// `w_slope_floor` as for rom_step_implicit (for the implicit methods). No
// plant instantiates the dense Rosenbrock code: with every plant type
// compiled for the host tools, its Eigen LUs would be most of their compile
// time.
template <class Plant>
void rom_step(Method m, const Plant& sys, typename Plant::State& x, const typename Plant::Scalar& h,
              bool w_slope_floor = false, CarryOf<Plant>* carry = nullptr) {
  switch (m) {
    case Method::explicit_euler: step_explicit_euler(sys, x, h, carry); return;
    case Method::semi_implicit_euler: step_semi_implicit_euler(sys, x, h); return;
    case Method::heun: step_heun(sys, x, h, carry); return;
    case Method::rk4: step_rk4(sys, x, h, carry); return;
    case Method::linear_implicit_euler:
    case Method::ros2: break;
  }
  rom_step_implicit(m, sys, x, h, sys.contact(x), w_slope_floor, carry);
}

}  // namespace cvt
