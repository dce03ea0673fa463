#pragma once
// The one progress display of the command line (docs/cli.md#progress): on a
// terminal, a bar on stderr with the fraction done, the simulated time, the
// wall time and an estimate of the time left, redrawn at most ten times a
// second and cleared when the job ends. When stderr is not a terminal, or
// the environment variable CI is set to anything but "" or "0" (CI runners
// may give jobs a pseudo-terminal), it prints nothing at all, so piped and
// redirected runs carry data only. update() may be called from several
// threads (sweeps).
//
// It is also where a long command notices SIGINT or SIGTERM
// (docs/cli.md#interruption): update() on the thread that made the
// Progress throws cvtcli::Interrupted naming how far the job got, whether
// or not a bar is drawn. A command that writes rows polls the flag itself
// between rows and makes its Progress with Interrupts::polled_by_caller.
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace cvtcli {

class Progress {
 public:
  enum class Interrupts { stop_at_update, polled_by_caller };
  // label: what runs (e.g. "mbd case 1"); total: the job's size in `unit`,
  // the unit of update(): "s" for simulated seconds (shown as "t 1.2/10 s"),
  // a count's name such as "points" (shown as "12/40 points"), or "" for
  // the percentage alone.
  Progress(std::string label, double total, std::string unit = "s", std::FILE* out = stderr,
           Interrupts interrupts = Interrupts::stop_at_update);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Reports `done` of `total`; draws if at least 0.1 s passed since the last draw.
  void update(double done);
  // Clears the line (also done by the destructor).
  void finish();
  bool enabled() const { return enabled_; }

  // How far a job got, for `interrupted at ...`: "t = 1.25 s",
  // "120/400 plant runs", "42 % of the run".
  static std::string position(double done, double total, const std::string& unit);

  // The line update() would draw (for tests): label, bar, percent, the
  // amount done, wall time and time left.
  static std::string format(const std::string& label, double done, double total, double wall_s,
                            const std::string& unit = "s", int width = 24);
  // Whether a bar may be drawn on `out`: a terminal, and CI unset.
  static bool wanted(std::FILE* out);

 private:
  using clock = std::chrono::steady_clock;
  std::string label_, unit_;
  double total_;
  std::mutex mutex_;
  std::FILE* out_;
  bool enabled_;
  bool stop_at_update_;
  std::thread::id owner_;
  bool drawn_ = false;
  clock::time_point start_, last_;
};

}  // namespace cvtcli
