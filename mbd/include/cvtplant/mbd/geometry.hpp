#pragma once
// Geometry of the drive (docs/mbd.md#geometry): pulley centres, the pitch
// line (two arcs and the two free strands tangent to them) and where the
// chain enters each wrap. The wrap angles and the pitch line's length are the
// seed's open-chain formulas (cvtplant/physics/seed.hpp).
namespace cvt::mbd {

struct Vec2 {
  double x = 0, y = 0;
};

// Pulley j = 0 (driver, centre at the origin) and j = 1 (driven, at (C, 0)).
// Both turn counter-clockwise for positive speeds; the chain runs
// counter-clockwise round the loop, so the upper strand runs from the driven
// to the driver pulley and is the tight one while the driver drives.
struct DriveGeometry {
  double r_m[2];                 // pitch radii
  double center_distance_m;
  double strand_tilt_rad;        // delta = asin((r2 - r1) / C) = (pi - theta1) / 2
  double wrap_rad[2];            // theta1 = pi - 2 delta, theta2 = pi + 2 delta
  Vec2 centre[2];
  double entry_angle_rad[2];     // polar angle where the chain enters each wrap
  double pitch_line_m;           // r1 theta1 + r2 theta2 + 2 sqrt(C^2 - (r2 - r1)^2)
  double strand_m;               // length of each free strand, sqrt(C^2 - (r2 - r1)^2)

  DriveGeometry(double r1_m, double r2_m, double center_distance_m);

  // Point of the pitch line at arc length s from the driver's entry point,
  // in the running direction (s taken modulo the pitch line length).
  Vec2 pitch_point(double s_m) const;
};

// The driven radius that, with driver radius r1_m, gives a pitch line of
// length pitch_line_m on centre distance c_m (the same chain at another ratio).
double driven_radius_for(double r1_m, double pitch_line_m, double c_m);

}  // namespace cvt::mbd
