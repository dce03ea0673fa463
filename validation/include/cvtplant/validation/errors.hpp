#pragma once
// Errors of the validation module. The command line maps InputError to exit
// 2 (bad input: a scene the reference cannot run, an unknown parameter, an
// unwritable cache) and RunError to exit 1 (the input was fine but a run
// could not complete: the plant faulted, too few samples to compare).
#include <stdexcept>
#include <string>

namespace cvt::validation {

struct InputError : std::runtime_error {
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

struct RunError : std::runtime_error {
  explicit RunError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace cvt::validation
