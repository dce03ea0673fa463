#pragma once
// Reads one named numeric column from a CSV file with a header row
// (docs/analysis.md#input). Separators: ',' (also accepts ';' and tabs when the
// header contains no comma). Blank lines and lines starting with '#' are skipped.
// Every error names the file and the 1-based line number.
#include <string>
#include <vector>

namespace cvt::analysis {

struct CsvColumn {
  std::string name;
  std::vector<double> values;
};

// Throws InputError: unreadable file, empty file, missing column (the message
// lists the columns present), short row, non-numeric cell, NaN or infinity.
CsvColumn read_csv_column(const std::string& path, const std::string& column);

// Header names of a CSV file (for --help style listings and error messages).
std::vector<std::string> read_csv_header(const std::string& path);

}  // namespace cvt::analysis
