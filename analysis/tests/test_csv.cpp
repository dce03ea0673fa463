// CSV input errors name the file, the line and the column (docs/analysis.md#input).
#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>

#include "cvtplant/analysis/csv.hpp"
#include "cvtplant/analysis/errors.hpp"

using namespace cvt::analysis;

namespace {
std::string write(const char* name, const char* text) {
  const std::string p = std::string("/tmp/cvt_analysis_test_") + name;
  std::ofstream(p) << text;
  return p;
}
std::string error_of(const std::string& path, const char* col) {
  try {
    read_csv_column(path, col);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("CSV: reads a named column, skipping comments and blank lines") {
  const auto p = write("ok.csv", "# comment\nt,a,b\n0,1.5,2\n\n1,-2e-3,3\n");
  const CsvColumn c = read_csv_column(p, "a");
  REQUIRE(c.values.size() == 2);
  CHECK(c.values[0] == 1.5);
  CHECK(c.values[1] == -2e-3);
}

TEST_CASE("CSV: errors carry line numbers") {
  const auto p = write("bad.csv", "t,a\n0,1\n1,x1\n");
  CHECK(error_of(p, "a").find("bad.csv:3: column 'a': 'x1' is not a number") != std::string::npos);
  CHECK(error_of(p, "zz").find("no column 'zz' (columns: t, a)") != std::string::npos);
  const auto n = write("nan.csv", "t,a\n0,1\n1,2\n2,NaN\n");
  CHECK(error_of(n, "a").find("nan.csv:4: column 'a': NaN") != std::string::npos);
  const auto i = write("inf.csv", "t,a\n0,inf\n");
  CHECK(error_of(i, "a").find("inf.csv:2") != std::string::npos);
  const auto s = write("short.csv", "t,a\n0\n");
  CHECK(error_of(s, "a").find("short.csv:2: row has 1 cells") != std::string::npos);
  const auto e = write("empty.csv", "");
  CHECK(error_of(e, "a").find("empty file") != std::string::npos);
  CHECK(error_of("/nonexistent/x.csv", "a").find("cannot read") != std::string::npos);
}
