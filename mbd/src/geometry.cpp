#include "cvtplant/mbd/geometry.hpp"

#include <cmath>
#include <stdexcept>

namespace cvt::mbd {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

// docs/mbd.md#sheave-deformation (seed Eq. 4)
double deformation_amplitude_rad(double r_driver_m, double r_driven_m) {
  return 0.00045 / std::pow(r_driver_m / r_driven_m, 0.55);
}

double deformation_centre_rad(double r_driver_m, double r_driven_m) {
  return kPi * r_driver_m / (3.0 * r_driven_m) + 23.0 * kPi / 180.0;
}

// docs/mbd.md#sheave-deformation (seed Eq. 3)
double flank_angle_rad(double beta0_rad, double amplitude_rad, double zeta_rad, double centre_rad) {
  return beta0_rad + 0.5 * amplitude_rad * std::sin(zeta_rad - centre_rad + 0.5 * kPi);
}

// docs/mbd.md#geometry
DriveGeometry::DriveGeometry(double r1_m, double r2_m, double c_m) : r_m{r1_m, r2_m}, center_distance_m(c_m) {
  if (!(r1_m > 0 && r2_m > 0 && c_m > r1_m + r2_m))
    throw std::invalid_argument("geometry: need r1, r2 > 0 and a centre distance above r1 + r2");
  strand_tilt_rad = std::asin((r2_m - r1_m) / c_m);
  wrap_rad[0] = kPi - 2.0 * strand_tilt_rad;
  wrap_rad[1] = kPi + 2.0 * strand_tilt_rad;
  centre[0] = {0.0, 0.0};
  centre[1] = {c_m, 0.0};
  // The strands touch both circles where the common normal is
  // (-sin delta, +-cos delta): upper tangent points at polar angle
  // pi/2 + delta, lower ones at -(pi/2 + delta).
  entry_angle_rad[0] = 0.5 * kPi + strand_tilt_rad;
  entry_angle_rad[1] = -0.5 * kPi - strand_tilt_rad;
  pitch_line_m = 2.0 * c_m * std::cos(strand_tilt_rad) + r1_m * wrap_rad[0] + r2_m * wrap_rad[1];
}

Vec2 DriveGeometry::pitch_point(double s) const {
  s = std::fmod(s, pitch_line_m);
  if (s < 0) s += pitch_line_m;
  const double strand = center_distance_m * std::cos(strand_tilt_rad);
  const double arc1 = r_m[0] * wrap_rad[0], arc2 = r_m[1] * wrap_rad[1];
  auto on_circle = [&](int j, double angle) {
    return Vec2{centre[j].x + r_m[j] * std::cos(angle), centre[j].y + r_m[j] * std::sin(angle)};
  };
  if (s < arc1) return on_circle(0, entry_angle_rad[0] + s / r_m[0]);
  s -= arc1;
  const Vec2 a = on_circle(0, entry_angle_rad[0] + wrap_rad[0]);  // driver exit (lower strand start)
  const Vec2 b = on_circle(1, entry_angle_rad[1]);                // driven entry
  if (s < strand) return {a.x + (b.x - a.x) * s / strand, a.y + (b.y - a.y) * s / strand};
  s -= strand;
  if (s < arc2) return on_circle(1, entry_angle_rad[1] + s / r_m[1]);
  s -= arc2;
  const Vec2 c = on_circle(1, entry_angle_rad[1] + wrap_rad[1]);  // driven exit (upper strand start)
  const Vec2 d = on_circle(0, entry_angle_rad[0]);                // driver entry
  return {c.x + (d.x - c.x) * s / strand, c.y + (d.y - c.y) * s / strand};
}

}  // namespace cvt::mbd
