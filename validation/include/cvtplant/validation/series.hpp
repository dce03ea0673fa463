#pragma once
// One model's time series on the validation's sample grid (SI units),
// the plant's or the multibody reference's (docs/validation.md#method).
#include <cstddef>
#include <vector>

namespace cvt::validation {

// slip1_m_s is the driver slip, the mean over the wrap; wrap_slip_m_s the
// slip the whole driver wrap shares (whole_wrap_slip), which gross slip is
// read from. ratio_geom is the geometric ratio r2/r1 of the running radii
// (the reference's mean bolt radii, the plant's pitch radii), F_ax2_N the
// driven pulley's axial force (NaN where a plant has none: no wedging).
// The inputs as applied over the frame that starts at the sample: the
// clamping forces (commands; 0 on fixed sheaves, NaN where a plant has no
// driven clamping) and the torques (the load with the road load).
struct Series {
  std::vector<double> t_s, omega1_rad_s, omega2_rad_s, F_ax1_N, torque_driver_Nm, slip1_m_s, wrap_slip_m_s,
      ratio_geom, F_ax2_N, clamp1_N, clamp2_N, tau_in_Nm, tau_load_Nm;

  std::size_t size() const { return t_s.size(); }
  void reserve(std::size_t n);
  // Every `step`-th of the first n samples (step 0 counts as 1).
  Series select(std::size_t n, std::size_t step = 1) const;
};

// Every column of a Series, in the order above (the reference cache's).
inline constexpr std::vector<double> Series::*kSeriesColumns[] = {
    &Series::t_s,     &Series::omega1_rad_s,     &Series::omega2_rad_s, &Series::F_ax1_N,
    &Series::torque_driver_Nm, &Series::slip1_m_s, &Series::wrap_slip_m_s, &Series::ratio_geom, &Series::F_ax2_N,
    &Series::clamp1_N, &Series::clamp2_N, &Series::tau_in_Nm, &Series::tau_load_Nm};

// The slip the whole of a wrap shares, from the smallest and largest slip
// of its parts (the reference's bolts, the plant's two lumps): the smallest
// where every part slides forward, the largest (negative) where every part
// slides backwards, else 0 (some part grips or they slide opposite ways)
// [m/s]; NaN when lo > hi or either is NaN (no part in the wrap). Gross slip
// is this beyond kGrossSlip_m_s (docs/validation.md#method).
double whole_wrap_slip(double lo, double hi);

}  // namespace cvt::validation
