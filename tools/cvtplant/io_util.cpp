#include "io_util.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>

namespace cvtcli {

double parse_finite(const std::string& text, const std::string& what) {
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  if (text.empty() || end == s || *end != '\0')
    throw UsageError{what + ": '" + text + "' is not a number"};
  if (errno == ERANGE || !std::isfinite(v))
    throw UsageError{what + ": '" + text + "' is not a finite number"};
  return v;
}

std::vector<double> parse_list(const std::string& text, std::size_t n, const std::string& what) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(parse_finite(item, what));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (n != 0 && out.size() != n)
    throw UsageError{what + ": expected " + std::to_string(n) + " comma-separated values, got " +
                     std::to_string(out.size())};
  return out;
}

std::FILE* open_output(const std::string& path) {
  if (path == "-") return stdout;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw UsageError{"cannot write '" + path + "': " + std::strerror(errno)};
  return f;
}

void close_output(std::FILE* f) {
  if (f == nullptr) return;
  if (f == stdout) {
    std::fflush(f);
    return;
  }
  if (std::fclose(f) != 0) throw RunError{std::string("closing output failed: ") + std::strerror(errno)};
}

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << '\n'; }

}  // namespace cvtcli
