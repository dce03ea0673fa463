#pragma once
// Run summary built from the samples as they stream past (docs/mbd.md#summary):
// constant memory whatever the run length.
#include "cvtplant/mbd/model.hpp"

namespace cvt::mbd {

struct RunSummary {
  double t_end_s = 0;
  double omega_end_rad_s[2] = {0, 0};
  double ratio_end = 0;
  // Ratio of the pulleys' angle increments = mean omega1 / mean omega2, over
  // the whole run and over the last window; NaN if the driven pulley did not turn.
  double ratio_mean = 0, ratio_window = 0;
  double F_ax_mean_N[2] = {0, 0};
  double F_ax_window_mean_N[2] = {0, 0};
  double F_ax1_ripple_N = 0;  // peak to peak of the samples in the last window
  double slip_window_mean_m_s[2] = {0, 0};
  double tension_tight_end_N = 0, tension_slack_end_N = 0;
  int wrap_links_end[2] = {0, 0};
  double window_s = 1.0;
  Sample last;
};

class SummaryBuilder {
 public:
  // window_s: the closing window for ripple and window means (the whole run if shorter).
  explicit SummaryBuilder(double t_end_s, double window_s = 1.0);
  void add(const Sample& s);
  RunSummary result() const;

 private:
  double t_end_, window_start_;
  long long n_ = 0, n_window_ = 0;
  double phi0_[2] = {0, 0}, phi_w_[2] = {0, 0};
  bool have_window_ = false;
  double fax_sum_[2] = {0, 0}, fax_w_sum_[2] = {0, 0}, slip_w_sum_[2] = {0, 0};
  long long slip_w_n_[2] = {0, 0};
  double fax1_min_ = 0, fax1_max_ = 0;
  Sample first_, last_;
};

}  // namespace cvt::mbd
