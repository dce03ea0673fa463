// Buffered CSV output with shortest round-trip numbers (docs/cli.md#csv-numbers).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "cvtplant/analysis/csv_writer.hpp"

using namespace cvt::analysis;

namespace {
std::string fmt(double v) {
  char buf[40];
  return std::string(buf, format_double(buf, v));
}
std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
double from_bits(std::uint64_t b) {
  double v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}
// What a reader of the file gets back: the C library's strtod, not to_chars' twin.
double parse(const std::string& s) { return std::strtod(s.c_str(), nullptr); }
}  // namespace

TEST_CASE("format_double: every double reads back to the same bits") {
  std::mt19937_64 rng(20240611);
  long checked = 0;
  for (int i = 0; i < 200000; ++i) {
    // Random bit patterns cover every exponent, subnormals included.
    const double v = from_bits(rng());
    if (!std::isfinite(v)) continue;
    const std::string s = fmt(v);
    REQUIRE_MESSAGE(bits(parse(s)) == bits(v), s);
    ++checked;
  }
  CHECK(checked > 190000);
  for (double v : {0.0, -0.0, 1.0, -1.0, 0.1, 1e-3, 3300.0, std::numeric_limits<double>::min(),
                   std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
                   std::numeric_limits<double>::lowest(), std::nextafter(1.0, 2.0)})
    CHECK_MESSAGE(bits(parse(fmt(v))) == bits(v), fmt(v));
}

TEST_CASE("format_double: the shortest text, and a defined spelling of non-finite values") {
  CHECK(fmt(0.001) == "0.001");
  CHECK(fmt(3300.0) == "3300");
  CHECK(fmt(-0.0) == "-0");
  CHECK(fmt(0.1 + 0.2) == "0.30000000000000004");  // 17 digits where 17 are needed
  CHECK(fmt(1e-300) == "1e-300");
  CHECK(fmt(std::nan("")) == "nan");
  CHECK(fmt(-std::nan("")) == "nan");
  CHECK(fmt(INFINITY) == "inf");
  CHECK(fmt(-INFINITY) == "-inf");
}

TEST_CASE("CsvWriter: rows across many buffer blocks arrive whole and in order") {
  std::FILE* f = std::tmpfile();
  REQUIRE(f != nullptr);
  const int rows = 20000;  // ~1 MB: about 16 blocks of 64 KiB
  {
    CsvWriter w(f);
    w.text("i");
    w.text("x");
    w.text("label");
    w.end_row();
    for (int i = 0; i < rows; ++i) {
      w.integer(i);
      w.num(std::sqrt(static_cast<double>(i)) * 1e-7);
      w.text(i % 2 ? "odd" : "even");
      w.end_row();
    }
    // A cell longer than the buffer passes straight through.
    w.text(std::string(70000, 'z'));
    w.end_row();
  }  // the destructor hands over the rest
  std::rewind(f);
  std::string all;
  char buf[65536];
  std::size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) all.append(buf, got);
  std::fclose(f);
  std::size_t pos = all.find('\n');
  REQUIRE(all.substr(0, pos) == "i,x,label");
  for (int i = 0; i < rows; ++i) {
    const std::size_t next = all.find('\n', pos + 1);
    REQUIRE(next != std::string::npos);
    const std::string line = all.substr(pos + 1, next - pos - 1);
    const std::size_t c1 = line.find(','), c2 = line.rfind(',');
    REQUIRE(std::stoi(line.substr(0, c1)) == i);
    REQUIRE(bits(parse(line.substr(c1 + 1, c2 - c1 - 1))) == bits(std::sqrt(static_cast<double>(i)) * 1e-7));
    REQUIRE(line.substr(c2 + 1) == (i % 2 ? "odd" : "even"));
    pos = next;
  }
  CHECK(all.substr(pos + 1) == std::string(70000, 'z') + "\n");
}
