#pragma once
// Buffered CSV output for the offline tools (docs/cli.md#csv-numbers): every
// double is written in its shortest form that reads back to the same bits
// (the text std::to_chars gives, its digits from libfmt's Dragonbox), so a
// CSV carries the run exactly and formatting costs a fraction of printf's.
// Rows are assembled in a 64 KiB buffer and handed to the FILE* in whole
// blocks; write errors show on the FILE (ferror) as with fprintf, so the
// callers' checks of the output stay the same.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

namespace cvt::analysis {

// Writes the shortest round-trip text of `v` to `out` (at least 40 chars of
// room: it copies fixed-size blocks, so bytes past the returned length may be
// overwritten) and returns the
// number of characters; NaN and infinities as nan, inf, -inf.
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
    reserve(kCell);
    sep();
    n_ += cell(buf_ + n_, v, col_);
    ++col_;
  }
  // `count` numbers in a row: the cost of num() per cell without its per-cell
  // bookkeeping.
  void nums(const double* v, std::size_t count);
  void integer(long v);
  void text(std::string_view s);
  // Ends the row.
  void end_row() {
    reserve(1);
    buf_[n_++] = '\n';
    col_ = 0;
  }
  // Hands the buffered rows to the FILE* (not fflush: the FILE keeps its own
  // buffering); a no-op without a FILE.
  void flush();

 private:
  static constexpr std::size_t kSize = 65536;
  static constexpr std::size_t kCell = 41;  // a comma and format_double's room
  static constexpr std::size_t kText = 24;  // the longest shortest double: -2.2250738585072014e-308
  static constexpr std::size_t kCached = 64;
  // A column's last number and its text: a value repeated from the previous
  // row (a set point, a flag, a quantity at rest) is copied, not formatted.
  struct Cached {
    std::uint64_t bits = 0;
    std::uint32_t len = 0;  // 0: nothing cached yet
    char text[kText];
  };
  // Column `col`'s number at `out`, from the cache or formatted.
  std::size_t cell(char* out, double v, std::size_t col);
  void reserve(std::size_t k) {
    if (n_ + k + 1 > kSize) flush();
  }
  void sep() {
    if (col_ > 0) buf_[n_++] = ',';
  }
  std::FILE* f_;
  std::size_t n_ = 0;
  std::size_t col_ = 0;  // cells written in the current row
  Cached cached_[kCached];
  char buf_[kSize];
};

}  // namespace cvt::analysis
