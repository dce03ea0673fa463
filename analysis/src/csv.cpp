#include "cvtplant/analysis/csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "cvtplant/analysis/errors.hpp"

namespace cvt::analysis {
namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t' || s[a] == '\r' || s[a] == '"')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r' || s[b - 1] == '"')) --b;
  return s.substr(a, b - a);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t p = line.find(sep, start);
    out.push_back(trim(line.substr(start, p == std::string::npos ? std::string::npos : p - start)));
    if (p == std::string::npos) break;
    start = p + 1;
  }
  return out;
}

bool skip_line(const std::string& line) {
  const std::string t = trim(line);
  return t.empty() || t[0] == '#';
}

char detect_separator(const std::string& header) {
  if (header.find(',') != std::string::npos) return ',';
  if (header.find(';') != std::string::npos) return ';';
  if (header.find('\t') != std::string::npos) return '\t';
  return ',';
}

struct Header {
  std::vector<std::string> names;
  char sep = ',';
  long line_no = 0;
};

Header read_header(std::ifstream& in, const std::string& path) {
  Header h;
  std::string line;
  while (std::getline(in, line)) {
    ++h.line_no;
    if (skip_line(line)) continue;
    h.sep = detect_separator(line);
    h.names = split(line, h.sep);
    return h;
  }
  throw InputError(path + ": empty file (expected a header row)");
}

}  // namespace

std::vector<std::string> read_csv_header(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
  return read_header(in, path).names;
}

CsvColumn read_csv_column(const std::string& path, const std::string& column) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
  const Header h = read_header(in, path);
  std::size_t col = h.names.size();
  for (std::size_t i = 0; i < h.names.size(); ++i)
    if (h.names[i] == column) {
      col = i;
      break;
    }
  if (col == h.names.size()) {
    std::string have;
    for (const auto& n : h.names) have += (have.empty() ? "" : ", ") + n;
    throw InputError(path + ": no column '" + column + "' (columns: " + have + ")");
  }
  CsvColumn out;
  out.name = column;
  std::string line;
  long line_no = h.line_no;
  while (std::getline(in, line)) {
    ++line_no;
    if (skip_line(line)) continue;
    const std::vector<std::string> cells = split(line, h.sep);
    const std::string where = path + ":" + std::to_string(line_no);
    if (cells.size() <= col)
      throw InputError(where + ": row has " + std::to_string(cells.size()) + " cells, column '" + column +
                       "' is cell " + std::to_string(col + 1));
    const std::string& cell = cells[col];
    const char* s = cell.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (cell.empty() || end == s || *end != '\0')
      throw InputError(where + ": column '" + column + "': '" + cell + "' is not a number");
    if (std::isnan(v)) throw InputError(where + ": column '" + column + "': NaN is not allowed");
    if (!std::isfinite(v) || errno == ERANGE)
      throw InputError(where + ": column '" + column + "': '" + cell + "' is not a finite number");
    out.values.push_back(v);
  }
  if (out.values.empty()) throw InputError(path + ": column '" + column + "' has no data rows");
  return out;
}

}  // namespace cvt::analysis
