// Buffered CSV output with shortest round-trip numbers (docs/cli.md#csv-numbers).
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

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
// The whole of a temporary file, which is then closed.
std::string read_and_close(std::FILE* f) {
  std::rewind(f);
  std::string all;
  char buf[65536];
  std::size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) all.append(buf, got);
  std::fclose(f);
  return all;
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

// std::to_chars, the former writer, as the independent reference for the
// text: format_double takes its digits from Dragonbox and lays them out itself.
std::string reference(double v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

TEST_CASE("format_double: the same text as std::to_chars (random bit patterns, integers, decimal grids)") {
  std::mt19937_64 rng(77);
  long differ = 0, checked = 0;
  auto check = [&](double v) {
    ++checked;
    if (fmt(v) != reference(v) && differ++ < 10) FAIL_CHECK(fmt(v) << " vs to_chars " << reference(v));
  };
  for (int i = 0; i < 1000000; ++i) {
    const double v = from_bits(rng());
    if (std::isfinite(v)) check(v);
  }
  // Whole numbers around the fast path's bound and 2^53, frame times,
  // small and large magnitudes around each switch between plain and
  // scientific (1e-05 against 0.0001, 1e+16 against 1000000000000000).
  for (long k = -200000; k <= 200000; ++k) {
    check(static_cast<double>(k));
    check(static_cast<double>(k) * 0.001);
    check(static_cast<double>(k) * 1e-7);
  }
  for (long k = -2000; k <= 2000; ++k) check(9007199254740992.0 + static_cast<double>(k) * 2);
  for (int exp10 = -330; exp10 <= 310; ++exp10)
    for (const char* mant : {"1", "12", "123", "99999", "1234567", "123456789012345", "9999999999999999",
                             "12345678901234567"}) {
      const double v = std::strtod((std::string(mant) + "e" + std::to_string(exp10)).c_str(), nullptr);
      check(v);
      check(-v);
    }
  CHECK(differ == 0);
  CHECK(checked > 2000000);
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
  const std::string all = read_and_close(f);
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

TEST_CASE("CsvWriter: nums() writes what num() writes; a value repeated in its column is the same text") {
  // Columns of changing values, constants and values that repeat from row to
  // row (what the column cache copies), more columns than it keeps, and a
  // row that starts with text.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<std::vector<double>> rows;
  for (int r = 0; r < 3000; ++r) {
    std::vector<double> v;
    for (int c = 0; c < 80; ++c) {
      if (c % 4 == 0) v.push_back(u(rng));                               // changes
      if (c % 4 == 1) v.push_back(3300.0);                                // constant
      if (c % 4 == 2) v.push_back(std::floor(r / 7.0) * 0.1 + 1e-9);      // repeats for 7 rows
      if (c % 4 == 3) v.push_back(r % 3 == 0 ? std::nan("") : -0.0);      // special values
    }
    rows.push_back(v);
  }
  auto write = [&](bool whole_rows) {
    std::FILE* f = std::tmpfile();
    {
      CsvWriter w(f);
      for (const auto& v : rows) {
        if (whole_rows) {
          w.text("row");
          w.nums(v.data(), v.size());
        } else {
          w.text("row");
          for (double x : v) w.num(x);
        }
        w.end_row();
      }
    }
    return read_and_close(f);
  };
  const std::string by_cell = write(false), by_row = write(true);
  CHECK(by_row == by_cell);
  // And each cell is format_double's text of its value.
  std::string expected;
  for (const auto& v : rows) {
    expected += "row";
    for (double x : v) expected += "," + fmt(x);
    expected += "\n";
  }
  CHECK(by_row == expected);
}
