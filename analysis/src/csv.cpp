#include "cvtplant/analysis/csv.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>

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

// A cell or name for a message: at most 40 characters, control characters
// shown as '?', so a 50 MB cell is never echoed back.
std::string shown(const std::string& text) {
  constexpr std::size_t kMax = 40;
  std::string out = text.substr(0, kMax);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (text.size() <= kMax) return "'" + out + "'";
  return "'" + out + "...' (" + std::to_string(text.size()) + " characters)";
}

// Lines of a file, with a cap on the bytes read (0: none). Refuses
// directories and devices: only regular files and pipes hold a CSV.
class LineReader {
 public:
  LineReader(const std::string& path, std::size_t max_bytes) : path_(path), max_bytes_(max_bytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw InputError("cannot read " + shown(path) + ": " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InputError(shown(path) + " is a directory, not a CSV file");
    if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
      throw InputError(shown(path) + " is not a regular file or a pipe");
    f_ = std::fopen(path.c_str(), "rb");
    if (f_ == nullptr) throw InputError("cannot read " + shown(path) + ": " + std::strerror(errno));
  }
  ~LineReader() { std::fclose(f_); }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  bool getline(std::string& line) {
    line.clear();
    int c = 0;
    bool any = false;
    while ((c = getc_unlocked(f_)) != EOF) {
      any = true;
      if (max_bytes_ != 0 && ++read_ > max_bytes_)
        throw LimitError(shown(path_) + " is larger than the read cap of " + std::to_string(max_bytes_) + " bytes",
                         static_cast<double>(read_));
      if (c == '\n') return true;
      line.push_back(static_cast<char>(c));
    }
    if (std::ferror(f_)) throw InputError("reading " + shown(path_) + " failed: " + std::strerror(errno));
    return any;
  }

 private:
  std::string path_;
  std::size_t max_bytes_;
  std::size_t read_ = 0;
  std::FILE* f_ = nullptr;
};

struct Header {
  std::vector<std::string> names;
  char sep = ',';
  long line_no = 0;
};

Header read_header(LineReader& in, const std::string& path) {
  Header h;
  std::string line;
  while (in.getline(line)) {
    ++h.line_no;
    // A UTF-8 byte-order mark (spreadsheets write one) is no part of the
    // first name.
    if (h.line_no == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
    if (skip_line(line)) continue;
    h.sep = detect_separator(line);
    h.names = split(line, h.sep);
    return h;
  }
  throw InputError(path + ": empty file (expected a header row)");
}

}  // namespace

std::vector<std::string> read_csv_header(const std::string& path) {
  LineReader in(path, 0);
  return read_header(in, path).names;
}

std::vector<CsvColumn> read_csv_columns(const std::string& path, const ColumnPicker& pick, std::size_t max_bytes) {
  LineReader in(path, max_bytes);
  const Header h = read_header(in, path);
  const std::vector<std::string> wanted = pick(h.names);
  std::vector<std::size_t> index;
  std::vector<CsvColumn> out;
  for (const std::string& column : wanted) {
    std::size_t col = h.names.size();
    for (std::size_t i = 0; i < h.names.size(); ++i)
      if (h.names[i] == column) {
        col = i;
        break;
      }
    if (col == h.names.size()) {
      std::string have;
      for (const auto& n : h.names) have += (have.empty() ? "" : ", ") + n;
      if (have.size() > 400) have = have.substr(0, 400) + "...";
      for (char& c : have)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
      throw InputError(path + ": no column " + shown(column) + " (columns: " + have + ")");
    }
    index.push_back(col);
    out.push_back(CsvColumn{column, {}});
  }
  std::string line;
  long line_no = h.line_no;
  while (in.getline(line)) {
    ++line_no;
    if (skip_line(line)) continue;
    const std::vector<std::string> cells = split(line, h.sep);
    const std::string where = path + ":" + std::to_string(line_no);
    // A row of another width than the header's is not the table the header
    // describes: refused, longer as well as shorter.
    if (cells.size() != h.names.size())
      throw InputError(where + ": row has " + std::to_string(cells.size()) + " cells, the header has " +
                       std::to_string(h.names.size()));
    for (std::size_t k = 0; k < index.size(); ++k) {
      const std::string& column = out[k].name;
      const std::string& cell = cells[index[k]];
      const char* s = cell.c_str();
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(s, &end);
      if (cell.empty() || end == s || *end != '\0')
        throw InputError(where + ": column '" + column + "': " + shown(cell) + " is not a number");
      if (std::isnan(v)) throw InputError(where + ": column '" + column + "': NaN is not allowed");
      if (!std::isfinite(v) || errno == ERANGE)
        throw InputError(where + ": column '" + column + "': " + shown(cell) + " is not a finite number");
      out[k].values.push_back(v);
    }
  }
  for (const CsvColumn& c : out)
    if (c.values.empty()) throw InputError(path + ": column '" + c.name + "' has no data rows");
  return out;
}

CsvColumn read_csv_column(const std::string& path, const std::string& column, std::size_t max_bytes) {
  return read_csv_columns(
             path, [&](const std::vector<std::string>&) { return std::vector<std::string>{column}; }, max_bytes)
      .front();
}

}  // namespace cvt::analysis
