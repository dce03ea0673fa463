// Runs that go bad stop with the time and the quantity (docs/mbd.md#failures).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "run_helpers.hpp"

using namespace cvt::mbd;

namespace {

RunFailure failure_of(const MbdParams& p, const RunOptions& o) {
  try {
    simulate(p, o, {});
  } catch (const RunFailure& e) {
    return e;
  }
  FAIL("the run did not fail");
  return RunFailure(0, "");
}

}  // namespace

TEST_CASE("an energy ledger that does not close stops the run, naming the time and the residual") {
  RunOptions o;
  o.t_end_s = 0.2;
  o.ledger_tol = 1e-13;
  const RunFailure f = failure_of(seed_case(1), o);
  CHECK(f.t_s > 0);
  CHECK(f.t_s <= 0.2);
  CHECK(f.quantity.find("energy ledger residual") != std::string::npos);
  CHECK(std::string(f.what()).find("at t = ") == 0);
}

TEST_CASE("the step cap stops a run that needs more work than allowed") {
  RunOptions o;
  o.t_end_s = 0.2;
  o.max_steps = 50;
  const RunFailure f = failure_of(seed_case(1), o);
  CHECK(f.quantity.find("step cap of 50 steps") != std::string::npos);
  o.method = Method::rk4;
  o.max_steps = 1000;  // 0.2 s at 1e-6 s is 200000 steps: refused before any work
  CHECK_THROWS_AS(simulate(seed_case(1), o, {}), std::invalid_argument);
}

TEST_CASE("RK4 beyond its stability limit blows up and is stopped at the first bad sample") {
  RunOptions o;
  o.method = Method::rk4;
  o.dt_s = 2e-5;  // the stiffest modes (about -6e5 1/s) need dt < 4.6e-6 s
  o.t_end_s = 0.05;
  const RunFailure f = failure_of(seed_case(1), o);
  CHECK(f.t_s > 0);
  CHECK(f.t_s < 0.05);
  CHECK(!f.quantity.empty());
}

TEST_CASE("bad states are named: non-finite, a joint torn apart, a link off the drive, runaway speed") {
  const ChainModel m(seed_case(1));
  const std::vector<double> y0 = m.initial_state();
  CHECK(m.state_problem(y0.data()).empty());
  std::vector<double> y = y0;
  y[static_cast<std::size_t>(ChainModel::link_state(7, 4))] = std::numeric_limits<double>::quiet_NaN();
  CHECK(m.state_problem(y.data()) == "state of link 7 is not finite");
  y = y0;
  y[static_cast<std::size_t>(ChainModel::link_state(12, 0))] += 0.1;  // 10 cm: joints 11-12 and 12-13 torn
  CHECK(m.state_problem(y.data()).find("joint 11-12 stretched") == 0);
  y = y0;
  y[static_cast<std::size_t>(ChainModel::link_state(3, 0))] = 0.0;  // link 3's bolt near the driver's axis
  y[static_cast<std::size_t>(ChainModel::link_state(3, 1))] = 0.0;
  CHECK(m.state_problem(y.data()).find("link 3 sank to the hub of the driver pulley") != std::string::npos);
  y = y0;
  y[static_cast<std::size_t>(m.pulley_speed(1))] = 2e4;
  CHECK(m.state_problem(y.data()).find("driven pulley speed") == 0);
  std::vector<double> dydt(y0.size());
  y = y0;
  y[static_cast<std::size_t>(ChainModel::link_state(3, 2))] = std::numeric_limits<double>::infinity();
  CHECK_FALSE(m.rhs(0.0, y.data(), dydt.data()));
  CHECK(m.fault().quantity.find("link") != std::string::npos);
}

TEST_CASE("parameters out of range are refused") {
  MbdParams p = seed_case(1);
  p.links = 2;
  CHECK_THROWS_AS(ChainModel{p}, std::invalid_argument);
  p = seed_case(1);
  p.sheaves = SheaveMode::clamped;  // without a clamping force
  CHECK_THROWS_AS(ChainModel{p}, std::invalid_argument);
  CHECK_THROWS_AS(seed_case(3), std::invalid_argument);
}
