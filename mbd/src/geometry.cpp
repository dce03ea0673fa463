#include "cvtplant/mbd/geometry.hpp"

#include <cmath>
#include <stdexcept>

#include "cvtplant/physics/seed.hpp"

namespace cvt::mbd {

// docs/mbd.md#geometry
DriveGeometry::DriveGeometry(double r1_m, double r2_m, double c_m) : r_m{r1_m, r2_m}, center_distance_m(c_m) {
  if (!(r1_m > 0 && r2_m > 0 && c_m > r1_m + r2_m))
    throw std::invalid_argument("geometry: need r1, r2 > 0 and a centre distance above r1 + r2");
  wrap_rad[0] = seed::wrap_angle_driver_rad(r1_m, r2_m, c_m);
  wrap_rad[1] = seed::wrap_angle_driven_rad(r1_m, r2_m, c_m);
  strand_tilt_rad = 0.5 * (kPi - wrap_rad[0]);
  centre[0] = {0.0, 0.0};
  centre[1] = {c_m, 0.0};
  // The strands touch both circles where the common normal is
  // (-sin delta, +-cos delta): upper tangent points at polar angle
  // pi/2 + delta, lower ones at -(pi/2 + delta).
  entry_angle_rad[0] = 0.5 * kPi + strand_tilt_rad;
  entry_angle_rad[1] = -0.5 * kPi - strand_tilt_rad;
  pitch_line_m = seed::chain_length_m(r1_m, r2_m, c_m);
  strand_m = 0.5 * (pitch_line_m - r1_m * wrap_rad[0] - r2_m * wrap_rad[1]);
}

Vec2 DriveGeometry::pitch_point(double s) const {
  s = std::fmod(s, pitch_line_m);
  if (s < 0) s += pitch_line_m;
  const double arc1 = r_m[0] * wrap_rad[0], arc2 = r_m[1] * wrap_rad[1];
  auto on_circle = [&](int j, double angle) {
    return Vec2{centre[j].x + r_m[j] * cos(angle), centre[j].y + r_m[j] * sin(angle)};
  };
  if (s < arc1) return on_circle(0, entry_angle_rad[0] + s / r_m[0]);
  s -= arc1;
  const Vec2 a = on_circle(0, entry_angle_rad[0] + wrap_rad[0]);  // driver exit (lower strand start)
  const Vec2 b = on_circle(1, entry_angle_rad[1]);                // driven entry
  if (s < strand_m) return {a.x + (b.x - a.x) * s / strand_m, a.y + (b.y - a.y) * s / strand_m};
  s -= strand_m;
  if (s < arc2) return on_circle(1, entry_angle_rad[1] + s / r_m[1]);
  s -= arc2;
  const Vec2 c = on_circle(1, entry_angle_rad[1] + wrap_rad[1]);  // driven exit (upper strand start)
  const Vec2 d = on_circle(0, entry_angle_rad[0]);                // driver entry
  return {c.x + (d.x - c.x) * s / strand_m, c.y + (d.y - c.y) * s / strand_m};
}

double driven_radius_for(double r1_m, double pitch_line_m, double c_m) {
  // The pitch line grows with r2 (r2 theta2 and the strands' tilt): bisection.
  double lo = 1e-6, hi = c_m - r1_m - 1e-9;
  if (!(seed::chain_length_m(r1_m, lo, c_m) < pitch_line_m && seed::chain_length_m(r1_m, hi, c_m) > pitch_line_m))
    throw std::invalid_argument("geometry: no driven radius fits that chain at that driver radius");
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (seed::chain_length_m(r1_m, mid, c_m) < pitch_line_m ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace cvt::mbd
