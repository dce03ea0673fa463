#pragma once
// Scalar time series helpers: validation, normalisation, delay embedding,
// power spectrum, small statistics (docs/analysis.md#conventions).
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

namespace cvt::analysis {

// Throws InputError if the series has fewer than `min_points` samples, contains
// a non-finite value, or is constant (std below 1e-12 of its scale).
void validate_series(const std::vector<double>& x, std::size_t min_points, const std::string& what = "series");

double mean(const std::vector<double>& x);
double stddev(const std::vector<double>& x);  // population (1/N)
// (x - mean)/std; throws InputError for a constant series.
std::vector<double> zscore(const std::vector<double>& x);

// Delay vectors y_i = [x_i, x_{i+tau}, ..., x_{i+(m-1)tau}], i = 0..n-1, stored
// row-major (docs/analysis.md#embedding). n = N - (m-1) tau - extra, where
// `extra` keeps room for future samples (FNN needs one more coordinate).
struct Embedding {
  int m = 1;
  int tau = 1;
  std::size_t n = 0;
  std::vector<double> data;  // n*m
  const double* row(std::size_t i) const { return data.data() + i * static_cast<std::size_t>(m); }
};
Embedding delay_embed(const std::vector<double>& x, int m, int tau, std::size_t extra = 0);
// Embeds an already multi-dimensional trajectory (rows of `dim` values).
Embedding from_rows(const std::vector<double>& rows, int dim);

// In-place radix-2 FFT (size must be a power of two).
void fft(std::vector<std::complex<double>>& a);

// One-sided Hann-windowed periodogram of the mean-removed series, zero-padded
// to a power of two >= 2N. freq in cycles/sample.
struct Spectrum {
  std::vector<double> freq;
  std::vector<double> power;
};
Spectrum periodogram(const std::vector<double>& x);

// The strongest local maxima of the periodogram (docs/analysis.md#spectral-lines)
// at or above min_Hz, strongest first, their frequencies refined by a
// parabola through ln P at the peak bin and its two neighbours: at most
// `count`, each within 20 dB of the strongest bin at or above min_Hz (bin 0,
// the mean, excluded). Frequencies in Hz for a sample interval dt [s] (dt = 1:
// cycles per sample); power_rel is each line's power over the strongest bin's.
struct Lines {
  std::vector<double> Hz, power_rel;
  double resolution_Hz = 0;  // one bin of the zero-padded transform
};
Lines spectral_lines(const std::vector<double>& x, double dt, int count, double min_Hz = 0);

// Rosenstein's mean period: 1 / (power-weighted mean frequency), in samples.
double mean_period_samples(const std::vector<double>& x);

// Default Theiler window (docs/analysis.md#theiler): round(mean period),
// clamped to [1, N/20].
int default_theiler(const std::vector<double>& x);

// Ordinary least squares y = a + b x with the slope's standard error.
struct LineFit {
  double intercept = 0, slope = 0, slope_se = 0, r2 = 0;
  std::size_t n = 0;
};
LineFit fit_line(const double* x, const double* y, std::size_t n);

// Two-sided 95% Student-t quantile for `dof` degrees of freedom.
double t95(int dof);

}  // namespace cvt::analysis
