// The force elements against mechanics they must obey, by finite differences
// of their own energy functions (docs/mbd.md#joint, docs/mbd.md#contact).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <functional>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/mbd/elements.hpp"
#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/physics/seed.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;
using Link = std::array<double, 6>;  // x, y, theta, vx, vy, omega

namespace {

detail::ChainConst chain_const(double mu0 = 0.25, cvt::FrictionLaw law = cvt::FrictionLaw::case1) {
  detail::ChainConst c;
  c.half_length_m = 0.5 * kL;
  c.k_N_m = 90e3;
  c.p_Ns_m = 2.7e3;
  c.Kb_N_m = 200e3;
  c.friction = cvt::friction_presets::table2_case1<double>();
  c.friction.law = law;
  c.friction.mu0 = mu0;
  return c;
}

detail::JointForces<double> joint(const detail::ChainConst& c, const Link& a, const Link& b) {
  return detail::joint_forces<double>(c, a.data(), std::cos(a[2]), std::sin(a[2]), b.data(), std::cos(b[2]),
                                      std::sin(b[2]));
}

// The driver as the model sets it up: groove unloaded at r1, Eq. 3-4 deformation.
detail::PulleyConst driver() {
  const DriveGeometry g(kR1, kR2, kC);
  detail::PulleyConst pc;
  pc.ox_m = 0;
  pc.oy_m = 0;
  pc.width_at_axis_m = 2.0 * kR1 * std::tan(kBeta0);
  pc.beta0_rad = kBeta0;
  pc.cos_beta0 = std::cos(kBeta0);
  pc.sin_beta0 = std::sin(kBeta0);
  pc.half_amp_rad = 0.5 * cvt::seed::deformation_amplitude_rad(kR1 / kR2);
  const double c = g.entry_angle_rad[0] + cvt::seed::deformation_centre_rad(kR1 / kR2);
  pc.wx = std::cos(c);
  pc.wy = std::sin(c);
  pc.reject_radius_m = 1.01 * kR1;
  return pc;
}

detail::ContactForces<double> contact(const detail::ChainConst& c, const detail::PulleyConst& pc, const Link& q,
                                      double omega, double s = 0.0) {
  return detail::contact_forces<double>(c, pc, q.data(), std::cos(q[2]), std::sin(q[2]), omega, s);
}

// A link whose front pin (the bolt) sits at polar angle psi, radius rho, the
// link along the local tangent turned by tilt, moving with velocity (vx, vy, w).
Link link_with_bolt_at(double rho, double psi, double tilt, double vx, double vy, double w) {
  const double th = psi + 0.5 * kPi + tilt;
  const double bx = rho * std::cos(psi), by = rho * std::sin(psi);
  return {bx - 0.5 * kL * std::cos(th), by - 0.5 * kL * std::sin(th), th, vx, vy, w};
}

double central(const std::function<double(double)>& f, double h) { return (f(h) - f(-h)) / (2 * h); }

}  // namespace

TEST_CASE("joint: forces are -dV/dq - dR/dqdot of its spring energy and damper dissipation function") {
  const auto c = chain_const();
  // Two links on a curve, the joint stretched and moving in all directions.
  const Link a = {0.01, 0.02, 0.3, 1.2, -0.4, 35.0};
  Link b = a;
  b[2] = 0.55;
  b[0] = a[0] + 0.5 * kL * std::cos(a[2]) + 0.004 + 0.5 * kL * std::cos(b[2]);
  b[1] = a[1] + 0.5 * kL * std::sin(a[2]) + 0.003 + 0.5 * kL * std::sin(b[2]);
  b[3] = 1.5;
  b[4] = 0.2;
  b[5] = 31.0;
  const auto f = joint(c, a, b);
  for (int link = 0; link < 2; ++link) {
    for (int k = 0; k < 3; ++k) {
      auto V = [&](double h) {
        Link aa = a, bb = b;
        (link == 0 ? aa : bb)[k] += h;
        return joint(c, aa, bb).potential_J;
      };
      auto R = [&](double h) {  // R = p |d|^2 / 2 = dissipation / 2
        Link aa = a, bb = b;
        (link == 0 ? aa : bb)[3 + k] += h;
        return 0.5 * joint(c, aa, bb).dissipation_W;
      };
      const double expected = -central(V, k == 2 ? 1e-7 : 1e-8) - central(R, 1e-4);
      const double got = link == 0 ? f.fa[k] : f.fb[k];
      CAPTURE(link);
      CAPTURE(k);
      CHECK(got == doctest::Approx(expected).epsilon(1e-6).scale(1.0));
    }
  }
  CHECK(f.dissipation_W > 0);
}

