#pragma once
// The one progress display of the command line (docs/cli.md#progress): on a
// terminal, a bar on stderr with the fraction done, the simulated time, the
// wall time and an estimate of the time left, redrawn at most ten times a
// second and cleared when the job ends. When stderr is not a terminal it
// prints nothing at all, so piped and redirected runs carry data only.
#include <chrono>
#include <cstdio>
#include <string>

namespace cvtcli {

class Progress {
 public:
  // label: what runs (e.g. "mbd case 1"); total: the job's size in the unit
  // of update() (simulated seconds for a simulation).
  Progress(std::string label, double total, std::FILE* out = stderr);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Reports `done` of `total`; draws if at least 0.1 s passed since the last draw.
  void update(double done);
  // Clears the line (also done by the destructor).
  void finish();
  bool enabled() const { return enabled_; }

  // The line update() would draw (for tests): label, bar, percent, simulated
  // time, wall time and time left.
  static std::string format(const std::string& label, double done, double total, double wall_s, int width = 24);

 private:
  using clock = std::chrono::steady_clock;
  std::string label_;
  double total_;
  std::FILE* out_;
  bool enabled_;
  bool drawn_ = false;
  clock::time_point start_, last_;
};

}  // namespace cvtcli
