// Geometry of the drive and the seed's sheave deformation (docs/mbd.md#geometry).
#include <doctest/doctest.h>

#include <cmath>

#include "cvtplant/mbd/geometry.hpp"
#include "cvtplant/physics/seed.hpp"
#include "run_helpers.hpp"

using namespace cvt::mbd;
using namespace cvt::mbd::testing;

TEST_CASE("pitch line: two arcs and two tangent strands, length by summing the path") {
  const DriveGeometry g(kR1, kR2, kC);
  CHECK(g.wrap_rad[0] == doctest::Approx(wrap_driver_rad()).epsilon(1e-14));
  CHECK(g.wrap_rad[0] + g.wrap_rad[1] == doctest::Approx(2.0 * kPi).epsilon(1e-14));
  // The closed form 2 C cos(delta) + r1 theta1 + r2 theta2 against the length of
  // the polygon through 200000 points of pitch_point (chords undercut arcs by
  // O(h^2), far below the tolerance).
  const int n = 200000;
  double len = 0;
  Vec2 prev = g.pitch_point(0.0);
  for (int i = 1; i <= n; ++i) {
    const Vec2 p = g.pitch_point(g.pitch_line_m * i / n);
    len += std::hypot(p.x - prev.x, p.y - prev.y);
    prev = p;
  }
  CHECK(len == doctest::Approx(g.pitch_line_m).epsilon(1e-9));
  CHECK(g.pitch_line_m == doctest::Approx(1.6013780).epsilon(1e-7));
  // 53.4 unstretched links: 44 links fill it only with their joints stretched.
  CHECK(g.pitch_line_m / kL == doctest::Approx(53.38).epsilon(1e-3));
}

TEST_CASE("pitch line: the strands touch both pitch circles at right angles to the radius") {
  const DriveGeometry g(kR1, kR2, kC);
  const double arc1 = kR1 * g.wrap_rad[0];
  const double strand = std::sqrt(kC * kC - (kR2 - kR1) * (kR2 - kR1));
  const Vec2 a = g.pitch_point(arc1), b = g.pitch_point(arc1 + strand);  // lower strand ends
  CHECK(std::hypot(a.x, a.y) == doctest::Approx(kR1).epsilon(1e-12));
  CHECK(std::hypot(b.x - kC, b.y) == doctest::Approx(kR2).epsilon(1e-12));
  const double dx = b.x - a.x, dy = b.y - a.y;
  CHECK(std::fabs(dx * a.x + dy * a.y) < 1e-12);
  CHECK(std::fabs(dx * (b.x - kC) + dy * b.y) < 1e-12);
  // The upper strand enters the driver wrap at polar angle pi/2 + delta.
  const Vec2 e = g.pitch_point(0.0);
  CHECK(std::atan2(e.y, e.x) == doctest::Approx(0.5 * kPi + std::asin((kR2 - kR1) / kC)).epsilon(1e-12));
}

TEST_CASE("sheave deformation, seed Eq. 3-4 as printed (the core's formulas the model uses)") {
  // Delta = 0.00045 / (r/r')^0.55, theta_c = pi r/(3 r') + 23 pi/180 with r, r' = 3 in, 4.5 in.
  using namespace cvt::seed;
  CHECK(deformation_amplitude_rad(kR1 / kR2) == doctest::Approx(0.00045 * std::pow(1.5, 0.55)).epsilon(1e-14));
  CHECK(deformation_amplitude_rad(kR1 / kR2) == doctest::Approx(5.624e-4).epsilon(1e-3));
  CHECK(deformation_centre_rad(kR1 / kR2) == doctest::Approx(2.0 * kPi / 9.0 + 23.0 * kPi / 180.0).epsilon(1e-14));
  // beta peaks at zeta = theta_c with beta0 + Delta/2 and is beta0 a quarter turn away.
  const double amp = 5e-4, c = 1.1;
  CHECK(flank_angle_rad(kBeta0, amp, c, c) == doctest::Approx(kBeta0 + 0.5 * amp).epsilon(1e-15));
  CHECK(flank_angle_rad(kBeta0, amp, c, c + 0.5 * kPi) == doctest::Approx(kBeta0).epsilon(1e-12));
}
