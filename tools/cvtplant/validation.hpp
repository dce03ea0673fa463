#pragma once
// The real-time plant against the multibody reference (docs/validation.md):
// a plant scene turned into the reference's inputs, reference runs cached on
// disk by their inputs and the reference's version, both models sampled on
// the same grid, and the error measures of `cvtplant validate` and
// `cvtplant calibrate`.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvtcli::validation {

// One time series of either model on the sample grid (SI units). slip1_m_s
// is the driver slip, the mean over the wrap; wrap_slip_m_s the slip the
// whole driver wrap shares (whole_wrap_slip), which gross slip is read from.
struct Series {
  std::vector<double> t_s, omega1_rad_s, omega2_rad_s, F_ax1_N, torque_driver_Nm, slip1_m_s, wrap_slip_m_s;
  std::size_t size() const { return t_s.size(); }
  void reserve(std::size_t n);
  // Every `step`-th of the first n samples.
  Series select(std::size_t n, std::size_t step = 1) const;
};

// `--sheaves scene|clamped|fixed` of validate and calibrate
// (docs/validation.md#method): each scene's own sheaves, or one mode for all.
enum class SheaveChoice { scene, clamped, fixed };
CLI::Option* add_sheaves_option(CLI::App* sub, std::string& choice);
SheaveChoice sheave_choice(const std::string& name);
const char* sheave_mode_name(cvt::mbd::SheaveMode m);  // "fixed", "clamped"

// The reference's sheaves for a scene: with `scene`, fixed where the plant's
// driver sheave is fixed (the tension feature with `fixed_sheaves`: its
// axial force is then the chain's, as on the reference's fixed pulleys),
// else clamped (the plant's axial force is its clamping input).
cvt::mbd::SheaveMode reference_sheaves(const cvt::Scene& s, SheaveChoice c);

// The reference's inputs for a plant scene, or why it cannot run that scene
// (a reason in `why_not`); the single place that maps a scene to the
// reference (docs/validation.md#method). The scene's friction law, inertias
// and half sheave angle are copied; its torque profiles, road load and start
// speeds (a start at speed, docs/mbd.md#start-at-speed) become the
// reference's; its sheaves are reference_sheaves(s, c). Clamped sheaves
// (docs/mbd.md#clamped-sheaves) are pushed by the scene's clamping profile;
// fixed sheaves are the seed's pulleys, whose axial force is an output.
// Refused: held pulleys, initial lump states, a start with one pulley at
// rest, sine profiles, clamping below 100 N (clamped).
std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice c, std::string& why_not);

// The slip the whole of a wrap shares, from the smallest and largest slip
// of its parts (the reference's bolts, the plant's two lumps): the smallest
// where every part slides forward, the largest (negative) where every part
// slides backwards, else 0 (some part grips or they slide opposite ways)
// [m/s]. Gross slip is this beyond kGrossSlip_m_s (docs/validation.md#method).
double whole_wrap_slip(double lo, double hi);

// The text that identifies a reference run: every input and the reference's
// version (cvt::mbd::kReferenceVersion). Equal texts give equal runs.
std::string reference_key(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r);

// 64-bit FNV-1a of the key, as 16 hex digits (the cache file's name).
std::string key_hash(const std::string& key);

struct ReferenceRun {
  Series series;
  // Movable sheave openings [m] per sample (docs/mbd.md#clamped-sheaves).
  std::vector<double> sheave1_m, sheave2_m;
  bool from_cache = false;
  double cpu_s = 0, wall_s = 0, ledger_residual_rel = 0;
  long long steps = 0;
  // A run that stopped early (a link left the drive, the ledger, the step
  // cap): the reason, and `series` holds the samples up to then.
  std::string failure;
};

// The first sample time at which the reference's movable sheave (0 driver,
// 1 driven) is within 0.1 mm of its end stop (the chain at a ratio limit: the
// stop, not only the clamping force, then holds the sheave), or -1: never.
double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m);

// The reference run for (p, r): read from `cache_dir` if a run with the same
// key is there, else run (progress bar labelled `label`) and stored. A run
// that fails (integrator, ledger, step cap) throws RunError naming the time
// and quantity; nothing is cached then.
ReferenceRun reference_run(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r, const std::string& cache_dir,
                           const std::string& label);

// The plant on the same grid (every frame whose time is a multiple of
// sample_s). Throws RunError if the plant faults.
Series plant_run(const cvt::Scene& s, double sample_s);

// Error of one quantity: relative RMS over the run (RMS of the difference over
// RMS of the reference), and the mean of each over the steady-state window.
struct ErrorRow {
  std::string quantity, unit;
  double rel_rms = 0;
  double plant_ss = 0, reference_ss = 0, ss_rel = 0;  // ss_rel = (plant - ref) / |ref|
};

struct Comparison {
  std::vector<ErrorRow> rows;
  double compared_s = 0;  // the samples compared: t in [0, compared_s]
  double window_s = 0;  // steady-state window: the last second (or the last half of a shorter run)
  double ripple_plant_N = 0, ripple_reference_N = 0;  // F_ax1 peak to peak over the window
  // Time of the first sample at which the whole driver wrap slides by more
  // than kGrossSlip_m_s (|wrap_slip_m_s|; negative: never).
  double gross_slip_plant_s = -1, gross_slip_reference_s = -1;
};

// Slip speed of the whole driver wrap above which it is in gross slip [m/s].
inline constexpr double kGrossSlip_m_s = 1.0;

// plant and reference must share the grid (same t_s) over the first n
// samples of each; the comparison uses those n samples.
Comparison compare(const Series& plant, const Series& reference, std::size_t n);

// Relative RMS of plant - reference over one column (samples where either is
// NaN left out): RMS of the difference over RMS of the reference.
double rel_rms(const std::vector<double>& plant, const std::vector<double>& reference);

}  // namespace cvtcli::validation
