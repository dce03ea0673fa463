#include "cvtplant/mbd/summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cvt::mbd {

SummaryBuilder::SummaryBuilder(double t_end_s, double window_s)
    : t_end_(t_end_s), window_start_(std::max(0.0, t_end_s - window_s)) {}

void SummaryBuilder::add(const Sample& s) {
  if (n_ == 0) {
    first_ = s;
    for (int j = 0; j < 2; ++j) phi0_[j] = s.phi_rad[j];
  }
  ++n_;
  last_ = s;
  for (int j = 0; j < 2; ++j) fax_sum_[j] += s.F_ax_N[j];
  if (s.t_s >= window_start_ - 1e-12) {
    if (!have_window_) {
      have_window_ = true;
      for (int j = 0; j < 2; ++j) phi_w_[j] = s.phi_rad[j];
      fax1_min_ = fax1_max_ = s.F_ax_N[0];
    }
    ++n_window_;
    fax1_min_ = std::min(fax1_min_, s.F_ax_N[0]);
    fax1_max_ = std::max(fax1_max_, s.F_ax_N[0]);
    for (int j = 0; j < 2; ++j) {
      fax_w_sum_[j] += s.F_ax_N[j];
      if (std::isfinite(s.slip_m_s[j])) {
        slip_w_sum_[j] += s.slip_m_s[j];
        ++slip_w_n_[j];
      }
    }
  }
}

RunSummary SummaryBuilder::result() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RunSummary r;
  r.t_end_s = t_end_;
  r.window_s = t_end_ - window_start_;
  r.last = last_;
  auto angle_ratio = [&](const double* phi_from) {
    const double d1 = last_.phi_rad[0] - phi_from[0], d2 = last_.phi_rad[1] - phi_from[1];
    return std::fabs(d2) > 1e-9 ? d1 / d2 : nan;
  };
  r.ratio_mean = angle_ratio(phi0_);
  r.ratio_window = have_window_ ? angle_ratio(phi_w_) : nan;
  r.ratio_end = last_.ratio;
  for (int j = 0; j < 2; ++j) {
    r.omega_end_rad_s[j] = last_.omega_rad_s[j];
    r.F_ax_mean_N[j] = n_ > 0 ? fax_sum_[j] / static_cast<double>(n_) : nan;
    r.F_ax_window_mean_N[j] = n_window_ > 0 ? fax_w_sum_[j] / static_cast<double>(n_window_) : nan;
    r.slip_window_mean_m_s[j] = slip_w_n_[j] > 0 ? slip_w_sum_[j] / static_cast<double>(slip_w_n_[j]) : nan;
    r.wrap_links_end[j] = last_.wrap_links[j];
  }
  r.F_ax1_ripple_N = n_window_ > 0 ? fax1_max_ - fax1_min_ : nan;
  r.tension_tight_end_N = last_.tension_tight_N;
  r.tension_slack_end_N = last_.tension_slack_N;
  return r;
}

}  // namespace cvt::mbd
