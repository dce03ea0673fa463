#include "io_util.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "options.hpp"

namespace cvtcli {

double parse_finite(const std::string& text, const std::string& what) {
  double v = 0;
  const std::string why = check_real(text, Range{-INFINITY, INFINITY}, &v);
  if (!why.empty()) throw UsageError{what + ": " + why};
  return v;
}

std::vector<double> parse_list(const std::string& text, std::size_t n, const std::string& what) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(parse_finite(item, what));
    if (n != 0 && out.size() > n) break;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (n != 0 && out.size() != n)
    throw UsageError{what + ": expected " + std::to_string(n) + " comma-separated values, got " +
                     (out.size() > n ? "more" : std::to_string(out.size()))};
  return out;
}

std::map<std::string, double> parse_assignments(const std::vector<std::string>& items, const std::string& flag) {
  std::map<std::string, double> out;
  for (const auto& kv : items) {
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError{flag + " '" + kv + "': expected name=value"};
    out[kv.substr(0, eq)] = parse_finite(kv.substr(eq + 1), flag + " " + kv.substr(0, eq));
  }
  return out;
}

std::string read_input_file(const std::string& path, std::size_t max_bytes, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw UsageError{what + ": cannot read " + quoted(path, 200) + ": " + std::strerror(errno)};
  if (S_ISDIR(st.st_mode)) throw UsageError{what + ": " + quoted(path, 200) + " is a directory, not a file"};
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw UsageError{what + ": " + quoted(path, 200) + " is not a regular file or a pipe"};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw UsageError{what + ": cannot read " + quoted(path, 200) + ": " + std::strerror(errno)};
  std::string text;
  char buf[65536];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) {
    if (text.size() + got > max_bytes) {
      std::fclose(f);
      throw UsageError{what + ": " + quoted(path, 200) + " is larger than " + std::to_string(max_bytes) + " bytes"};
    }
    text.append(buf, got);
  }
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (failed) throw UsageError{what + ": reading " + quoted(path, 200) + " failed: " + std::strerror(err)};
  return text;
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

std::FILE* open_output(const std::string& path, const std::string& flag, const std::vector<std::string>& inputs) {
  if (path == "-") return stdout;
  if (path.empty()) throw UsageError{flag + ": empty file name"};
  for (const std::string& in : inputs)
    if (same_file(path, in))
      throw UsageError{flag + ": " + quoted(path, 200) + " is the input file " + quoted(in, 200) +
                       "; writing would destroy it"};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw UsageError{flag + ": " + quoted(path, 200) + " is a directory"};
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw UsageError{flag + ": cannot write " + quoted(path, 200) + ": " + std::strerror(errno)};
  return f;
}

namespace {
int g_write_errno = 0;  // errno of the first failed write seen by output_ok
}  // namespace

bool output_ok(std::FILE* f) {
  if (f == nullptr || std::ferror(f) == 0) return true;
  if (g_write_errno == 0) g_write_errno = errno;
  return false;
}

std::string write_error_reason(int fresh_errno) {
  const int e = fresh_errno != 0 ? fresh_errno : g_write_errno;
  return e != 0 ? std::strerror(e) : "write error";
}

void check_output(std::FILE* f) {
  if (output_ok(f)) return;
  throw RunError{std::string("writing ") + (f == stdout ? "to stdout" : "the output") +
                 " failed: " + write_error_reason(0)};
}

void close_output(std::FILE* f) {
  if (f == nullptr) return;
  output_ok(f);
  errno = 0;
  if (f == stdout) {
    if (std::fflush(f) != 0 || std::ferror(f) != 0)
      throw RunError{"writing to stdout failed: " + write_error_reason(errno)};
    return;
  }
  const bool write_failed = std::ferror(f) != 0;
  const bool close_failed = std::fclose(f) != 0;
  if (write_failed || close_failed) throw RunError{"writing the output failed: " + write_error_reason(errno)};
}

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << '\n'; }

}  // namespace cvtcli
