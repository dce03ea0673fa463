// Heap-free number formatting (no newlib stdio: its printf pulls in malloc).
#include <cstring>

#include "cvtplant/port/console.hpp"

namespace cvt::port {
namespace {

// Appends to a bounded buffer; always keeps room for the NUL.
struct Sink {
  char* out;
  std::size_t cap;
  std::size_t n = 0;
  void put(char c) {
    if (cap != 0 && n + 1 < cap) out[n] = c;
    if (cap != 0) out[(n + 1 < cap) ? n + 1 : cap - 1] = '\0';
    ++n;
  }
  std::size_t written() const { return (cap == 0) ? 0 : (n < cap ? n : cap - 1); }
};

void put_u64(Sink& s, std::uint64_t v) {
  char digits[20];
  int k = 0;
  do {
    digits[k++] = static_cast<char>('0' + v % 10u);
    v /= 10u;
  } while (v != 0);
  while (k > 0) s.put(digits[--k]);
}

void put_u64_width(Sink& s, std::uint64_t v, int width) {
  char digits[20];
  for (int k = width - 1; k >= 0; --k) {
    digits[k] = static_cast<char>('0' + v % 10u);
    v /= 10u;
  }
  for (int k = 0; k < width; ++k) s.put(digits[k]);
}

constexpr std::uint64_t kPow10[] = {1ull, 10ull, 100ull, 1000ull, 10000ull, 100000ull,
                                    1000000ull, 10000000ull, 100000000ull, 1000000000ull};

}  // namespace

std::size_t format_u64(char* out, std::size_t cap, std::uint64_t v) {
  Sink s{out, cap};
  put_u64(s, v);
  return s.written();
}

std::size_t format_i64(char* out, std::size_t cap, std::int64_t v) {
  Sink s{out, cap};
  // Negate in unsigned arithmetic so INT64_MIN is representable.
  std::uint64_t mag = static_cast<std::uint64_t>(v);
  if (v < 0) {
    s.put('-');
    mag = 0u - mag;
  }
  put_u64(s, mag);
  return s.written();
}

std::size_t format_hex(char* out, std::size_t cap, std::uint64_t v, int digits) {
  Sink s{out, cap};
  if (digits < 1) digits = 1;
  if (digits > 16) digits = 16;
  s.put('0');
  s.put('x');
  for (int k = digits - 1; k >= 0; --k) s.put("0123456789ABCDEF"[(v >> (4 * k)) & 0xFu]);
  return s.written();
}

std::size_t format_f64(char* out, std::size_t cap, double v, int decimals) {
  Sink s{out, cap};
  if (decimals < 0) decimals = 0;
  if (decimals > 9) decimals = 9;
  if (v != v) {
    for (const char* p = "nan"; *p; ++p) s.put(*p);
    return s.written();
  }
  // Sign from the bit pattern, so that -0.0 prints as "-0.000".
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const bool negative = (bits >> 63) != 0;
  double mag = negative ? -v : v;
  if (negative) s.put('-');
  if (mag > 1.7976931348623157e308) {
    for (const char* p = "inf"; *p; ++p) s.put(*p);
    return s.written();
  }
  if (mag < 1e15) {
    // Scale to an integer number of 10^-decimals units: exact below 2^53,
    // i.e. always here since 1e15 * 1e9 would not be -- so split first.
    const double ip = static_cast<double>(static_cast<std::uint64_t>(mag));
    const double frac = mag - ip;  // exact: Sterbenz
    std::uint64_t ipart = static_cast<std::uint64_t>(ip);
    std::uint64_t fpart = static_cast<std::uint64_t>(frac * static_cast<double>(kPow10[decimals]) + 0.5);
    if (fpart >= kPow10[decimals]) {  // rounding carried into the integer part
      fpart -= kPow10[decimals];
      ++ipart;
    }
    put_u64(s, ipart);
    if (decimals > 0) {
      s.put('.');
      put_u64_width(s, fpart, decimals);
    }
    return s.written();
  }
  // Large magnitudes: d.dddddd e+XX by repeated division (human reading only).
  int exp10 = 0;
  while (mag >= 10.0) {
    mag /= 10.0;
    ++exp10;
  }
  std::uint64_t m = static_cast<std::uint64_t>(mag * 1e6 + 0.5);
  if (m >= 10000000ull) {
    m /= 10u;
    ++exp10;
  }
  put_u64(s, m / 1000000ull);
  s.put('.');
  put_u64_width(s, m % 1000000ull, 6);
  s.put('e');
  s.put('+');
  put_u64_width(s, static_cast<std::uint64_t>(exp10), exp10 >= 100 ? 3 : 2);
  return s.written();
}

}  // namespace cvt::port