TEST_CASE("joint: the damper ignores rigid motion of the pair (frame invariance)") {
  auto c = chain_const();
  const Link a0 = {0.1, -0.05, 1.0, 0, 0, 0};
  Link b0 = {0, 0, 1.4, 0, 0, 0};
  b0[0] = a0[0] + 0.5 * kL * std::cos(a0[2]) + 0.006 + 0.5 * kL * std::cos(b0[2]);
  b0[1] = a0[1] + 0.5 * kL * std::sin(a0[2]) - 0.002 + 0.5 * kL * std::sin(b0[2]);
  // Rigid motion: turning at 80 rad/s about (0.3, 0.2) plus a translation.
  const double W = 80.0, ox = 0.3, oy = 0.2, Vx = 3.0, Vy = -1.0;
  auto rigid = [&](Link l) {
    l[3] = Vx - W * (l[1] - oy);
    l[4] = Vy + W * (l[0] - ox);
    l[5] = W;
    return l;
  };
  const auto moving = joint(c, rigid(a0), rigid(b0));
  const auto still = joint(c, a0, b0);
  CHECK(moving.dissipation_W < 1e-18);
  for (int k = 0; k < 3; ++k) {
    CHECK(moving.fa[k] == doctest::Approx(still.fa[k]).epsilon(1e-12));
    CHECK(moving.fb[k] == doctest::Approx(still.fb[k]).epsilon(1e-12));
  }
  // The naive damper (difference of absolute pin velocities) would not: the
  // pins' velocities differ by W z x Delta under rigid rotation.
  const double dx = b0[0] - 0.5 * kL * std::cos(b0[2]) - a0[0] - 0.5 * kL * std::cos(a0[2]);
  const double dy = b0[1] - 0.5 * kL * std::sin(b0[2]) - a0[1] - 0.5 * kL * std::sin(a0[2]);
  CHECK(c.p_Ns_m * W * W * (dx * dx + dy * dy) > 1.0);
}

TEST_CASE("joint: internal forces, no net force or moment (momentum and angular momentum)") {
  const auto c = chain_const();
  const Link a = {0.2, 0.1, -0.7, 4.0, 1.0, -20.0};
  const Link b = {0.2 + 0.035, 0.1 - 0.02, -0.2, 3.0, -2.0, 55.0};
  const auto f = joint(c, a, b);
  CHECK(std::fabs(f.fa[0] + f.fb[0]) < 1e-9);
  CHECK(std::fabs(f.fa[1] + f.fb[1]) < 1e-9);
  const double moment = f.fa[2] + f.fb[2] + (a[0] * f.fa[1] - a[1] * f.fa[0]) + (b[0] * f.fb[1] - b[1] * f.fb[0]);
  CHECK(std::fabs(moment) < 1e-9 * (std::fabs(f.fa[0]) + std::fabs(f.fa[1])));
}

TEST_CASE("contact: unilateral (Eq. 5): no force outside the groove, K_b times the compression inside") {
  const auto c = chain_const();
  auto pc = driver();
  pc.half_amp_rad = 0;  // plain groove: compression 2 (r1 - rho) tan(beta0)
  const Link out = link_with_bolt_at(kR1 + 1e-4, 2.0, 0, 0, 0, 0);
  CHECK_FALSE(contact(c, pc, out, 0.0).active);
  const Link in = link_with_bolt_at(kR1 - 1e-3, 2.0, 0, 0, 0, 0);
  const auto f = contact(c, pc, in, 0.0);
  REQUIRE(f.active);
  CHECK(f.bolt_force_N == doctest::Approx(200e3 * 2.0 * 1e-3 * std::tan(kBeta0)).epsilon(1e-9));
  // Wedge: the in-plane push is 2 F_b tan(beta0), radially outwards.
  CHECK(std::hypot(f.f[0], f.f[1]) == doctest::Approx(2.0 * f.bolt_force_N * std::tan(kBeta0)).epsilon(1e-9));
  // A movable sheave opened by more than the compression releases the bolt.
  CHECK_FALSE(contact(c, pc, in, 0.0, 2.1e-3 * std::tan(kBeta0)).active);
}

