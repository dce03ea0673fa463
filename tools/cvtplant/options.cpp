#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "commands.hpp"

namespace cvtcli {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A CLI11 transform that checks the token (and may rewrite it) before CLI11
// converts it; the description is what --help prints after the type.
CLI::Validator make_check(std::function<std::string(std::string&)> test, const std::string& desc) {
  return CLI::Validator(std::move(test), desc);
}

}  // namespace

std::string Range::text() const {
  return std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string check_real(const std::string& token, const Range& r, double* out) {
  const char* s = token.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  if (token.empty() || end == s || *end != '\0' || token.size() > 64) return quoted(token) + " is not a number";
  if (!std::isfinite(v)) return quoted(token) + " is not a finite number";
  if (errno == ERANGE) return quoted(token) + " is outside the range of a double";
  if (!r.contains(v)) return quoted(token) + " is outside " + r.text();
  if (out != nullptr) *out = v;
  return {};
}

std::string check_int(const std::string& token, long long lo, long long hi, long long* out) {
  std::size_t i = (!token.empty() && (token[0] == '-' || token[0] == '+')) ? 1 : 0;
  bool digits = i < token.size() && token.size() <= 20;
  for (; digits && i < token.size(); ++i) digits = token[i] >= '0' && token[i] <= '9';
  if (!digits) return quoted(token) + " is not an integer";
  errno = 0;
  const long long v = std::strtoll(token.c_str(), nullptr, 10);
  if (errno == ERANGE || v < lo || v > hi)
    return quoted(token) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi);
  if (out != nullptr) *out = v;
  return {};
}

CLI::Option* add_real(CLI::App* app, const std::string& name, double& var, const Range& r, const std::string& help) {
  // The accepted token is rewritten to its exact decimal form, so CLI11's own
  // conversion stores the value that was checked.
  return app->add_option(name, var, help)->transform(make_check(
      [r](std::string& t) {
        double v = 0;
        std::string why = check_real(t, r, &v);
        if (why.empty()) {
          char buf[40];
          std::snprintf(buf, sizeof buf, "%.17g", v);
          t = buf;
        }
        return why;
      },
      "in " + r.text()));
}

namespace {
template <class Int>
CLI::Option* add_integer(CLI::App* app, const std::string& name, Int& var, long long lo, long long hi,
                         const std::string& help) {
  return app->add_option(name, var, help)->transform(make_check(
      [lo, hi](std::string& t) {
        long long v = 0;
        std::string why = check_int(t, lo, hi, &v);
        if (why.empty()) t = std::to_string(v);
        return why;
      },
      "in " + std::to_string(lo) + ".." + std::to_string(hi)));
}
}  // namespace

CLI::Option* add_int(CLI::App* app, const std::string& name, int& var, long long lo, long long hi,
                     const std::string& help) {
  return add_integer(app, name, var, lo, hi, help);
}
CLI::Option* add_int(CLI::App* app, const std::string& name, long& var, long long lo, long long hi,
                     const std::string& help) {
  return add_integer(app, name, var, lo, hi, help);
}
CLI::Option* add_int(CLI::App* app, const std::string& name, long long& var, long long lo, long long hi,
                     const std::string& help) {
  return add_integer(app, name, var, lo, hi, help);
}

void add_caps(CLI::App* app, Caps& caps, bool steps, bool memory) {
  if (steps)
    add_real(app, "--max-steps", caps.max_steps, {1, kMaxStepsLimit},
             "Refuse a run estimated above this many integrator steps (default 1e9)");
  if (memory)
    add_real(app, "--max-memory-mb", caps.max_memory_mb, {1, kMaxMemoryMbLimit},
             "Refuse a run estimated to store more than this many MB (default 1024)");
}

void require_steps(double steps, const Caps& caps, const std::string& how) {
  if (steps <= caps.max_steps) return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "the run needs %.3g integrator steps", steps);
  throw UsageError{std::string(buf) + " (" + how + "), above the cap of " + num(caps.max_steps) +
                   "; raise it with --max-steps"};
}

void require_memory(double bytes, const Caps& caps, const std::string& how) {
  if (bytes <= caps.max_memory_mb * 1048576.0) return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "the run needs about %.0f MB", std::ceil(bytes / 1048576.0));
  throw UsageError{std::string(buf) + " (" + how + "), above the cap of " + num(caps.max_memory_mb) +
                   " MB; raise it with --max-memory-mb"};
}

std::uint64_t memory_cap_bytes(const Caps& caps) {
  return static_cast<std::uint64_t>(caps.max_memory_mb * 1048576.0);
}

std::string fmt_count(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, n < 1e7 ? "%.0f" : "%.3g", n);
  return buf;
}

std::string exact_number(double v) {
  // %g with the fewest digits that read back to v: 0.0005, 99.99999, 1e-300.
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string quoted(const std::string& text, std::size_t max_chars) {
  // Control characters would reach the user's terminal: shown as '?'.
  std::string shown = text.substr(0, max_chars);
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (text.size() <= max_chars) return "'" + shown + "'";
  return "'" + shown + "...' (" + std::to_string(text.size()) + " characters)";
}

}  // namespace cvtcli
