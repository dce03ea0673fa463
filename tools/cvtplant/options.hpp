#pragma once
// One place for the validation of numeric options and of the work a run may
// do (docs/cli.md#ranges). Every numeric flag of every subcommand is added
// through add_real/add_int: the value must be a finite number in a stated
// range (nan, inf, "1e8" for an integer, trailing text are refused), and the
// range is shown in --help. Every run estimates its work before it starts
// and refuses above a cap that the user can raise (--max-steps,
// --max-memory-mb), with the figure and the option in the message.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace cvtcli {

// An interval of allowed values; an open end excludes its bound.
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;
  // "(0, 1e5]"
  std::string text() const;
  bool contains(double v) const;
};

// Strict parsing of one token (the whole token must be the number).
// Returns an empty string on success, else why the token was refused
// ("'nan' is not a finite number", "5 is above the maximum 4", ...).
std::string check_real(const std::string& token, const Range& r, double* out);
std::string check_int(const std::string& token, long long lo, long long hi, long long* out);

// Adds a flag whose value must be a finite number in `r`.
CLI::Option* add_real(CLI::App* app, const std::string& name, double& var, const Range& r, const std::string& help);
// Adds a flag whose value must be an integer (decimal digits only) in lo..hi.
CLI::Option* add_int(CLI::App* app, const std::string& name, int& var, long long lo, long long hi,
                     const std::string& help);
CLI::Option* add_int(CLI::App* app, const std::string& name, long& var, long long lo, long long hi,
                     const std::string& help);
CLI::Option* add_int(CLI::App* app, const std::string& name, long long& var, long long lo, long long hi,
                     const std::string& help);

// Caps on the work and memory of one run. The defaults keep a run on this
// kind of host under about ten minutes and 1 GiB; the flags raise them.
struct Caps {
  double max_steps = 1e9;        // integrator steps (or map iterations), summed over the run
  double max_memory_mb = 1024;   // stored samples, traces and working copies
};
inline constexpr double kMaxStepsLimit = 1e15;
inline constexpr double kMaxMemoryMbLimit = 1e7;

// Adds --max-steps and/or --max-memory-mb.
void add_caps(CLI::App* app, Caps& caps, bool steps, bool memory);

// Throws UsageError if `steps` exceeds the cap: "the run needs 2.0e+12
// integrator steps (<how>), above the cap of 1e+09; raise it with --max-steps".
void require_steps(double steps, const Caps& caps, const std::string& how);
// The same for an estimate of memory in bytes (--max-memory-mb).
void require_memory(double bytes, const Caps& caps, const std::string& how);
// The cap in bytes, for readers that must stop early (a stream of unknown size).
std::uint64_t memory_cap_bytes(const Caps& caps);

// A count for a message: "10000", "1e+08".
std::string fmt_count(double n);

// A value for a message, exactly: the shortest text that reads back to the
// same double ("99.99999", "0.1", "1e-300"), so a refused value is never
// shown rounded into the range it violates.
std::string exact_number(double v);

// 'text' for a message, cut to `max_chars` with the full length said, so a
// 50 MB cell is never echoed back.
std::string quoted(const std::string& text, std::size_t max_chars = 40);

}  // namespace cvtcli
