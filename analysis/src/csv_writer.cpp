// Buffered CSV output with shortest round-trip numbers (docs/cli.md#csv-numbers).
#include "cvtplant/analysis/csv_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace cvt::analysis {

std::size_t format_double(char* out, double v) {
  // to_chars spells non-finite values as "nan"/"-nan"/"inf"/"-inf"; one
  // spelling for NaN whatever its sign bit keeps files comparable.
  if (std::isnan(v)) {
    std::memcpy(out, "nan", 3);
    return 3;
  }
  const auto r = std::to_chars(out, out + 32, v);
  return static_cast<std::size_t>(r.ptr - out);
}

void CsvWriter::integer(long v) {
  reserve(24);
  sep();
  const auto r = std::to_chars(buf_ + n_, buf_ + n_ + 24, v);
  n_ = static_cast<std::size_t>(r.ptr - buf_);
}

void CsvWriter::text(std::string_view s) {
  if (n_ + s.size() + 2 > kSize) flush();
  if (s.size() + 2 > kSize) {  // larger than the buffer: straight through
    sep();
    flush();
    if (f_ != nullptr) std::fwrite(s.data(), 1, s.size(), f_);
    return;
  }
  sep();
  std::memcpy(buf_ + n_, s.data(), s.size());
  n_ += s.size();
}

void CsvWriter::flush() {
  if (f_ != nullptr && n_ > 0) std::fwrite(buf_, 1, n_, f_);
  n_ = 0;
}

}  // namespace cvt::analysis
