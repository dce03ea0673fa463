#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "commands.hpp"
#include "cvtplant/files/interrupt.hpp"

namespace cvtcli {

namespace {

std::string seconds(double s) {
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s) / 3600, (static_cast<int>(s) % 3600) / 60);
  return buf;
}

}  // namespace

bool Progress::wanted(std::FILE* out) {
  const char* ci = std::getenv("CI");
  if (ci != nullptr && *ci != '\0' && std::strcmp(ci, "0") != 0) return false;
  return isatty(fileno(out)) == 1;
}

Progress::Progress(std::string label, double total, std::string unit, std::FILE* out, Interrupts interrupts)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), out_(out),
      enabled_(total > 0 && wanted(out)), stop_at_update_(interrupts == Interrupts::stop_at_update),
      owner_(std::this_thread::get_id()), start_(clock::now()), last_(start_) {}

std::string Progress::position(double done, double total, const std::string& unit) {
  char buf[96];
  if (unit == "s")
    std::snprintf(buf, sizeof buf, "t = %.6g s", done);
  else if (!unit.empty())
    std::snprintf(buf, sizeof buf, "%.0f/%.0f %s", done, total, unit.c_str());
  else
    std::snprintf(buf, sizeof buf, "%.0f %% of the run", total > 0 ? 100.0 * std::clamp(done / total, 0.0, 1.0) : 0.0);
  return buf;
}

Progress::~Progress() { finish(); }

std::string Progress::format(const std::string& label, double done, double total, double wall_s,
                             const std::string& unit, int width) {
  const double f = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
  const int filled = static_cast<int>(std::floor(f * width));
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(width - filled), '.');
  char amount[96] = "";
  if (unit == "s")
    std::snprintf(amount, sizeof amount, "  t %.3g/%.3g s", done, total);
  else if (!unit.empty())
    std::snprintf(amount, sizeof amount, "  %.0f/%.0f %s", done, total, unit.c_str());
  char buf[320];
  std::snprintf(buf, sizeof buf, "%s [%s] %3.0f%%%s  wall %s  left %s", label.c_str(), bar.c_str(), 100.0 * f,
                amount, seconds(wall_s).c_str(), f > 0 ? seconds(wall_s * (1.0 - f) / f).c_str() : "?");
  return buf;
}

void Progress::update(double done) {
  // Other threads (a sweep's workers) cannot unwind the command: only its own.
  if (stop_at_update_ && cvt::files::interrupted() && std::this_thread::get_id() == owner_) {
    finish();
    throw Interrupted{position(done, total_, unit_)};
  }
  if (!enabled_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  const double wall = std::chrono::duration<double>(now - start_).count();
  std::fprintf(out_, "\r%s\033[K", format(label_, done, total_, wall, unit_).c_str());
  std::fflush(out_);
}

void Progress::finish() {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!drawn_) return;
  std::fprintf(out_, "\r\033[K");
  std::fflush(out_);
  drawn_ = false;
}

}  // namespace cvtcli
