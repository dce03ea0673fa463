#pragma once
// Bad input to an estimator (too few points, constant series, NaN, ...).
// The CLI maps it to exit code 2 (docs/cli.md); library users catch it.
#include <stdexcept>
#include <string>

namespace cvt::analysis {

struct InputError : std::runtime_error {
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// A run whose work or input, measured before the analysis starts, exceeds
// the caller's cap (BenettinOptions::max_steps, the byte cap of
// read_csv_column). The CLI names the flag that raises it.
struct LimitError : InputError {
  LimitError(const std::string& what, double needed_amount) : InputError(what), needed(needed_amount) {}
  double needed;  // steps or bytes
};

}  // namespace cvt::analysis
