// Energy ledger, convergence with tolerance, the two integrators against each
// other, determinism (docs/mbd.md#energy-ledger, docs/mbd.md#tolerances).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

TEST_CASE("energy is conserved with friction and damping off: E(t) - E(0) = W_in - W_load") {
  MbdParams p = seed_case(1);
  p.friction.law = cvt::FrictionLaw::constant;
  p.friction.mu0 = 0.0;
  p.joint_damping_Ns_m = 0.0;
  RunOptions o;
  o.t_end_s = 0.2;
  o.ledger_tol = 1.0;  // measured here, not enforced
  const Recorded r = record(p, o);
  const Sample& e = r.samples.back();
  CHECK(e.D_friction_J == 0.0);
  CHECK(e.D_damping_J == 0.0);
  CHECK(e.W_in_J > 100.0);  // the input did work: 100 N m through the driver's turn
  const double stored = e.E_kin_J + e.E_el_J - r.stats.energy0_J;
  CHECK(std::fabs(stored - (e.W_in_J - e.W_load_J)) <= 1e-6 * std::max(e.W_in_J, r.stats.energy0_J));
  CHECK(r.stats.ledger_residual_max_rel <= 1e-6);
  MESSAGE("conservative run: W_in " << e.W_in_J << " J, W_load " << e.W_load_J << " J, E - E0 " << stored
                                    << " J, max ledger residual " << r.stats.ledger_residual_max_rel);
}

TEST_CASE("energy ledger closes to 1e-6 with friction and damping, both cases, both integrators") {
  for (int c = 1; c <= 2; ++c) {
    for (Method m : {Method::bdf, Method::rk4}) {
      RunOptions o;
      o.method = m;
      o.t_end_s = m == Method::bdf ? 0.3 : 0.01;
      o.ledger_tol = 1.0;
      const Recorded r = record(seed_case(c), o);
      const Sample& e = r.samples.back();
      CAPTURE(c);
      CAPTURE(static_cast<int>(m));
      CHECK(r.stats.ledger_residual_max_rel <= 1e-6);
      MESSAGE("case " << c << (m == Method::bdf ? " BDF" : " RK4") << " " << o.t_end_s
                      << " s: max ledger residual " << r.stats.ledger_residual_max_rel);
      CHECK(e.D_friction_J > 0);
      CHECK(e.D_damping_J > 0);
      // Losses only ever grow.
      for (std::size_t k = 1; k < r.samples.size(); ++k) {
        CHECK(r.samples[k].D_friction_J >= r.samples[k - 1].D_friction_J);
        CHECK(r.samples[k].D_damping_J >= r.samples[k - 1].D_damping_J);
      }
    }
  }
}

TEST_CASE("convergence: halving rtol changes the outputs by less than rtol over the first half second") {
  for (int c = 1; c <= 2; ++c) {
    RunOptions o;
    o.t_end_s = 0.5;
    const double rtol = o.rtol;
    const Recorded a = record(seed_case(c), o);
    o.rtol = 0.5 * rtol;
    const Recorded b = record(seed_case(c), o);
    REQUIRE(a.samples.size() == b.samples.size());
    double fa[2] = {0, 0}, fb[2] = {0, 0};
    for (std::size_t k = 0; k < a.samples.size(); ++k)
      for (int j = 0; j < 2; ++j) {
        fa[j] += a.samples[k].F_ax_N[j];
        fb[j] += b.samples[k].F_ax_N[j];
      }
    CAPTURE(c);
    const Sample &ea = a.samples.back(), &eb = b.samples.back();
    CHECK(rel_diff(ea.omega_rad_s[0], eb.omega_rad_s[0]) < rtol);
    CHECK(rel_diff(ea.omega_rad_s[1], eb.omega_rad_s[1]) < rtol);
    CHECK(rel_diff(fa[0], fb[0]) < rtol);
    CHECK(rel_diff(fa[1], fb[1]) < rtol);
    CHECK(b.stats.steps > a.stats.steps);
    MESSAGE("case " << c << ", rtol " << rtol << " vs " << 0.5 * rtol << ": omega1 " << rel_diff(ea.omega_rad_s[0], eb.omega_rad_s[0])
                    << ", omega2 " << rel_diff(ea.omega_rad_s[1], eb.omega_rad_s[1]) << ", mean F_ax1 "
                    << rel_diff(fa[0], fb[0]) << ", mean F_ax2 " << rel_diff(fa[1], fb[1]));
  }
}

TEST_CASE("BDF and the seed's RK4 (dt 1e-6) agree sample by sample") {
  RunOptions o;
  o.t_end_s = 0.02;
  o.sample_s = 1e-3;
  const Recorded bdf = record(seed_case(2), o);
  o.method = Method::rk4;
  o.dt_s = 1e-6;
  const Recorded rk4 = record(seed_case(2), o);
  REQUIRE(bdf.samples.size() == rk4.samples.size());
  // BDF at its default rtol (5e-7) and RK4 differ by about 1e-8 here; 1e-7
  // leaves a factor of ten.
  double worst[3] = {0, 0, 0};
  for (std::size_t k = 1; k < bdf.samples.size(); ++k) {
    const Sample &a = bdf.samples[k], &b = rk4.samples[k];
    CAPTURE(a.t_s);
    const double d[3] = {std::fabs(a.omega_rad_s[0] - b.omega_rad_s[0]) / (1.0 + std::fabs(b.omega_rad_s[0])),
                         std::fabs(a.omega_rad_s[1] - b.omega_rad_s[1]) / (1.0 + std::fabs(b.omega_rad_s[1])),
                         rel_diff(a.F_ax_N[0], b.F_ax_N[0])};
    CHECK(d[0] < 1e-7);
    CHECK(d[1] < 1e-7);
    CHECK(d[2] < 1e-7);
    for (int i = 0; i < 3; ++i) worst[i] = std::max(worst[i], d[i]);
  }
  MESSAGE("BDF against RK4 dt 1e-6 over 20 ms: omega1 " << worst[0] << ", omega2 " << worst[1] << " (of 1 + |omega|), F_ax1 "
                                                        << worst[2] << " (relative)");
  CHECK(rk4.stats.steps == 20000);
  CHECK(rk4.stats.rhs_evals == 80000);
}

TEST_CASE("determinism: the same run twice gives the same samples bit for bit") {
  RunOptions o;
  o.t_end_s = 0.1;
  const Recorded a = record(seed_case(2), o);
  const Recorded b = record(seed_case(2), o);
  REQUIRE(a.samples.size() == b.samples.size());
  bool same = true;
  for (std::size_t k = 0; k < a.samples.size(); ++k)
    same = same && std::memcmp(&a.samples[k], &b.samples[k], sizeof(Sample)) == 0;
  CHECK(same);
}
