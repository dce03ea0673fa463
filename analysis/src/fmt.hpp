#pragma once
// The toolkit's messages and verdict reasons: printf-style text with up to
// three numbers, cut at 319 characters.
#include <cstdio>
#include <string>

namespace cvt::analysis::detail {

inline std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[320];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

}  // namespace cvt::analysis::detail
