// The chain's block elimination of the BDF's Newton systems
// (docs/mbd.md#linear-algebra): against the system it solves, I - gamma J
// multiplied out from the model's sparse Jacobian, and a run against the same
// run with KLU.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "chain_solver.hpp"
#include "cvtplant/mbd/model.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;
using cvt::mbd::testing::state_at;

namespace {

// For each gamma, solves (I - gamma J) x = b for a b with entries of every
// size the states have, and checks the residual against the size of the
// terms that make it up (a backward-stable solve leaves a few ulps of them).
void check_solves(const MbdParams& p, double t, ChainModel::Phase phase = ChainModel::Phase::run) {
  const std::vector<double> y = state_at(p, t);
  ChainModel m(p);
  m.set_phase(phase);
  const int n = m.size();
  REQUIRE(static_cast<int>(y.size()) == n);
  const SparsePattern& pat = m.pattern();
  std::vector<double> J(static_cast<std::size_t>(pat.nnz()));
  m.jacobian(t, y.data(), J.data());
  detail::ChainSolver solver(m);
  solver.set_jacobian(J.data());
  std::uint64_t lcg = 12345;
  auto unit = [&lcg] {
    lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(lcg >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  };
  // The BDF's gamma is h times a coefficient near 1: steps of 1e-7 to 1e-3 s.
  for (const double gamma : {1e-7, 1e-5, 1e-4, 1e-3}) {
    CAPTURE(gamma);
    REQUIRE(solver.factor(gamma));
    std::vector<double> b(static_cast<std::size_t>(n)), x(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) b[i] = unit() * m.tolerance_scale(i);
    solver.solve(b.data(), x.data());
    // r = x - gamma J x - b, and the size of its terms, row by row.
    std::vector<double> r(x), size(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      r[i] -= b[i];
      size[i] = std::fabs(x[i]) + std::fabs(b[i]);
    }
    for (int c = 0; c < n; ++c)
      for (auto k = pat.col_start[c]; k < pat.col_start[c + 1]; ++k) {
        const double term = gamma * J[k] * x[c];
        r[pat.row[k]] -= term;
        size[pat.row[k]] += std::fabs(term);
      }
    double worst = 0;
    int worst_row = -1;
    for (int i = 0; i < n; ++i) {
      REQUIRE(std::isfinite(x[i]));
      const double e = std::fabs(r[i]) / size[i];
      if (e > worst) worst = e, worst_row = i;
    }
    CAPTURE(worst_row);
    // Elimination along 44-53 links: growth of a few hundred ulps at most.
    CHECK(worst <= 1e-12);
  }
}

// The same run with each solver: the trajectories differ by rounding in the
// Newton corrections, which the error control keeps at the tolerance's size.
void check_runs_agree(const MbdParams& p, double t_end, double bound_rel) {
  RunOptions o;
  o.t_end_s = t_end;
  o.sample_s = 1e-3;
  o.linear_solver = LinearSolver::chain;
  const auto chain = cvt::mbd::testing::record(p, o);
  o.linear_solver = LinearSolver::klu;
  const auto klu = cvt::mbd::testing::record(p, o);
  REQUIRE(chain.samples.size() == klu.samples.size());
  REQUIRE(chain.samples.size() >= 10);
  double w_max = 0, f_max = 0;
  for (const Sample& s : klu.samples)
    for (int j = 0; j < 2; ++j) {
      w_max = std::max(w_max, std::fabs(s.omega_rad_s[j]));
      f_max = std::max(f_max, std::fabs(s.F_ax_N[j]));
    }
  double dw = 0, df = 0;
  for (std::size_t k = 0; k < klu.samples.size(); ++k)
    for (int j = 0; j < 2; ++j) {
      dw = std::max(dw, std::fabs(chain.samples[k].omega_rad_s[j] - klu.samples[k].omega_rad_s[j]));
      df = std::max(df, std::fabs(chain.samples[k].F_ax_N[j] - klu.samples[k].F_ax_N[j]));
    }
  MESSAGE("speed difference ", dw / w_max, ", axial force difference ", df / f_max, " (relative to the largest)");
  CHECK(dw <= bound_rel * w_max);
  CHECK(df <= bound_rel * f_max);
  // Both closed the ledger and did about the same work.
  CHECK(chain.stats.ledger_residual_max_rel < 1e-6);
  CHECK(klu.stats.ledger_residual_max_rel < 1e-6);
  CHECK(std::fabs(static_cast<double>(chain.stats.steps - klu.stats.steps)) <= 0.1 * static_cast<double>(klu.stats.steps));
}

}  // namespace

TEST_CASE("chain solver: fixed sheaves, seed case 1, links entering, leaving and slipping") {
  check_solves(seed_case(1), 0.05);
}

TEST_CASE("chain solver: clamped sheaves, seed case 2, and the hold of a start at speed") {
  MbdParams p = cvt::mbd::testing::clamped_case2();
  check_solves(p, 0.05);
  p.start.active = true;
  p.start.omega1_rad_s = 20.0;
  p.start.omega2_rad_s = 20.0 * 0.0762 / 0.1143;
  p.start.hold_s = 0.1;
  check_solves(p, 0.02, ChainModel::Phase::hold);
}

TEST_CASE("chain solver: the same run as with KLU, to the tolerance's size") {
  check_runs_agree(seed_case(1), 0.1, 1e-5);
  MbdParams p = cvt::mbd::testing::clamped_case2();
  check_runs_agree(p, 0.1, 1e-5);
}
