#pragma once
// The BDF's Newton systems (I - gamma J) x = b solved with the chain's
// structure (docs/mbd.md#linear-algebra): a closed chain of links, each
// coupled to its two neighbours, bordered by the pulleys and sheaves, with
// the pulley angles and the ledger integrals that nothing depends on.
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <vector>

#include "cvtplant/mbd/model.hpp"

namespace cvt::mbd::detail {

// The solver on the values of the model's sparse pattern (ChainModel::pattern()).
class ChainSolver {
 public:
  // Throws std::logic_error if the pattern is not the chain's (an entry
  // outside the structure the elimination relies on).
  explicit ChainSolver(const ChainModel& m);

  // The Jacobian J, its values in pattern order (ChainModel::jacobian()),
  // kept for the factorisations until the next one.
  void set_jacobian(const double* values);
  // Factors A = I - gamma J. False if a pivot is zero or not finite (the
  // caller retries with a smaller step).
  bool factor(double gamma);
  // x = A^-1 b for the last factored A (x and b distinct, length n).
  void solve(const double* b, double* x) const;

 private:
  // Where each pattern entry of J goes: an offset into jac_.
  std::vector<std::int64_t> dest_;
  std::vector<double> jac_;
  // Offsets of J's parts in jac_: position rows (their diagonal, their
  // velocity), velocity rows against positions and velocities (9 per link and
  // neighbour, row-major) and against the border, border rows against
  // positions, velocities and the border, angle rows against the border and
  // their diagonal, ledger diagonals and ledger rows (dense, n each).
  std::size_t off_qq_ = 0, off_qv_ = 0, off_vq_ = 0, off_vv_ = 0, off_vb_ = 0, off_bq_ = 0, off_bv_ = 0,
              off_bb_ = 0, off_pb_ = 0, off_pp_ = 0, off_ll_ = 0, off_lrow_ = 0;

  int N_ = 0;   // links
  int n_ = 0;   // states
  int nb_ = 0;  // border unknowns: pulley speeds (and sheave openings and rates)
  int w_ = 0;   // unknowns of the Schur complement: the last link's 3 and the border
  std::vector<int> nbr_;     // nbr_[3 i + s]: link i's neighbour s (0: i-1, 1: i, 2: i+1)
  std::vector<int> border_;  // state index of each border unknown
  int angle_[2] = {0, 0};    // pulley angle states
  int ledger_[5] = {0, 0, 0, 0, 0};

  // Factorisation of A = I - gamma J. Positions are eliminated
  // (q = (b_q - a_qv v) / a_qq); links 0..N-2 form a block-tridiagonal T of
  // 3x3 velocity blocks, the last link and the border the Schur complement
  // S = C - Bt T^-1 R.
  double gamma_ = 0;
  std::vector<double> aqq_, ratio_;  // a_qq and a_qv / a_qq per position row
  std::vector<double> K_;            // reduced blocks, 9 per (link, neighbour), row-major
  std::vector<double> Kb_;           // 3N x nb, row-major: velocity rows against the border
  std::vector<double> Bv_;           // nb x 3N: border rows against velocities (positions eliminated)
  // Thomas: y_i = r_i - M_i y_{i-1}; x_i = Ginv_i y_i - P_i x_{i+1}.
  std::vector<double> M_, Ginv_, P_;
  std::vector<double> X_;   // T^-1 R, 3(N-1) x w column-major
  std::vector<double> Bt_;  // the last link's rows against links 0 and N-2: two 3x3 blocks
  std::vector<double> S_;   // w x w LU (row-major), row interchanges in piv_
  std::vector<int> piv_;
  mutable std::vector<double> tq_, r_, e_;

  void thomas_solve(double* v) const;  // T^-1 in place, 3(N-1) entries
};

// A SUNDIALS direct linear solver around ChainSolver, owning it, and the
// placeholder matrix CVODE's matrix-based interface wants: the linear system
// is formed by chain_linear_system() (CVodeSetLinSysFn) from the model's
// Jacobian, never as a SUNMatrix.
SUNLinearSolver make_chain_linear_solver(const ChainModel& m, SUNContext ctx);
SUNMatrix make_chain_placeholder_matrix(SUNContext ctx);
// CVODE's linear-system hook: a new Jacobian when !jok, then A = I - gamma J
// is factored by the solver's setup. jcur tells CVODE whether J is fresh.
int chain_linear_system(SUNLinearSolver S, const ChainModel& m, double t, const double* y, bool jok, int* jcur,
                        double gamma);

}  // namespace cvt::mbd::detail
