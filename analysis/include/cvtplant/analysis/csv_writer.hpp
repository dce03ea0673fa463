#pragma once
// Buffered CSV output for the offline tools (docs/cli.md#csv-numbers): every
// double is written in its shortest form that reads back to the same bits
// (std::to_chars), so a CSV carries the run exactly and formatting costs a
// fraction of printf's. Rows are assembled in a 64 KiB buffer and handed to
// the FILE* in whole blocks; write errors show on the FILE (ferror) as with
// fprintf, so the callers' checks of the output stay the same.
#include <cstddef>
#include <cstdio>
#include <string_view>

namespace cvt::analysis {

// Writes the shortest round-trip text of `v` to `out` (at least 32 chars)
// and returns the number of characters; NaN and infinities as nan, inf, -inf.
std::size_t format_double(char* out, double v);

class CsvWriter {
 public:
  explicit CsvWriter(std::FILE* f) : f_(f) {}
  ~CsvWriter() { flush(); }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // A number, an integer or a text cell, preceded by a comma unless it is the
  // first cell of the row.
  void num(double v) {
    reserve(40);
    sep();
    n_ += format_double(buf_ + n_, v);
  }
  void integer(long v);
  void text(std::string_view s);
  // Ends the row.
  void end_row() {
    reserve(1);
    buf_[n_++] = '\n';
    first_ = true;
  }
  // Hands the buffered rows to the FILE* (not fflush: the FILE keeps its own
  // buffering); a no-op without a FILE.
  void flush();

 private:
  static constexpr std::size_t kSize = 65536;
  void reserve(std::size_t k) {
    if (n_ + k + 1 > kSize) flush();
  }
  void sep() {
    if (!first_) buf_[n_++] = ',';
    first_ = false;
  }
  std::FILE* f_;
  std::size_t n_ = 0;
  bool first_ = true;
  char buf_[kSize];
};

}  // namespace cvt::analysis
