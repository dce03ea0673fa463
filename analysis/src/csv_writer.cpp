// Buffered CSV output with shortest round-trip numbers (docs/cli.md#csv-numbers).
#include "cvtplant/analysis/csv_writer.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace cvt::analysis {
namespace {

constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Decimal digits of s (1 for 0).
int digit_count(std::uint64_t s) {
  static constexpr std::uint64_t kPow10[] = {1ull,
                                             10ull,
                                             100ull,
                                             1000ull,
                                             10000ull,
                                             100000ull,
                                             1000000ull,
                                             10000000ull,
                                             100000000ull,
                                             1000000000ull,
                                             10000000000ull,
                                             100000000000ull,
                                             1000000000000ull,
                                             10000000000000ull,
                                             100000000000000ull,
                                             1000000000000000ull,
                                             10000000000000000ull,
                                             100000000000000000ull,
                                             1000000000000000000ull};
  // log10(2) ~ 1233 / 4096: the count is t or t + 1.
  const int t = ((64 - __builtin_clzll(s | 1)) * 1233) >> 12;
  return t + ((s | 1) >= kPow10[t]);
}

// Eight digits of v < 10^8, leading zeros included, computed in the lanes of
// one 64-bit word (two 4-digit halves, then four 2-digit pairs, then eight
// digits): a few multiplications instead of a chain of divisions. The
// constants are exact quotients over each lane's range (x / 100 for
// x < 10^4: x 10486 >> 20; x / 10 for x < 100: x 103 >> 10).
inline void write8(char* p, std::uint32_t v) {
  const std::uint64_t halves = (v / 10000) | (static_cast<std::uint64_t>(v % 10000) << 32);
  const std::uint64_t hundreds = ((halves * 10486) >> 20) & 0x0000007F0000007Full;
  const std::uint64_t pairs = hundreds | ((halves - hundreds * 100) << 16);
  const std::uint64_t tens = ((pairs * 103) >> 10) & 0x000F000F000F000Full;
  std::uint64_t digits = (tens | ((pairs - tens * 10) << 8)) | 0x3030303030303030ull;
#if __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  digits = __builtin_bswap64(digits);  // the first digit in the lowest lane
#endif
  std::memcpy(p, &digits, 8);
}

// Seventeen digits of s < 10^17 into tmp[7, 24), leading zeros included;
// the number's n digits are the last n. Readers copy fixed blocks of 17
// bytes from them (tmp holds 48), never a variable length.
inline void digits17(char* tmp, std::uint64_t s) {
  const std::uint64_t top = s / 100000000;
  write8(tmp + 16, static_cast<std::uint32_t>(s - top * 100000000));
  write8(tmp + 8, static_cast<std::uint32_t>(top % 100000000));
  tmp[7] = static_cast<char>('0' + top / 100000000);
}

// The body of format_double, inlined into the writer's cells.
inline std::size_t format(char* out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  char* p = out;
  *p = '-';
  p += bits >> 63;
  if (((bits >> 52) & 0x7ff) == 0x7ff) {
    // One spelling for NaN whatever its sign bit keeps files comparable.
    if ((bits << 12) != 0) {
      std::memcpy(out, "nan", 3);
      return 3;
    }
    std::memcpy(p, "inf", 3);
    return static_cast<std::size_t>(p + 3 - out);
  }
  const double a = std::fabs(v);
  char tmp[48];  // only the digits written are read into the text
  // Whole numbers below 10^5 (0, flags, set points): their digits are the
  // shortest text, and plain is never longer than scientific there.
  if (a < 1e5 && a == static_cast<double>(static_cast<std::uint32_t>(a))) {
    const auto u = static_cast<std::uint32_t>(a);
    const int n = digit_count(u);
    digits17(tmp, u);
    std::memcpy(p, tmp + 24 - n, 17);
    return static_cast<std::size_t>(p + n - out);
  }
  const auto dec = fmt::detail::dragonbox::to_decimal(a);  // a = s 10^e, s without trailing zeros
  const std::uint64_t s = dec.significand;
  const int e = dec.exponent;
  const int n = digit_count(s);
  const int x = e + n - 1;  // the scientific exponent
  const int ax = x < 0 ? -x : x;
  const int len_sci = n + (n > 1 ? 1 : 0) + 2 + (ax >= 100 ? 3 : 2);  // d[.ddd]e+XX
  const int len_plain = e >= 0 ? n + e : (x >= 0 ? n + 1 : 2 - e);  // ddd000, dd.dd, 0.00ddd
  digits17(tmp, s);
  const char* d = tmp + 24 - n;
  if (len_plain <= len_sci) {
    if (e >= 0) {
      // Above 2^53 to_chars writes the double's exact integer, not the
      // shortest digits padded with zeros (as long, equally round-trip).
      if (a >= 9007199254740992.0) return static_cast<std::size_t>(std::to_chars(p, p + 32, a).ptr - out);
      std::memcpy(p, d, 17);
      std::memset(p + n, '0', static_cast<std::size_t>(e));
      return static_cast<std::size_t>(p + n + e - out);
    }
    if (x >= 0) {  // dd.dd: the integer digits, the point, the rest
      std::memcpy(p, d, 17);
      p[x + 1] = '.';
      std::memcpy(p + x + 2, d + x + 1, 17);
      return static_cast<std::size_t>(p + n + 1 - out);
    }
    // 0.00ddd
    const int zeros = -x - 1;
    std::memcpy(p, "0.0000", 6);
    std::memcpy(p + 2 + zeros, d, 17);
    return static_cast<std::size_t>(p + 2 + zeros + n - out);
  }
  p[0] = d[0];
  char* q = p + 1;
  if (n > 1) {
    p[1] = '.';
    std::memcpy(p + 2, d + 1, 16);
    q = p + n + 1;
  }
  *q++ = 'e';
  *q++ = x < 0 ? '-' : '+';
  if (ax >= 100) *q++ = static_cast<char>('0' + ax / 100);
  std::memcpy(q, kPairs + 2 * (ax % 100), 2);
  return static_cast<std::size_t>(q + 2 - out);
}

}  // namespace

