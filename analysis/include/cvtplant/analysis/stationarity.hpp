#pragma once
// Stationarity of a sampled series over consecutive windows
// (docs/analysis.md#stationarity): every estimator of section 4 (delay,
// dimension, exponent, recurrences) assumes that the series samples one
// invariant set; a series whose level, spread or spectral lines move over the
// record does not, and no verdict on chaos is drawn from it.
#include <string>
#include <vector>

namespace cvt::analysis {

struct StationarityOptions {
  double dt = 1.0;            // sample interval [s]
  int windows = 4;            // equal, consecutive windows
  // Stationary only if all hold (each in the units stated):
  double max_mean_shift = 0.5;   // largest minus smallest window mean, in the whole series' standard deviations
  double max_std_ratio = 1.5;    // largest over smallest window standard deviation
  double max_line_shift = 0.05;  // relative shift of the dominant line between windows (or 2 frequency bins of a window, whichever is larger)
  double min_line_fraction = 0.2;  // ... tested only where that line carries at least this fraction of the power
  double max_mean_frequency_shift = 0.2;  // otherwise (broadband): (max - min) / mean of the windows' mean frequencies
  int peaks_per_window = 3;      // lines reported per window
};

struct WindowStats {
  double t_begin_s = 0, t_end_s = 0;
  double mean = 0, std = 0;
  std::vector<double> peaks_Hz;  // the strongest spectral lines, strongest first
  std::vector<double> peak_power_rel;  // their power over the window's strongest
  double dominant_line_Hz = 0;   // the line nearest the whole series' dominant line
  double mean_Hz = 0;            // power-weighted mean frequency (1 / Rosenstein's mean period)
};

struct Stationarity {
  std::vector<WindowStats> windows;
  double dominant_Hz = 0;       // the whole series' strongest line
  double dominant_fraction = 0; // the power within 2 window bins of it over the total
  bool line_tested = false;     // dominant_fraction >= min_line_fraction: the line test applies, else the mean-frequency test
  double mean_frequency_shift = 0;  // (max - min) / mean of the windows' mean_Hz
  double mean_shift = 0;        // (max - min window mean) / std of the series
  double std_ratio = 0;         // max / min window std
  double line_shift = 0;        // max |window's dominant line - dominant_Hz| / dominant_Hz
  double line_tolerance = 0;    // the relative shift allowed (max_line_shift or 2 bins)
  bool stationary = false;
  std::vector<std::string> reasons;
};

// Throws InputError for fewer than 64 samples per window or a non-finite value.
Stationarity stationarity(const std::vector<double>& x, const StationarityOptions& opt);

}  // namespace cvt::analysis
