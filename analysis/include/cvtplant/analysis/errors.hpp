#pragma once
// Bad input to an estimator (too few points, constant series, NaN, ...).
// The CLI maps it to exit code 2 (docs/cli.md); library users catch it.
#include <stdexcept>
#include <string>

namespace cvt::analysis {

struct InputError : std::runtime_error {
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace cvt::analysis
