// The sparse Jacobian (dual-number element derivatives) against central
// differences of the right-hand side, in a running configuration
// (docs/mbd.md#bdf-and-the-jacobian).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cvtplant/mbd/model.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;
using cvt::mbd::testing::state_at;

namespace {

void check_jacobian(const MbdParams& p, double t, ChainModel::Phase phase = ChainModel::Phase::run) {
  std::vector<double> y = state_at(p, t);
  ChainModel m(p);
  m.set_phase(phase);
  const int n = m.size();
  REQUIRE(static_cast<int>(y.size()) == n);
  const SparsePattern& pat = m.pattern();
  std::vector<double> vals(static_cast<std::size_t>(pat.nnz()));
  m.jacobian(t, y.data(), vals.data());
  std::vector<double> fp(static_cast<std::size_t>(n)), fm(static_cast<std::size_t>(n));
  int columns_checked = 0;
  for (int j = 0; j < n; ++j) {
    const double h = 1e-7 * (m.tolerance_relative(j) * std::fabs(y[j]) + m.tolerance_scale(j));
    std::vector<double> yp = y, ym = y;
    yp[j] += h;
    ym[j] -= h;
    REQUIRE(m.rhs(t, yp.data(), fp.data()));
    REQUIRE(m.rhs(t, ym.data(), fm.data()));
    std::vector<double> fd(static_cast<std::size_t>(n)), ad(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) fd[i] = (fp[i] - fm[i]) / (2 * h);
    for (auto k = pat.col_start[j]; k < pat.col_start[j + 1]; ++k) ad[pat.row[k]] = vals[k];
    double scale = 0, err = 0;
    for (int i = 0; i < n; ++i) {
      scale = std::max(scale, std::fabs(fd[i]));
      err = std::max(err, std::fabs(fd[i] - ad[i]));  // also catches entries missing from the pattern
    }
    CAPTURE(j);
    CHECK(err <= 2e-5 * scale + 1e-9);
    // The pulley speeds' own entries (the load's slope, the drive's power)
    // are small beside a column's contact terms: each on its own scale.
    if (j == m.pulley_speed(0) || j == m.pulley_speed(1))
      for (const int i : {m.pulley_speed(0), m.pulley_speed(1), m.ledger(0), m.ledger(1)}) {
        CAPTURE(i);
        CHECK(std::fabs(fd[i] - ad[i]) <= 1e-5 * std::fabs(fd[i]) + 1e-9);
      }
    ++columns_checked;
  }
  CHECK(columns_checked == n);
}

}  // namespace

TEST_CASE("jacobian: fixed sheaves, seed case 1, links entering, leaving and slipping") {
  check_jacobian(seed_case(1), 0.05);
}

TEST_CASE("jacobian: clamped sheaves, seed case 2 (Stribeck)") {
  check_jacobian(cvt::mbd::testing::clamped_case2(), 0.05);
}

TEST_CASE("jacobian: road load and torque profiles, running and in the hold of a start at speed") {
  // The road load's slope enters the driven pulley's row and the load-work
  // row; in the hold the driver is held and the driven pulley free under
  // the load at t = 0 (docs/mbd.md#start-at-speed).
  MbdParams p = seed_case(1);
  p.sheaves = SheaveMode::clamped;
  p.clamp1_N = TimeProfile::constant(3300.0);
  p.tau_in_Nm.points = {{0.0, 20.0}, {0.1, 40.0}};
  p.tau_load_Nm.points = {{0.0, 5.0}, {0.1, 10.0}};
  p.road.T0_Nm = 10.0;
  p.road.cv_Nms_rad = 0.5;
  p.road.ca_Nms2_rad2 = 0.02;
  p.start.active = true;
  p.start.omega1_rad_s = 20.0;
  p.start.omega2_rad_s = 20.0 * 0.0762 / 0.1143;
  p.start.hold_s = 0.1;
  check_jacobian(p, 0.02);
  check_jacobian(p, 0.02, ChainModel::Phase::hold);
}