// The shortest digits come from Dragonbox (libfmt's, the digit generation
// behind fmt's "{}"); the layout follows std::to_chars(double) exactly, so
// the text is the one to_chars gives: plain or scientific, whichever is
// shorter, plain on a tie (0.001, 3300, 1e-05, 1.5e+20). The tests compare
// the two on random bit patterns and decimal grids.
std::size_t format_double(char* out, double v) { return format(out, v); }

std::size_t CsvWriter::cell(char* out, double v, std::size_t col) {
  if (col >= kCached) return format(out, v);
  Cached& c = cached_[col];
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  // A fixed-size copy: bytes past the text are scratch (format_double's
  // contract), in the buffer's reserved room.
  if (c.len > 0 && c.bits == bits) {
    std::memcpy(out, c.text, kText);
    return c.len;
  }
  const std::size_t len = format(out, v);
  c.bits = bits;
  c.len = static_cast<std::uint32_t>(len);
  std::memcpy(c.text, out, kText);
  return len;
}

void CsvWriter::nums(const double* v, std::size_t count) {
  // Room for a block of cells at a time, not per cell.
  constexpr std::size_t kBlock = 256;
  for (std::size_t start = 0; start < count; start += kBlock) {
    const std::size_t end = start + kBlock < count ? start + kBlock : count;
    reserve((end - start) * kCell);
    char* p = buf_ + n_;
    std::size_t col = col_;
    for (std::size_t k = start; k < end; ++k, ++col) {
      *p = ',';
      p += col > 0 ? 1 : 0;
      p += cell(p, v[k], col);
    }
    col_ = col;
    n_ = static_cast<std::size_t>(p - buf_);
  }
}

void CsvWriter::integer(long v) {
  reserve(24);
  sep();
  const auto r = std::to_chars(buf_ + n_, buf_ + n_ + 24, v);
  n_ = static_cast<std::size_t>(r.ptr - buf_);
  ++col_;
}

void CsvWriter::text(std::string_view s) {
  if (n_ + s.size() + 2 > kSize) flush();
  if (s.size() + 2 > kSize) {  // larger than the buffer: straight through
    sep();
    flush();
    if (f_ != nullptr) std::fwrite(s.data(), 1, s.size(), f_);
    ++col_;
    return;
  }
  sep();
  std::memcpy(buf_ + n_, s.data(), s.size());
  n_ += s.size();
  ++col_;
}

void CsvWriter::flush() {
  if (f_ != nullptr && n_ > 0) std::fwrite(buf_, 1, n_, f_);
  n_ = 0;
}

}  // namespace cvt::analysis
