#pragma once
// The ripple of a sampled signal over a time window (docs/analysis.md#ripple):
// its linear trend removed, the spread of what is left and its dominant
// frequency. Used to compare the link-passing ripple of the driver's axial
// force, plant against the multibody reference (docs/rom.md#link-ripple).
#include <cstddef>
#include <vector>

namespace cvt::analysis {

struct RippleOptions {
  double min_hz = 20.0;  // the dominant frequency is searched at and above this (the trend's leakage sits below)
  double band = 0.2;     // the line's band: [f / (1 + band), f (1 + band)] around the dominant frequency f
};

struct RippleWindow {
  double t_begin_s = 0, t_end_s = 0;  // the window [t_begin, t_end)
  std::size_t samples = 0;
  double mean = 0;            // mean of the window
  double std = 0;             // standard deviation (1/N) of the detrended window
  double peak_to_peak = 0;    // max - min of the detrended window
  double peak_hz = 0;         // frequency of the Hann periodogram's largest bin at or above min_hz
  double line_amplitude = 0;  // sqrt(2 var_band): the amplitude of a sine carrying the detrended variance in the band
};

// The samples of (t, y) with t_begin <= t < t_end. Throws InputError: t and y
// of different lengths, a non-finite value, t not increasing with a uniform
// step (within 1e-3 of it), fewer than 16 samples in the window, or no
// periodogram bin between min_hz and the Nyquist frequency.
RippleWindow ripple_window(const std::vector<double>& t_s, const std::vector<double>& y, double t_begin_s,
                           double t_end_s, const RippleOptions& o = {});

}  // namespace cvt::analysis
