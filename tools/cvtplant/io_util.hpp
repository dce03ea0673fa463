#pragma once
// Small shared helpers for subcommands: strict number parsing, input files
// read with a size cap, outputs whose write errors fail the run, and JSON
// printing with deterministic number formatting.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "commands.hpp"

namespace cvtcli {

// Parses a finite double or throws UsageError naming `what`.
double parse_finite(const std::string& text, const std::string& what);

// Parses "a,b,c,..." into exactly `n` finite doubles (n = 0: any count >= 1).
std::vector<double> parse_list(const std::string& text, std::size_t n, const std::string& what);

// Parses repeated "name=value" options (`--param`) into a map of finite
// doubles; a later assignment of a name replaces an earlier one. Throws
// UsageError naming `flag` (and the name, for a bad value).
std::map<std::string, double> parse_assignments(const std::vector<std::string>& items, const std::string& flag);

// Reads a whole input file of at most `max_bytes` (a regular file or a pipe;
// a directory, a device such as /dev/null or /dev/zero, or a larger input
// is a UsageError naming `what` and the path).
std::string read_input_file(const std::string& path, std::size_t max_bytes, const std::string& what);

// Whether two paths name the same file (device and inode); false if either
// does not exist.
bool same_file(const std::string& a, const std::string& b);

// Opens `path` for writing ("-" = stdout) or throws UsageError naming `flag`.
// `inputs` are files the command reads: writing over one of them is refused.
std::FILE* open_output(const std::string& path, const std::string& flag = "output",
                       const std::vector<std::string>& inputs = {});
// Whether every write to `f` so far succeeded; on the first failure the
// system's reason (EPIPE, ENOSPC) is kept for the message of close_output,
// so call it right after writing. nullptr is fine.
bool output_ok(std::FILE* f);
// Throws RunError if a write to `f` has failed (closed pipe, full disk).
void check_output(std::FILE* f);
// Flushes and closes (stdout is only flushed); a failed write is a RunError.
void close_output(std::FILE* f);
// Why the last failed write failed ("Broken pipe", "No space left on device").
std::string write_error_reason(int fresh_errno);

// Prints JSON to stdout with a trailing newline.
void print_json(const nlohmann::json& j);

}  // namespace cvtcli
