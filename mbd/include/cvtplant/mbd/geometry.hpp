#pragma once
// Geometry of the drive (docs/mbd.md#geometry): pulley centres, the pitch
// line (two arcs and the two free strands tangent to them), wrap angles, and
// the seed's sheave deformation (Eq. 3-4).
#include <array>

namespace cvt::mbd {

struct Vec2 {
  double x = 0, y = 0;
};

// Seed Eq. 4 (Sferra's correlations), read as printed with r the driver and
// r' the driven pitch radius: amplitude of the groove-angle variation [rad]
// and the wrap angle of its maximum [rad]. docs/mbd.md#sheave-deformation
double deformation_amplitude_rad(double r_driver_m, double r_driven_m);
double deformation_centre_rad(double r_driver_m, double r_driven_m);

// Seed Eq. 3: local half sheave angle at wrap angle zeta [rad].
double flank_angle_rad(double beta0_rad, double amplitude_rad, double zeta_rad, double centre_rad);

// Pulley j = 0 (driver, centre at the origin) and j = 1 (driven, at (C, 0)).
// Both turn counter-clockwise for positive speeds; the chain runs
// counter-clockwise round the loop, so the upper strand runs from the driven
// to the driver pulley and is the tight one while the driver drives.
struct DriveGeometry {
  double r_m[2];                 // pitch radii
  double center_distance_m;
  double strand_tilt_rad;        // delta = asin((r2 - r1) / C)
  double wrap_rad[2];            // theta1 = pi - 2 delta, theta2 = pi + 2 delta
  Vec2 centre[2];
  double entry_angle_rad[2];     // polar angle where the chain enters each wrap
  double pitch_line_m;           // 2 C cos(delta) + r1 theta1 + r2 theta2

  DriveGeometry(double r1_m, double r2_m, double center_distance_m);

  // Point of the pitch line at arc length s from the driver's entry point,
  // in the running direction (s taken modulo the pitch line length).
  Vec2 pitch_point(double s_m) const;
};

}  // namespace cvt::mbd