TEST_CASE("contact without friction: the force is -grad of the bolt energy, deformed groove included") {
  const auto c = chain_const(0.0, cvt::FrictionLaw::constant);
  const auto pc = driver();
  const Link q = link_with_bolt_at(kR1 - 2e-3, 1.3, 0.1, 0, 0, 0);
  const auto f = contact(c, pc, q, 0.0);
  REQUIRE(f.active);
  for (int k = 0; k < 3; ++k) {
    auto V = [&](double h) {
      Link qq = q;
      qq[k] += h;
      return contact(c, pc, qq, 0.0).potential_J;
    };
    CAPTURE(k);
    CHECK(f.f[k] == doctest::Approx(-central(V, 1e-8)).epsilon(1e-6).scale(1e-6));
  }
  CHECK(f.pulley_moment_Nm == 0.0);
  CHECK(f.dissipation_W == 0.0);
}

TEST_CASE("contact with friction: Eq. 7 normal force, and the power balance of link, pulley and bolt spring") {
  const auto c = chain_const();  // seed case 1 law
  const auto pc = driver();
  // Bolt sliding outwards and backwards against a sheave turning at 40 rad/s.
  const Link q = link_with_bolt_at(kR1 - 1.5e-3, 2.4, -0.05, 0.3, -1.1, 25.0);
  const double omega = 40.0;
  const auto f = contact(c, pc, q, omega);
  REQUIRE(f.active);
  // Slip of the bolt against the sheave, and the slip angle gamma.
  const double h = 0.5 * kL;
  const double bx = q[0] + h * std::cos(q[2]), by = q[1] + h * std::sin(q[2]);
  const double rho = std::hypot(bx, by), ex = bx / rho, ey = by / rho;
  const double gx = q[3] - h * std::sin(q[2]) * q[5] + omega * by;
  const double gy = q[4] + h * std::cos(q[2]) * q[5] - omega * bx;
  const double gr = gx * ex + gy * ey, gt = -gx * ey + gy * ex, g = std::hypot(gr, gt);
  CHECK(gt == doctest::Approx(f.slip_t_m_s).epsilon(1e-12));
  // Eq. 3: local flank angle at this wrap angle.
  const DriveGeometry geo(kR1, kR2, kC);
  const double beta =
      cvt::seed::flank_angle_rad(kBeta0, cvt::seed::deformation_amplitude_rad(kR1 / kR2),
                                 cvt::seed::deformation_centre_rad(kR1 / kR2), std::atan2(by, bx) - geo.entry_angle_rad[0]);
  // Eq. 6 and the seed's smoothing, from the core's law directly.
  const double mu = cvt::friction_coefficient(c.friction, g), sgn = cvt::friction_sign(c.friction, g);
  const double N = f.normal_N;
  // Eq. 7: N = F_r tan(beta) + F_b / cos(beta), F_r = -mu N sgn sin(gamma), sin(gamma) = g_r/|g|.
  const double Fr = -mu * sgn * N * gr / g;
  CHECK(N == doctest::Approx(Fr * std::tan(beta) + f.bolt_force_N / std::cos(beta)).epsilon(1e-12));
  // Power: what the contact does on the link and the pulley equals minus the
  // rate of the bolt energy minus the friction loss (>= 0).
  const double power = f.f[0] * q[3] + f.f[1] * q[4] + f.f[2] * q[5] + f.pulley_moment_Nm * omega;
  auto V = [&](double s) {
    Link qq = q;
    for (int k = 0; k < 3; ++k) qq[k] += s * q[3 + k];
    return contact(c, pc, qq, omega).potential_J;
  };
  const double dVdt = central(V, 1e-7);
  CHECK(f.dissipation_W > 0);
  CHECK(power == doctest::Approx(-dVdt - f.dissipation_W).epsilon(1e-6));
  // The loss is friction times slip over both flanks, the meridian slip g_r/cos(beta).
  CHECK(f.dissipation_W ==
        doctest::Approx(2.0 * mu * sgn * N * (gr * gr / std::cos(beta) + gt * gt) / g).epsilon(1e-10));
}
