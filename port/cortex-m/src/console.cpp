#include <cstring>

#include "cvtplant/port/console.hpp"
#include "cvtplant/port/semihosting.hpp"

namespace cvt::port {

Console& console() {
  // Constant-initialised (no constructor code, no guard: -fno-threadsafe-statics).
  static Console instance;
  return instance;
}

void Console::flush() {
  if (used_ == 0) return;
  line_[used_] = '\0';
  semihost_write0(line_);
  used_ = 0;
}

void Console::put(const char* s, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    // SYS_WRITE0 stops at NUL, so a NUL can't be sent; drop it.
    if (s[i] == '\0') continue;
    line_[used_++] = s[i];
    if (s[i] == '\n' || used_ == sizeof line_ - 1) flush();
  }
}

Console& Console::operator<<(const char* s) {
  put(s, std::strlen(s));
  return *this;
}

Console& Console::operator<<(char c) {
  put(&c, 1);
  return *this;
}

Console& Console::signed_(long long v) {
  char buf[24];
  put(buf, format_i64(buf, sizeof buf, v));
  return *this;
}

Console& Console::unsigned_(unsigned long long v) {
  char buf[24];
  put(buf, format_u64(buf, sizeof buf, v));
  return *this;
}

Console& Console::operator<<(double v) { return fixed(v, 6); }

Console& Console::fixed(double v, int decimals) {
  char buf[40];
  put(buf, format_f64(buf, sizeof buf, v, decimals));
  return *this;
}

Console& Console::hex(std::uint64_t v, int digits) {
  char buf[20];
  put(buf, format_hex(buf, sizeof buf, v, digits));
  return *this;
}

Console& Console::bits(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return hex(b, 8);
}

Console& Console::bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return hex(b, 16);
}

}  // namespace cvt::port
