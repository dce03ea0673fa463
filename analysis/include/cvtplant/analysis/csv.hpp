#pragma once
// Reads one named numeric column from a CSV file with a header row
// (docs/analysis.md#input). Separators: ',' (also accepts ';' and tabs when the
// header contains no comma). Blank lines and lines starting with '#' are skipped.
// Every error names the file and the 1-based line number.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace cvt::analysis {

struct CsvColumn {
  std::string name;
  std::vector<double> values;
};

// Throws InputError: unreadable file, a directory or device, empty file,
// missing column (the message lists the columns present), a row with
// another number of cells than the header (shorter or longer), non-numeric
// cell (quoted up to 40 characters), NaN or infinity; LimitError once more
// than `max_bytes` have been read (0: no cap), so an endless stream such as
// /dev/zero stops. A UTF-8 byte-order mark before the header is skipped.
CsvColumn read_csv_column(const std::string& path, const std::string& column, std::size_t max_bytes = 0);

// Several columns in one pass over the file, so a pipe can be read: `pick`
// gets the header's names and returns the columns wanted (in that order).
using ColumnPicker = std::function<std::vector<std::string>(const std::vector<std::string>& header)>;
std::vector<CsvColumn> read_csv_columns(const std::string& path, const ColumnPicker& pick, std::size_t max_bytes = 0);

// Header names of a CSV file (for --help style listings and error messages).
std::vector<std::string> read_csv_header(const std::string& path);

}  // namespace cvt::analysis
