#pragma once
// The one rule for a name that becomes part of a file name, a line of a
// generated file or a report heading (a scene's `name`; docs/cli.md#names).
#include <cstddef>
#include <string>

namespace cvt::files {

inline constexpr std::size_t kMaxNameChars = 64;

// Why `name` cannot be such a name, or "" when it can: it must have 1 to 64
// characters, each a letter, a digit, '-', '_' or '.', the first a letter
// or a digit (so no path separator, no "..", no hidden file, no space or
// control character).
std::string name_problem(const std::string& name);

}  // namespace cvt::files
