#pragma once
// A test rig's measured log as a calibration case (docs/validation.md#measured-csv):
// the CSV reader, and the plant driven frame by frame by the logged inputs
// with its outputs on the log's sample times.
#include <string>
#include <vector>

#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// The fewest data rows a log must have.
inline constexpr std::size_t kMeasuredMinRows = 3;

// A measured log in SI units, one entry per row. tau_load_Nm is 0 where the
// log has no load torque (the scene's road load, if it has one, still
// acts); clamp2_N is empty where the log has no driven clamping; ratio is
// empty where the log has none.
struct MeasuredLog {
  std::string source;  // the file, for messages
  std::vector<double> t_s, tau_in_Nm, tau_load_Nm, clamp1_N, clamp2_N, omega1_rad_s, omega2_rad_s, ratio;
  // The piston areas the pressures were turned into forces with [m^2]
  // (0: the log gave forces).
  double piston_area1_m2 = 0, piston_area2_m2 = 0;

  std::size_t size() const { return t_s.size(); }
  bool has_ratio() const { return !ratio.empty(); }
  bool has_clamp2() const { return !clamp2_N.empty(); }
};

// Piston areas a caller gives (a command line's options), used instead of
// the file's `# piston_area1_m2 = ...` lines; 0: none given.
struct PistonAreas {
  double area1_m2 = 0, area2_m2 = 0;
};

// Reads a log (docs/validation.md#measured-csv). Throws InputError naming
// the file (and the line) for: an unreadable file, an unknown column or
// units (omega1_rpm is known, omega1_rps is not), a column given twice or
// in two units, a missing column, a row of another width, a cell that is
// not a finite number, time not strictly increasing, fewer than
// kMeasuredMinRows rows, a negative clamping force or pressure, a pressure
// without its piston area, a bad metadata line.
MeasuredLog read_measured_csv(const std::string& path, const PistonAreas& areas = {});

// Writes a log in the format read_measured_csv reads (forces, SI units; the
// ratio column where the log has one); throws InputError if it cannot.
void write_measured_csv(const std::string& path, const MeasuredLog& log);

// Whether scene s can be driven by the log; else why (a driven clamping
// log on a plant without driven clamping, a log longer than the plant may run).
bool measured_fits_scene(const MeasuredLog& log, const cvt::Scene& s, std::string& why);

// The plant's start speeds from the log: at its first time, the
// least-squares line through the rows of its first 20 ms (at least three
// rows), so one noisy sample does not set them. (A fit refines them.)
void measured_start(const MeasuredLog& log, cvt::RomInitial& initial);

// The plant of scene s (features, parameters, initial state) driven frame by
// frame from the log's first time by its inputs, linearly interpolated to the start of each frame and
// held over it; its outputs linearly interpolated to every `every`-th
// row's time, times as the log's less its first. Throws as plant_run.
Series measured_plant_run(const cvt::Scene& s, const MeasuredLog& log, int every);

// The log's measured outputs on the same rows, as a Series (the quantities
// a log does not have are NaN).
Series measured_series(const MeasuredLog& log, int every);

}  // namespace cvt::validation
