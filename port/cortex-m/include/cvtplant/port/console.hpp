#pragma once
// Line-buffered text console over semihosting, with a heap-free formatter.
// No newlib stdio: printf would pull in malloc (see port/cortex-m/ld/no_heap.ld).
// docs/build.md#console
#include <cstddef>
#include <cstdint>

namespace cvt::port {

// Heap-free number formatting into a caller buffer. Each returns the number
// of characters written (excluding the terminating NUL, which is always
// written when cap > 0). Output is truncated, never overflowed, if cap is too
// small. The exact texts are pinned by tests/target/test_port.cpp.
std::size_t format_i64(char* out, std::size_t cap, std::int64_t v);
std::size_t format_u64(char* out, std::size_t cap, std::uint64_t v);
// "0x" followed by exactly `digits` hex digits (1..16), upper case.
std::size_t format_hex(char* out, std::size_t cap, std::uint64_t v, int digits);
// Fixed notation with `decimals` (0..9) digits after the point, rounded half
// away from zero. |v| >= 1e15 switches to "d.ddddddde+XX" (7 significant
// digits, the last one may be off by one ulp of the decimal: it is for human
// reading). Use format_hex on the bit pattern when exactness matters.
// Non-finite values print as "nan", "inf", "-inf".
std::size_t format_f64(char* out, std::size_t cap, double v, int decimals);

// Console: buffered, flushed at '\n' or when the 128-byte line buffer fills.
class Console {
 public:
  Console& operator<<(const char* s);
  Console& operator<<(char c);
  // Overloads on the fundamental types (int32_t is `long` on arm-none-eabi
  // but `int` on Linux, so fixed-width overloads would be ambiguous).
  Console& operator<<(int v) { return signed_(v); }
  Console& operator<<(long v) { return signed_(v); }
  Console& operator<<(long long v) { return signed_(v); }
  Console& operator<<(unsigned v) { return unsigned_(v); }
  Console& operator<<(unsigned long v) { return unsigned_(v); }
  Console& operator<<(unsigned long long v) { return unsigned_(v); }
  Console& operator<<(double v);  // 6 decimals; use fixed() for control
  Console& operator<<(float v) { return *this << static_cast<double>(v); }
  Console& fixed(double v, int decimals);
  Console& hex(std::uint64_t v, int digits);
  // Exact IEEE-754 bits, e.g. "0x3EAAAAAB": for bit-exact comparisons with
  // the host build.
  Console& bits(float v);
  Console& bits(double v);
  void flush();

 private:
  Console& signed_(long long v);
  Console& unsigned_(unsigned long long v);
  void put(const char* s, std::size_t n);
  char line_[129] = {};
  std::size_t used_ = 0;
};

// The single console instance of the image.
Console& console();

}  // namespace cvt::port
